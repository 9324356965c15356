#!/usr/bin/env bash
# Parses a region too large for one machine on a Slurm cluster: cuts it into C x R tiles, each
# extracted with an overlap around its core box (one osmium extract job, one pass over the
# input), then parses every tile in one shared frame as a job array (osmparse --origin, and
# --keep-inside its core box, so an object that crosses a tile edge is kept by one tile only).
# Before that, two shorter job arrays gather the statistics the height and roof rules read of
# the whole region (osmparse --write-region-statistics, each tile over its core box): the first
# the tagged heights, the second the roof tags, whose groups depend on the heights the first
# gives; each tile's parse reads every tile's (--region-statistics, summed), as one parse would.
# render loads the tile scenes as one city: render OUTDIR/tile_*.scene -o city.png (docs/farm.md).
#
#   scripts/farm/parse_farm.sh REGION.osm.pbf OUTDIR --tiles CxR [farm options] [-- osmparse options]
#
# Writes OUTDIR/tile_R_C.scene (row R from the south, column C from the west) and, when every
# tile is parsed, OUTDIR/tiles.txt (the scenes, one a line). With terrain, give osmparse both
# --dem and --dem-resolution (render joins the tiles' fields only on one grid). Farm options:
#   --tiles CxR             C columns (west to east) and R rows (south to north); required
#   --overlap M             metres of data beyond each core box (default 500): what lies near a
#                           core edge must be parsed from the same data as in one whole parse
#   --origin LAT,LON        the shared origin (default: the centre of the region's bounds)
#   --partition NAME        Slurm partition (default: the cluster's default)
#   --time-per-task T       Slurm time limit of one task, e.g. 01:00:00
#   --cpus-per-task N       threads of each osmparse (default 1)
#   --work DIR              extracts, task list and logs (default: OUTDIR/farm)
#   --osmparse BIN          the osmparse program as the nodes see it (default: this checkout's build/bin/osmparse)
#   --wait                  return only when every tile is parsed, with the status
# On a real cluster REGION, OUTDIR, --work and the program must be on a file system every node
# mounts at the same path (all paths are made absolute here). Prints the job ids.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)

die() { echo "parse_farm: $*" >&2; exit 1; }
[ $# -ge 2 ] || die "usage: $0 REGION.osm.pbf OUTDIR --tiles CxR [farm options] [-- osmparse options] (see the script's header)"
absolute() { case "$1" in /*) echo "$1" ;; *) echo "$(pwd)/$1" ;; esac; }
region=$(absolute "$1")
out=$(absolute "$2")
shift 2

tiles="" overlap=500 origin="" partition="" task_time="" cpus=1 work="" wait=0
osmparse="$here/../../build/bin/osmparse"
while [ $# -gt 0 ]; do
  case "$1" in
    --tiles) tiles=$2; shift 2 ;;
    --overlap) overlap=$2; shift 2 ;;
    --origin) origin=$2; shift 2 ;;
    --partition) partition=$2; shift 2 ;;
    --time-per-task) task_time=$2; shift 2 ;;
    --cpus-per-task) cpus=$2; shift 2 ;;
    --work) work=$(absolute "$2"); shift 2 ;;
    --osmparse) osmparse=$(absolute "$2"); shift 2 ;;
    --wait) wait=1; shift ;;
    --) shift; break ;;
    *) die "unknown option '$1' (osmparse options go after --)" ;;
  esac
done
parse_options=("$@")
osmparse=$(cd "$(dirname "$osmparse")" && pwd)/$(basename "$osmparse")

[ -f "$region" ] || die "$region: no such file"
[ -x "$osmparse" ] || die "$osmparse: no osmparse program (build it, or give --osmparse)"
command -v osmium > /dev/null || die "osmium not found (osmium-tool cuts the tiles)"
command -v sbatch > /dev/null || die "sbatch not found: this script submits to Slurm"
[[ "$tiles" =~ ^([1-9][0-9]*)x([1-9][0-9]*)$ ]] || die "--tiles: expected CxR, e.g. 2x2"
columns=${BASH_REMATCH[1]} rows=${BASH_REMATCH[2]}
[[ "$overlap" =~ ^[0-9]+([.][0-9]+)?$ ]] || die "--overlap: a number of metres"
[[ "$cpus" =~ ^[1-9][0-9]*$ ]] || die "--cpus-per-task: a positive integer"
dem=0 dem_resolution=0
for option in "${parse_options[@]}"; do
  case "$option" in
    -o|--output|--origin|--keep-inside|--geojson|--region-statistics|--write-region-statistics)
      die "osmparse option $option is the farm's own" ;;
    --dem|--dem=*) dem=1 ;;
    --dem-resolution|--dem-resolution=*) dem_resolution=1 ;;
  esac
done
# Each tile's default cell follows its own extract's size: render joins the tiles' terrain only
# on one grid.
[ $dem = 0 ] || [ $dem_resolution = 1 ] || die "--dem on the farm needs --dem-resolution M: every tile's terrain on one grid"

# The region's bounds: the file header's box (an extract's), or the nodes' (osmium reads them all).
bounds=$(osmium fileinfo -g header.boxes "$region" 2> /dev/null | head -n 1)
[ -n "$bounds" ] || bounds=$(osmium fileinfo -e -g data.bbox "$region") || die "$region: osmium cannot read it"
[[ "$bounds" =~ ^\(([-0-9.]+),([-0-9.]+),([-0-9.]+),([-0-9.]+)\)$ ]] || die "$region: no bounds (no nodes?)"
min_lon=${BASH_REMATCH[1]} min_lat=${BASH_REMATCH[2]} max_lon=${BASH_REMATCH[3]} max_lat=${BASH_REMATCH[4]}
if [ -z "$origin" ]; then
  origin=$(awk -v a="$min_lat" -v b="$max_lat" -v c="$min_lon" -v d="$max_lon" 'BEGIN { printf "%.7f,%.7f", (a + b) / 2, (c + d) / 2 }')
fi
[[ "$origin" =~ ^-?[0-9.]+,-?[0-9.]+$ ]] || die "--origin: expected LAT,LON"

mkdir -p "$out" || die "$out: cannot create"
work=${work:-$out/farm}
mkdir -p "$work/logs" "$work/extracts" || die "$work: cannot create"

# The tiles' edges, each printed once, so neighbours share it to the digit. The outer edges are the
# world's: an anchor a little beyond the data (a lamp beside the last road) still has a tile.
# Each extract reaches `overlap` metres beyond its core (degrees of longitude at the widest
# latitude of the region), clamped to the region's bounds.
awk -v columns="$columns" -v rows="$rows" -v overlap="$overlap" -v a="$min_lat" -v b="$max_lat" \
    -v c="$min_lon" -v d="$max_lon" -v dir="$work/extracts" -v out="$out" '
  function max(x, y) { return x > y ? x : y }
  function min(x, y) { return x < y ? x : y }
  BEGIN {
    pi = atan2(0, -1)
    dlat = overlap / 111320
    widest = max(a < 0 ? -a : a, b < 0 ? -b : b)
    dlon = overlap / (111320 * cos(min(widest, 89) * pi / 180))
    for (r = 0; r <= rows; ++r) lat[r] = sprintf("%.9f", a + r * (b - a) / rows)
    for (k = 0; k <= columns; ++k) lon[k] = sprintf("%.9f", c + k * (d - c) / columns)
    lat[0] = "-90"; lat[rows] = "90"; lon[0] = "-180"; lon[columns] = "180"
    config = dir "/extracts.json"
    printf "{\"directory\": \"%s\", \"extracts\": [", dir > config
    for (r = 0; r < rows; ++r)
      for (k = 0; k < columns; ++k) {
        s = max(a, lat[r] - dlat); n = min(b, lat[r + 1] + dlat)
        w = max(c, lon[k] - dlon); e = min(d, lon[k + 1] + dlon)
        name = "tile_" r "_" k
        printf "%s{\"output\": \"%s.osm.pbf\", \"bbox\": [%.9f, %.9f, %.9f, %.9f]}", (r + k > 0 ? ", " : ""), name, w, s, e, n > config
        # name, core box for --keep-inside, extract file, scene
        print name, lat[r] "," lon[k] "," lat[r + 1] "," lon[k + 1], dir "/" name ".osm.pbf", out "/" name ".scene"
      }
    print "]}" > config
  }' > "$work/tiles.txt"
count=$(wc -l < "$work/tiles.txt")

# One osmparse per line, each word quoted: the task lists of the two statistics passes and the
# parse. Pass 2 reads every tile's pass 1 statistics (osmparse sums them), the parse pass 2's.
mkdir -p "$work/statistics" || die "$work/statistics: cannot create"
rm -f "$work/statistics/"*.stats
every_tile() {  # --region-statistics for each tile's file of pass $1
  while read -r name _; do printf -- '--region-statistics\n%s\n' "$work/statistics/${name}_$1.stats"; done < "$work/tiles.txt"
}
mapfile -t pass_1 < <(every_tile 1)
mapfile -t pass_2 < <(every_tile 2)
: > "$work/statistics_1.txt"
: > "$work/statistics_2.txt"
: > "$work/tasks.txt"
while read -r name box extract scene; do
  tile=(--origin "$origin" --keep-inside "$box" --threads "$cpus" "${parse_options[@]}")
  echo "$(printf '%q ' "$osmparse" "$extract" --write-region-statistics "$work/statistics/${name}_1.stats" \
    "${tile[@]}")" >> "$work/statistics_1.txt"
  echo "$(printf '%q ' "$osmparse" "$extract" --write-region-statistics "$work/statistics/${name}_2.stats" \
    "${pass_1[@]}" "${tile[@]}")" >> "$work/statistics_2.txt"
  echo "$(printf '%q ' "$osmparse" "$extract" -o "$scene" "${pass_2[@]}" "${tile[@]}")" >> "$work/tasks.txt"
done < "$work/tiles.txt"

sbatch_common=(--parsable --chdir "$work")
[ -n "$partition" ] && sbatch_common+=(--partition "$partition")
[ -n "$task_time" ] && sbatch_common+=(--time "$task_time")
job_name=citygen-parse-$(basename "$out" | tr -c 'A-Za-z0-9_\n-' '_')

# smart: ways whole with all their nodes, multipolygons whole with all their members, so an
# object in two tiles is the same object in both. One pass over the region for every tile.
cat > "$work/extract.sh" << EOF
#!/usr/bin/env bash
set -euo pipefail
start=\$(date +%s.%N)
osmium extract --overwrite --strategy smart --set-bounds --config $(printf '%q' "$work/extracts/extracts.json") $(printf '%q' "$region")
echo "cut $count tiles in \$(awk -v a="\$start" -v b="\$(date +%s.%N)" 'BEGIN { printf "%.2f", b - a }') s"
EOF
# Slurm runs a copy of the job script from its spool directory: name the task list by its path.
cat > "$work/task.sh" << EOF
#!/usr/bin/env bash
# One array task: line SLURM_ARRAY_TASK_ID + 1 of the task list \$1.
set -euo pipefail
line=\$(sed -n "\$((SLURM_ARRAY_TASK_ID + 1))p" "\$1")
[ -n "\$line" ] || { echo "no task \$SLURM_ARRAY_TASK_ID in \$1" >&2; exit 1; }
echo "task \$SLURM_ARRAY_TASK_ID on \$(hostname): \$line"
start=\$(date +%s.%N)
eval "\$line"
echo "parse_seconds: \$(awk -v a="\$start" -v b="\$(date +%s.%N)" 'BEGIN { printf "%.2f", b - a }')"
EOF
{
  echo '#!/usr/bin/env bash'
  echo '# Runs after every tile is parsed: the list render takes.'
  echo 'set -euo pipefail'
  echo "cut -d' ' -f4 $(printf '%q' "$work/tiles.txt") > $(printf '%q' "$out/tiles.txt.partial")"
  echo "mv $(printf '%q' "$out/tiles.txt.partial") $(printf '%q' "$out/tiles.txt")"
  echo "touch $(printf '%q' "$work/parse.done")"
} > "$work/done.sh"
chmod +x "$work/extract.sh" "$work/task.sh" "$work/done.sh"
rm -f "$work/parse.done" "$out/tiles.txt"

extract_job=$(sbatch "${sbatch_common[@]}" --job-name "$job_name-extract" --cpus-per-task 1 \
  --output "$work/logs/extract.log" "$work/extract.sh")
echo "parse_farm: origin $origin, $count tiles of $bounds with ${overlap} m overlap"
echo "parse_farm: extract job $extract_job"
# Each array runs after the last one succeeded: statistics pass 1, pass 2, the parse.
after=$extract_job
for pass in 1 2; do
  after=$(sbatch "${sbatch_common[@]}" --job-name "$job_name-statistics-$pass" --array "0-$((count - 1))" \
    --cpus-per-task "$cpus" --dependency "afterok:$after" --kill-on-invalid-dep=yes \
    --output "$work/logs/statistics_${pass}_%a.log" "$work/task.sh" "$work/statistics_$pass.txt")
  echo "parse_farm: region statistics pass $pass: array job $after"
done
array_job=$(sbatch "${sbatch_common[@]}" --job-name "$job_name" --array "0-$((count - 1))" --cpus-per-task "$cpus" \
  --dependency "afterok:$after" --kill-on-invalid-dep=yes --output "$work/logs/task_%a.log" "$work/task.sh" \
  "$work/tasks.txt")
echo "parse_farm: array job $array_job ($count tasks); logs in $work/logs"
done_job=$(sbatch "${sbatch_common[@]}" --job-name "$job_name-done" --dependency "afterok:$array_job" \
  --kill-on-invalid-dep=yes --output "$work/logs/done.log" "$work/done.sh")
echo "parse_farm: done job $done_job"
if [ "$wait" -eq 1 ]; then
  # As render_farm.sh: until the last job has left the queue; only its file says it succeeded.
  while squeue -h -j "$done_job" -o %T 2> /dev/null | grep -qE 'PENDING|CONFIGURING|RUNNING|COMPLETING'; do
    sleep 0.5
  done
  [ -f "$work/parse.done" ] || die "a job failed or was cancelled (logs in $work/logs)"
  echo "parse_farm: done: $out/tiles.txt"
fi
