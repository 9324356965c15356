#!/usr/bin/env bash
# Height benchmark, run by hand (never from ctest): how well osmparse guesses the height of a
# building the map gives none. Each extract is parsed twice: as it is (the truth: buildings whose
# height or building:levels is tagged) and with --hide-height-tags (every height-like tag
# forgotten), then with half of the buildings' tags hidden (seeded), where the rules can use
# the tagged neighbours. Prints, per extract and protocol, the error over the hidden buildings
# of today's rules beside the old seeded random height in [8, 30] m (the formula it used,
# recomputed here for the same buildings): mean absolute error and median absolute
# percentage error.
#
#   tests/bench/height_bench.sh [FILE ...]   (default: Monaco and Kaiserslautern)
set -euo pipefail
cd "$(dirname "$0")/../.."
osmparse=build/bin/osmparse
[ -x "$osmparse" ] || { echo "height_bench.sh: build first ($osmparse missing)" >&2; exit 1; }
files=("$@")
[ ${#files[@]} -gt 0 ] || files=(../shared/data/osm/monaco.osm.pbf ../shared/data/osm/kaiserslautern.osm.gz)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
printf '%-30s %8s %10s %10s %10s %10s %12s\n' extract buildings "MAE random" "MAE rules" "MdAPE rand" "MdAPE rules" "rules used"
for f in "${files[@]}"; do
    name=$(basename "$f")
    "$osmparse" --quiet "$f" -o "$work/truth.scene" --geojson "$work/truth.geojson"
  for fraction in 1 0.5; do
    "$osmparse" --quiet "$f" -o "$work/hidden.scene" --geojson "$work/hidden.geojson" --hide-height-tags $fraction
    python3 - "$work/truth.geojson" "$work/hidden.geojson" "$name, hide $fraction" <<'PY'
import json, sys, statistics
from collections import Counter

M = (1 << 64) - 1
def mix64(z):
    z = (z + 0x9e3779b97f4a7c15) & M
    z = ((z ^ (z >> 30)) * 0xbf58476d1ce4e5b9) & M
    z = ((z ^ (z >> 27)) * 0x94d049bb133111eb) & M
    return z ^ (z >> 31)
def old_random_height(osm, seed=1, lo=8.0, hi=30.0):
    # hash_keys(seed, type, id) and hash_to_unit from common/rng.h, as the old rule used them.
    kind = {'n': 0, 'w': 1, 'r': 2}[osm[0]]
    h = mix64(seed ^ mix64(kind))
    h = mix64(h ^ mix64(int(osm[1:]) & M))
    h = mix64(h)
    return lo + (h >> 11) * 2.0 ** -53 * (hi - lo)

def buildings(path):
    out = {}
    for feat in json.load(open(path))['features']:
        p = feat['properties']
        if p.get('kind') != 'building': continue
        out.setdefault(p['osm'], []).append(p)
    return out

truth, hidden = buildings(sys.argv[1]), buildings(sys.argv[2])
err_rand, err_rules, ape_rand, ape_rules, rules = [], [], [], [], Counter()
for osm, parts in truth.items():
    if osm not in hidden or len(hidden[osm]) != len(parts): continue
    for t, h in zip(parts, hidden[osm]):
        if t['height_source'] == 'random' or t['part'] or t['min_height'] > 0: continue
        if h['height_source'] != 'random': continue  # this one kept its tags
        true_h = t['height']
        err_rules.append(abs(h['height'] - true_h))
        err_rand.append(abs(old_random_height(osm) - true_h))
        ape_rules.append(err_rules[-1] / true_h * 100)
        ape_rand.append(err_rand[-1] / true_h * 100)
        rules[h.get('height_rule', '?')] += 1
n = len(err_rules)
used = ', '.join(f'{k} {v}' for k, v in rules.most_common())
print(f'{sys.argv[3]:<30} {n:8d} {statistics.mean(err_rand):9.2f}m {statistics.mean(err_rules):9.2f}m '
      f'{statistics.median(ape_rand):9.0f}% {statistics.median(ape_rules):10.0f}%  {used}')
PY
  done
done
