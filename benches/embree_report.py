"""The table of benches/embree.sh: medians, ratios and per-ray agreement of shadowlab and Embree.

Usage: python3 embree_report.py OUT MESH_NAME [...]

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
from pathlib import Path

SETS = ["camera", "random", "grid"]
CAVEAT = "†: Embree f32, not watertight; shadowlab f64, exact"


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
        f"   {'query':8} {'set':7} {'thr':>3}  {'shadowlab':>22}  {'Embree 1-ray':>22}  "
        f"{'Embree 16-wide':>22}  {'÷ 1-ray':>8}  {'÷ 16-wide':>9}"
    )
    print(header)
    for what in ["closest", "anyhit"]:
        for set_name in SETS:
            rays = ours[0]["rays"][set_name]
            for n in threads:
                ms = medians(ours, what=what, set=set_name, threads=n)
                single = medians(theirs, what=what, set=set_name, mode="single", threads=n)
                packet = medians(theirs, what=what, set=set_name, mode="packet16", threads=n)
                ratio_single = statistics.median(e / s for s, e in zip(ms, single))
                ratio_packet = statistics.median(e / s for s, e in zip(ms, packet))
                print(
                    f"   {what:8} {set_name:7} {n:>3}  "
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
        "   agreement (repeat 1): rays whose answers differ, shadowlab against Embree's single rays; "
        "Embree's 16-wide packets against its single rays"
    )
    print(
        f"   {'set':7} {'rays':>9}  {'closest hit/miss':>16}  {'closest triangle':>16}  "
        f"{'any hit':>8}  {'packets: closest, any':>21}"
    )
    for set_name in SETS:
        a = answers(directory / f"shadowlab-{set_name}.closest", "i")
        b = answers(directory / f"embree-{set_name}.closest", "i")
        c = answers(directory / f"shadowlab-{set_name}.anyhit", "B")
        d = answers(directory / f"embree-{set_name}.anyhit", "B")
        hit_miss = sum((x < 0) != (y < 0) for x, y in zip(a, b))
        triangle = sum(x >= 0 and y >= 0 and x != y for x, y in zip(a, b))
        any_hit = sum(x != y for x, y in zip(c, d))
        packets = first["packet_vs_single_differ"][set_name]
        print(
            f"   {set_name:7} {len(a):>9}  {hit_miss:>16}  {triangle:>16}  {any_hit:>8}  "
            f"{packets['closest']:>12}, {packets['anyhit']}"
        )
    print(
        "   (closest triangle: rays both hit, on different triangles; shadowlab breaks ties at a "
        "shared edge by the smaller index, Embree by its tree)"
    )


def main():
    if len(sys.argv) < 3:
        sys.exit("usage: embree_report.py OUT MESH_NAME [...]")
    out = Path(sys.argv[1])
    for name in sys.argv[2:]:
        report(out, name)


if __name__ == "__main__":
    main()
