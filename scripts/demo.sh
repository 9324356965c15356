#!/usr/bin/env bash
# The main job: installs what is missing, builds the two programs (not the tests, so a fresh
# machine reaches the first picture sooner), parses the bundled example into a scene and
# renders it to an image.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release > /dev/null
cmake --build build -j"$(nproc)" --target osmparse render
mkdir -p out
build/bin/osmparse examples/neukolln.osm.bz2 -o out/neukolln.scene
build/bin/osmparse --info out/neukolln.scene
build/bin/render out/neukolln.scene -o out/neukolln.png
echo "wrote out/neukolln.png"
