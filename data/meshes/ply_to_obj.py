#!/usr/bin/env python3
"""Convert a PLY mesh (ASCII, binary little- or big-endian; optionally gzip-compressed) to OBJ.

Reads the vertex element's x, y, z properties and the face element's vertex_indices (or
vertex_index) list; every other element and property is skipped. Faces are written as OBJ `f` lines
with all their vertices (1-based); polygons are left for the OBJ loader to triangulate.
Coordinates are written exactly: ASCII tokens as they stand, binary values in Python's shortest
round-trip form of the (exactly widened) double, so every coordinate reads back as the same number.
Python 3 standard library only. The output is written to a temporary file and renamed into place.

Usage: ply_to_obj.py INPUT.ply[.gz] OUTPUT.obj ["HEADER COMMENT"]
"""

import gzip
import os
import struct
import sys

SCALAR_FORMATS = {
    "char": "b", "int8": "b", "uchar": "B", "uint8": "B",
    "short": "h", "int16": "h", "ushort": "H", "uint16": "H",
    "int": "i", "int32": "i", "uint": "I", "uint32": "I",
    "float": "f", "float32": "f", "double": "d", "float64": "d",
}


def fail(message):
    sys.exit("ply_to_obj: " + message)


def read_header(stream):
    """Returns (format, elements); elements is a list of (name, count, properties), each property
    (name, scalar_type) or (name, ("list", count_type, item_type))."""
    if stream.readline().strip() != b"ply":
        fail("not a PLY file (no 'ply' magic line)")
    fmt, elements = None, []
    while True:
        line = stream.readline()
        if not line:
            fail("header ends without end_header")
        words = line.decode("ascii").split()
        if not words or words[0] in ("comment", "obj_info"):
            continue
        if words[0] == "end_header":
            break
        if words[0] == "format":
            fmt = words[1]
        elif words[0] == "element":
            elements.append((words[1], int(words[2]), []))
        elif words[0] == "property":
            if not elements:
                fail("property before any element")
            if words[1] == "list":
                elements[-1][2].append((words[4], ("list", words[2], words[3])))
            else:
                elements[-1][2].append((words[2], words[1]))
        else:
            fail("unknown header line: %s" % line.decode("ascii").strip())
    if fmt not in ("ascii", "binary_little_endian", "binary_big_endian"):
        fail("unsupported format %r" % fmt)
    return fmt, elements


def ascii_row(stream):
    """The next data line's tokens."""
    line = stream.readline()
    if not line:
        fail("file ends inside the data")
    return line.decode("ascii").split()


def binary_reader(stream, endian):
    def read(type_name):
        code = SCALAR_FORMATS.get(type_name)
        if code is None:
            fail("unknown property type %r" % type_name)
        size = struct.calcsize(code)
        data = stream.read(size)
        if len(data) != size:
            fail("file ends inside the data")
        return struct.unpack(endian + code, data)[0]
    return read


def convert(source, target, header_comment):
    opener = gzip.open if source.endswith(".gz") else open
    with opener(source, "rb") as stream:
        fmt, elements = read_header(stream)
        if fmt == "ascii":
            read = None
        else:
            read = binary_reader(stream, "<" if fmt == "binary_little_endian" else ">")
        positions, faces = [], []
        for name, count, properties in elements:
            names = [p[0] for p in properties]
            if name == "vertex":
                try:
                    xyz = [names.index(axis) for axis in ("x", "y", "z")]
                except ValueError:
                    fail("vertex element without x, y, z")
            if name == "face":
                lists = [n for n in ("vertex_indices", "vertex_index") if n in names]
                list_name = lists[0] if lists else None
                if list_name is None:
                    fail("face element without vertex_indices")
            for row_index in range(count):
                values = []
                if read is None:
                    tokens = ascii_row(stream)
                    at = 0
                    for _, kind in properties:
                        if isinstance(kind, tuple):
                            n = int(tokens[at])
                            values.append(tokens[at + 1: at + 1 + n])
                            at += 1 + n
                        else:
                            values.append(tokens[at])
                            at += 1
                    if at != len(tokens):
                        fail("%s %d: %d values, expected %d" % (name, row_index, len(tokens), at))
                else:
                    for _, kind in properties:
                        if isinstance(kind, tuple):
                            n = read(kind[1])
                            values.append([read(kind[2]) for _ in range(n)])
                        else:
                            values.append(read(kind))
                if name == "vertex":
                    if read is None:
                        positions.append(" ".join(values[i] for i in xyz))
                    else:
                        positions.append(" ".join(repr(float(values[i])) for i in xyz))
                elif name == "face":
                    faces.append([int(i) for i in values[names.index(list_name)]])
    for face in faces:
        if len(face) < 3 or not all(0 <= i < len(positions) for i in face):
            fail("bad face %r" % (face,))
    temporary = target + ".tmp"
    with open(temporary, "w", encoding="ascii", newline="\n") as out:
        for line in header_comment.splitlines():
            out.write("# %s\n" % line)
        out.write("# %d vertices, %d faces\n" % (len(positions), len(faces)))
        for p in positions:
            out.write("v %s\n" % p)
        for face in faces:
            out.write("f %s\n" % " ".join(str(i + 1) for i in face))
    os.replace(temporary, target)
    print("%s: %d vertices, %d faces" % (target, len(positions), len(faces)))


def main():
    if len(sys.argv) not in (3, 4):
        sys.exit(__doc__)
    convert(sys.argv[1], sys.argv[2], sys.argv[3] if len(sys.argv) == 4 else "")


if __name__ == "__main__":
    main()
