#!/usr/bin/env bash
# Denoiser benchmark (run by hand): the bundled example at 640x360, a day and a night view, and
# Monaco's harbour and sea from the air by day (the view where glints and the sea's guides once
# gave magenta halos) and a Monaco street at night (both skipped without
# ../shared/data/osm/monaco.osm.pbf), each against a 1024-spp reference rendered with another
# seed (the same seed would share its first samples with every test image and flatter them). PSNR on the 8-bit tone-mapped PNGs (idiff),
# for raw renders at 16..256 spp and --denoise at 16 and 64 spp; the equal-quality factor is the
# raw spp (log-interpolated) that matches denoised 16 spp, over 16. Filter seconds: median of
# RUNS (default 3) denoise_seconds from --stats (the filter alone, 2 threads here). CPU with
# --denoise: median render_cpu_seconds of 16 spp with --denoise over that without (the guides' extra
# rays and the filter).
#   tests/bench/denoise_bench.sh
#   REF_SPP=256 WIDTH=320 HEIGHT=180 tests/bench/denoise_bench.sh   # a quicker look
#   VIEWS=sea WIDTH=160 HEIGHT=90 tests/bench/denoise_bench.sh        # the sea view alone
# CACHE=DIR keeps the reference and the raw renders (which the denoiser does not change) in DIR
# between runs, named <view>_<width>x<height>_spp<n>_seed1000.png and <view>_<width>x<height>_raw<n>.png;
# empty DIR yourself when the path tracer or the example changes.
set -euo pipefail
cd "$(dirname "$0")/../.."
RUNS=${RUNS:-3}
WIDTH=${WIDTH:-640} HEIGHT=${HEIGHT:-360} REF_SPP=${REF_SPP:-1024}
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release > /dev/null
cmake --build build -j2 --target osmparse render > /dev/null

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
CACHE=${CACHE:-$work}
mkdir -p "$CACHE"
build/bin/osmparse examples/neukolln.osm.bz2 -o "$work/city.scene" -q
monaco=../shared/data/osm/monaco.osm.pbf
views=${VIEWS:-day night sea street}
if [[ " $views " == *" sea "* || " $views " == *" street "* ]]; then
  if [ -f "$monaco" ]; then build/bin/osmparse "$monaco" -o "$work/monaco.scene" -q
  else echo "denoise_bench.sh: no $monaco, the sea and street views are skipped" >&2; views=${views//sea/}; views=${views//street/}; fi
fi
# A view's scene and flags: the bundled example by day or night, Monaco from the air (its test
# renders with seed 4, as in the issue that found the halos), or a Monaco street at night at
# eye height (lamp-lit walls, where a filter can spread fireflies into blobs).
view_args() {
  case $1 in
    sea) echo "$work/monaco.scene --camera=-600,-450,250 --look-at=0,0,20 --fov 40" ;;
    street) echo "$work/monaco.scene --camera=-15,-54,1.7 --look-at=80,-32,3 --fov 60 --time night" ;;
    *) echo "$work/city.scene --time $1" ;;
  esac
}
render() { local scene=$1; shift; build/bin/render "$scene" --width "$WIDTH" --height "$HEIGHT" -q "$@"; }
psnr() { { idiff "$1" "$2" || true; } | awk '/Peak SNR/ { print $4 }'; }
median() { sort -g | awk '{ v[NR] = $1 } END { print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2 }'; }

echo "| view | raw 16 | raw 32 | raw 64 | raw 128 | raw 256 | denoised 16 | denoised 64 | equal-quality spp of denoised 16 | factor | filter seconds | CPU with --denoise |"
echo "|---|---|---|---|---|---|---|---|---|---|---|---|"
for view in $views; do
  read -r -a args <<< "$(view_args "$view")"
  ref_args=("${args[@]}")
  [ "$view" = sea ] && args+=(--seed 4)
  ref="$CACHE/${view}_${WIDTH}x${HEIGHT}_spp${REF_SPP}_seed1000.png"
  [ -s "$ref" ] || { render "${ref_args[@]}" --spp "$REF_SPP" --seed 1000 -o "$work/ref.png" && mv "$work/ref.png" "$ref"; }
  cp "$ref" "$work/ref_$view.png"
  declare -A raw=()
  for spp in 16 32 64 128 256; do
    cached="$CACHE/${view}_${WIDTH}x${HEIGHT}_raw${spp}.png"
    [ -s "$cached" ] || { render "${args[@]}" --spp "$spp" -o "$work/raw.png" && mv "$work/raw.png" "$cached"; }
    raw[$spp]=$(psnr "$work/ref_$view.png" "$cached")
  done
  for run in $(seq "$RUNS"); do
    render "${args[@]}" --spp 16 --denoise --stats -o "$work/dn16.png" > "$work/dn16_$run.stats"
    render "${args[@]}" --spp 16 --stats -o "$work/raw16.png" > "$work/raw16_$run.stats"
  done
  median_of() { awk -v key="$1:" '$1 == key { print $2 }' "$work"/$2_*.stats | median; }
  seconds=$(median_of denoise_seconds dn16)
  cost=$(awk -v a="$(median_of render_cpu_seconds dn16)" -v b="$(median_of render_cpu_seconds raw16)" 'BEGIN { printf "%.2fx", a / b }')
  dn16=$(psnr "$work/ref_$view.png" "$work/dn16.png")
  render "${args[@]}" --spp 64 --denoise -o "$work/dn64.png"
  dn64=$(psnr "$work/ref_$view.png" "$work/dn64.png")
  # The raw spp whose PSNR equals denoised 16's: linear in log2(spp) between measured points.
  equal=$(printf '%s\n' 16:${raw[16]} 32:${raw[32]} 64:${raw[64]} 128:${raw[128]} 256:${raw[256]} | awk -F: -v target="$dn16" '
    { spp[NR] = $1; p[NR] = $2 }
    END {
      if (target <= p[1]) { print "<16"; exit }
      for (i = 2; i <= NR; ++i)
        if (target <= p[i]) { f = (target - p[i-1]) / (p[i] - p[i-1]); printf "%.0f\n", 2 ^ (log(spp[i-1]) / log(2) + f); exit }
      print ">256" }')
  factor=$(awk -v e="$equal" 'BEGIN { if (e ~ /^[0-9.]+$/) printf "%.1f", e / 16; else print "-" }')
  echo "| $view | ${raw[16]} | ${raw[32]} | ${raw[64]} | ${raw[128]} | ${raw[256]} | $dn16 | $dn64 | $equal | $factor | $seconds | $cost |"
done
echo "(PSNR in dB against ${REF_SPP} spp, ${WIDTH}x${HEIGHT}; night is the --time night of this branch)"
