#!/usr/bin/env bash
# Height benchmark, run by hand (never from ctest): how well osmparse guesses the height of a
# building the map gives none. Each extract is parsed twice: as it is (the truth: whole buildings
# on the ground whose height or building:levels is tagged; a last row per protocol adds the
# building:parts and raised buildings) and with --hide-height-tags (every height-like tag
# forgotten), then with half of the buildings' tags hidden, where the rules can use the tagged
# neighbours; both once per seed in HALF_SEEDS (default 1..12), errors pooled: the seed picks the
# hidden half, each guess's +-10% jitter and the old random height, and the tagged samples are
# small (65 and 17 buildings), so one seed's figure moves by metres (the old random guess on
# Kaiserslautern: 20.8 m with seed 1, 18.2 m over seeds 1..12). Prints, per extract and protocol
# and per rule that decided, the error over the hidden buildings of today's rules beside the old
# seeded random height in [8, 30] m (the formula it used, recomputed here for the same buildings
# and seed): mean and median absolute error.
#
# Every extract is one city: per city the mean error, its ratio to the random guess's (the targets:
# at most 0.7 with every tag hidden, 0.5 with half), and the rules that decided. An extract with
# fewer than MIN_TAGGED (default 15) tagged whole buildings is too small a sample and is skipped.
# Then leave-one-city-out for the constants the bench can refit without a rebuild: a scale for
# each group of the type-and-area rules (kBaseLevels for the fabric rule, the type table's
# heights for the others, in osmparse/buildings/infer_heights.cpp), fitted as the median over cities
# (each city's median ratio truth / guess with every tag hidden, one vote per city with at least
# 10 such guesses): for each city, the scale fitted on the other cities multiplies the built
# rules (exact with every tag hidden, where nothing in the extract calibrates them; with half
# hidden it is applied to the guesses of the type-and-area rules only, before the extract's own
# calibration, so it overstates the change there). A city's own figure is the "LOO" column.
#
#   tests/bench/height_bench.sh [FILE ...]   (default: every extract in ../shared/data/osm, or $OSM_DATA)
#   OSMPARSE=/path/to/old/osmparse tests/bench/height_bench.sh   (measure another build)
set -euo pipefail
files=()
for f in "$@"; do files+=("$(realpath "$f")"); done  # named from where it was called
cd "$(dirname "$0")/../.."
osmparse=${OSMPARSE:-build/bin/osmparse}
[ -x "$osmparse" ] || { echo "height_bench.sh: build first ($osmparse missing)" >&2; exit 1; }
data=${OSM_DATA:-../shared/data/osm}  # OSM_DATA: where the extracts are, when not beside the repository
[ ${#files[@]} -gt 0 ] || files=("$data"/monaco.osm.pbf "$data"/kaiserslautern.osm.gz "$data"/malta.osm.pbf
                                  "$data"/osm2streets/*/input.osm)
min_tagged=${MIN_TAGGED:-15}
half_seeds=${HALF_SEEDS:-1 2 3 4 5 6 7 8 9 10 11 12}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
printf '%-34s %8s %10s %10s %6s %10s %10s\n' "extract, protocol, rule" buildings "MAE random" "MAE rules" ratio "MdAE rand" "MdAE rules"
for f in "${files[@]}"; do
    name=$(basename "$f")
    [ "$name" = input.osm ] && name=$(basename "$(dirname "$f")")
    "$osmparse" --quiet "$f" -o "$work/truth.scene" --geojson "$work/truth.geojson"
    for seed in $half_seeds; do
        "$osmparse" --quiet "$f" -o "$work/hidden.scene" --geojson "$work/hide_1_$seed.geojson" \
            --hide-height-tags 1 --seed "$seed"
        "$osmparse" --quiet "$f" -o "$work/hidden.scene" --geojson "$work/hide_0.5_$seed.geojson" \
            --hide-height-tags 0.5 --seed "$seed"
    done
    mkdir -p "$work/$name"
    mv "$work"/truth.geojson "$work"/hide_*.geojson "$work/$name/"
    python3 - "$work/$name" "$name" "$min_tagged" $half_seeds <<'PY'
import json, math, sys, statistics
from collections import defaultdict

M = (1 << 64) - 1
def mix64(z):
    z = (z + 0x9e3779b97f4a7c15) & M
    z = ((z ^ (z >> 30)) * 0xbf58476d1ce4e5b9) & M
    z = ((z ^ (z >> 27)) * 0x94d049bb133111eb) & M
    return z ^ (z >> 31)
def old_random_height(osm, seed, lo=8.0, hi=30.0):
    # hash_keys(seed, type, id) and hash_to_unit from common/rng.h, as the old rule used them.
    kind = {'n': 0, 'w': 1, 'r': 2}[osm[0]]
    h = mix64(seed ^ mix64(kind))
    h = mix64(h ^ mix64(int(osm[1:]) & M))
    h = mix64(h)
    return lo + (h >> 11) * 2.0 ** -53 * (hi - lo)

HOUSES = {'house', 'detached', 'semidetached_house', 'terrace', 'bungalow', 'villa'}
SHEDS = {'garage', 'garages', 'carport', 'shed', 'kiosk', 'hut', 'toilets', 'transformer_tower', 'service',
         'greenhouse', 'cabin', 'farm_auxiliary', 'barn', 'stable', 'cowshed', 'farm'}
HOMES = {'apartments', 'residential', 'dormitory'}
FABRIC = {'yes', 'building', '', 'office', 'commercial', 'civic', 'public', 'government'}
def footprint(geometry):
    """Area (m2) and plan depth 2 area / perimeter of the outer ring, projected locally."""
    ring = geometry['coordinates'][0]
    lat0 = ring[0][1]
    kx, ky = 111320 * math.cos(math.radians(lat0)), 110540
    pts = [(x * kx, y * ky) for x, y in ring]
    a = sum(pts[i][0] * pts[i + 1][1] - pts[i + 1][0] * pts[i][1] for i in range(len(pts) - 1)) / 2
    per = sum(math.dist(pts[i], pts[i + 1]) for i in range(len(pts) - 1))
    return abs(a), (2 * abs(a) / per if per else 0)
def group(p, area, depth):
    """The group of osmparse's type-and-area rules (PriorGroup) as the bench can tell it from
    the type and the footprint (the point blocks by their depth and plan area, holes
    ignored)."""
    t = p['type']
    if area > 1000 and t in HOUSES: t = 'residential'
    if area < 30 or t in SHEDS: return 'shed'
    if t in HOUSES: return 'houses'
    if t in HOMES: return 'tower' if depth >= 13 and area <= 2000 else 'flats'
    if t in FABRIC: return 'fabric'
    return 'other types'

def buildings(path, geometry=False):
    out = {}
    for feat in json.load(open(path))['features']:
        p = feat['properties']
        if p.get('kind') != 'building': continue
        if geometry: p['area'], p['depth'] = footprint(feat['geometry'])
        out.setdefault(p['osm'], []).append(p)
    return out

work, name, min_tagged, half_seeds = sys.argv[1], sys.argv[2], int(sys.argv[3]), [int(s) for s in sys.argv[4:]]
truth = buildings(f'{work}/truth.geojson', geometry=True)
tagged = sum(1 for parts in truth.values() for t in parts
             if t['height_source'] != 'random' and not t['part'] and t['min_height'] == 0)
if tagged < min_tagged:
    print(f'{name:<34} {tagged:8d} tagged whole buildings: too few, skipped')
    sys.exit(0)
def errors(hidden, seed, with_parts=False):
    """Per building whose tags were hidden: rule, group, guess, truth, the old random guess. The
    truth: whole buildings standing on the ground whose height comes from their own tags;
    with_parts adds building:parts and raised buildings (their tops: the guess stands on the
    ground once min_height is hidden too)."""
    out = []
    for osm, parts in truth.items():
        if osm not in hidden or len(hidden[osm]) != len(parts): continue
        for t, h in zip(parts, hidden[osm]):
            if t['height_source'] == 'random': continue
            if not with_parts and (t['part'] or t['min_height'] > 0): continue
            if h['height_source'] != 'random': continue  # this one kept its tags
            out.append((h.get('height_rule', '?'), group(t, t['area'], t['depth']), h['height'], t['height'],
                        old_random_height(osm, seed)))
    return out
def row(label, errs):
    if not errs: return
    rules = [abs(e[2] - e[3]) for e in errs]
    rand = [abs(e[4] - e[3]) for e in errs]
    print(f'{label:<34} {len(errs):8d} {statistics.mean(rand):9.2f}m {statistics.mean(rules):9.2f}m '
          f'{statistics.mean(rules) / statistics.mean(rand):6.2f} '
          f'{statistics.median(rand):9.2f}m {statistics.median(rules):9.2f}m')
record = {}
for protocol, key, runs in [(f'hide 1 x{len(half_seeds)} seeds', 'all', [(f'1_{s}', s) for s in half_seeds]),
                            (f'hide 0.5 x{len(half_seeds)} seeds', 'half', [(f'0.5_{s}', s) for s in half_seeds])]:
    errs, with_parts = [], []
    for tag, seed in runs:
        hidden = buildings(f'{work}/hide_{tag}.geojson')
        errs += errors(hidden, seed)
        with_parts += errors(hidden, seed, with_parts=True)
    row(f'{name}, {protocol}', errs)
    by_rule = defaultdict(list)
    for e in errs:
        by_rule[e[0]].append(e)
        if e[0] == 'type and area': by_rule[f'type and area: {e[1]}'].append(e)
    for rule in sorted(by_rule): row(f'  rule: {rule}', by_rule[rule])
    row('  parts and raised ones too', with_parts)
    record[key] = errs
json.dump(record, open(f'{work}/../{name}.errors.json', 'w'))
PY
done

# Leave one city out: the scale of each group, fitted on the other cities (the median over them
# of each city's median log(truth / guess) with every tag hidden), against the built rules.
python3 - "$work" <<'PY'
import glob, json, math, os, statistics, sys
from collections import defaultdict
work = sys.argv[1]
BUILT = {'houses': 1.0, 'fabric': 1.0, 'flats': 1.0, 'other types': 1.0}  # the built rules: scale 1
MIN_GROUP = 10  # a city's group needs this many buildings to vote
cities = {os.path.basename(f)[:-len('.errors.json')]: json.load(open(f)) for f in sorted(glob.glob(f'{work}/*.errors.json'))}
if len(cities) < 2: sys.exit(0)
votes = defaultdict(dict)  # group -> city -> median log ratio truth / unscaled guess
for city, rec in cities.items():
    by = defaultdict(list)
    for rule, g, guess, truth, rand in rec['all']:
        if rule == 'type and area' and g in BUILT and guess > 0: by[g].append(math.log(truth / (guess / BUILT[g])))
    for g, logs in by.items():
        if len(logs) >= MIN_GROUP: votes[g][city] = statistics.median(logs)
print()
print('scale per group: each city\'s own median truth / rule, every tag hidden')
for g in BUILT:
    v = votes.get(g, {})
    print(f'  {g:<12} ' + '  '.join(f'{c} {math.exp(m):.2f}' for c, m in v.items()) +
          (f'   all: {math.exp(statistics.median(v.values())):.2f} (built {BUILT[g]:.2f})' if v else ''))
print()
print(f'{"leave one city out":<26} {"MAE rand":>9} {"built":>8} {"ratio":>6} {"LOO":>8} {"ratio":>6}   (hide 1 | hide 0.5)')
for city, rec in cities.items():
    scale = {}
    for g in BUILT:
        others = [m for c, m in votes.get(g, {}).items() if c != city]
        scale[g] = math.exp(statistics.median(others)) if others else BUILT[g]
    out = []
    for key in ('all', 'half'):
        errs = rec[key]
        rand = statistics.mean(abs(e[4] - e[3]) for e in errs)
        built = statistics.mean(abs(e[2] - e[3]) for e in errs)
        loo = statistics.mean(abs((e[2] * scale[e[1]] / BUILT[e[1]] if e[0] == 'type and area' and e[1] in BUILT else e[2]) - e[3])
                              for e in errs)
        out.append(f'{rand:8.2f}m {built:7.2f}m {built / rand:6.2f} {loo:7.2f}m {loo / rand:6.2f}')
    print(f'{city:<26} ' + ' | '.join(out))
PY
