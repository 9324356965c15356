#!/usr/bin/env bash
# Installs what is missing, builds once and runs every test, fast lane first:
#   install     scripts/install-deps.sh ci. The ci profile, not test: CI runs on a fresh machine
#               and its slow stages need clang, Slurm and Blender; a local run wants the same
#               suite CI runs (without them the farm and Blender tests would only be skipped).
#   build       gcc, Release, everything (tests included) into build/
#   fast tests  ctest -LE slow: every test but the three labelled slow (tests/CMakeLists.txt)
#   farm        the slurm_farm and parse_farm tests (a single-node Slurm started by each test)
#   blender     the blender_gltf_import test (Blender imports render's glTF)
#   browser     the viewer_browser test (the viewer's page in headless Chromium)
#   asan build  scripts/check-sanitizers.sh build: clang, ASan+UBSan, with the fuzzers
#   asan tests  scripts/check-sanitizers.sh test: the suite sanitized, less farm, Blender and
#               the real extracts
#   fuzzers     scripts/check-sanitizers.sh fuzz: each libFuzzer harness for FUZZ_SECONDS
# and prints each stage's wall time at the end (and which stage failed). The first failing stage
# stops the run. CITYGEN_SKIP_SANITIZERS=1 skips the sanitizer and fuzz stages (for a quick
# local run; CI always runs them).
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=$(nproc)

names=() times=()
current=""
report() {
    local status=$? i total=0
    echo
    echo "stage        seconds"
    for i in "${!names[@]}"; do
        printf '%-12s %7s\n' "${names[$i]}" "${times[$i]}"
        total=$((total + times[i]))
    done
    if [ -n "$current" ]; then
        local spent=$(($(date +%s) - stage_start))
        printf '%-12s %7s  FAILED\n' "$current" "$spent"
        total=$((total + spent))
    fi
    printf '%-12s %7s\n' total "$total"
    [ -z "$current" ] || echo "test.sh: stage '$current' failed (exit $status)"
}
trap report EXIT

# stage NAME COMMAND...: runs COMMAND and records its wall time under NAME.
stage() {
    current=$1; shift
    echo "=== $current" >&2
    stage_start=$(date +%s)
    "$@"
    names+=("$current"); times+=("$(($(date +%s) - stage_start))")
    current=""
}

ctest_in_build() { (cd build && ctest --output-on-failure -j"$jobs" "$@"); }

stage install scripts/install-deps.sh ci
stage build scripts/build.sh ci
stage "fast tests" ctest_in_build -LE slow
stage farm ctest_in_build -R '^(slurm_farm|parse_farm)$'
stage blender ctest_in_build -R '^blender_gltf_import$'
stage browser ctest_in_build -R '^viewer_browser$'
if [ "${CITYGEN_SKIP_SANITIZERS:-0}" != 1 ]; then
    stage "asan build" scripts/check-sanitizers.sh build
    stage "asan tests" scripts/check-sanitizers.sh test
    stage fuzzers scripts/check-sanitizers.sh fuzz
fi
