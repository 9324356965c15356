#!/usr/bin/env bash
# The sanitizer and fuzz stages of CI (run by scripts/test.sh): builds everything with clang,
# AddressSanitizer and UndefinedBehaviorSanitizer (any report aborts) in a second build
# directory, runs the test suite there (so a compiler-dependent result cannot hide behind gcc
# either), then runs each libFuzzer harness in tests/fuzz for FUZZ_SECONDS (default 60) from its
# seed corpus. Fails on any test failure, crash, sanitizer report, timeout (over 10 s on one
# input) or out-of-memory (over 2 GB).
# The sanitized suite leaves out the tests labelled slow or extract (tests/CMakeLists.txt): the
# farm and Blender only run the programs through Slurm and Blender, and the real extracts run the
# code the fixtures and the parse fuzzer already reach under the sanitizers, many times slower
# at -O1 (the gcc build runs them all). SANITIZE_ALL=1 runs them too.
# Usage: scripts/check-sanitizers.sh [build|test|fuzz|all]   (default all; test.sh times each)
# Environment: SANITIZE_BUILD_DIR (default build-sanitize), FUZZ_SECONDS, SANITIZE_ALL.
set -euo pipefail
cd "$(dirname "$0")/.."
what=${1:-all}
case $what in build|test|fuzz|all) ;; *) echo "usage: $0 [build|test|fuzz|all]" >&2; exit 2 ;; esac
start=$(date +%s)
dir=${SANITIZE_BUILD_DIR:-build-sanitize}
seconds=${FUZZ_SECONDS:-60}
jobs=$(nproc)

sanitize="-fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer"
# Third-party code UBSan skips, each with its reason (tests/fuzz/ubsan_ignore.txt).
sanitize="$sanitize -fsanitize-ignorelist=$PWD/tests/fuzz/ubsan_ignore.txt"
# Coverage instrumentation for the fuzzers' benefit; harmless in the other binaries.
coverage="-fsanitize=fuzzer-no-link"
build() {
    cmake -S . -B "$dir" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
        -DCMAKE_CXX_COMPILER=clang++ \
        -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g $sanitize $coverage" \
        -DCMAKE_EXE_LINKER_FLAGS="$sanitize" \
        -DCITYGEN_FUZZ=ON -DCITYGEN_TCMALLOC=OFF > /dev/null
    cmake --build "$dir" -j"$jobs"
}

# Third-party libraries (TBB, Embree, OpenImageIO) keep some memory until exit on purpose.
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1:strict_string_checks=1:detect_stack_use_after_return=1
export LSAN_OPTIONS=suppressions=$PWD/tests/fuzz/lsan.supp:print_suppressions=0
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
# ASan reserves terabytes of address space for its shadow: no ulimit -v in the hostile set.
export HOSTILE_MEMORY_KB=unlimited
# ASan and UBSan at -O1 run 4-10x slower than the Release build: the tests' time limits (the
# hostile set's, the viewer's stop) stretch by this factor.
export TEST_SLOWDOWN=5
run_tests() {
    local select=(-LE 'slow|extract')
    [ "${SANITIZE_ALL:-0}" = 1 ] && select=()
    (cd "$dir" && ctest --output-on-failure -j"$jobs" "${select[@]}")
}

# Each fuzzer: a scratch corpus (where libFuzzer adds what it finds) seeded from the repository.
run_fuzzer() {
    local name=$1; shift
    local work; work=$(mktemp -d)
    echo "fuzzing $name for ${seconds}s" >&2
    if ! "$dir/bin/$name" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 \
            -artifact_prefix="$dir/fuzz-$name-" "$work" "$@" > "$dir/fuzz-$name.log" 2>&1; then
        tail -n 60 "$dir/fuzz-$name.log" >&2
        echo "check-sanitizers: $name failed (reproducer in $dir/fuzz-$name-*)" >&2
        rm -rf "$work"
        return 1
    fi
    local runs cov
    runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$dir/fuzz-$name.log")
    cov=$(grep -o 'cov: [0-9]* ft: [0-9]*' "$dir/fuzz-$name.log" | tail -n 1)
    echo "$name: $runs runs, $cov, corpus $(ls "$work" | wc -l) new inputs" >&2
    rm -rf "$work"
}
fuzz() {
    run_fuzzer scene_loader_fuzz tests/fuzz/corpus/scene_loader tests/golden
    run_fuzzer parse_pipeline_fuzz -max_len=65536 tests/fuzz/corpus/parse_pipeline
    run_fuzzer cli_values_fuzz -max_len=256 tests/fuzz/corpus/cli_values
    rm -f /tmp/citygen-fuzz-*.osm
}

case $what in
    build) build ;;
    test) run_tests ;;
    fuzz) fuzz ;;
    all)
        build; built=$(date +%s)
        run_tests; tested=$(date +%s)
        fuzz; end=$(date +%s)
        echo "check-sanitizers: build $((built - start)) s, sanitized tests $((tested - built)) s, fuzzing $((end - tested)) s, total $((end - start)) s" >&2
        ;;
esac
