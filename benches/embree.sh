#!/usr/bin/env bash
# The ray-casting comparison with Intel Embree 4.4 (issue 15, "Ray casting"), in one run: the same
# meshes and the same rays (f32, written once by shadowlab's side), the same thread counts, closest
# and any hit, shadowlab's exact f64 BVH (examples/ray_bench.rs) and Embree's f32 single rays and
# 16-wide packets (benches/embree_bench.cpp), run interleaved (shadowlab, Embree, shadowlab, ...);
# then a table of medians and ratios and the per-ray agreement of their answers. The grid set's
# closest hits are also timed through `Bvh::closest_hits_grid` (row `grid·rows`), the entry point the
# logarithmic shadow map casts through: swept triangle by triangle on a mesh with at least 64 rays
# per triangle (data/meshes/bunny-small.obj's 3 674 triangles; not the bunny's nor the dragon's).
#
# Usage: bash benches/embree.sh [MESH.obj ...]
#   (default: data/meshes/bunny.obj, and data/meshes/dragon.obj if fetched: fetch-dragon.sh there)
# Environment:
#   REPEATS=5        interleaved repeats (each: one shadowlab process, then one Embree process)
#   RUNS=3 WARMUP=1  timed and untimed runs of each measurement inside a process
#   THREADS=1,2      thread counts (rayon pool sizes; Embree's "threads=N" and N casting threads)
#   IDLE_GATE=1      before each timed process wait until the CPUs are >= 95 % idle over 2 s
#                    (/proc/stat), for at most IDLE_TIMEOUT=1800 s; IDLE_GATE=0 runs ungated, and
#                    what it prints is then a smoke run, not a measurement
#   EMBREE_ENV=/tmp/shadowlab-embree   scratch folder for the venv, the headers and the C++ bench
#   EMBREE_INCLUDE=DIR                 Embree 4.4 headers (DIR/embree4/rtcore.h) to use instead of
#                                      Debian's
#   OUT=DIR          where inputs, answers and JSON results go (default: a new folder under /tmp)
#
# Set-up on first use (needs PyPI and Debian's package archive, python3 with venv, g++, apt-get,
# dpkg-deb): a venv with the `embreex` wheel, which carries Embree's official 4.4.0 build as
# libembree4.so (the version the library reports is printed and checked), and Embree's public headers
# from Debian's `libembree-dev` 4.4.x. The wheel has no headers and Debian has no 4.4.0: its 4.4.1
# headers are Embree 4.4.0's byte for byte (compared with Embree's v4.4.0 and v4.4.1 tags), except
# the version macros of rtcore_config.h, and that file's layout options (instance levels, instance
# arrays, no API namespace) are Embree's defaults, which its release builds use. Nothing of Embree is
# kept in this repository.
set -euo pipefail

fail() {
  echo "embree.sh: $*" >&2
  exit 1
}

# Mesh paths and OUT are taken relative to where the script is called from; it runs from the root.
meshes=()
for mesh in "$@"; do
  [ -f "$mesh" ] || fail "$mesh does not exist"
  meshes+=("$(realpath "$mesh")")
done
[ -n "${OUT:-}" ] && OUT=$(realpath -m "$OUT")
cd "$(dirname "$0")/.."

EMBREEX_VERSION=4.4.0.post1
REPEATS=${REPEATS:-5}
RUNS=${RUNS:-3}
WARMUP=${WARMUP:-1}
THREADS=${THREADS:-1,2}
IDLE_GATE=${IDLE_GATE:-1}
IDLE_TIMEOUT=${IDLE_TIMEOUT:-1800}
ENV_DIR=${EMBREE_ENV:-/tmp/shadowlab-embree}

need() {
  command -v "$1" >/dev/null || fail "$1 is missing: $2"
}

need python3 "it makes the venv for the embreex wheel"
need g++ "it builds benches/embree_bench.cpp"
need cargo "it builds shadowlab's side"

# The embreex wheel's libembree4 (in a venv, set up if missing); prints its path.
embree_library() {
  local lib
  find_library() {
    find "$ENV_DIR/venv" -path '*/embreex.libs/libembree4*.so*' -print -quit 2>/dev/null || true
  }
  lib=$(find_library)
  if [ -z "$lib" ]; then
    echo "setting up $ENV_DIR/venv with embreex $EMBREEX_VERSION" >&2
    [ -x "$ENV_DIR/venv/bin/python3" ] || python3 -m venv "$ENV_DIR/venv" ||
      fail "python3 -m venv failed (on Debian: apt-get install python3-venv)"
    "$ENV_DIR/venv/bin/pip" install -q "embreex==$EMBREEX_VERSION" ||
      fail "pip could not install embreex==$EMBREEX_VERSION"
    lib=$(find_library)
    [ -n "$lib" ] || fail "the embreex wheel in $ENV_DIR/venv carries no libembree4 library"
  fi
  echo "$lib"
}

# The first Debian package source of this machine's own apt configuration: its archive's URI.
debian_archive() {
  local uri
  uri=$(grep -hE '^URIs:' /etc/apt/sources.list.d/*.sources 2>/dev/null | awk '{print $2; exit}')
  [ -n "$uri" ] || uri=$(grep -hsE '^deb ' /etc/apt/sources.list | awk '{print $2; exit}')
  [ -n "$uri" ] || fail "no Debian package source in /etc/apt: set EMBREE_INCLUDE to Embree 4.4's headers"
  echo "$uri"
}

# Embree 4.4's headers from Debian's libembree-dev (unstable or testing), fetched with a private apt
# state in the scratch folder (the system's sources and lists are not touched); prints the folder
# that holds embree4/.
embree_headers() {
  if [ -n "${EMBREE_INCLUDE:-}" ]; then
    [ -f "$EMBREE_INCLUDE/embree4/rtcore.h" ] || fail "EMBREE_INCLUDE=$EMBREE_INCLUDE has no embree4/rtcore.h"
    echo "$EMBREE_INCLUDE"
    return
  fi
  local include="$ENV_DIR/include"
  if [ ! -f "$include/embree4/rtcore.h" ]; then
    need apt-get "it fetches Debian's libembree-dev for Embree's headers (or set EMBREE_INCLUDE)"
    need dpkg-deb "it unpacks Debian's libembree-dev (or set EMBREE_INCLUDE)"
    local apt="$ENV_DIR/apt" archive version
    archive=$(debian_archive)
    rm -rf "$apt"
    mkdir -p "$apt/lists/partial" "$apt/cache/archives/partial" "$apt/deb"
    printf 'deb %s %s main\n' "$archive" unstable "$archive" testing >"$apt/sources.list"
    local opts=(-o "Dir::Etc::SourceList=$apt/sources.list" -o Dir::Etc::SourceParts=/dev/null
      -o "Dir::State::Lists=$apt/lists" -o "Dir::Cache=$apt/cache" -o APT::Sandbox::User=root)
    echo "fetching Debian's package lists (unstable, testing) for libembree-dev" >&2
    apt-get "${opts[@]}" -qq update >&2 || fail "apt-get update of Debian unstable/testing failed"
    version=$(apt-cache "${opts[@]}" madison libembree-dev | awk -F'|' '{gsub(/ /, "", $2); print $2}' |
      grep -m1 '^4\.4\.' || true)
    [ -n "$version" ] ||
      fail "Debian has no libembree-dev 4.4.x any more: set EMBREE_INCLUDE to Embree 4.4's headers"
    (cd "$apt/deb" && apt-get "${opts[@]}" -qq download "libembree-dev=$version") ||
      fail "apt-get download libembree-dev=$version failed"
    dpkg-deb -x "$apt"/deb/libembree-dev_*.deb "$apt/root"
    mkdir -p "$include"
    cp -r "$apt/root/usr/include/embree4" "$include/"
    echo "Debian libembree-dev $version" >"$include/SOURCE"
  fi
  echo "$include"
}

lib=$(embree_library)
include=$(embree_headers)
bench="$ENV_DIR/embree_bench"
# Built every time (a few seconds), so that it always matches the source, headers and library.
g++ -std=c++17 -O3 -march=x86-64-v3 -DNDEBUG -pthread -I"$include" benches/embree_bench.cpp \
  "$lib" -Wl,-rpath,"$(dirname "$lib")" -o "$bench"
versions=$("$bench" --version)
headers=$include
[ -f "$include/SOURCE" ] && headers="$include, from $(cat "$include/SOURCE")"
echo "$versions; headers in $headers"
[[ $versions =~ ^Embree\ library\ 4\.4\.[0-9]+\ .*headers\ 4\.4\.[0-9]+$ ]] ||
  fail "this is not Embree 4.4 (library and headers): $versions"

cargo build --release --quiet --example ray_bench
shadowlab=target/release/examples/ray_bench

# The share of idle CPU time (idle + iowait, all CPUs) over the next 2 s, in per cent.
idle_percent() {
  local a b i total=0
  read -ra a </proc/stat
  sleep 2
  read -ra b </proc/stat
  for i in 1 2 3 4 5 6 7 8; do total=$((total + b[i] - a[i])); done
  echo $((100 * (b[4] - a[4] + b[5] - a[5]) / (total > 0 ? total : 1)))
}

wait_idle() {
  [ "$IDLE_GATE" = 0 ] && return
  local start=$SECONDS idle
  while idle=$(idle_percent) && [ "$idle" -lt 95 ]; do
    ((SECONDS - start < IDLE_TIMEOUT)) ||
      fail "the machine was not idle within ${IDLE_TIMEOUT} s (last: $idle % idle over 2 s); IDLE_GATE=0 runs anyway, as a smoke run that measures nothing"
    echo "  waiting for an idle machine ($idle % idle over 2 s)" >&2
    sleep 5
  done
}

if [ ${#meshes[@]} -eq 0 ]; then
  meshes=(data/meshes/bunny.obj)
  [ -f data/meshes/dragon.obj ] && meshes+=(data/meshes/dragon.obj)
fi
out=${OUT:-$(mktemp -d /tmp/shadowlab-embree-run.XXXXXX)}
mkdir -p "$out"
[ "$IDLE_GATE" = 0 ] &&
  echo "IDLE_GATE=0: not gated on an idle machine; these figures are a smoke run, not a measurement"
for mesh in "${meshes[@]}"; do
  name=$(basename "$mesh" .obj)
  dir="$out/$name"
  "$shadowlab" write "$mesh" "$dir"
  rm -f "$dir"/shadowlab-*.json "$dir"/embree-*.json   # the report reads every repeat in $dir
  for ((repeat = 1; repeat <= REPEATS; repeat++)); do
    hits=()
    [ "$repeat" = 1 ] && hits=(--hits)
    echo "== $name: repeat $repeat of $REPEATS: shadowlab, then Embree" >&2
    wait_idle
    "$shadowlab" time "$dir" --threads "$THREADS" --runs "$RUNS" --warmup "$WARMUP" "${hits[@]}" \
      >"$dir/shadowlab-$repeat.json"
    wait_idle
    "$bench" "$dir" --threads "$THREADS" --runs "$RUNS" --warmup "$WARMUP" "${hits[@]}" \
      >"$dir/embree-$repeat.json"
  done
done
names=()
for mesh in "${meshes[@]}"; do names+=("$(basename "$mesh" .obj)"); done
smoke=()
[ "$IDLE_GATE" = 0 ] && smoke=(--ungated)
python3 benches/embree_report.py "${smoke[@]}" "$out" "${names[@]}"
echo "inputs, answers and JSON results: $out"
