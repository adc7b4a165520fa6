#!/usr/bin/env python3
"""Render shadowlab's exported shadow maps again with OpenGL and compare them.

Usage:
    python3 reproduce_maps_gl.py EXPORT_DIR [COMBINATION ...]

EXPORT_DIR is the ``export/`` directory that ``shadowlab analyze --export``
writes. Without COMBINATION, every subdirectory of EXPORT_DIR that holds a
``setup.json`` is checked. For each partition of each light, the script

* draws ``EXPORT_DIR/scene.obj`` (its ``v`` and ``f`` lines) through the
  partition's ``projection · view``, honouring the conventions ``setup.json``
  states (docs/setup-format.md), into a GL_DEPTH_COMPONENT32F framebuffer of
  ``map_size`` texels a side: depth test LESS (GREATER and clear 0 for
  reversed depth), no culling;
* reads it back with glReadPixels (row 0 at the bottom), turns it into
  shadowlab's window depth (GL's: near 0, 1 where empty) and rounds it as the
  partition's ``depth_format`` stores it;
* compares it with ``COMBINATION/map-light{L}-part{P}.npy``: the texels covered
  (depth < 1) by one map and not the other, and the largest and the
  99.9th-percentile absolute depth difference over texels both cover.

Exit status: 0 when every map agrees within COVERAGE_TOLERANCE and
DEPTH_TOLERANCE, 1 when one does not, 2 on bad input, a set-up it does not
handle (more than one frame) or no usable OpenGL 4.5 context.

Needs numpy, PyOpenGL and Mesa's EGL (Debian: libegl-mesa0 libgl1-mesa-dri).
The context is headless: EGL on Mesa's surfaceless platform, software
rasterizer (llvmpipe) unless LIBGL_ALWAYS_SOFTWARE is set otherwise.
"""

import argparse
import json
import os
import sys
from pathlib import Path

os.environ.setdefault("PYOPENGL_PLATFORM", "egl")
os.environ.setdefault("EGL_PLATFORM", "surfaceless")
os.environ.setdefault("LIBGL_ALWAYS_SOFTWARE", "1")

import numpy as np
from OpenGL import EGL, GL

# shadowlab rasterizes in f64 with GL's exact rules (8-bit sub-pixel snapping,
# top-left fill rule, depth interpolated at texel centres). GL gets f32
# positions and an f32 matrix, so each vertex lands within a few f32 ulps of
# where shadowlab puts it: a texel centre that close to an edge (or to the near
# or far plane) may flip between covered and not. At most this fraction of a
# map's texels may differ so.
COVERAGE_TOLERANCE = 1e-4
# Over texels both maps cover, the 99.9th percentile of |depth difference| must
# stay below this. Rounding positions and matrix entries to f32 (relative error
# 6e-8 each, amplified by cancellation in projection · view · p) and f32
# interpolation give errors of 1e-7 to 1e-6 in window depth; 1e-5 is about
# eight times the largest p99.9 measured on the samples (1.3e-6). The last
# 0.1 % (thin triangles, whose depth plane tilts as their vertices round, and
# steep texels) are printed as the maximum but not judged. A unorm
# depth_format adds one storage step: a depth near a step's boundary may round
# either way.
DEPTH_TOLERANCE = 1e-5

NDC_DEPTHS = ("negative-one-to-one", "zero-to-one", "reversed-zero-to-one")

VERTEX_SHADER = """#version 330 core
layout(location = 0) in vec3 position;
uniform mat4 clip_from_world;
void main() { gl_Position = clip_from_world * vec4(position, 1.0); }
"""
FRAGMENT_SHADER = """#version 330 core
void main() {}
"""


class InputError(Exception):
    """Bad or unsupported input: exit status 2."""


def load_obj(path):
    """The positions (f64) and triangles (u32) of an OBJ's v and f lines."""
    positions, triangles = [], []
    with open(path, encoding="utf-8") as lines:
        for line in lines:
            if line.startswith("v "):
                positions.append([float(x) for x in line.split()[1:4]])
            elif line.startswith("f "):
                corners = [int(t.split("/")[0]) - 1 for t in line.split()[1:]]
                triangles += [(corners[0], corners[k], corners[k + 1])
                              for k in range(1, len(corners) - 1)]
    positions = np.array(positions, dtype=np.float64).reshape(-1, 3)
    triangles = np.array(triangles, dtype=np.int64).reshape(-1, 3)
    if triangles.size and (triangles.min() < 0
                           or triangles.max() >= len(positions)):
        raise InputError(f"{path}: a face index is not a vertex (only positive "
                         "indices are read)")
    return positions, triangles.astype(np.uint32)


def make_context():
    """A current OpenGL 4.5 core context without a surface."""
    display = EGL.eglGetDisplay(EGL.EGL_DEFAULT_DISPLAY)
    if not EGL.eglInitialize(display, None, None):
        raise RuntimeError("eglInitialize failed")
    config = EGL.EGLConfig()
    count = EGL.EGLint()
    # No surface is made: EGL_SURFACE_TYPE would otherwise default to windows.
    wanted = (EGL.EGLint * 5)(EGL.EGL_RENDERABLE_TYPE, EGL.EGL_OPENGL_BIT,
                              EGL.EGL_SURFACE_TYPE, EGL.EGL_DONT_CARE,
                              EGL.EGL_NONE)
    if not EGL.eglChooseConfig(display, wanted, config, 1, count) \
            or count.value < 1:
        raise RuntimeError("no EGL config renders OpenGL")
    EGL.eglBindAPI(EGL.EGL_OPENGL_API)
    attributes = (EGL.EGLint * 7)(
        EGL.EGL_CONTEXT_MAJOR_VERSION, 4, EGL.EGL_CONTEXT_MINOR_VERSION, 5,
        EGL.EGL_CONTEXT_OPENGL_PROFILE_MASK,
        EGL.EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL.EGL_NONE)
    context = EGL.eglCreateContext(display, config, EGL.EGL_NO_CONTEXT,
                                   attributes)
    if not context or not EGL.eglMakeCurrent(display, EGL.EGL_NO_SURFACE,
                                             EGL.EGL_NO_SURFACE, context):
        raise RuntimeError("no surfaceless OpenGL 4.5 core context "
                           "(glClipControl needs 4.5)")
    return display, context


def compile_program():
    """A program that only transforms positions: depth is all it writes."""
    program = GL.glCreateProgram()
    for kind, source in ((GL.GL_VERTEX_SHADER, VERTEX_SHADER),
                         (GL.GL_FRAGMENT_SHADER, FRAGMENT_SHADER)):
        shader = GL.glCreateShader(kind)
        GL.glShaderSource(shader, source)
        GL.glCompileShader(shader)
        if not GL.glGetShaderiv(shader, GL.GL_COMPILE_STATUS):
            raise RuntimeError(GL.glGetShaderInfoLog(shader).decode())
        GL.glAttachShader(program, shader)
    GL.glLinkProgram(program)
    if not GL.glGetProgramiv(program, GL.GL_LINK_STATUS):
        raise RuntimeError(GL.glGetProgramInfoLog(program).decode())
    return program


def upload_mesh(positions, triangles):
    """Binds a vertex array of f32 positions and u32 indices."""
    GL.glBindVertexArray(GL.glGenVertexArrays(1))
    GL.glBindBuffer(GL.GL_ARRAY_BUFFER, GL.glGenBuffers(1))
    vertices = np.ascontiguousarray(positions, dtype=np.float32)
    GL.glBufferData(GL.GL_ARRAY_BUFFER, vertices.nbytes, vertices,
                    GL.GL_STATIC_DRAW)
    GL.glVertexAttribPointer(0, 3, GL.GL_FLOAT, GL.GL_FALSE, 0, None)
    GL.glEnableVertexAttribArray(0)
    GL.glBindBuffer(GL.GL_ELEMENT_ARRAY_BUFFER, GL.glGenBuffers(1))
    indices = np.ascontiguousarray(triangles, dtype=np.uint32)
    GL.glBufferData(GL.GL_ELEMENT_ARRAY_BUFFER, indices.nbytes, indices,
                    GL.GL_STATIC_DRAW)


def clip_from_world(partition, conventions):
    """Return projection · view in GL's layout for column vectors.

    The result is a row-major f64 matrix that takes (x, y, z, 1) of the scene's
    right-handed world to clip space with NDC y up and the file's NDC depth.
    """
    def matrix(values):
        m = np.array(values, dtype=np.float64).reshape(4, 4)
        return m if conventions["matrix_order"] == "row-major" else m.T
    view, projection = matrix(partition["view"]), matrix(partition["projection"])
    if conventions["world"] == "left-handed":
        view[:, 2] = -view[:, 2]  # the file's world is the scene's (x, y, -z)
    if conventions["ndc_y"] == "down":
        projection[1] = -projection[1]  # Vulkan's y: GL's row 0 stays the bottom
    return projection @ view


def render_depth(program, count, matrix, side, ndc_depth):
    """The window depth GL stores at each texel, row 0 at the bottom."""
    framebuffer = GL.glGenFramebuffers(1)
    GL.glBindFramebuffer(GL.GL_FRAMEBUFFER, framebuffer)
    renderbuffer = GL.glGenRenderbuffers(1)
    GL.glBindRenderbuffer(GL.GL_RENDERBUFFER, renderbuffer)
    GL.glRenderbufferStorage(GL.GL_RENDERBUFFER, GL.GL_DEPTH_COMPONENT32F,
                             side, side)
    GL.glFramebufferRenderbuffer(GL.GL_FRAMEBUFFER, GL.GL_DEPTH_ATTACHMENT,
                                 GL.GL_RENDERBUFFER, renderbuffer)
    GL.glDrawBuffer(GL.GL_NONE)
    GL.glReadBuffer(GL.GL_NONE)
    status = GL.glCheckFramebufferStatus(GL.GL_FRAMEBUFFER)
    if status != GL.GL_FRAMEBUFFER_COMPLETE:
        raise RuntimeError(f"framebuffer of {side}² incomplete: {status:#x}")
    reversed_z = ndc_depth == "reversed-zero-to-one"
    GL.glClipControl(GL.GL_LOWER_LEFT,
                     GL.GL_NEGATIVE_ONE_TO_ONE
                     if ndc_depth == "negative-one-to-one"
                     else GL.GL_ZERO_TO_ONE)
    GL.glViewport(0, 0, side, side)
    GL.glDisable(GL.GL_CULL_FACE)
    GL.glEnable(GL.GL_DEPTH_TEST)
    GL.glDepthMask(GL.GL_TRUE)
    GL.glDepthFunc(GL.GL_GREATER if reversed_z else GL.GL_LESS)
    GL.glClearDepth(0.0 if reversed_z else 1.0)
    GL.glClear(GL.GL_DEPTH_BUFFER_BIT)
    GL.glUseProgram(program)
    GL.glUniformMatrix4fv(GL.glGetUniformLocation(program, "clip_from_world"),
                          1, GL.GL_TRUE, matrix.astype(np.float32))
    GL.glDrawElements(GL.GL_TRIANGLES, count, GL.GL_UNSIGNED_INT, None)
    depth = np.empty((side, side), dtype=np.float32)
    GL.glPixelStorei(GL.GL_PACK_ALIGNMENT, 4)
    GL.glReadPixels(0, 0, side, side, GL.GL_DEPTH_COMPONENT, GL.GL_FLOAT, depth)
    GL.glDeleteFramebuffers(1, [framebuffer])
    GL.glDeleteRenderbuffers(1, [renderbuffer])
    window = depth.astype(np.float64)
    return 1.0 - window if reversed_z else window  # GL's depth: near 0


UNORM_STEPS = {"unorm24": 2.0**24 - 1, "unorm16": 2.0**16 - 1}


def as_stored(window, depth_format):
    """The window depth as ``depth_format`` stores it, decoded (f64)."""
    if depth_format == "f32":
        return window.astype(np.float32).astype(np.float64)
    if depth_format == "reversed-f32":
        return 1.0 - (1.0 - window).astype(np.float32).astype(np.float64)
    steps = UNORM_STEPS.get(depth_format)
    if steps is None:
        raise InputError(f"unknown depth_format {depth_format!r}")
    return np.floor(np.clip(window, 0.0, 1.0) * steps + 0.5) / steps


def compare(ours, theirs):
    """Texels covered by one only; max and p99.9 of |Δ|; texels both cover."""
    covered, their_covered = ours < 1.0, theirs < 1.0
    flips = int(np.count_nonzero(covered != their_covered))
    difference = np.abs(ours - theirs)[covered & their_covered]
    if difference.size == 0:
        return flips, 0.0, 0.0, 0
    return (flips, float(difference.max()),
            float(np.percentile(difference, 99.9)), difference.size)


def check_combination(export, name, program, count):
    """Prints one line per map; returns whether every map agrees."""
    directory = export / name
    with open(directory / "setup.json", encoding="utf-8") as file:
        setup = json.load(file)
    conventions = setup["conventions"]
    if conventions["ndc_depth"] not in NDC_DEPTHS:
        raise InputError(f"{name}: ndc_depth {conventions['ndc_depth']!r}")
    if len(setup["frames"]) != 1:
        raise InputError(f"{name}: {len(setup['frames'])} frames; the export "
                         "holds the maps of one frame, this script reads one")
    agree, maps = True, set(directory.glob("map-light*-part*.npy"))
    for light, entry in enumerate(setup["frames"][0]["lights"]):
        for part, partition in enumerate(entry["partitions"]):
            side = partition["map_size"]
            path = directory / f"map-light{light}-part{part}.npy"
            maps.discard(path)
            theirs = np.load(path).astype(np.float64)
            if theirs.shape != (side, side):
                raise InputError(f"{path}: shape {theirs.shape}, map_size {side}")
            window = render_depth(program, count,
                                  clip_from_world(partition, conventions),
                                  side, conventions["ndc_depth"])
            ours = as_stored(window, partition["depth_format"])
            flips, largest, p999, both = compare(ours, theirs)
            fraction = flips / side**2
            steps = UNORM_STEPS.get(partition["depth_format"])
            tolerance = DEPTH_TOLERANCE + (1.0 / steps if steps else 0.0)
            ok = fraction <= COVERAGE_TOLERANCE and p999 <= tolerance
            agree &= ok
            print(f"{name} light {light} part {part} ({side}², "
                  f"{partition['depth_format']}): covered "
                  f"{np.count_nonzero(ours < 1)} GL / "
                  f"{np.count_nonzero(theirs < 1)} shadowlab, by one only "
                  f"{flips} ({fraction:.2e}); |depth diff| over {both} "
                  f"covered by both: max {largest:.3e}, p99.9 {p999:.3e}: "
                  f"{'ok' if ok else 'DIFFERS'}")
    if maps:
        raise InputError(f"{name}: maps the set-up has no partition for: "
                         f"{sorted(p.name for p in maps)}")
    return agree


def main():
    """Check the combinations the command line names; return the exit status."""
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("export", type=Path, help="the export/ directory")
    parser.add_argument("combinations", nargs="*",
                        help="combination directories (default: every one with "
                             "a setup.json)")
    args = parser.parse_args()
    names = args.combinations or sorted(
        p.parent.name for p in args.export.glob("*/setup.json"))
    if not names:
        print(f"{args.export}: no */setup.json", file=sys.stderr)
        return 2
    try:
        positions, triangles = load_obj(args.export / "scene.obj")
        display, _ = make_context()
        print(f"GL: {GL.glGetString(GL.GL_RENDERER).decode()}, "
              f"{GL.glGetString(GL.GL_VERSION).decode()}; scene.obj: "
              f"{len(positions)} vertices, {len(triangles)} triangles")
        program = compile_program()
        upload_mesh(positions, triangles)
        agree = True
        for name in names:
            agree &= check_combination(args.export, name, program,
                                       triangles.size)
        EGL.eglTerminate(display)
    except KeyError as error:
        print(f"error: a field is missing: {error}", file=sys.stderr)
        return 2
    except (InputError, OSError, ValueError, RuntimeError) as error:
        print(f"error: {error}", file=sys.stderr)
        return 2
    print(f"{'all maps agree' if agree else 'some maps differ'} (tolerances: "
          f"coverage {COVERAGE_TOLERANCE:g} of a map's texels, depth p99.9 "
          f"{DEPTH_TOLERANCE:g}, plus one step for unorm formats)")
    return 0 if agree else 1


if __name__ == "__main__":
    sys.exit(main())
