#!/usr/bin/env bash
# Viewer benchmark (issue 23), run by hand (never from ctest): for Monaco and Kaiserslautern,
# stored and procedural, day and night, starts `render --serve` and drives it as the page does
# (viewer_bench.py): frames per second while the camera moves (a new camera every 30 ms), the
# median width of those frames, the median latency from a camera sent to the first frame showing
# it, and the seconds to 16 and 64 spp once it stops. RUNS rounds; the table gives medians.
#
#   tests/bench/viewer_bench.sh            (RUNS=3, SECONDS_MOVING=6, SIZE=960x540; RENDER=, OSMPARSE=)
set -euo pipefail
cd "$(dirname "$0")/../.."
runs=${RUNS:-3}
moving=${SECONDS_MOVING:-6}
size=${SIZE:-960x540}
osmparse=${OSMPARSE:-build/bin/osmparse}
render=${RENDER:-build/bin/render}
for tool in "$osmparse" "$render" python3; do
    command -v "$tool" > /dev/null || { echo "viewer_bench.sh: $tool not found (build first)" >&2; exit 1; }
done
work=$(mktemp -d)
server=
trap '[ -n "$server" ] && kill "$server" 2>/dev/null; rm -rf "$work"' EXIT

cities=(monaco:../shared/data/osm/monaco.osm.pbf kaiserslautern:../shared/data/osm/kaiserslautern.osm.gz)
for city in "${cities[@]}"; do
    "$osmparse" "${city#*:}" -q -o "$work/${city%%:*}.scene"
done

median() { sort -g | awk '{ a[NR] = $1 } END { print (NR % 2) ? a[(NR + 1) / 2] : (a[NR / 2] + a[NR / 2 + 1]) / 2 }'; }
field() { tr ' ' '\n' | sed -n "s/^$1=//p"; }

echo "viewer benchmark: ${size} window, ${moving} s moving per run, median of $runs runs, $(nproc) cores"
echo "render: $render"
echo
printf '%-15s %-10s %-6s %8s %8s %9s %9s %9s\n' city mode time fps width latency_ms 16spp_s 64spp_s
for city in "${cities[@]}"; do
    name=${city%%:*}
    for mode in stored procedural; do
        mode_args=""
        [ "$mode" = procedural ] && mode_args="--procedural"
        # shellcheck disable=SC2086
        "$render" "$work/$name.scene" --serve 0 --serve-out "$work" $mode_args -q > "$work/url" &
        server=$!
        for _ in $(seq 600); do grep -q "http://" "$work/url" 2>/dev/null && break; sleep 0.1; done
        port=$(grep -o 'http://[^/]*' "$work/url" | sed 's/.*://')
        for time in day night; do
            : > "$work/results"
            for run in $(seq "$runs"); do
                python3 tests/bench/viewer_bench.py --port "$port" --seconds "$moving" --width "${size%x*}" \
                    --height "${size#*x}" --extra="--time $time $mode_args" >> "$work/results"
            done
            row=()
            for key in moving_fps moving_width latency_ms still_16spp_s still_64spp_s; do
                row+=("$(field "$key" < "$work/results" | median)")
            done
            printf '%-15s %-10s %-6s %8s %8s %9s %9s %9s\n' "$name" "$mode" "$time" "${row[@]}"
        done
        kill "$server"; wait "$server" 2>/dev/null || true; server=
    done
done
