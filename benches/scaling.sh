#!/usr/bin/env bash
# How the main job's time and memory grow with triangles, pixels and texels (issue 15, "Scaling"):
# three sweeps of `shadowlab analyze` on variants of the outdoor scene, each varying one quantity,
# every run a whole process (`/usr/bin/time`: wall time and peak RSS) plus the phase times the run
# reports (results.json), the median of REPEATS runs; then render-mesh's peak RSS on each mesh.
#
#   triangles: the ground plane's segments (2·s² triangles) — 128, 256, 512, 1024 — with the image
#              at 1024×768 and one lispsm map of 2048²;
#   pixels:    the image at 512×384, 1024×768, 2048×1536, 4096×3072 — lispsm, 2048²;
#   texels:    lispsm and logarithmic at 512², 1024², 2048², 4096², 1024×768 (one process per size).
#
# Usage: [REPEATS=3] [IDLE_WAIT=600] bash benches/scaling.sh   (release build; data/meshes/dragon.obj
# is used for render-mesh if fetched). Each timed run waits for an idle machine (≥ 95 % idle over
# 2 s), at most IDLE_WAIT seconds.
set -euo pipefail
cd "$(dirname "$0")/.."
REPEATS=${REPEATS:-3}
cargo build --release --quiet
bin=$PWD/target/release/shadowlab
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# shellcheck source=benches/idle.sh
source benches/idle.sh

# The outdoor scene with its ground's segments and its image size replaced, written to $1.
variant() {
  sed -e "s/^segments = 24$/segments = $2/" -e "s/^image = \[1024, 768\]$/image = [$3, $4]/" \
    data/scenes/outdoor.toml > "$1"
  # The scene's relative mesh paths are resolved from its folder.
  sed -i "s#\.\./meshes/#$PWD/data/meshes/#" "$1"
}

# One row: label, then medians over REPEATS of wall s, peak MiB, and the summed phases of
# results.json (shadow pass, lookup, footprints, all in ms) and its truth_ms.
measure() {
  local label=$1; shift
  for _ in $(seq "$REPEATS"); do
    wait_idle
    rm -rf "$work/out"
    /usr/bin/time -f "%e %M" -o "$work/time" "$bin" analyze "$@" --timing-runs 1 --out "$work/out" > /dev/null
    python3 - "$work/time" "$work/out/results.json" <<'EOF'
import json, sys
wall, kb = open(sys.argv[1]).read().split()
d = json.load(open(sys.argv[2]))
phase = lambda k: sum(m["ms"].get(k, 0) for m in d["measurements"] if isinstance(m.get("ms"), dict))
print(wall, int(kb) / 1024, phase("shadow_pass"), phase("lookup"), phase("footprints"), d["truth_ms"], d["visible"])
EOF
  done > "$work/rows"
  python3 - "$label" "$work/rows" <<'EOF'
import statistics, sys
rows = [list(map(float, l.split())) for l in open(sys.argv[2])]
med = [statistics.median(c) for c in zip(*rows)]
print("| %s | %.2f | %.0f | %.1f | %.1f | %.1f | %.1f | %d |" % (sys.argv[1], *med[:6], med[6]))
EOF
}

header() {
  echo
  echo "| $1 | wall s | peak MiB | shadow pass ms | lookup ms | footprints ms | truth ms | visible px |"
  echo "|---|---:|---:|---:|---:|---:|---:|---:|"
}

echo "== $(lscpu | sed -n 's/^Model name: *//p'), $(nproc) CPUs; commit $(git rev-parse --short HEAD); medians of $REPEATS"
header "triangles (ground segments s: 2·s² + the rest)"
for s in 128 256 512 1024; do
  variant "$work/scene.toml" "$s" 1024 768
  measure "s = $s" "$work/scene.toml" --techniques lispsm --resolutions 2048
done
header "pixels"
for size in "512 384" "1024 768" "2048 1536" "4096 3072"; do
  read -r w h <<< "$size"
  variant "$work/scene.toml" 24 "$w" "$h"
  measure "${w}×${h}" "$work/scene.toml" --techniques lispsm --resolutions 2048
done
header "texels"
for technique in lispsm logarithmic; do
  for res in 512 1024 2048 4096; do
    measure "$technique ${res}²" outdoor --techniques "$technique" --resolutions "$res"
  done
done

echo
echo "| render-mesh (light 2048² + eye 1024×768, PNG and EXR written) | triangles | wall s | peak MiB |"
echo "|---|---:|---:|---:|"
for mesh in data/meshes/bunny.obj data/meshes/dragon.obj; do
  [ -f "$mesh" ] || continue
  wait_idle
  rm -rf "$work/mesh"
  /usr/bin/time -f "%e %M" -o "$work/time" "$bin" render-mesh "$mesh" --out "$work/mesh" > /dev/null
  read -r wall kb < "$work/time"
  triangles=$(grep -c '^f ' "$mesh")
  echo "| $(basename "$mesh") | $triangles | $wall | $((kb / 1024)) |"
done
