#!/usr/bin/env bash
# Scale benchmark (issue 25), run by hand (never from ctest): a real extract tiled N x N by
# make_metropolis (SIZES, default 1 2 4 8), parsed and rendered procedural by day and at night
# from the same view (the 1x1 city's automatic view: what the city shows, now with more city
# around it; the 1x1 city is the south-west tile), at WIDTHxHEIGHT and SPP. Prints, per size: buildings; the parse's wall and CPU
# seconds, peak memory and microseconds per building, and its slowest stages; each render's wall
# seconds (load, BVH build, exposure meter, tracing) and peak memory; at night the lamps, window strips and the
# lights' memory. One run per size (the 8x8 takes minutes); RUNS=3 for medians of the small ones.
#
#   tests/bench/scale_bench.sh [OSM]   (SIZES="1 2 4 8", WIDTH=1920, HEIGHT=1080, SPP=16; OSMPARSE=, RENDER=)
set -euo pipefail
args=()
for f in "$@"; do args+=("$(realpath "$f")"); done
cd "$(dirname "$0")/../.."
osm=${args[0]:-../shared/data/osm/kaiserslautern.osm.gz}
sizes=${SIZES:-1 2 4 8}
width=${WIDTH:-1920} height=${HEIGHT:-1080} spp=${SPP:-16} runs=${RUNS:-1}
osmparse=${OSMPARSE:-build/bin/osmparse}
render=${RENDER:-build/bin/render}
metropolis=${METROPOLIS:-build/bin/make_metropolis}
for tool in "$osmparse" "$render" "$metropolis" /usr/bin/time; do
    command -v "$tool" > /dev/null || { echo "scale_bench.sh: $tool not found (build first)" >&2; exit 1; }
done
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

median() { sort -g | awk '{ a[NR] = $1 } END { print (NR % 2) ? a[(NR + 1) / 2] : (a[NR / 2] + a[NR / 2 + 1]) / 2 }'; }
value() { sed -n "s/^$1: //p" "$2" | head -1; }   # a "key: value" line of --stats and friends

echo "scale benchmark: $(basename "$osm") tiled N x N, procedural render ${width}x${height} ${spp} spp, $(nproc) cores, $runs run(s)"
echo

view="" first_corner="" first_camera="" first_look=""
printf '%-4s %9s | %8s %8s %8s %7s | %-44s\n' N buildings parse_s cpu_s peak_MB us/bldg "slowest stages (s)"
rows=()
for n in $sizes; do
    "$metropolis" "$osm" "$n" "$work/metro.osm.pbf"
    : > "$work/parse_times"
    for run in $(seq "$runs"); do
        /usr/bin/time -f "%e %U %S %M" -o "$work/time" "$osmparse" "$work/metro.osm.pbf" -o "$work/metro.scene" \
            2> "$work/report"
        cat "$work/time" >> "$work/parse_times"
    done
    wall=$(awk '{print $1}' "$work/parse_times" | median)
    cpu=$(awk '{print $2 + $3}' "$work/parse_times" | median)
    peak=$(awk '{print $4 / 1024}' "$work/parse_times" | median)
    "$render" "$work/metro.scene" --print-scene-info > "$work/info"
    buildings=$(sed -n 's/^buildings: *\([0-9]*\).*/\1/p' "$work/info" | head -1)
    # The three slowest stages of the report's table ("stage seconds" ... "sum of stages").
    stages=$(awk '/^stage +seconds/ { on = 1; next } /^sum of stages/ { on = 0 }
                  on && NF >= 2 { v = $NF; $NF = ""; sub(/ +$/, ""); print v "\t" $0 }' "$work/report" |
             sort -gr | head -3 | awk -F'\t' '{ printf "%s%s %s", (NR > 1 ? ", " : ""), $2, $1 }')
    printf '%-4s %9s | %8.2f %8.2f %8.0f %7.1f | %-44s\n' "$n" "$buildings" "$wall" "$cpu" "$peak" \
        "$(awk -v t="$wall" -v b="$buildings" 'BEGIN { print 1e6 * t / b }')" "$stages"
    # The 1x1 city's automatic view, kept for every size. Each scene is centred on its own data,
    # and the 1x1 city is the south-west tile: the view moves with the bounds' south-west corner.
    corner=$(sed -n 's/^bounds: \[\([^,]*\), \([^]]*\)\].*/\1 \2/p' "$work/info")
    if [ -z "$view" ]; then
        "$render" "$work/metro.scene" --procedural --width 64 --height 36 --spp 1 -q --stats -o "$work/v.png" > "$work/v"
        first_corner=$corner
        first_camera=$(value camera "$work/v") first_look=$(value look_at "$work/v")
    fi
    moved() { echo "$1" | awk -F, -v c="$corner" -v f="$first_corner" \
        'BEGIN { split(c, n, " "); split(f, o, " ") } { printf "%.3f,%.3f,%s", $1 - o[1] + n[1], $2 - o[2] + n[2], $3 }'; }
    view="--camera=$(moved "$first_camera") --look-at=$(moved "$first_look")"
    for time in day night; do
        # shellcheck disable=SC2086  # $view is two whole words
        /usr/bin/time -f "%e %M" -o "$work/rtime" "$render" "$work/metro.scene" --procedural --time "$time" \
            --width "$width" --height "$height" --spp "$spp" $view -q --stats --print-memory-info \
            --print-scene-geometry-info -o "$work/$time-$n.png" > "$work/stats"
        rows+=("$(printf '%-4s %-6s %8.1f %7.1f %7.1f %7.1f %8.1f %8.0f %8s %9s %8.1f' "$n" "$time" \
            "$(awk '{print $1}' "$work/rtime")" "$(value load_seconds "$work/stats")" \
            "$(value build_seconds "$work/stats")" "$(value exposure_seconds "$work/stats")" \
            "$(value render_seconds "$work/stats")" \
            "$(awk '{print $2 / 1024}' "$work/rtime")" "$(value light_lamps "$work/stats")" \
            "$(value light_window_strips "$work/stats")" \
            "$(awk -v b="$(value light_bytes "$work/stats")" 'BEGIN { print b / 1e6 }')")")
        [ -n "${KEEP_IMAGES:-}" ] && cp "$work/$time-$n.png" "$KEEP_IMAGES/"
    done
done
echo
printf '%-4s %-6s %8s %7s %7s %7s %8s %8s %8s %9s %8s\n' N time wall_s load_s bvh_s meter_s trace_s peak_MB lamps strips light_MB
printf '%s\n' "${rows[@]}"
