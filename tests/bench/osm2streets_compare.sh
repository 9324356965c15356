#!/usr/bin/env bash
# Road surface vs osm2streets on its test cases (area and intersection over union).
# Bench-only dependency: Debian's python3-shapely, installed here when missing.
set -euo pipefail
cd "$(dirname "$0")/../.."
shared=${1:-../shared/data/osm}
[ -x build/bin/osmparse ] || { echo "build first (build/bin/osmparse missing)" >&2; exit 1; }
/usr/bin/python3 -c "import shapely" 2>/dev/null || apt-get install -y -q python3-shapely >/dev/null
/usr/bin/python3 tests/bench/osm2streets_compare.py build/bin/osmparse "$shared"
