#!/usr/bin/env bash
# Installs what is missing, builds, and runs every test (each GoogleTest case is a ctest test),
# then the sanitizer and fuzz stage (scripts/check-sanitizers.sh: the suite again under clang
# with ASan+UBSan, and each libFuzzer harness for a minute). CITYGEN_SKIP_SANITIZERS=1 skips
# that stage (for a quick local run; CI always runs it).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh
(cd build && ctest --output-on-failure -j"$(nproc)")
if [ "${CITYGEN_SKIP_SANITIZERS:-0}" != 1 ]; then
    scripts/check-sanitizers.sh
fi
