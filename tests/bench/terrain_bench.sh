#!/usr/bin/env bash
# Terrain benchmark (issue 22), run by hand (never from ctest), on Monaco with its SRTM3 tile:
#  1. parse: median wall seconds and peak RSS (GNU time) of RUNS runs without --dem, with --dem
#     and with --dem --dem-resolution 2, and their ratio to the run without.
#  2. render: median render_seconds (--stats) of RUNS runs of the day view from the sea
#     (scripts/gallery.sh's monaco_sea camera, 480x270, 16 spp, no denoising) of the flat scene,
#     the DEM scene with stored terrain and with --geometry-terrain procedural, the terrain's
#     buffer_bytes_terrain (--print-memory-info) and their ratios.
#  3. the fit, from --geojson with z (docs/terrain.md "In the GeoJSON") against the DEM itself
#     (the .hgt read from the zip, bilinear): the largest z step between road, joint and sidewalk
#     pieces at shared vertices; building vertices above the lowest road or land-cover vertex
#     within 2 m; road grade p50/p99 beside the DEM's slope along the same segments; the RMS of
#     land-cover vertices beyond 10 m from any road vertex against the DEM.
#
#   tests/bench/terrain_bench.sh [OSM [DEM]]   (RUNS=5; OSMPARSE=, RENDER= to measure other builds)
set -euo pipefail
args=()
for f in "$@"; do args+=("$(realpath "$f")"); done  # named from where it was called
cd "$(dirname "$0")/../.."
osm=${args[0]:-../shared/data/osm/monaco.osm.pbf}
dem=${args[1]:-../shared/data/dem/N43E007.hgt.zip}
runs=${RUNS:-5}
osmparse=${OSMPARSE:-build/bin/osmparse}
render=${RENDER:-build/bin/render}
for tool in "$osmparse" "$render" /usr/bin/time python3; do
    command -v "$tool" > /dev/null || { echo "terrain_bench.sh: $tool not found (build first)" >&2; exit 1; }
done
for f in "$osm" "$dem"; do [ -f "$f" ] || { echo "terrain_bench.sh: $f not found" >&2; exit 1; }; done
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

median() { sort -g | awk '{ a[NR] = $1 } END { print (NR % 2) ? a[(NR + 1) / 2] : (a[NR / 2] + a[NR / 2 + 1]) / 2 }'; }
ratio() { awk -v a="$1" -v b="$2" 'BEGIN { printf "%.2f", a / b }'; }

echo "terrain benchmark: $(basename "$osm") with $(basename "$dem"), median of $runs runs, $(nproc) cores"
echo "osmparse: $osmparse; render: $render"
echo

# Part 1: parse. Each round runs the three variants one after the other, so load slows them alike.
parse_names=(no-dem dem dem-res-2)
parse_args() {
    case $1 in
        no-dem) ;;
        dem) echo "--dem $dem" ;;
        dem-res-2) echo "--dem $dem --dem-resolution 2" ;;
    esac
}
for run in $(seq "$runs"); do
    for name in "${parse_names[@]}"; do
        # shellcheck disable=SC2046  # parse_args gives whole words without spaces
        /usr/bin/time -f '%e %M' -o "$work/time" "$osmparse" -q "$osm" -o "$work/$name.scene" $(parse_args "$name")
        tail -1 "$work/time" >> "$work/parse.$name"
    done
done
echo "Part 1, parse (wall s and peak RSS from /usr/bin/time -f '%e %M'; goal <= 1.3x without --dem):"
echo "| run | command | s | x no-dem | peak MB | x no-dem |"
echo "|---|---|---|---|---|---|"
base_s=$(awk '{ print $1 }' "$work/parse.no-dem" | median)
base_kb=$(awk '{ print $2 }' "$work/parse.no-dem" | median)
for name in "${parse_names[@]}"; do
    s=$(awk '{ print $1 }' "$work/parse.$name" | median)
    kb=$(awk '{ print $2 }' "$work/parse.$name" | median)
    printf '| %s | `osmparse %s -o %s.scene%s` | %.2f | %s | %.1f | %s |\n' "$name" "$(basename "$osm")" "$name" \
        "$(parse_args "$name" | sed "s|$dem|$(basename "$dem")|; s|^.|  &|" | sed 's|^  | |')" "$s" "$(ratio "$s" "$base_s")" \
        "$(awk -v k="$kb" 'BEGIN { print k / 1024 }')" "$(ratio "$kb" "$base_kb")"
done
echo

# Part 2: render the view from the sea.
view=(--width 480 --height 270 --spp 16 -q --camera 700,-1500,120 --look-at -150,-650,50 --stats --print-memory-info)
render_names=(no-dem stored procedural)
render_scene() { case $1 in no-dem) echo no-dem ;; *) echo dem ;; esac; }
render_args() { case $1 in procedural) echo "--geometry-terrain procedural" ;; esac; }
for run in $(seq "$runs"); do
    for name in "${render_names[@]}"; do
        # shellcheck disable=SC2046
        "$render" "$work/$(render_scene "$name").scene" -o "$work/$name.png" "${view[@]}" $(render_args "$name") \
            > "$work/render.$name.$run" 2>&1
    done
done
value() { grep "^$1:" "$2" | head -1 | awk '{ print $2 }'; }
echo "Part 2, render (render_seconds from --stats, buffer_bytes_terrain from --print-memory-info; goal <= 1.3x):"
echo "render SCENE -o out.png ${view[*]} [--geometry-terrain procedural]"
echo "| run | scene, options | s | x no-dem | terrain bytes | x stored |"
echo "|---|---|---|---|---|---|"
base_s=$(for run in $(seq "$runs"); do value render_seconds "$work/render.no-dem.$run"; done | median)
stored_bytes=$(value buffer_bytes_terrain "$work/render.stored.1")
for name in "${render_names[@]}"; do
    s=$(for run in $(seq "$runs"); do value render_seconds "$work/render.$name.$run"; done | median)
    bytes=$(value buffer_bytes_terrain "$work/render.$name.1")
    printf '| %s | %s.scene %s | %.3f | %s | %s | %s |\n' "$name" "$(render_scene "$name")" "$(render_args "$name")" \
        "$s" "$(ratio "$s" "$base_s")" "$bytes" "$(ratio "$bytes" "$stored_bytes")"
done
echo

# Part 3: the fit, from the GeoJSON of the native-resolution DEM scene.
"$osmparse" -q "$osm" -o "$work/fit.scene" --dem "$dem" --geojson "$work/fit.geojson"
echo "Part 3, the fit: osmparse $(basename "$osm") -o fit.scene --dem $(basename "$dem") --geojson fit.geojson"
python3 - "$work/fit.geojson" "$dem" <<'PY'
import json, math, re, struct, sys, zipfile
from collections import defaultdict

features = json.load(open(sys.argv[1]))["features"]
zpath = sys.argv[2]

# SRTM3: 1201 x 1201 big-endian int16, rows north to south, the tile named by its south-west corner.
with zipfile.ZipFile(zpath) as z:
    name = next(n for n in z.namelist() if n.lower().endswith(".hgt"))
    raw = z.read(name)
m = re.match(r"([NS])(\d+)([EW])(\d+)", name.split("/")[-1].upper())
south = int(m.group(2)) * (1 if m.group(1) == "N" else -1)
west = int(m.group(4)) * (1 if m.group(3) == "E" else -1)
size = int(math.isqrt(len(raw) // 2))
cells = size - 1
heights = struct.unpack(">%dh" % (size * size), raw)

def dem(lon, lat):
    x = (lon - west) * cells
    y = (south + 1 - lat) * cells
    c, r = min(int(x), cells - 1), min(int(y), cells - 1)
    fx, fy = x - c, y - r
    h = lambda rr, cc: heights[rr * size + cc]
    return ((h(r, c) * (1 - fx) + h(r, c + 1) * fx) * (1 - fy)
            + (h(r + 1, c) * (1 - fx) + h(r + 1, c + 1) * fx) * fy)

def rings(f):
    g = f["geometry"]
    if g["type"] == "Polygon":
        return g["coordinates"]
    if g["type"] == "MultiPolygon":
        return [r for p in g["coordinates"] for r in p]
    return []

if not features or len((rings(features[0]) or [[features[0]["geometry"]["coordinates"]]])[0][0]) < 3:
    sys.exit("terrain_bench.sh: the GeoJSON has no z (an osmparse without GeoJSON z, or no field)")

lat0 = math.radians(sum(c[1] for f in features[:200] for r in rings(f) for c in r) /
                    max(1, sum(len(r) for f in features[:200] for r in rings(f))))
M_LAT = 111320.0
M_LON = 111320.0 * math.cos(lat0)
def metres(a, b):
    return math.hypot((a[0] - b[0]) * M_LON, (a[1] - b[1]) * M_LAT)

class Grid:  # points bucketed in cells of `cell` metres, for "within d metres"
    def __init__(self, cell):
        self.cell, self.cells = cell, defaultdict(list)
    def key(self, p):
        return (int(math.floor(p[0] * M_LON / self.cell)), int(math.floor(p[1] * M_LAT / self.cell)))
    def add(self, p):
        self.cells[self.key(p)].append(p)
    def near(self, p, d):
        kx, ky = self.key(p)
        for i in (-1, 0, 1):
            for j in (-1, 0, 1):
                for q in self.cells.get((kx + i, ky + j), ()):
                    if metres(p, q) <= d:
                        yield q

kinds = defaultdict(list)
for f in features:
    kinds[f["properties"].get("kind")].append(f)

# Steps: vertices of different road/joint/sidewalk pieces at the same lon/lat (1e-7 deg).
pieces = kinds["road"] + kinds["joint"] + kinds["sidewalk"]
at = defaultdict(list)
for i, f in enumerate(pieces):
    for r in rings(f):
        for c in r:
            at[(round(c[0] * 1e7), round(c[1] * 1e7))].append((i, c[2]))
step, shared = 0.0, 0
for key, zs in at.items():
    if len({i for i, _ in zs}) < 2:
        continue
    shared += 1
    step = max(step, max(z for _, z in zs) - min(z for _, z in zs))

# Buildings: vertex z above the lowest road or land-cover vertex within 2 m.
ground = Grid(2.0)
for f in kinds["road"] + kinds["joint"] + kinds["land_cover"]:
    for r in rings(f):
        for c in r:
            ground.add(c)
gaps = []
for f in kinds["building"]:
    for r in rings(f):
        for c in r[:-1]:
            near = [q[2] for q in ground.near(c, 2.0)]
            if near:
                gaps.append(c[2] - min(near))
gaps.sort()

# A road quad's four sides: the two along it give its grade (beside the DEM's slope on the same
# sides), the two across it (the shorter pair) its cross-slope, which the fit makes level.
# Sides under 1 m are left out: a millimetre of rounding there is a large grade.
grades, dem_grades, cross = [], [], []
road_vertices = Grid(10.0)
for f in kinds["road"]:
    for r in rings(f):
        for c in r:
            road_vertices.add(c)
        if len(r) != 5:
            continue
        sides = [(r[k], r[k + 1]) for k in range(4)]
        lengths = [metres(a, b) for a, b in sides]
        across = (1, 3) if lengths[1] + lengths[3] < lengths[0] + lengths[2] else (0, 2)
        for k, (a, b) in enumerate(sides):
            h = lengths[k]
            if h < 1.0:
                continue
            if k in across:
                cross.append(abs(b[2] - a[2]) / h)
            else:
                grades.append(abs(b[2] - a[2]) / h)
                dem_grades.append(abs(dem(b[0], b[1]) - dem(a[0], a[1])) / h)

# Land cover vertices away from roads against the DEM; apart, the classes the fit sets on purpose
# (water levelled at its shore, the sea and the piers and quays raised above it: paved).
diffs, by_class = [], defaultdict(list)
for f in kinds["land_cover"]:
    for r in rings(f):
        for c in r[:-1]:
            if next(road_vertices.near(c, 10.0), None) is None:
                d = c[2] - dem(c[0], c[1])
                diffs.append(d)
                by_class[f["properties"]["class"]].append(d)

def pct(v, p):
    v = sorted(v)
    return v[min(len(v) - 1, int(p / 100 * len(v)))] if v else float("nan")

print("| measure | value | n | goal |")
print("|---|---|---|---|")
print("| largest step between road/joint/sidewalk pieces at shared vertices | %.3f m | %d shared points | <= 0.01 m |" % (step, shared))
if gaps:
    print("| building vertex z - lowest road/land-cover vertex z within 2 m: max | %.3f m | %d vertices | <= 0.05 m (wall foot) |" % (gaps[-1], len(gaps)))
    print("| the same: min, p50, p99 | %.3f / %.3f / %.3f m | | |" % (gaps[0], pct(gaps, 50), pct(gaps, 99)))
print("| road grade along p50 / p99 (abs dz / length of a quad's sides along the road) | %.1f%% / %.1f%% | %d sides | |" % (100 * pct(grades, 50), 100 * pct(grades, 99), len(grades)))
print("| DEM slope along the same sides p50 / p99 | %.1f%% / %.1f%% | | |" % (100 * pct(dem_grades, 50), 100 * pct(dem_grades, 99)))
print("| road cross-slope p50 / p99 / max (the quad's ends) | %.2f%% / %.2f%% / %.1f%% | %d ends | level |" % (100 * pct(cross, 50), 100 * pct(cross, 99), 100 * max(cross or [0]), len(cross)))
if diffs:
    rms = math.sqrt(sum(d * d for d in diffs) / len(diffs))
    mean = sum(diffs) / len(diffs)
    print("| land cover z - DEM, vertices beyond 10 m of any road vertex: RMS (mean) | %.2f m (%+.2f) | %d vertices | <= 0.5 m beyond resampling |" % (rms, mean, len(diffs)))
    for cover in sorted(by_class):
        v = by_class[cover]
        print("| the same, %s | %.2f m (%+.2f) | %d vertices | |" % (cover, math.sqrt(sum(d * d for d in v) / len(v)), sum(v) / len(v), len(v)))
print()
print("The DEM is %s read bilinearly (%d x %d posts). The RMS includes the field's resampling of the" % (name, size, size))
print("tile to its grid (81 m at native resolution) and the cell triangles (ground_height) against the")
print("bilinear DEM. Building vertices stand at the footprint's lowest ground, so uphill vertices sit")
print("below the ground near them (negative values) by design; the positive maximum is the one that")
print("would show a gap, but a road or land-cover vertex within 2 m may lie outside the footprint,")
print("downhill, or on a road cut, so it is not the ground under the wall: an upper bound, not the gap.")
PY
echo
echo "load average at the end: $(cut -d' ' -f1-3 /proc/loadavg)"
