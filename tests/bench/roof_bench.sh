#!/usr/bin/env bash
# Roof benchmark, run by hand (never from ctest): how well osmparse guesses the roof shape of a
# building the map gives none, measured as tests/bench/height_bench.sh measures heights. Each
# extract is parsed as it is (the truth: whole buildings on the ground whose roof:shape is tagged)
# and with --hide-roof-tags 1 (every roof:shape forgotten: the defaults see no evidence) and 0.5
# (half forgotten, once per seed in HALF_SEEDS, default 1..12: the defaults read the other half).
# Prints per extract and protocol, over the buildings whose tag was hidden: how often the guess
# is right about flat or pitched (any other shape), how often it is the very shape, and the mean
# error of the roof's height. A last line per extract counts the untagged roofs of the plain
# parse that came out pitched (Malta's roofs are flat: one of its 13,212 buildings is tagged).
#
#   tests/bench/roof_bench.sh [FILE ...]   (default: every extract in ../shared/data/osm, or $OSM_DATA)
#   OSMPARSE=/path/to/old/osmparse tests/bench/roof_bench.sh   (it needs --hide-roof-tags)
set -euo pipefail
files=()
for f in "$@"; do files+=("$(realpath "$f")"); done
cd "$(dirname "$0")/../.."
osmparse=${OSMPARSE:-build/bin/osmparse}
[ -x "$osmparse" ] || { echo "roof_bench.sh: build first ($osmparse missing)" >&2; exit 1; }
data=${OSM_DATA:-../shared/data/osm}
[ ${#files[@]} -gt 0 ] || files=("$data"/monaco.osm.pbf "$data"/kaiserslautern.osm.gz "$data"/malta.osm.pbf
                                  "$data"/osm2streets/*/input.osm)
half_seeds=${HALF_SEEDS:-1 2 3 4 5 6 7 8 9 10 11 12}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
printf '%-30s %8s %12s %12s %14s\n' "extract, protocol" roofs "flat/pitched" "same shape" "roof height MAE"
for f in "${files[@]}"; do
    name=$(basename "$f")
    [ "$name" = input.osm ] && name=$(basename "$(dirname "$f")")
    "$osmparse" --quiet "$f" -o "$work/s.scene" --geojson "$work/truth.geojson"
    "$osmparse" --quiet "$f" -o "$work/s.scene" --geojson "$work/hide_1.geojson" --hide-roof-tags 1
    runs=(1)
    for seed in $half_seeds; do
        "$osmparse" --quiet "$f" -o "$work/s.scene" --geojson "$work/hide_0.5_$seed.geojson" --hide-roof-tags 0.5 --seed "$seed"
        runs+=("0.5_$seed")
    done
    python3 - "$work" "$name" "${runs[@]}" <<'PY'
import json, statistics, sys
work, name, runs = sys.argv[1], sys.argv[2], sys.argv[3:]
def roofs(path):
    out = {}
    for feat in json.load(open(path))['features']:
        p = feat['properties']
        if p.get('kind') == 'building' and not p['part'] and p['min_height'] == 0: out.setdefault(p['osm'], []).append(p)
    return out
truth = roofs(f'{work}/truth.geojson')
def row(label, pairs):
    if not pairs:
        print(f'{label:<30} {0:8d}   (no tagged roof hidden)')
        return
    cls = sum((t['roof_shape'] == 'flat') == (h['roof_shape'] == 'flat') for t, h in pairs) / len(pairs)
    same = sum(t['roof_shape'] == h['roof_shape'] for t, h in pairs) / len(pairs)
    mae = statistics.mean(abs(t['roof_height'] - h['roof_height']) for t, h in pairs)
    print(f'{label:<30} {len(pairs):8d} {100 * cls:11.1f}% {100 * same:11.1f}% {mae:13.2f}m')
for protocol, tags in [('hide 1', ['1']), (f'hide 0.5 x{len(runs) - 1} seeds', [r for r in runs if r != '1'])]:
    pairs = []
    for tag in tags:
        hidden = roofs(f'{work}/hide_{tag}.geojson')
        for osm, parts in truth.items():
            if osm not in hidden or len(hidden[osm]) != len(parts): continue
            for t, h in zip(parts, hidden[osm]):
                if not t['roof_inferred'] and h['roof_inferred']: pairs.append((t, h))
    row(f'{name}, {protocol}', pairs)
untagged = [p for parts in truth.values() for p in parts if p['roof_inferred']]
pitched = sum(p['roof_shape'] != 'flat' for p in untagged)
print(f'{"  untagged roofs pitched":<30} {pitched:8d} of {len(untagged)}')
PY
done
