#!/usr/bin/env bash
# Installs what the tests need (scripts/install-deps.sh test, or the profile in $1) and builds
# everything, tests included, into build/ (executables in build/bin/).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh "${1:-test}"
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DCITYGEN_BUILD_TESTS=ON >/dev/null
cmake --build build -j"$(nproc)"
