"""The table of benches/embree.sh: medians, ratios and per-ray agreement of shadowlab and Embree.

Usage: python3 embree_report.py [--ungated] OUT MESH_NAME [...]
(--ungated: the runs were not gated on an idle machine; every table then says it is no measurement)

OUT/MESH_NAME holds the inputs (examples/ray_bench.rs `write`), the JSON of every repeat
(shadowlab-K.json, embree-K.json for K = 1, 2, ...) and the answers per ray of repeat 1
({shadowlab,embree}-SET.closest as i32 triangle indices, -1 for a miss; .anyhit as u8).

Rates: per repeat, a measurement's rate is its rays over the median of its timed runs; the table
shows the median over repeats. Ratios are taken per repeat (shadowlab's repeat K against Embree's
repeat K, which ran right after it) and their median is shown: a pairwise ratio holds when the
machine's speed drifts between repeats. Standard library only.
"""

import json
import statistics
import sys
from array import array
from fractions import Fraction
from pathlib import Path

SETS = ["camera", "random", "grid"]
CAVEAT = "†: Embree f32, not watertight; shadowlab f64, exact"
# Rays whose closest triangles differ are checked in exact arithmetic up to this many per set.
MAX_EXACT_CHECKS = 10_000


class Mesh:
    """mesh.bin: the f32 positions and the triangles."""

    def __init__(self, path):
        data = path.read_bytes()
        vertices = int.from_bytes(data[:4], "little")
        self.positions = array("f")
        self.positions.frombytes(data[8 : 8 + 12 * vertices])
        self.corners = array("I")
        self.corners.frombytes(data[8 + 12 * vertices :])

    def vertex(self, k):
        return [Fraction(float(x)) for x in self.positions[3 * k : 3 * k + 3]]

    def exact_t(self, ray, triangle):
        """The exact parameter at which the ray meets the triangle (edges included), or None."""
        origin, direction = ray
        p0, p1, p2 = (self.vertex(k) for k in self.corners[3 * triangle : 3 * triangle + 3])
        e1 = [b - a for a, b in zip(p0, p1)]
        e2 = [b - a for a, b in zip(p0, p2)]
        s = [b - a for a, b in zip(p0, origin)]
        back = [-x for x in direction]
        det = determinant(back, e1, e2)
        if det == 0:
            return None
        t, u, v = (
            determinant(s, e1, e2) / det,
            determinant(back, s, e2) / det,
            determinant(back, e1, s) / det,
        )
        return t if u >= 0 and v >= 0 and u + v <= 1 else None

    def judge(self, ray, ours, theirs):
        """How Embree's closest triangle compares, exactly, with shadowlab's."""
        ours_t, theirs_t = self.exact_t(ray, ours), self.exact_t(ray, theirs)
        if theirs_t is None:
            return "missed"
        if ours_t is None or theirs_t < ours_t:
            return "shadowlab wrong"
        return "tie" if theirs_t == ours_t else "farther"


class Rays:
    """rays-SET.bin: f32 origins and directions."""

    def __init__(self, path):
        self.values = array("f")
        self.values.frombytes(path.read_bytes()[8:])

    def ray(self, i):
        values = [Fraction(float(x)) for x in self.values[6 * i : 6 * i + 6]]
        return values[:3], values[3:]


def determinant(a, b, c):
    return (
        a[0] * (b[1] * c[2] - b[2] * c[1])
        - a[1] * (b[0] * c[2] - b[2] * c[0])
        + a[2] * (b[0] * c[1] - b[1] * c[0])
    )


def load(directory, side):
    """Every repeat's JSON of one side, in repeat order."""
    runs = sorted(directory.glob(f"{side}-*.json"), key=lambda p: int(p.stem.split("-")[1]))
    return [json.loads(p.read_text()) for p in runs]


def medians(repeats, **key):
    """Per repeat: the median ms of the record matching `key`."""
    out = []
    for report in repeats:
        (record,) = [r for r in report["records"] if all(r.get(k) == v for k, v in key.items())]
        out.append(statistics.median(record["ms"]))
    return out


def rate(ms, rays):
    return rays / (ms * 1e3)  # Mrays/s


def answers(path, code):
    values = array(code)
    with open(path, "rb") as f:
        values.frombytes(f.read())
    return values


def number(x):
    """Three significant digits (all digits from 100 on)."""
    return f"{x:.0f}" if x >= 100 else f"{x:.1f}" if x >= 10 else f"{x:.2f}"


def spread(values):
    """`median [min–max]` of per-repeat values."""
    return f"{number(statistics.median(values))} [{number(min(values))}–{number(max(values))}]"


def report(out, name):
    directory = out / name
    ours, theirs = load(directory, "shadowlab"), load(directory, "embree")
    if not ours or len(ours) != len(theirs):
        sys.exit(f"{directory}: {len(ours)} shadowlab and {len(theirs)} Embree results")
    first = theirs[0]
    threads = sorted({r["threads"] for r in ours[0]["records"]})
    print(
        f"== {name}: {ours[0]['triangles']} triangles ({ours[0]['degenerate']} of zero area), "
        f"Embree {first['version']} (headers {first['headers']}); interleaved repeats: {len(ours)}, "
        f"each the median of {len(ours[0]['records'][0]['ms'])} timed runs after "
        f"{ours[0]['warmup']} untimed"
    )
    print(f"   rates in Mrays/s, median [min–max] over repeats; ratios shadowlab ÷ Embree. {CAVEAT}")
    header = (
        f"   {'query':8} {'set':9} {'thr':>3}  {'shadowlab':>22}  {'Embree 1-ray':>22}  "
        f"{'Embree 16-wide':>22}  {'÷ 1-ray':>8}  {'÷ 16-wide':>9}"
    )
    print(header)
    # shadowlab's batch queries, and the grid set's closest hits row by row (`rows`: the entry
    # point the logarithmic shadow map casts through, swept where the grid has enough rays per
    # triangle), each against the same Embree measurements.
    rows = [(what, set_name, "batch") for what in ["closest", "anyhit"] for set_name in SETS]
    rows.insert(SETS.index("grid") + 1, ("closest", "grid", "rows"))
    for what, set_name, mode in rows:
        rays = ours[0]["rays"][set_name]
        label = set_name if mode == "batch" else f"{set_name}·{mode}"
        for n in threads:
            ms = medians(ours, what=what, set=set_name, mode=mode, threads=n)
            single = medians(theirs, what=what, set=set_name, mode="single", threads=n)
            packet = medians(theirs, what=what, set=set_name, mode="packet16", threads=n)
            ratio_single = statistics.median(e / s for s, e in zip(ms, single))
            ratio_packet = statistics.median(e / s for s, e in zip(ms, packet))
            print(
                f"   {what:8} {label:9} {n:>3}  "
                f"{spread([rate(m, rays) for m in ms]):>22}  "
                f"{spread([rate(m, rays) for m in single]):>22}  "
                f"{spread([rate(m, rays) for m in packet]):>22}  "
                f"{ratio_single:>7.2f}×†  {ratio_packet:>7.2f}×†"
            )
    print(f"   BVH build, ms, median [min–max] over repeats; ratio shadowlab ÷ Embree. {CAVEAT}")
    print(
        f"   {'thr':>3}  {'shadowlab':>22}  {'Embree (default)':>22}  {'Embree (HIGH)':>22}  "
        f"{'÷ default':>9}"
    )
    for n in threads:
        ms = medians(ours, what="build", threads=n)
        default = medians(theirs, what="build", threads=n)
        high = medians(theirs, what="build-high", threads=n)
        ratio = statistics.median(s / e for s, e in zip(ms, default))
        print(
            f"   {n:>3}  {spread(ms):>22}  {spread(default):>22}  {spread(high):>22}  "
            f"{ratio:>8.2f}×†"
        )
    print(
        "   agreement (repeat 1): rays answered differently, shadowlab against Embree's single rays, "
        "and Embree's 16-wide packets against its single rays"
    )
    print(
        f"   {'set':7} {'rays':>9}  {'closest hit/miss':>16}  {'any hit':>8}  "
        f"{'closest triangle (missed, farther, tie, shadowlab wrong)':>56}  "
        f"{'packets: closest, any':>21}"
    )
    mesh = Mesh(directory / "mesh.bin")
    for set_name in SETS:
        a = answers(directory / f"shadowlab-{set_name}.closest", "i")
        b = answers(directory / f"embree-{set_name}.closest", "i")
        c = answers(directory / f"shadowlab-{set_name}.anyhit", "B")
        d = answers(directory / f"embree-{set_name}.anyhit", "B")
        hit_miss = sum((x < 0) != (y < 0) for x, y in zip(a, b))
        any_hit = sum(x != y for x, y in zip(c, d))
        other = [(i, x, y) for i, (x, y) in enumerate(zip(a, b)) if x >= 0 and y >= 0 and x != y]
        verdicts = {"missed": 0, "farther": 0, "tie": 0, "shadowlab wrong": 0}
        if len(other) <= MAX_EXACT_CHECKS:
            rays = Rays(directory / f"rays-{set_name}.bin")
            for i, ours_t, theirs_t in other:
                verdicts[mesh.judge(rays.ray(i), ours_t, theirs_t)] += 1
            exact = ", ".join(str(v) for v in verdicts.values())
        else:
            exact = "not checked"
        packets = first["packet_vs_single_differ"][set_name]
        print(
            f"   {set_name:7} {len(a):>9}  {hit_miss:>16}  {any_hit:>8}  "
            f"{f'{len(other)} ({exact})':>56}  {packets['closest']:>12}, {packets['anyhit']}"
        )
    print(
        "   closest triangle: both hit, different triangles; checked in exact rational arithmetic on "
        "the f32 inputs,\n   Embree's triangle is: missed by the exact ray (an edge decided the "
        "other way in f32), farther than shadowlab's\n   (Embree missed the nearer surface), at the "
        "same t, or nearer than shadowlab's or shadowlab's is not hit at all (shadowlab wrong)"
    )


def main():
    args = sys.argv[1:]
    ungated = args[:1] == ["--ungated"]
    args = args[1:] if ungated else args
    if len(args) < 2:
        sys.exit("usage: embree_report.py [--ungated] OUT MESH_NAME [...]")
    for name in args[1:]:
        if ungated:
            print("!! smoke run, not gated on an idle machine: these timings are not a measurement")
        report(Path(args[0]), name)


if __name__ == "__main__":
    main()
