#!/usr/bin/env bash
# Map-content benchmark, run by hand (never from ctest): what land cover, the sea, paths,
# trees, lanes and crossings cost. Prints tables of
#   1. parse: median wall seconds of RUNS runs (after a warm-up) and scene bytes, for an
#      osmparse without the map content (BEFORE, e.g. a build of the commit before it) and
#      this one, on Monaco and Kaiserslautern;
#   2. render: seconds and geometry memory (Embree + our buffers) for stored and procedural
#      geometry, with --trees all and --trees none, on Monaco at 320x180, 4 spp.
#
#   BEFORE=/path/to/old/osmparse tests/bench/map_content_bench.sh   (RUNS=5 by default)
set -euo pipefail
cd "$(dirname "$0")/../.."
runs=${RUNS:-5}
after=build/bin/osmparse
render=build/bin/render
before=${BEFORE:-}
data=../shared/data/osm
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

median_seconds() {  # command...
    "$@" > /dev/null 2>&1
    local times=()
    for _ in $(seq "$runs"); do
        local start end
        start=$(date +%s.%N)
        "$@" > /dev/null 2>&1
        end=$(date +%s.%N)
        times+=("$(awk -v a="$start" -v b="$end" 'BEGIN { print b - a }')")
    done
    printf '%s\n' "${times[@]}" | sort -g | awk '{ a[NR] = $1 } END { print (NR % 2) ? a[(NR + 1) / 2] : (a[NR / 2] + a[NR / 2 + 1]) / 2 }'
}

printf '%-22s %-8s %10s %12s\n' input osmparse seconds scene_bytes
for input in monaco.osm.pbf monaco.osm.bz2 kaiserslautern.osm.gz; do
    for which in before after; do
        bin=$after
        [ "$which" = before ] && bin=$before
        [ -n "$bin" ] || continue
        t=$(median_seconds "$bin" -q "$data/$input" -o "$work/$which.scene")
        printf '%-22s %-8s %10.3f %12d\n' "$input" "$which" "$t" "$(stat -c %s "$work/$which.scene")"
    done
done

echo
printf '%-10s %-12s %10s %14s %10s\n' trees geometry seconds geometry_MB triangles
for trees in all none; do
    "$after" -q "$data/monaco.osm.pbf" --trees "$trees" -o "$work/m-$trees.scene"
    for mode in stored procedural; do
        flag=""
        [ "$mode" = procedural ] && flag=--procedural
        out=$("$render" "$work/m-$trees.scene" -o "$work/m.png" --width 320 --height 180 --spp 4 -q --stats \
              --print-memory-info --print-scene-geometry-info $flag)
        secs=$(echo "$out" | awk '/^render_seconds:/ { r = $2 } /^build_seconds:/ { b = $2 } END { print r + b }')
        mb=$(echo "$out" | awk '/^geometry_bytes:/ { print $2 / 1e6 }')
        tris=$(echo "$out" | awk '/^triangles:/ { print $2 }')
        printf '%-10s %-12s %10.2f %14.1f %10s\n' "$trees" "$mode" "$secs" "$mb" "$tris"
    done
done
