#!/usr/bin/env bash
# Parse benchmark, run by hand (never from ctest): osmparse beside `osmium export -f geojsonseq`
# (libosmium's own tool doing the same reading: node locations, multipolygon assembly, every
# object written out) on Monaco and Kaiserslautern, each as XML and as PBF (Kaiserslautern's PBF
# is made with `osmium cat` in a temporary directory), and Malta as PBF and as XML (made the same
# way: the issue's targets name both formats for Kaiserslautern and Malta). Every run of
# a round does osmium, osmparse and (optionally) an older osmparse one after the other, so a
# shared machine slows them alike. Prints median wall time of RUNS runs (after one warm-up
# run), the ratio to osmium, peak resident memory (GNU time) and its ratio, then the median
# time of each stage from osmparse's report, and how the cost grows from Monaco to Kaiserslautern.
#
#   tests/bench/parse_bench.sh [OLD_OSMPARSE]      (RUNS=5, THREADS=0 by default)
#
# Targets (issue 25): time <= 2x osmium export on XML and <= 3x on PBF.
set -euo pipefail
cd "$(dirname "$0")/../.."
runs=${RUNS:-5}
threads=${THREADS:-0}
shared=../shared/data/osm
osmparse=build/bin/osmparse
old=${1:-}
for tool in "$osmparse" osmium /usr/bin/time; do
    command -v "$tool" > /dev/null || { echo "parse_bench.sh: $tool not found (build, or scripts/install-deps.sh)" >&2; exit 1; }
done
[ -z "$old" ] || [ -x "$old" ] || { echo "parse_bench.sh: $old is not an executable" >&2; exit 1; }
for f in monaco.osm.bz2 monaco.osm.pbf kaiserslautern.osm.gz malta.osm.pbf; do
    [ -f "$shared/$f" ] || { echo "parse_bench.sh: $shared/$f not found" >&2; exit 1; }
done

# The older binary gets the same --threads when it has the option (older ones use every core).
old_threads=()
[ -n "$old" ] && "$old" --help 2>&1 | grep -q -- --threads && old_threads=(--threads "$threads")

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
bunzip2 -c "$shared/monaco.osm.bz2" > "$work/monaco.osm"
cp "$shared/monaco.osm.pbf" "$shared/malta.osm.pbf" "$work/"
gunzip -c "$shared/kaiserslautern.osm.gz" > "$work/kaiserslautern.osm"
osmium cat --no-progress -O "$work/kaiserslautern.osm" -o "$work/kaiserslautern.osm.pbf"
osmium cat --no-progress -O "$work/malta.osm.pbf" -o "$work/malta.osm"
inputs=(monaco.osm monaco.osm.pbf kaiserslautern.osm kaiserslautern.osm.pbf malta.osm malta.osm.pbf)
tools=(osmium new)
[ -n "$old" ] && tools+=(old)

# One timed run of `tool` on `input`: appends "seconds peak_kb user_s system_s" to $work/<tool>.<input>.runs and
# keeps osmparse's report (stage times) in $work/<tool>.<input>.report.<run>.
run_once() {
    local tool=$1 input=$2 run=$3 start end
    local cmd
    case $tool in
        osmium) cmd=(osmium export -f geojsonseq --overwrite "$work/$input" -o "$work/out.geojsonseq") ;;
        new) cmd=("$osmparse" --threads "$threads" "$work/$input" -o "$work/out.scene") ;;
        old) cmd=("$old" "${old_threads[@]}" "$work/$input" -o "$work/out.scene") ;;
    esac
    start=$(date +%s.%N)
    /usr/bin/time -f "%M %U %S" -o "$work/rss" "${cmd[@]}" > /dev/null 2> "$work/$tool.$input.report.$run"
    end=$(date +%s.%N)
    echo "$(awk -v a="$start" -v b="$end" 'BEGIN { print b - a }') $(tail -1 "$work/rss")" >> "$work/$tool.$input.runs"
}

median() { sort -g | awk '{ a[NR] = $1 } END { print (NR % 2) ? a[(NR + 1) / 2] : (a[NR / 2] + a[NR / 2 + 1]) / 2 }'; }

for input in "${inputs[@]}"; do
    for tool in "${tools[@]}"; do run_once "$tool" "$input" warmup; rm -f "$work/$tool.$input.runs"; done
    for run in $(seq "$runs"); do
        for tool in "${tools[@]}"; do run_once "$tool" "$input" "$run"; done
    done
done

seconds() { awk '{ print $1 }' "$work/$1.$2.runs" | median; }
cpu_seconds() { awk '{ print $3 + $4 }' "$work/$1.$2.runs" | median; }
peak_mb() { awk '{ if ($2 > m) m = $2 } END { printf "%.1f", m / 1024 }' "$work/$1.$2.runs"; }
ratio() { awk -v a="$1" -v b="$2" 'BEGIN { printf "%.2f", a / b }'; }

echo "$runs runs each (after one warm-up), median wall time; osmparse --threads $threads; $(nproc) cores,"
echo "load average at the end: $(cut -d' ' -f1-3 /proc/loadavg) (the machine may be shared: compare ratios of one run)"
echo
# CPU seconds (user + system) move less than wall time when other jobs share the cores.
header="| input | MB | osmium s | osmium cpu s | osmium MB | osmparse s | x osmium | cpu s | MB | x osmium MB |"
rule="|---|---|---|---|---|---|---|---|---|---|"
[ -n "$old" ] && header="$header old s | old x osmium | old cpu s | old MB |" && rule="$rule---|---|---|---|"
echo "$header"
echo "$rule"
for input in "${inputs[@]}"; do
    mb=$(awk -v n="$(stat -c %s "$work/$input")" 'BEGIN { printf "%.1f", n / 1048576 }')
    o_s=$(seconds osmium "$input"); o_mb=$(peak_mb osmium "$input")
    n_s=$(seconds new "$input"); n_mb=$(peak_mb new "$input")
    line="| $input | $mb | $(printf %.3f "$o_s") | $(printf %.2f "$(cpu_seconds osmium "$input")") | $o_mb | $(printf %.3f "$n_s") | $(ratio "$n_s" "$o_s") | $(printf %.2f "$(cpu_seconds new "$input")") | $n_mb | $(ratio "$n_mb" "$o_mb") |"
    if [ -n "$old" ]; then
        d_s=$(seconds old "$input"); d_mb=$(peak_mb old "$input")
        line="$line $(printf %.3f "$d_s") | $(ratio "$d_s" "$o_s") | $(printf %.2f "$(cpu_seconds old "$input")") | $d_mb |"
    fi
    echo "$line"
done

# Median seconds of each stage over the runs, from the report osmparse prints on stderr.
stage_medians() {
    local tool=$1 input=$2
    for run in $(seq "$runs"); do
        sed -n '/^stage  *seconds$/,$p' "$work/$tool.$input.report.$run" | sed 1d
    done | awk '{ s = $NF; $NF = ""; sub(/ +$/, ""); if (!($0 in seen)) { seen[$0] = 1; order[++n] = $0 }
                  v[$0] = v[$0] " " s }
                END { for (i = 1; i <= n; ++i) print order[i] "\t" v[order[i]] }' |
        while IFS=$'\t' read -r stage values; do
            printf '%s\t%s\n' "$stage" "$(tr ' ' '\n' <<< "$values" | sed '/^$/d' | median)"
        done
}

echo
for tool in "${tools[@]:1}"; do
    echo "Stage times (median s) of $([ "$tool" = new ] && echo "$osmparse" || echo "$old"); stages that run side by side overlap, so their sum exceeds the wall time:"
    printf '| %-20s |' stage; for input in "${inputs[@]}"; do printf ' %s |' "$input"; done; echo
    printf '|---|'; for _ in "${inputs[@]}"; do printf -- '---|'; done; echo
    for input in "${inputs[@]}"; do stage_medians "$tool" "$input" > "$work/$tool.$input.stages"; done
    cut -f1 "$work/$tool.${inputs[0]}.stages" | while read -r stage; do
        printf '| %-20s |' "$stage"
        for input in "${inputs[@]}"; do
            printf ' %s |' "$(awk -F'\t' -v s="$stage" '$1 == s { printf "%.3f", $2 }' "$work/$tool.$input.stages")"
        done
        echo
    done
    echo
done

echo "Growth from Monaco to Kaiserslautern (time ratio; Kaiserslautern has ~4x the nodes, ~12x the buildings):"
for format in osm osm.pbf; do
    line="  ${format}:"
    for tool in "${tools[@]}"; do
        line="$line $tool $(ratio "$(seconds "$tool" "kaiserslautern.$format")" "$(seconds "$tool" "monaco.$format")")x"
    done
    echo "$line"
done
