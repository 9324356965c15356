#!/usr/bin/env bash
# The tiled parse end to end on a single-node Slurm started here (scripts/farm/local_slurm.sh): a
# 3x3 metropolis of the bundled example (tests/bench/make_metropolis.cpp) cut into 2x2 tiles by
# scripts/farm/parse_farm.sh: the cuts cross in the middle copy, the north-south one along the
# west edge of its town (the tiles west of it parse 431 of its buildings, then leave them). A
# view across the tile edges, rendered from the 4 tile scenes and from one parse of the whole (same --origin),
# must show the same object in at least 99.9% of its pixels (id AOVs, compared by OSM identity:
# build/bin/compare_id_aovs), forests included: a crown's leaves follow where its tree stands, not
# its index in the scene, which differs between a tile and the whole (99.57% when it did); the
# tiles' region statistics (two passes before the parse) are those of the whole region. An
# island cut by both cuts: its sea matches too (at least 99.9%; 84% when a tile made its sea
# within its extract and kept it by the centroid, as other land cover). Then
# with terrain (--dem, a made-up SRTM tile:
# build/bin/write_srtm_tile), the tiles' fields joined by render: at least 99.85%. Each tile's
# field is warped from its own extract, so the fields differ by millimetres where tiles overlap,
# and which of two surfaces that close wins a pixel depends on the CPU's float paths: 99.913% on
# the machine of stop 34, 99.892% on an AMD EPYC with that build and the next alike. Every
# daemon started is stopped by PID at the end. Exit 77 (ctest: skipped) only when Slurm cannot run on this machine.
#   tests/farm/parse_farm_test.sh BUILD_BIN_DIR
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
bin=$(cd "${1:-$root/build/bin}" && pwd)
work=$(mktemp -d /tmp/citygen-parse-farm-XXXXXX)
cleanup() {
  "$root/scripts/farm/local_slurm.sh" stop "$work/slurm" || true
  rm -rf "$work"
}
trap cleanup EXIT
fail() { echo "parse_farm_test: FAIL: $*" >&2; exit 1; }
now() { date +%s.%N; }
since() { awk -v a="$1" -v b="$(now)" 'BEGIN { printf "%.1f", b - a }'; }
command -v osmium > /dev/null || { echo "parse_farm_test: SKIPPED (no osmium-tool)"; exit 77; }

# Dense ids (osmium renumber): the copies' fresh ids reach 1e11, where osmium extract's id sets
# take a minute to clear.
"$bin/make_metropolis" "$root/examples/neukolln.osm.bz2" 3 "$work/metro.osm.pbf" > /dev/null
osmium renumber --no-progress "$work/metro.osm.pbf" -o "$work/region.osm.pbf"

start=$(now)
set +e
env_line=$("$root/scripts/farm/local_slurm.sh" start "$work/slurm")
status=$?
set -e
if [ $status -eq 77 ]; then echo "parse_farm_test: SKIPPED (Slurm cannot run here, see above)"; exit 77; fi
[ $status -eq 0 ] || { tail -n 20 "$work"/slurm/*.log "$work"/slurm/*.out >&2 || true; fail "local Slurm did not start"; }
eval "$env_line"
echo "slurm started in $(since "$start") s"

view=(--width 320 --height 180 --camera -400,-500,350 --look-at 0,0,0 -q --spp 1 --aovs id)
region=$work/region.osm.pbf overlap=300
# Parses $region on the farm into $work/$1 and as one scene, renders both from $view, compares the ids.
farm_and_compare() {
  local name=$1
  shift
  start=$(now)
  "$root/scripts/farm/parse_farm.sh" "$region" "$work/$name" --tiles 2x2 --overlap "$overlap" \
    --osmparse "$bin/osmparse" --wait -- "$@" > "$work/$name.log" || { cat "$work/$name.log" >&2; fail "parse_farm $name"; }
  echo "farm parse ($name: extract + 4 tasks) took $(since "$start") s"
  origin=$(sed -n 's/^parse_farm: origin \([-0-9.]*,[-0-9.]*\),.*/\1/p' "$work/$name.log")
  [ -n "$origin" ] || fail "parse_farm printed no origin"
  mapfile -t tiles < "$work/$name/tiles.txt"
  [ ${#tiles[@]} -eq 4 ] || fail "$name: ${#tiles[@]} tile scenes, not 4"
  "$bin/osmparse" "$region" -q --origin "$origin" "$@" -o "$work/$name-one.scene"
  "$bin/render" "$work/$name-one.scene" "${view[@]}" -o "$work/$name-one.exr"
  "$bin/render" "${tiles[@]}" "${view[@]}" -o "$work/$name-tiles.exr"
  "$bin/compare_id_aovs" "$work/$name-one.exr" "$work/$name-one.scene" -- "$work/$name-tiles.exr" "${tiles[@]}" \
    > "$work/$name-ids.txt"
  percent=$(sed -n 's/^ids_equal_percent: //p' "$work/$name-ids.txt")
  echo "$name: ids equal in $percent% of the view's pixels"
}

farm_and_compare default
awk -v p="$percent" 'BEGIN { exit !(p >= 99.9) }' || fail "ids equal in only $percent% of the pixels (at least 99.9)"
# The region's statistics the tiles read are the region's: the records of the tiles' last pass,
# concatenated, are those of one gathering over the whole (roof counts summed per group).
"$bin/osmparse" "$region" -q --origin "$origin" --write-region-statistics "$work/whole.stats"
records() {
  awk '$1 == "roofs" { t[$2] += $3; p[$2] += $4; next }
       $1 != "end" && $1 != "citygen-region-statistics" { print }
       END { for (g in t) print "roofs", g, t[g], p[g] }' "$@" | sort
}
[ "$(grep -c '^tagged ' "$work/whole.stats")" -gt 100 ] || fail "the region has under 100 tagged heights"
[ "$(records "$work"/default/farm/statistics/tile_*_2.stats)" = "$(records "$work/whole.stats")" ] ||
  fail "the tiles' region statistics are not the whole region's"
# The sea: an island cut by both cuts, the tiles' extracts (50 m overlap) each a quarter of the
# region and a little more, each tile's sea made within its core (tile_sea_box).
region=$root/tests/data/map_island.osm overlap=50
view=(--width 160 --height 90 --camera -150,-250,300 --look-at 0,0,0 -q --spp 1 --aovs id)
farm_and_compare sea
awk -v p="$percent" 'BEGIN { exit !(p >= 99.9) }' || fail "with the sea: ids equal in only $percent% of the pixels (at least 99.9)"
region=$work/region.osm.pbf overlap=300
view=(--width 320 --height 180 --camera -400,-500,350 --look-at 0,0,0 -q --spp 1 --aovs id)
# With terrain: every tile's field over its own extract, joined by render (merge_scenes.h).
"$bin/write_srtm_tile" "$work/N52E013.hgt"
farm_and_compare terrain --trees mapped --dem "$work/N52E013.hgt" --dem-resolution 30
awk -v p="$percent" 'BEGIN { exit !(p >= 99.85) }' || { cat "$work/terrain-ids.txt" >&2; fail "with --dem: ids equal in only $percent% of the pixels (at least 99.85)"; }

# Scenes of another frame are refused with one line.
"$bin/osmparse" "$root/examples/neukolln.osm.bz2" -q -o "$work/other.scene"
set +e
"$bin/render" "${tiles[@]}" "$work/other.scene" -q -o "$work/refused.png" 2> "$work/refused.txt"
status=$?
set -e
[ $status -ne 0 ] || fail "render merged scenes of two origins"
[ "$(wc -l < "$work/refused.txt")" -eq 1 ] && grep -q "parse the tiles with one --origin" "$work/refused.txt" ||
  fail "the refusal is not one clear line: $(cat "$work/refused.txt")"
[ -f "$work/refused.png" ] && fail "a refused render wrote its image"

pids=$(cat "$work"/slurm/*.started.pid)
"$root/scripts/farm/local_slurm.sh" stop "$work/slurm"
for pid in $pids; do
  if kill -0 "$pid" 2> /dev/null && ! grep -q '^State:[[:space:]]*Z' "/proc/$pid/status" 2> /dev/null; then
    fail "daemon $pid still runs after stop"
  fi
done
echo "parse_farm_test: 4 tiles parsed on the farm; a view across their edges shows the same objects in $(sed -n 's/^ids_equal_percent: //p' "$work/default-ids.txt")% of its pixels; daemons stopped"
