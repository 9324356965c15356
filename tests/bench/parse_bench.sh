#!/usr/bin/env bash
# Parse benchmark, run by hand (never from ctest): osmparse beside `osmium fileinfo -e`
# (a full read of the same file by libosmium's own tool) on Monaco, unpacked to XML.
# Prints a table: median wall time of RUNS runs each (after one warm-up run), the
# ratio, and peak resident memory (GNU time). Target once roads are in: ratio <= 2.
#
#   tests/bench/parse_bench.sh [FILE.osm|FILE.osm.bz2|FILE.osm.pbf]   (RUNS=5 by default)
set -euo pipefail
cd "$(dirname "$0")/../.."
runs=${RUNS:-5}
source_file=${1:-../shared/data/osm/monaco.osm.bz2}
osmparse=build/bin/osmparse
for tool in "$osmparse" osmium /usr/bin/time; do
    command -v "$tool" > /dev/null || { echo "parse_bench.sh: $tool not found (build, or scripts/install-deps.sh)" >&2; exit 1; }
done
[ -f "$source_file" ] || { echo "parse_bench.sh: $source_file not found" >&2; exit 1; }

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
input=$work/$(basename "${source_file%.bz2}")
if [[ $source_file == *.bz2 ]]; then bunzip2 -c "$source_file" > "$input"; else cp "$source_file" "$input"; fi

# Runs a command `runs` times; prints "median_seconds max_peak_rss_kb".
measure() {
    "$@" > /dev/null 2>&1  # warm-up: file in page cache
    local times=() rss=0
    for _ in $(seq "$runs"); do
        local start end
        start=$(date +%s.%N)
        /usr/bin/time -f %M -o "$work/rss" "$@" > /dev/null 2>&1
        end=$(date +%s.%N)
        times+=("$(awk -v a="$start" -v b="$end" 'BEGIN { print b - a }')")
        local r
        r=$(tail -1 "$work/rss")
        (( r > rss )) && rss=$r
    done
    local median
    median=$(printf '%s\n' "${times[@]}" | sort -g | awk '{ a[NR] = $1 } END { print (NR % 2) ? a[(NR + 1) / 2] : (a[NR / 2] + a[NR / 2 + 1]) / 2 }')
    echo "$median $rss"
}

read -r osmium_s osmium_kb < <(measure osmium fileinfo -e "$input")
read -r parse_s parse_kb < <(measure "$osmparse" --quiet "$input" -o "$work/out.scene")
size_mb=$(awk -v n="$(stat -c %s "$input")" 'BEGIN { printf "%.1f", n / 1048576 }')

echo "input: $(basename "$input") (${size_mb} MB), $runs runs each, median wall time"
printf '| %-28s | %10s | %12s |\n' "command" "median s" "peak RSS MB"
printf '|%s|%s|%s|\n' "------------------------------" "------------" "--------------"
printf '| %-28s | %10.3f | %12.1f |\n' "osmium fileinfo -e" "$osmium_s" "$(awk -v k="$osmium_kb" 'BEGIN { print k / 1024 }')"
printf '| %-28s | %10.3f | %12.1f |\n' "osmparse (whole pipeline)" "$parse_s" "$(awk -v k="$parse_kb" 'BEGIN { print k / 1024 }')"
printf '| %-28s | %10.2f | %12s |\n' "ratio osmparse / osmium" "$(awk -v a="$parse_s" -v b="$osmium_s" 'BEGIN { print a / b }')" ""
