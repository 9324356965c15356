#!/usr/bin/env bash
# Night-city benchmark, run by hand (never from ctest): many-light sampling on real data.
# Monaco at night from a street-level and an elevated view: a high-spp reference (tree
# sampler), then each light sampler (uniform, power, tree) at SPP: tracing seconds (median of
# RUNS), MSE against the reference (linear EXR and displayed image, see mse()), and efficiency =
# 1 / (MSE x CPU seconds) relative to uniform (CPU seconds of all threads while tracing: on a
# shared machine the wall clock measures the neighbours' load). Then the cost of a night sample
# against a day sample
# (same view and spp), procedural geometry memory at night against day, and the same sampler
# comparison on Kaiserslautern's default view, to see how time and efficiency grow with the
# number of lamps (Monaco 1.5 k, Kaiserslautern 9 k).
# Targets (issue 9): tree >= 10x as efficient as uniform; night <= 1.5x day per sample;
# procedural night memory <= 1.2x day.
#
#   tests/bench/night_bench.sh      (SIZE=640x360 REF_SPP=1024 SPP=16 RUNS=3 by default;
#                                    SIZE=320x180 REF_SPP=256 RUNS=1 for a quick run;
#                                    VIEWS="monaco_street monaco_elevated" for some views only;
#                                    RENDER=path/to/render to measure another build; OUT=dir
#                                    for the images, default build/bench/night; references
#                                    are kept there and reused while they exist; MEMORY=0 skips
#                                    the memory table)
set -euo pipefail
cd "$(dirname "$0")/../.."
size=${SIZE:-640x360}
width=${size%x*}
height=${size#*x}
ref_spp=${REF_SPP:-1024}
spp=${SPP:-16}
runs=${RUNS:-3}
bin=build/bin
render=${RENDER:-$bin/render}
out=${OUT:-build/bench/night}
mkdir -p "$out"
for tool in "$bin/osmparse" "$render" oiiotool; do
    command -v "$tool" > /dev/null || { echo "night_bench.sh: $tool not found (build first; oiiotool: openimageio-tools)" >&2; exit 1; }
done

value() { awk -v k="$2:" '$1 == k { print $2; exit }' "$1"; }
median() { sort -g | awk '{ a[NR] = $1 } END { print (NR % 2) ? a[(NR + 1) / 2] : (a[NR / 2] + a[NR / 2 + 1]) / 2 }'; }
# Mean squared error of an EXR against the reference, over all channels: of the linear radiance,
# and of the displayed image (the reference's exposure, filmic curve, sRGB, as render writes a
# PNG). The linear MSE is dominated by the edges of directly seen lamps and lit windows (pixel
# jitter over a bright emitter, the same for every sampler); the display MSE is what the eye
# sees of the light sampling noise.
mse() {  # image reference exposure -> "linear display"
    paste <(oiiotool --dumpdata "$1" | grep Pixel) <(oiiotool --dumpdata "$2" | grep Pixel) |
        awk -v e="$3" '
            function show(x) { x *= e; y = x * (2.51 * x + 0.03) / (x * (2.43 * x + 0.59) + 0.14);
                               y = y < 0 ? 0 : (y > 1 ? 1 : y);
                               return y <= 0.0031308 ? 12.92 * y : 1.055 * y ^ (1 / 2.4) - 0.055 }
            { for (c = 0; c < 3; ++c) { a = $(4 + c); b = $(10 + c); lin += (a - b) ^ 2; d = show(a) - show(b); dis += d * d; n++ } }
            END { printf "%.4g %.4g\n", lin / n, dis / n }'
}

for city in monaco kaiserslautern; do
    scene=$out/$city.scene
    src=../shared/data/osm/$city.osm.pbf
    [ -f "$src" ] || src=../shared/data/osm/$city.osm.gz
    [ -f "$scene" ] || "$bin/osmparse" --quiet "$src" -o "$scene"
done

# The reference has its own seed: with the samplers' seed its first samples would be theirs, and
# the MSE of whatever sampler rendered it (the tree) would look smaller than it is.
common=(--width "$width" --height "$height" --quiet --stats)
seed=(--seed 1)
ref_seed=(--seed 1000)
# Monaco: along a street with lamps at eye height, and from above the harbour.
declare -A views=(
    [monaco_street]="--camera=-15,-54,1.7 --look-at=80,-32,3 --fov 60"
    [monaco_elevated]="--camera=-420,-520,190 --look-at=120,180,30 --fov 50"
    [kaiserslautern_default]=""
)
read -r -a order <<< "${VIEWS:-monaco_street monaco_elevated kaiserslautern_default}"

# seconds of tracing (median of RUNS) and MSEs against the reference for one sampler and view.
measure() {  # name scene reference exposure sampler view-args... -> prints "seconds cpu_seconds linear_mse display_mse"
    local name=$1 scene=$2 ref=$3 exposure=$4 sampler=$5; shift 5
    local times=() cpus=()
    for run in $(seq "$runs"); do
        "$render" "$scene" -o "$out/$name.exr" "${common[@]}" "${seed[@]}" --spp "$spp" --time night \
            --light-sampler "$sampler" "$@" > "$out/$name.log" 2>&1
        times+=("$(value "$out/$name.log" render_seconds)")
        cpus+=("$(value "$out/$name.log" render_cpu_seconds)")
    done
    echo "$(printf '%s\n' "${times[@]}" | median) $(printf '%s\n' "${cpus[@]}" | median) $(mse "$out/$name.exr" "$ref" "$exposure")"
}

printf '\n%s, %s spp against a %s-spp tree reference (median of %s runs)\n\n' "$size" "$spp" "$ref_spp" "$runs"
# The last column, uniform's display MSE over the sampler's, leaves the CPU seconds out: on a
# shared machine they move by 10-20% from run to run, the errors do not.
echo "| view | lights | sampler | seconds | CPU seconds | linear MSE | efficiency vs uniform | display MSE | efficiency vs uniform | uniform's display MSE / this |"
echo "|---|---|---|---|---|---|---|---|---|---|"
for v in "${order[@]}"; do
    city=${v%%_*}
    scene=$out/$city.scene
    read -r -a args <<< "${views[$v]}"
    ref=$out/${v}_reference.exr
    [ -f "$ref" ] && [ -f "$out/${v}_reference.log" ] ||
        "$render" "$scene" -o "$ref" "${common[@]}" "${ref_seed[@]}" --spp "$ref_spp" --time night "${args[@]}" \
            > "$out/${v}_reference.log" 2>&1
    lights=$("$render" "$scene" --time night --print-scene-geometry-info -q | awk '$1 == "light_lamps:" { l = $2 } $1 == "light_window_strips:" { s = $2 } END { print l " lamps + " s " window strips" }')
    # The reference's automatic exposure, as a multiplier (exposure.cpp: 8 x 16667 / (1.2 x 2^EV)).
    ev=$(value "$out/${v}_reference.log" exposure_ev)
    exposure=$(awk -v ev="$ev" 'BEGIN { print 8 * 1000 / 0.06 / (1.2 * 2 ^ ev) }')
    uniform_lin="" uniform_dis="" uniform_mse=""
    for sampler in uniform power tree; do
        read -r seconds cpu lin dis <<< "$(measure "${v}_$sampler" "$scene" "$ref" "$exposure" "$sampler" "${args[@]}")"
        eff_lin=$(awk -v m="$lin" -v s="$cpu" 'BEGIN { print 1 / (m * s) }')
        eff_dis=$(awk -v m="$dis" -v s="$cpu" 'BEGIN { print 1 / (m * s) }')
        [ -z "$uniform_lin" ] && uniform_lin=$eff_lin uniform_dis=$eff_dis uniform_mse=$dis
        awk -v v="$v" -v l="$lights" -v smp="$sampler" -v s="$seconds" -v c="$cpu" -v m="$lin" -v e="$eff_lin" -v u="$uniform_lin" \
            -v md="$dis" -v ed="$eff_dis" -v ud="$uniform_dis" -v um="$uniform_mse" \
            'BEGIN { printf "| %s | %s | %s | %.2f | %.2f | %.3g | %.2fx | %.3g | %.2fx | %.2f |\n", v, l, smp, s, c, m, e / u, md, ed / ud, um / md }'
    done
done

printf '\nCost of a sample, night (tree) against day, %s spp (median of %s runs)\n\n' "$spp" "$runs"
echo "| view | day seconds | night seconds | day CPU seconds | night CPU seconds | night / day (CPU) |"
echo "|---|---|---|---|---|---|"
for v in "${order[@]}"; do
    city=${v%%_*}
    read -r -a args <<< "${views[$v]}"
    day=() night=() day_cpu=() night_cpu=()
    for run in $(seq "$runs"); do
        for t in day night; do
            "$render" "$out/$city.scene" -o "$out/${v}_$t.png" "${common[@]}" "${seed[@]}" --spp "$spp" --time "$t" "${args[@]}" \
                > "$out/${v}_$t.log" 2>&1
        done
        day+=("$(value "$out/${v}_day.log" render_seconds)")
        night+=("$(value "$out/${v}_night.log" render_seconds)")
        day_cpu+=("$(value "$out/${v}_day.log" render_cpu_seconds)")
        night_cpu+=("$(value "$out/${v}_night.log" render_cpu_seconds)")
    done
    d=$(printf '%s\n' "${day[@]}" | median)
    n=$(printf '%s\n' "${night[@]}" | median)
    dc=$(printf '%s\n' "${day_cpu[@]}" | median)
    nc=$(printf '%s\n' "${night_cpu[@]}" | median)
    awk -v v="$v" -v d="$d" -v n="$n" -v dc="$dc" -v nc="$nc" \
        'BEGIN { printf "| %s | %.2f | %.2f | %.2f | %.2f | %.2fx |\n", v, d, n, dc, nc, nc / dc }'
done

[ "${MEMORY:-1}" = 0 ] && exit 0
printf '\nProcedural geometry memory (Embree + our buffers, plus the light BVH and lists at night)\n\n'
echo "| city | day MB | night MB | night / day |"
echo "|---|---|---|---|"
for city in monaco kaiserslautern; do
    for t in day night; do
        "$render" "$out/$city.scene" --procedural --time "$t" --print-memory-info -q > "$out/${city}_mem_$t.log"
    done
    d=$(value "$out/${city}_mem_day.log" geometry_bytes)
    n=$(( $(value "$out/${city}_mem_night.log" geometry_bytes) + $(value "$out/${city}_mem_night.log" light_bytes) ))
    awk -v c="$city" -v d="$d" -v n="$n" 'BEGIN { printf "| %s | %.2f | %.2f | %.3fx |\n", c, d / 1e6, n / 1e6, n / d }'
done
