#!/usr/bin/env bash
# Makes docs/gallery/: small renders of the bundled example, each made by the command the README
# shows under it (the lines below are those commands, with city.scene parsed from the example).
# Builds only osmparse and render. About a minute on two cores.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release > /dev/null
cmake --build build -j"$(nproc)" --target osmparse render > /dev/null
out=docs/gallery
mkdir -p "$out"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
ln -s "$OLDPWD/build/bin/osmparse" osmparse
ln -s "$OLDPWD/build/bin/render" render
gallery="$OLDPWD/$out"
run() { echo "$*" >&2; "$@"; }

run ./osmparse "$OLDPWD/examples/neukolln.osm.bz2" -o city.scene -q
size=(--width 480 --height 270 -q)
street=(--camera 0,0,1.7 --look-at 100,20,10 --fov 60)
closer=(--camera -40,-200,40 --look-at 0,-80,10)
run ./render city.scene -o "$gallery/day.jpg" "${size[@]}" --spp 64 --denoise
run ./render city.scene -o "$gallery/sunset.jpg" "${size[@]}" --spp 64 --denoise --time sunset
run ./render city.scene -o "$gallery/dusk.jpg" "${size[@]}" --spp 64 --denoise --time dusk
run ./render city.scene -o "$gallery/night.jpg" "${size[@]}" --spp 64 --denoise --time night
run ./render city.scene -o "$gallery/night_street.jpg" "${size[@]}" --spp 128 --denoise --time night "${street[@]}"
run ./render city.scene -o "$gallery/street.jpg" "${size[@]}" --spp 64 --denoise "${street[@]}"
run ./render city.scene -o "$gallery/stored.jpg" "${size[@]}" --spp 32 "${closer[@]}"
run ./render city.scene -o "$gallery/procedural.jpg" "${size[@]}" --spp 32 "${closer[@]}" --procedural
run ./render city.scene -o "$gallery/raw16.jpg" "${size[@]}" --spp 16 "${street[@]}"
run ./render city.scene -o "$gallery/denoised16.jpg" "${size[@]}" --spp 16 "${street[@]}" --denoise
# Monaco on its DEM, when the shared data is there.
data="$OLDPWD/../shared/data"
if [ -f "$data/osm/monaco.osm.pbf" ] && [ -f "$data/dem/N43E007.hgt.zip" ]; then
    run ./osmparse "$data/osm/monaco.osm.pbf" -o monaco.scene --dem "$data/dem/N43E007.hgt.zip" -q
    monaco=(--width 480 --height 270 -q --spp 16 --denoise)
    run ./render monaco.scene -o "$gallery/monaco_sea.png" "${monaco[@]}" --camera 700,-1500,120 --look-at -150,-650,50
    run ./render monaco.scene -o "$gallery/monaco_town.png" "${monaco[@]}" --camera 200,-1100,180 --look-at -400,0,40
    run ./render monaco.scene -o "$gallery/monaco_street.png" "${monaco[@]}" --camera 415,295,47.8 --look-at 356,447,68 --fov 60
    run ./render monaco.scene -o "$gallery/monaco_bridge.png" "${monaco[@]}" --camera -80,-110,45 --look-at -80,-25,32 --fov 60
    run ./render monaco.scene -o "$gallery/monaco_harbour.png" "${monaco[@]}" --camera 80,-150,50 --look-at 260,60,0 --fov 60
fi
echo "wrote $(ls "$gallery" | wc -l) images to $out" >&2
