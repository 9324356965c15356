#!/usr/bin/env bash
# Blender (headless) imports render's --export-gltf of the tiny fixture and finds what the file
# holds: an object per node, a building object per building with its OSM id as a custom
# property, the materials, every triangle, z-up again. Exit 77 (ctest: skipped) when Blender or
# its numpy is not installed (scripts/install-deps.sh installs both).
#   tests/blender/blender_gltf_test.sh BUILD_BIN_DIR
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
bin=$(cd "${1:-$root/build/bin}" && pwd)
if ! command -v blender > /dev/null; then
  echo "blender_gltf_test: SKIPPED: blender is not installed (apt-get install blender python3-numpy)"
  exit 77
fi
if ! blender --background --factory-startup --python-exit-code 1 --python-expr 'import numpy' > /dev/null 2>&1; then
  echo "blender_gltf_test: SKIPPED: Blender's glTF importer needs python3-numpy"
  exit 77
fi
work=$(mktemp -d /tmp/citygen-blender-XXXXXX)
trap 'rm -rf "$work"' EXIT
fail() { echo "blender_gltf_test: FAIL: $*" >&2; exit 1; }

"$bin/osmparse" "$root/tests/data/tiny_roundabout.osm" -q -o "$work/tiny.scene"
"$bin/render" "$work/tiny.scene" --export-gltf "$work/tiny.glb" --print-scene-geometry-info --print-scene-info -q \
  > "$work/info.txt"
blender --background --factory-startup --python-exit-code 1 --python "$root/tests/blender/import_gltf.py" \
  -- "$work/tiny.glb" > "$work/blender.txt" 2>&1 || { cat "$work/blender.txt" >&2; fail "Blender could not import"; }

value() { awk -v key="$1:" '$1 == key { print $2 }' "$2"; }
buildings=$(value buildings "$work/info.txt")
triangles=$(value triangles "$work/info.txt")
# Classes with triangles besides buildings: one object each.
classes=$(awk -F'[_:]' '/^triangles_[a-z]+: / && $2 != "building" { n++ } END { print n + 0 }' "$work/info.txt")
materials=$(awk -F'[_:]' '/^triangles_[a-z]+_[a-z_]+: / { sub(/^triangles_[a-z]+_/, "", $0); sub(/:.*/, "", $0); seen[$0] = 1 }
  END { n = 0; for (m in seen) n++; print n }' "$work/info.txt")
echo "expected: $buildings buildings, $classes other classes, $materials materials, $triangles triangles"
grep -E '^(objects|buildings_with_osm_id|materials|triangles|polygons_not_triangles|z_range|first_osm_ids):' "$work/blender.txt"
[ "$(value objects "$work/blender.txt")" = $((buildings + classes)) ] || fail "object count"
[ "$(value buildings_with_osm_id "$work/blender.txt")" = "$buildings" ] || fail "buildings with an OSM id"
[ "$(value materials "$work/blender.txt")" = "$materials" ] || fail "material count"
[ "$(value triangles "$work/blender.txt")" = "$triangles" ] || fail "triangle count"
[ "$(value polygons_not_triangles "$work/blender.txt")" = 0 ] || fail "polygons that are not triangles"
# Blender turned glTF's y-up back into z-up: ground at 0, buildings above it.
awk '$1 == "z_range:" { exit !($2 > -1 && $3 > 5) }' "$work/blender.txt" || fail "the town is not upright in Blender"
echo "blender_gltf_test: Blender imported the export as expected"
