#!/usr/bin/env bash
# Render benchmark (run by hand): citygen render on the parsed Monaco scene at 640x360, 16 spp,
# then the same triangles (--export-ply) with the same camera, resolution, samples and sun in
# Blender Cycles (CPU, max bounces 8, no denoising, no adaptive sampling). Prints a table of
# medians over RUNS runs (default 3).
#   tests/bench/render_bench.sh            # uses /tmp/monaco.osm (unpacked if missing)
#   RUNS=5 OSM=other.osm tests/bench/render_bench.sh
set -euo pipefail
cd "$(dirname "$0")/../.."
ROOT=$(pwd)
RUNS=${RUNS:-3}
OSM=${OSM:-/tmp/monaco.osm}
WIDTH=640 HEIGHT=360 SPP=16
THREADS=${THREADS:-$(nproc)}

if [ ! -f "$OSM" ]; then
  bunzip2 -kc "$ROOT/../shared/data/osm/monaco.osm.bz2" > "$OSM"
fi
if ! command -v blender > /dev/null; then
  echo "installing blender (Debian package) for the Cycles comparison" >&2
  apt-get install -y blender > /dev/null
fi
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release > /dev/null
cmake --build build -j2 --target osmparse render > /dev/null

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
build/bin/osmparse "$OSM" -o "$work/city.scene" -q

median() { sort -g | awk '{ v[NR] = $1 } END { print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2 }'; }
value() { grep "^$1:" "$2" | head -1 | cut -d' ' -f2; }

for i in $(seq "$RUNS"); do
  /usr/bin/time -f "%e" -o "$work/wall$i" build/bin/render "$work/city.scene" -o "$work/citygen.png" \
    --width $WIDTH --height $HEIGHT --spp $SPP --threads "$THREADS" -q \
    --stats --print-memory-info --print-scene-geometry-info > "$work/run$i.txt"
done
build/bin/render "$work/city.scene" --export-ply "$work/city.ply"

run1="$work/run1.txt"
for i in $(seq "$RUNS"); do
  blender -b --factory-startup -P tests/bench/cycles_render.py -- "$work/city.ply" "$work/cycles.png" \
    $WIDTH $HEIGHT $SPP "$(value camera "$run1")" "$(value look_at "$run1")" "$(value fov "$run1")" \
    "$(value sun_direction "$run1")" "$(value sun_irradiance "$run1")" "$THREADS" > "$work/cycles$i.txt" 2>&1
done

ours_render=$(for i in $(seq "$RUNS"); do value render_seconds "$work/run$i.txt"; done | median)
ours_build=$(for i in $(seq "$RUNS"); do value build_seconds "$work/run$i.txt"; done | median)
ours_wall=$(for i in $(seq "$RUNS"); do cat "$work/wall$i"; done | median)
ours_rps=$(for i in $(seq "$RUNS"); do value rays_per_second "$work/run$i.txt"; done | median)
ours_rss=$(for i in $(seq "$RUNS"); do value peak_rss_bytes "$work/run$i.txt"; done | median)
ours_geometry=$(value geometry_bytes "$run1")
triangles=$(value triangles "$run1")
cycles=$(for i in $(seq "$RUNS"); do value cycles_render_seconds "$work/cycles$i.txt"; done | median)
if [ -z "$cycles" ]; then
  echo "Cycles run failed:" >&2
  tail -20 "$work/cycles1.txt" >&2
  exit 1
fi

echo "render benchmark: $(basename "$OSM"), ${WIDTH}x${HEIGHT}, $SPP spp, $THREADS threads, median of $RUNS runs"
row() { awk -v label="$1" -v value="$2" -v format="$3" 'BEGIN { printf "| %-40s | %12" format " |\n", label, value }'; }
row "measure" "value" "s"
echo "|------------------------------------------|--------------|"
row "triangles" "$triangles" "s"
row "citygen render seconds (tracing only)" "$ours_render" ".3f"
row "citygen build seconds (geometry + BVH)" "$ours_build" ".3f"
row "citygen wall seconds (process, all)" "$ours_wall" ".3f"
row "citygen Mrays/s" "$(awk -v r="$ours_rps" 'BEGIN { print r / 1e6 }')" ".2f"
row "citygen geometry MB (Embree + buffers)" "$(awk -v b="$ours_geometry" 'BEGIN { print b / 1e6 }')" ".1f"
row "citygen peak RSS MB" "$(awk -v b="$ours_rss" 'BEGIN { print b / 1e6 }')" ".1f"
row "Cycles render seconds (sync+BVH+trace)" "$cycles" ".3f"
row "ratio Cycles / citygen wall" "$(awk -v a="$cycles" -v b="$ours_wall" 'BEGIN { print a / b }')" ".2f"
row "ratio Cycles / citygen tracing" "$(awk -v a="$cycles" -v b="$ours_render" 'BEGIN { print a / b }')" ".2f"
