#!/usr/bin/env bash
# osmparse never writes a scene that its own loader (or render's) refuses. Every fixture in
# tests/data/*.osm and every hostile OSM input (tests/data/make_hostile_inputs.sh) must either
#   fail: exit 1..127, exactly one line on stderr starting with "osmparse: ", no scene file and
#         no temporary file left; or
#   pass: exit 0, and the scene loads in `osmparse --info` and renders at 16x9 in render.
# Usage: every_input_loads.sh BIN_DIR SOURCE_DIR [WORK_DIR]   (ctest runs it as every_input_loads)
set -uo pipefail
bin=$(cd "$1" && pwd) src=$(cd "$2" && pwd)
work=${3:-$(mktemp -d)}
mkdir -p "$work/out"
trap '[ -n "${3:-}" ] || rm -rf "$work"' EXIT
seconds=${EVERY_INPUT_SECONDS:-60}

"$src/tests/data/make_hostile_inputs.sh" "$work/in" "$bin" > /dev/null || { echo "FAIL could not make the inputs"; exit 1; }

failures=0 passed=0 refused=0
fail() { echo "FAIL $name: $*"; failures=$((failures + 1)); }
for input in "$src"/tests/data/*.osm "$work"/in/*.osm; do
    name=$(basename "$input" .osm)
    [ -e "$work/out/$name.scene" ] && name="hostile_$name"  # a hostile input named as a fixture
    scene=$work/out/$name.scene err=$work/out/$name.err
    timeout -s KILL "$seconds" "$bin/osmparse" -q "$input" -o "$scene" 2> "$err"
    status=$?
    if [ "$status" -ne 0 ]; then
        lines=$(grep -c '' "$err")
        if [ "$status" -ge 124 ]; then fail "killed or timed out (exit $status)"
        elif [ "$lines" -ne 1 ]; then fail "exit $status with $lines lines on stderr, expected one"
        elif ! grep -q '^osmparse: ' "$err" || grep -q 'unexpected error' "$err"; then fail "not a clear message: $(cat "$err")"
        elif [ -e "$scene" ]; then fail "failed but left $scene"
        else refused=$((refused + 1))
        fi
    elif ! "$bin/osmparse" --info "$scene" > /dev/null 2> "$err.info"; then
        fail "written, but osmparse --info refuses it: $(cat "$err.info")"
    elif ! timeout -s KILL "$seconds" "$bin/render" -q "$scene" -o "$work/out/$name.png" --width 16 --height 9 --spp 1 \
            2> "$err.render"; then
        fail "written, but render refuses it: $(head -c 300 "$err.render")"
    else
        passed=$((passed + 1))
    fi
    ls "$work/out" | grep -q '\.tmp' && fail "temporary file left: $(ls "$work/out" | grep '\.tmp')"
done
echo "$passed scenes load, $refused inputs refused with one clear line, $failures failures"
[ "$failures" -eq 0 ]
