#!/usr/bin/env bash
# The peer comparison of issue 4, in one run: Mesa's llvmpipe (through the harness in
# ../shared/tools/peers, or $PEERS) and shadowlab's rasterizer, on the same meshes and views, then
# pixel-by-pixel coverage and depth comparisons. Usage: bash benches/peers.sh [MESH.obj ...]
# (default: data/meshes/bunny.obj, and data/meshes/dragon.obj if fetched). Installs Mesa and a Python
# venv with numpy and PyOpenGL on first use (setup.sh, needs apt and PyPI).
set -euo pipefail
cd "$(dirname "$0")/.."
PEERS=${PEERS:-../shared/tools/peers}
ENV=${PEER_ENV:-/tmp/peer-env}
[ -x "$ENV/venv/bin/python3" ] || bash "$PEERS/setup.sh" "$ENV"
meshes=("$@")
if [ ${#meshes[@]} -eq 0 ]; then
  meshes=(data/meshes/bunny.obj)
  [ -f data/meshes/dragon.obj ] && meshes+=(data/meshes/dragon.obj)
fi
cargo build --release --quiet
out=$(mktemp -d)
for mesh in "${meshes[@]}"; do
  name=$(basename "$mesh" .obj)
  echo "== $name: llvmpipe (2 threads), median of 11 runs"
  LP_NUM_THREADS=2 "$ENV/venv/bin/python3" "$PEERS/gl_depth_bench.py" --platform egl --runs 11 \
    --dump "$out/llvmpipe-$name" "$mesh" |
    "$ENV/venv/bin/python3" -c 'import json, sys
d = json.load(sys.stdin)
for k, v in d.items():
    if isinstance(v, dict) and "median_ms" in v:
        print("  %s: median %s ms, min %s ms, samples passed %s" % (k, v["median_ms"], v["min_ms"], v["samples_passed"]))'
  echo "== $name: shadowlab, same views, f32 inputs (as GL buffers hold them)"
  ./target/release/shadowlab render-mesh "$mesh" --f32-inputs --npy --out "$out" | sed 's/^/  /'
  for pass in light eye; do
    echo -n "  $pass vs llvmpipe: "
    "$ENV/venv/bin/python3" benches/compare_depth.py "$out/$name-$pass.npy" "$out/llvmpipe-${name}_$pass.npy"
  done
done
echo "== shadowlab timings: cargo bench --bench raster"
# One line per benchmark: its name, then criterion's [low median high] time and throughput.
cargo bench --bench raster 2>&1 | awk '
  /^raster\// { name = $1 }
  /^ +time:/ && !/%/ { sub(/^ +time: +/, ""); time = $0 }
  /^ +thrpt:/ && !/%/ { sub(/^ +thrpt: +/, ""); print "  " name "  time " time "  thrpt " $0 }'
rm -rf "$out"
