#!/usr/bin/env bash
# Night-city benchmark, run by hand (never from ctest): many-light sampling on real data.
# Monaco at night from a street-level and an elevated view: a high-spp reference (tree
# sampler), then each light sampler (uniform, power, tree) at SPP: tracing seconds (median of
# RUNS), MSE of the linear EXR against the reference (oiiotool --diff), and efficiency =
# 1 / (MSE x seconds) relative to uniform. Then the cost of a night sample against a day sample
# (same view and spp), procedural geometry memory at night against day, and the same sampler
# comparison on Kaiserslautern's default view, to see how time and efficiency grow with the
# number of lamps (Monaco 1.5 k, Kaiserslautern 9 k).
# Targets (issue 9): tree >= 10x as efficient as uniform; night <= 1.5x day per sample;
# procedural night memory <= 1.2x day.
#
#   tests/bench/night_bench.sh      (SIZE=640x360 REF_SPP=1024 SPP=16 RUNS=3 by default;
#                                    SIZE=320x180 REF_SPP=256 RUNS=1 for a quick run)
set -euo pipefail
cd "$(dirname "$0")/../.."
size=${SIZE:-640x360}
width=${size%x*}
height=${size#*x}
ref_spp=${REF_SPP:-1024}
spp=${SPP:-16}
runs=${RUNS:-3}
bin=build/bin
out=build/bench/night
mkdir -p "$out"
for tool in "$bin/osmparse" "$bin/render" oiiotool; do
    command -v "$tool" > /dev/null || { echo "night_bench.sh: $tool not found (build first; oiiotool: openimageio-tools)" >&2; exit 1; }
done

value() { awk -v k="$2:" '$1 == k { print $2; exit }' "$1"; }
median() { sort -g | awk '{ a[NR] = $1 } END { print (NR % 2) ? a[(NR + 1) / 2] : (a[NR / 2] + a[NR / 2 + 1]) / 2 }'; }
# Mean squared error over all channels of two EXRs.
mse() { oiiotool "$1" "$2" --diff 2>&1 | awk '/RMS error/ { print $4 * $4; exit }'; }

for city in monaco kaiserslautern; do
    scene=$out/$city.scene
    src=../shared/data/osm/$city.osm.pbf
    [ -f "$src" ] || src=../shared/data/osm/$city.osm.gz
    [ -f "$scene" ] || "$bin/osmparse" --quiet "$src" -o "$scene"
done

common=(--width "$width" --height "$height" --seed 1 --quiet --stats)
# Monaco: along a street with lamps at eye height, and from above the harbour.
declare -A views=(
    [monaco_street]="--camera=-15,-54,1.7 --look-at=80,-32,3 --fov 60"
    [monaco_elevated]="--camera=-420,-520,190 --look-at=120,180,30 --fov 50"
    [kaiserslautern_default]=""
)
order=(monaco_street monaco_elevated kaiserslautern_default)

# seconds of tracing (median of RUNS) and MSE against the reference for one sampler and view.
measure() {  # name view-args... -> prints "seconds mse"
    local name=$1 scene=$2 ref=$3 sampler=$4; shift 4
    local times=()
    for run in $(seq "$runs"); do
        "$bin/render" "$scene" -o "$out/$name.exr" "${common[@]}" --spp "$spp" --time night \
            --light-sampler "$sampler" "$@" > "$out/$name.log" 2>&1
        times+=("$(value "$out/$name.log" render_seconds)")
    done
    echo "$(printf '%s\n' "${times[@]}" | median) $(mse "$out/$name.exr" "$ref")"
}

printf '\n%s, %s spp against a %s-spp tree reference (median of %s runs)\n\n' "$size" "$spp" "$ref_spp" "$runs"
echo "| view | lights | sampler | seconds | MSE | efficiency vs uniform |"
echo "|---|---|---|---|---|---|"
for v in "${order[@]}"; do
    city=${v%%_*}
    scene=$out/$city.scene
    read -r -a args <<< "${views[$v]}"
    ref=$out/${v}_reference.exr
    [ -f "$ref" ] || "$bin/render" "$scene" -o "$ref" "${common[@]}" --spp "$ref_spp" --time night "${args[@]}" \
        > "$out/${v}_reference.log" 2>&1
    lights=$("$bin/render" "$scene" --time night --print-scene-geometry-info -q | awk '$1 == "light_lamps:" { l = $2 } $1 == "light_window_strips:" { s = $2 } END { print l " lamps + " s " window strips" }')
    uniform_eff=""
    for sampler in uniform power tree; do
        read -r seconds err <<< "$(measure "${v}_$sampler" "$scene" "$ref" "$sampler" "${args[@]}")"
        eff=$(awk -v m="$err" -v s="$seconds" 'BEGIN { print 1 / (m * s) }')
        [ -z "$uniform_eff" ] && uniform_eff=$eff
        awk -v v="$v" -v l="$lights" -v smp="$sampler" -v s="$seconds" -v m="$err" -v e="$eff" -v u="$uniform_eff" \
            'BEGIN { printf "| %s | %s | %s | %.2f | %.3g | %.2fx |\n", v, l, smp, s, m, e / u }'
    done
done

printf '\nCost of a sample, night (tree) against day, %s spp (median of %s runs)\n\n' "$spp" "$runs"
echo "| view | day seconds | night seconds | night / day |"
echo "|---|---|---|---|"
for v in "${order[@]}"; do
    city=${v%%_*}
    read -r -a args <<< "${views[$v]}"
    day=() night=()
    for run in $(seq "$runs"); do
        for t in day night; do
            "$bin/render" "$out/$city.scene" -o "$out/${v}_$t.png" "${common[@]}" --spp "$spp" --time "$t" "${args[@]}" \
                > "$out/${v}_$t.log" 2>&1
        done
        day+=("$(value "$out/${v}_day.log" render_seconds)")
        night+=("$(value "$out/${v}_night.log" render_seconds)")
    done
    d=$(printf '%s\n' "${day[@]}" | median)
    n=$(printf '%s\n' "${night[@]}" | median)
    awk -v v="$v" -v d="$d" -v n="$n" 'BEGIN { printf "| %s | %.2f | %.2f | %.2fx |\n", v, d, n, n / d }'
done

printf '\nProcedural geometry memory (Embree + our buffers, plus the light BVH and lists at night)\n\n'
echo "| city | day MB | night MB | night / day |"
echo "|---|---|---|---|"
for city in monaco kaiserslautern; do
    for t in day night; do
        "$bin/render" "$out/$city.scene" --procedural --time "$t" --print-memory-info -q > "$out/${city}_mem_$t.log"
    done
    d=$(value "$out/${city}_mem_day.log" geometry_bytes)
    n=$(( $(value "$out/${city}_mem_night.log" geometry_bytes) + $(value "$out/${city}_mem_night.log" light_bytes) ))
    awk -v c="$city" -v d="$d" -v n="$n" 'BEGIN { printf "| %s | %.1f | %.1f | %.2fx |\n", c, d / 1e6, n / 1e6, n / d }'
done
