#!/usr/bin/env bash
# The main job: installs what is missing, builds, parses the bundled example into a scene
# and renders it to an image.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh
mkdir -p out
build/bin/osmparse examples/neukolln.osm.bz2 -o out/neukolln.scene
build/bin/osmparse --info out/neukolln.scene
if [ -x build/bin/render ]; then
  build/bin/render out/neukolln.scene -o out/neukolln.png
  echo "wrote out/neukolln.png"
fi
