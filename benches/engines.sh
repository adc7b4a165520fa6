#!/usr/bin/env bash
# The measured table of docs/what-engines-ship.md: every engine's preset, SDSM and the papers'
# partitioned and optimized maps on every built-in scene — misclassified pixels and their causes
# (seams in blend bands and at cascade boundaries apart), surface shimmer on the camera walk with and without the engine's snapping,
# texels spent, and time — at one map side per cascade. Prints the markdown tables.
#
# Usage: benches/engines.sh [SIDE] [FRAMES]   (default 2048 texels per cascade, 24 frames)
set -euo pipefail
side=${1:-2048}
frames=${2:-24}
top=$(git rev-parse --show-toplevel)
cd "$top"
cargo build --release --quiet
bin=target/release/shadowlab
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

engines=bevy,filament,godot,babylon,threejs,unity,unreal
# Some of the presets' choices, each against its engine's default: Babylon's cascades fitted by a
# sphere, Bevy without its blend, Godot with a 10 % linear band.
choices=babylon:fit=sphere,bevy:blend=0,godot:blend=0.1
studied="$engines,$choices,sdsm,sdsm:kmeans,lispsm,uniform,optimal"
unsnapped=bevy:unsnapped,filament:unsnapped,godot:unsnapped,babylon:unsnapped,threejs:unsnapped,unity:unsnapped,unreal:unsnapped

echo "<!-- $(date -u +%F), commit $(git rev-parse --short HEAD), $(lscpu | sed -n 's/^Model name: *//p'), $(nproc) CPUs; side $side, $frames frames -->"
for scene in outdoor dueling-frusta cad-lattice chess-spot bunny; do
  "$bin" analyze "$scene" --techniques "$studied" --partitions 4 --resolutions "$side" \
    --timing-runs 3 --out "$out/$scene" >/dev/null
  "$bin" temporal "$scene" --frames "$frames" --resolution "$side" \
    --techniques "$engines,$unsnapped,$choices,sdsm,lispsm,uniform" --out "$out/$scene-walk" >/dev/null
  python3 - "$scene" "$out/$scene/results.json" "$out/$scene-walk/temporal.csv" <<'EOF'
import csv, json, sys
scene, results, walk = sys.argv[1:4]
data = json.load(open(results))
surface = {}
for row in csv.DictReader(open(walk)):
    if row["snap_texels"] != "0" or not row["surface_shimmer"]:
        continue
    surface.setdefault(row["technique"], []).append(int(row["surface_shimmer"]))
mean = lambda xs: sum(xs) / len(xs) if xs else float("nan")
print(f"\n### `{scene}` ({data['visible']} visible pixels)\n")
print("| technique | maps | misclassified | acne | peter-panning | aliasing | seam: band / boundary | surface shimmer (snapped / unsnapped) | texels (M) | ms |")
print("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
for m in data["measurements"]:
    s = m["setting"]
    t = s["technique"]
    if "misclassified" not in m:
        print(f"| {t} | | not defined: {m.get('error', '')} | | | | | | | |")
        continue
    texels = m["texels"] / 1e6
    un = surface.get(t + "/unsnapped")
    snapped = surface.get(t)
    shimmer = (f"{mean(snapped):.1f}" if snapped else "—") + (f" / {mean(un):.1f}" if un else "")
    causes = [m["acne"], m["peter_panning"], m["aliasing"], f"{m['seam_band']} / {m['seam_boundary']}"]
    print(f"| {t} | {m['texels'] // s['resolution'] ** 2} | {m['misclassified']} | " + " | ".join(map(str, causes))
          + f" | {shimmer} | {texels:.1f} | {m['ms']['total']:.1f} |")
EOF
done
