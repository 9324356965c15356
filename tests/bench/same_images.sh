#!/usr/bin/env bash
# Do two builds of render draw the same pictures? Renders a set of views (the bundled example
# and Monaco, day, dusk with fog and the denoiser, night, stored and procedural, a street) with
# each build and compares the PNGs byte for byte; prints one line per view and exits 1 on any
# difference. For changes meant to leave images alone (docs/bench/2026-12-ray-limit.md).
#
#   tests/bench/same_images.sh BIN_A BIN_B [SCENE_DIR]
#     BIN_A, BIN_B: folders holding render (and osmparse, used from BIN_A); SCENE_DIR keeps the
#     parsed scenes (default: a temporary folder). SIZE=480x270 SPP=8 by default.
set -euo pipefail
cd "$(dirname "$0")/../.."
a=$1 b=$2
size=${SIZE:-480x270}
spp=${SPP:-8}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
scenes=${3:-$work}
[ -f "$scenes/neukolln.scene" ] || "$a/osmparse" examples/neukolln.osm.bz2 -o "$scenes/neukolln.scene" -q
[ -f "$scenes/monaco.scene" ] ||
  "$a/osmparse" "${OSM:-../shared/data/osm/monaco.osm.bz2}" -o "$scenes/monaco.scene" -q

views=(
  "neukolln_day neukolln"
  "neukolln_night neukolln --time night"
  "neukolln_street_night neukolln --time night --camera 0,0,1.7 --look-at 100,20,10 --fov 60 --procedural"
  "monaco_day monaco"
  "monaco_day_procedural monaco --procedural"
  "monaco_night monaco --time night"
  "monaco_night_procedural monaco --time night --procedural"
  "monaco_dusk_fog_denoised monaco --time dusk --fog 0.01 --denoise"
  "monaco_street_night monaco --time night --camera -255,-146,53 --look-at -500,-330,95"
)
status=0
for view in "${views[@]}"; do
  read -r name scene args <<< "$view"
  for side in a b; do
    bin=$a
    [ $side = b ] && bin=$b
    # shellcheck disable=SC2086
    "$bin/render" "$scenes/$scene.scene" -o "$work/${name}_$side.png" --width "${size%x*}" --height "${size#*x}" \
      --spp "$spp" -q $args
  done
  if cmp -s "$work/${name}_a.png" "$work/${name}_b.png"; then
    echo "same       $name"
  else
    echo "DIFFERENT  $name"
    status=1
  fi
done
exit $status
