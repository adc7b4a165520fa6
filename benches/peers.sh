#!/usr/bin/env bash
# The rasterizer against its peers, in one run: Mesa's llvmpipe (the harness in
# ../shared/tools/peers, or $PEERS), Intel's Masked Occlusion Culling (MOC: direct call and its
# thread pool, built from MOC's public source by $PEERS/moc/build.sh) and shadowlab's criterion
# bench, on the same meshes and views — interleaved (every peer once per round, REPEATS rounds),
# each timed run started on an idle machine — then the medians side by side, and pixel-by-pixel
# coverage and depth comparisons of all three.
#
# Usage: [MOC_SRC=DIR] [REPEATS=10] [RUNS=11] bash benches/peers.sh [MESH.obj ...]
#   MESH      default data/meshes/bunny.obj, and data/meshes/dragon.obj if fetched
#             (data/meshes/fetch-dragon.sh); shadowlab's bench (benches/raster.rs) times those two
#   MOC_SRC   a checkout or bare git directory of github.com/GameTechDev/MaskedOcclusionCulling;
#             without it (and without a build in MOC_BUILD) MOC is left out, said so.
#   MOC_BUILD where MOC's bench is built (default /tmp/moc-build; reused)
#   REPEATS   interleaved rounds (default 10); RUNS draws per peer run after warm-ups (default 11)
#   IDLE_WAIT the longest wait for an idle machine before each timed run, seconds (default 600)
# Installs Mesa and a Python venv with numpy and PyOpenGL on first use ($PEERS/setup.sh: apt, PyPI).
set -euo pipefail
cd "$(dirname "$0")/.."
PEERS=${PEERS:-../shared/tools/peers}
ENV=${PEER_ENV:-/tmp/peer-env}
REPEATS=${REPEATS:-10}
RUNS=${RUNS:-11}
MOC_BUILD=${MOC_BUILD:-/tmp/moc-build}
PY="$ENV/venv/bin/python3"
[ -x "$PY" ] || bash "$PEERS/setup.sh" "$ENV"
meshes=("$@")
if [ ${#meshes[@]} -eq 0 ]; then
  meshes=(data/meshes/bunny.obj)
  [ -f data/meshes/dragon.obj ] && meshes+=(data/meshes/dragon.obj)
fi
for mesh in "${meshes[@]}"; do
  [ -f "$mesh" ] || { echo "peers.sh: no mesh at $mesh" >&2; exit 2; }
done
moc=""
if [ -x "$MOC_BUILD/moc_bench" ]; then
  moc="$MOC_BUILD/moc_bench"
elif [ -n "${MOC_SRC:-}" ]; then
  moc=$(bash "$PEERS/moc/build.sh" "$MOC_SRC" "$MOC_BUILD" | tail -n 1)
else
  echo "peers.sh: MOC left out (set MOC_SRC to its source; see $PEERS/moc/README.md)" >&2
fi
cargo build --release --quiet
cargo bench --bench raster --no-run --quiet 2>/dev/null
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

# shellcheck source=benches/idle.sh
source benches/idle.sh

echo "== machine: $(lscpu | sed -n 's/^Model name: *//p'), $(nproc) CPUs; commit $(git rev-parse --short HEAD)"
[ -n "$moc" ] && echo "== $(cat "$MOC_BUILD/moc-version.txt" 2>/dev/null || echo 'MOC source: unknown')"

echo "== coverage and depth, f32 inputs (as GL buffers hold them), once"
for mesh in "${meshes[@]}"; do
  name=$(basename "$mesh" .obj)
  LP_NUM_THREADS=2 "$PY" "$PEERS/gl_depth_bench.py" --platform egl --runs 1 \
    --dump "$out/llvmpipe-$name" "$mesh" > /dev/null
  ./target/release/shadowlab render-mesh "$mesh" --f32-inputs --npy --out "$out/$name" > /dev/null
  for pass in light eye; do
    echo -n "  $name $pass, shadowlab vs llvmpipe: "
    "$PY" benches/compare_depth.py "$out/$name/$name-$pass.npy" "$out/llvmpipe-${name}_$pass.npy"
  done
  if [ -n "$moc" ]; then
    "$moc" "$mesh" --threads 0 --runs 1 --dump "$out/moc-$name" > "$out/moc-$name.json"
    near=$(grep -o '"eye_near": [0-9.e+-]*' "$out/moc-$name.json" | cut -d' ' -f2)
    far=$(grep -o '"eye_far": [0-9.e+-]*' "$out/moc-$name.json" | cut -d' ' -f2)
    echo -n "  $name light, MOC vs shadowlab: "
    "$PY" "$PEERS/moc/compare_coverage.py" "$out/moc-${name}_light.npy" "$out/$name/$name-light.npy" --pass light
    echo -n "  $name eye, MOC vs shadowlab: "
    "$PY" "$PEERS/moc/compare_coverage.py" "$out/moc-${name}_eye.npy" "$out/$name/$name-eye.npy" \
      --pass eye --near "$near" --far "$far"
  fi
done

# The criterion bench's meshes are the bunny and the dragon: the names given among them.
names=$(for mesh in "${meshes[@]}"; do basename "$mesh" .obj; done | paste -sd'|')
# One line per timed cell: peer, mesh, pass, threads, median ms.
times="$out/times.tsv"
: > "$times"
for round in $(seq "$REPEATS"); do
  echo "== round $round of $REPEATS"
  for mesh in "${meshes[@]}"; do
    name=$(basename "$mesh" .obj)
    wait_idle
    LP_NUM_THREADS=2 "$PY" "$PEERS/gl_depth_bench.py" --platform egl --runs "$RUNS" "$mesh" |
      "$PY" -c 'import json, sys
d = json.load(sys.stdin)
for p in ("light", "eye"):
    print("llvmpipe\t%s\t%s\t2\t%s" % (sys.argv[1], p, d[p]["median_ms"]))' "$name" >> "$times"
    if [ -n "$moc" ]; then
      for t in 0 2; do
        wait_idle
        "$moc" "$mesh" --threads "$t" --runs "$RUNS" | "$PY" -c 'import json, sys
d = json.load(sys.stdin)
peer = "moc-direct" if sys.argv[2] == "0" else "moc-pool"
for p in ("light", "eye"):
    print("%s\t%s\t%s\t%s\t%s" % (peer, sys.argv[1], p, max(1, int(sys.argv[2])), d[p]["median_ms"]))' "$name" "$t" >> "$times"
      done
    fi
  done
  wait_idle
  # shadowlab: the criterion bench's 2048² light and 1024×768 eye cells, 1 and 2 threads; short
  # criterion runs, since the rounds repeat them. Criterion prints [low median high].
  cargo bench --bench raster -- --warm-up-time 1 --measurement-time 3 \
    "raster/($names)/(light-2048|eye-1024x768)/" 2>&1 |
    awk '
      /^raster\// { split($1, id, "/"); name = id[2]; pass = id[3]; sub(/-.*/, "", pass)
                    threads = id[4]; sub(/-threads/, "", threads) }
      /time: +\[/ && !/%/ {
        sub(/.*time: +\[/, ""); split($0, f, " "); value = f[3]; unit = f[4]
        if (unit == "µs" || unit == "us") value /= 1000; else if (unit == "s") value *= 1000
        print "shadowlab\t" name "\t" pass "\t" threads "\t" value }' >> "$times"
done

echo "== medians of $REPEATS rounds, ms (each peer run: median of $RUNS draws)"
"$PY" - "$times" <<'EOF'
import statistics, sys
from collections import defaultdict
cells = defaultdict(list)
for line in open(sys.argv[1]):
    peer, mesh, pass_, threads, ms = line.split("\t")
    cells[(peer, mesh, pass_, int(threads))].append(float(ms))
med = {k: statistics.median(v) for k, v in cells.items()}
columns = sorted({(m, p) for (_, m, p, _) in med}, key=lambda c: (c[0], c[1] != "light"))
rows = [("llvmpipe, 2 threads", "llvmpipe", 2), ("shadowlab, 1 thread", "shadowlab", 1),
        ("shadowlab, 2 threads", "shadowlab", 2), ("MOC direct, 1 thread", "moc-direct", 1),
        ("MOC CullingThreadpool(2)", "moc-pool", 2)]
print("| ms | " + " | ".join("%s %s" % c for c in columns) + " |")
print("|---|" + "---:|" * len(columns))
for label, peer, t in rows:
    if any((peer, m, p, t) in med for m, p in columns):
        print("| %s | " % label + " | ".join(
            "%.2f" % med[(peer, m, p, t)] if (peer, m, p, t) in med else "—" for m, p in columns) + " |")
ratios = [("llvmpipe ÷ shadowlab (2 threads)", ("llvmpipe", 2), ("shadowlab", 2)),
          ("shadowlab 1 thread ÷ MOC direct", ("shadowlab", 1), ("moc-direct", 1)),
          ("shadowlab 2 threads ÷ MOC pool(2)", ("shadowlab", 2), ("moc-pool", 2))]
for label, (a, ta), (b, tb) in ratios:
    if all((a, m, p, ta) in med and (b, m, p, tb) in med for m, p in columns):
        print("| %s | " % label + " | ".join(
            "%.2f×" % (med[(a, m, p, ta)] / med[(b, m, p, tb)]) for m, p in columns) + " |")
EOF
