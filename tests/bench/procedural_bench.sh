#!/usr/bin/env bash
# Stored vs procedural geometry benchmark, run by hand (never from ctest).
# Monaco parsed with random building heights averaging about 20, 40 and 80 m (tagged heights
# stay as mapped), each rendered at 640x360, 16 spp, from the same view, in both modes.
# Prints a table (median build and render time of RUNS runs; memory and counts from the first
# run; build = geometry + Embree BVH, render = tracing only) and
# draws build/bench/procedural/procedural_bench.png with gnuplot (installed here if missing).
# Targets (issue 5): procedural geometry memory >= 50x smaller than stored at 80 m;
# procedural render time <= 2x stored.
#
#   tests/bench/procedural_bench.sh [monaco.osm]      (RUNS=3, HEIGHTS="20 40 80" by default)
set -euo pipefail
cd "$(dirname "$0")/../.."
runs=${RUNS:-3}
heights=${HEIGHTS:-20 40 80}
osm=${1:-/tmp/monaco.osm}
[ -f "$osm" ] || osm=../shared/data/osm/monaco.osm.pbf
bin=build/bin
out=build/bench/procedural
mkdir -p "$out"
for tool in "$bin/osmparse" "$bin/render" /usr/bin/time; do
    [ -x "$tool" ] || { echo "procedural_bench.sh: $tool not found (build first)" >&2; exit 1; }
done
if ! command -v gnuplot > /dev/null; then
    SUDO=""; [ "$(id -u)" -ne 0 ] && SUDO="sudo"
    echo "procedural_bench.sh: installing gnuplot-nox for the plot" >&2
    DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends gnuplot-nox > /dev/null
fi

# One view for every run: from above the harbour towards Monte Carlo.
view=(--width 640 --height 360 --spp 16 --seed 1 --camera=-420,-520,190 --look-at=120,180,30 --fov 50)

# Value of "key: value" in a log.
value() { awk -v k="$2:" '$1 == k { print $2; exit }' "$1"; }
median() { sort -g | awk '{ a[NR] = $1 } END { print (NR % 2) ? a[(NR + 1) / 2] : (a[NR / 2] + a[NR / 2 + 1]) / 2 }'; }

data=$out/procedural_bench.dat
echo "# height mode primitives triangles geometry_mb embree_mb buffer_mb peak_rss_mb render_s mrays_per_s build_s" > "$data"
for h in $heights; do
    scene=$out/monaco_h$h.scene
    lo=$(awk -v h="$h" 'BEGIN { print 0.75 * h }')
    hi=$(awk -v h="$h" 'BEGIN { print 1.25 * h }')
    "$bin/osmparse" --quiet "$osm" -o "$scene" --building-min-h "$lo" --building-max-h "$hi"
    for mode in stored procedural; do
        flag=()
        [ "$mode" = procedural ] && flag=(--procedural)
        times=() rates=() builds=()
        for run in $(seq "$runs"); do
            log=$out/h${h}_${mode}_$run.log
            "$bin/render" "$scene" -o "$out/h${h}_${mode}.png" "${view[@]}" "${flag[@]}" --quiet --stats \
                --print-memory-info --print-scene-geometry-info > "$log" 2>&1
            times+=("$(value "$log" render_seconds)")
            rates+=("$(value "$log" rays_per_second)")
            builds+=("$(value "$log" build_seconds)")
        done
        log=$out/h${h}_${mode}_1.log
        t=$(printf '%s\n' "${times[@]}" | median)
        r=$(printf '%s\n' "${rates[@]}" | median)
        bt=$(printf '%s\n' "${builds[@]}" | median)
        awk -v h="$h" -v m="$mode" -v p="$(value "$log" primitives)" -v tri="$(value "$log" triangles)" \
            -v g="$(value "$log" geometry_bytes)" -v e="$(value "$log" embree_bytes)" \
            -v b="$(value "$log" buffer_bytes)" -v rss="$(value "$log" peak_rss_bytes)" -v t="$t" -v r="$r" -v bt="$bt" \
            'BEGIN { printf "%s %s %s %s %.3f %.3f %.3f %.1f %.3f %.3f %.3f\n", h, m, p, tri, g / 1e6, e / 1e6, b / 1e6, rss / 1e6, t, r / 1e6, bt }' \
            >> "$data"
    done
done

echo "Monaco, 640x360, 16 spp, median of $runs runs; memory from --print-memory-info"
printf '| %6s | %-10s | %11s | %11s | %12s | %11s | %8s | %8s | %8s |\n' "avg h" "mode" "primitives" "triangles" \
    "geometry MB" "peak RSS MB" "build s" "render s" "Mrays/s"
printf '|%s|%s|%s|%s|%s|%s|%s|%s|%s|\n' "--------" "------------" "-------------" "-------------" "--------------" \
    "-------------" "----------" "----------" "----------"
awk '!/^#/ { printf "| %6s | %-10s | %11s | %11s | %12.1f | %11.1f | %8.2f | %8.2f | %8.2f |\n", $1, $2, $3, $4, $5, $8, $11, $9, $10 }' "$data"
echo
awk '!/^#/ { if ($2 == "stored") { g[$1] = $5; t[$1] = $9 } else { printf "avg %s m: procedural geometry memory %.0fx smaller, render time %.2fx stored\n", $1, g[$1] / $5, $9 / t[$1] } }' "$data"

gnuplot <<GNUPLOT
set terminal pngcairo size 1100,420 font ",10"
set output "$out/procedural_bench.png"
set multiplot layout 1,2 title "Monaco, 640x360, 16 spp: stored vs procedural geometry"
set xlabel "average building height (m)"
set key top left
set grid
set logscale y
set ylabel "geometry memory (MB, log)"
plot "< awk '\$2 == \"stored\"' $data" using 1:5 with linespoints lw 2 title "stored", \
     "< awk '\$2 == \"procedural\"' $data" using 1:5 with linespoints lw 2 title "procedural"
unset logscale y
set ylabel "render time (s)"
set yrange [0:*]
plot "< awk '\$2 == \"stored\"' $data" using 1:9 with linespoints lw 2 title "stored", \
     "< awk '\$2 == \"procedural\"' $data" using 1:9 with linespoints lw 2 title "procedural"
unset multiplot
GNUPLOT
echo "plot: $out/procedural_bench.png"
