#!/usr/bin/env bash
# The main job: installs what the two programs need (scripts/install-deps.sh runtime: no
# GoogleTest, clang, Slurm or Blender), builds osmparse and render only (CITYGEN_BUILD_TESTS=OFF,
# so configuring needs no GoogleTest and a fresh machine reaches the first picture sooner),
# parses the bundled example into a scene and renders it to an image. Idempotent: a second run
# installs nothing and rebuilds only what changed. Shares build/ with scripts/build.sh, which
# turns the tests back on (the programs' objects are the same either way).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh runtime
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DCITYGEN_BUILD_TESTS=OFF > /dev/null
cmake --build build -j"$(nproc)" --target osmparse render
mkdir -p out
build/bin/osmparse examples/neukolln.osm.bz2 -o out/neukolln.scene
build/bin/osmparse --info out/neukolln.scene
build/bin/render out/neukolln.scene -o out/neukolln.png
echo "wrote out/neukolln.png"
