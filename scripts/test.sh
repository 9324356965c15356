#!/usr/bin/env bash
# Installs what is missing, builds, and runs every test (each GoogleTest case is a ctest test).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh
cd build && ctest --output-on-failure -j"$(nproc)"
