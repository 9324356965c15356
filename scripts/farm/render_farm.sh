#!/usr/bin/env bash
# Renders an animation or a tiled still on a Slurm cluster: one job array (a task per range of
# frames, or per tile) and a merge job that runs after every task succeeded (oiiotool pastes the
# tiles; ffmpeg, when the node has it, encodes the frames to a video). A render is a pure function
# of (scene, options, seed), so the result is byte for byte what one machine would make.
#
#   scripts/farm/render_farm.sh SCENE OUTPUT [farm options] [-- render options]
#
# Animation: OUTPUT is a frame pattern (/shared/out/city_%04d.png) and the render options name
# the path (--camera-path FILE or --orbit). Still: --tiles CxR, OUTPUT is the merged image.
# Farm options:
#   --frames A-B            frames to render (animation; required)
#   --frames-per-task N     frames per array task (default 1)
#   --tiles CxR             split a still into C columns and R rows of tiles
#   --width W --height H    frame size, passed on to render (default 1280x720)
#   --fps F                 passed on to render, and the video's rate (default 24)
#   --video FILE            encode the frames to FILE (.mp4, H.264) after the last one, if ffmpeg exists
#   --partition NAME        Slurm partition (default: the cluster's default)
#   --time-per-task T       Slurm time limit of one task, e.g. 00:30:00
#   --work DIR              tiles, task list and logs (default: OUTPUT's directory/farm-JOBNAME)
#   --render BIN            the render program as the nodes see it (default: this checkout's build/bin/render)
#   --wait                  return only when the merge job has ended, with its exit status
# On a real cluster the scene, camera path, render binary, OUTPUT and --work must be on a file
# system every node mounts at the same path (all paths are made absolute here). Prints the job ids.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)

die() { echo "render_farm: $*" >&2; exit 1; }
[ $# -ge 2 ] || die "usage: $0 SCENE OUTPUT [farm options] [-- render options] (see the script's header)"
absolute() { case "$1" in /*) echo "$1" ;; *) echo "$(pwd)/$1" ;; esac; }
scene=$(absolute "$1")
output=$(absolute "$2")
shift 2

frames="" per_task=1 tiles="" width=1280 height=720 fps=24 video="" partition="" task_time="" work="" wait=0
render="$here/../../build/bin/render"
while [ $# -gt 0 ]; do
  case "$1" in
    --frames) frames=$2; shift 2 ;;
    --frames-per-task) per_task=$2; shift 2 ;;
    --tiles) tiles=$2; shift 2 ;;
    --width) width=$2; shift 2 ;;
    --height) height=$2; shift 2 ;;
    --fps) fps=$2; shift 2 ;;
    --video) video=$(absolute "$2"); shift 2 ;;
    --partition) partition=$2; shift 2 ;;
    --time-per-task) task_time=$2; shift 2 ;;
    --work) work=$(absolute "$2"); shift 2 ;;
    --render) render=$(absolute "$2"); shift 2 ;;
    --wait) wait=1; shift ;;
    --) shift; break ;;
    *) die "unknown option '$1' (render options go after --)" ;;
  esac
done
render_options=("$@")
render=$(cd "$(dirname "$render")" && pwd)/$(basename "$render")

[ -f "$scene" ] || die "$scene: no such scene"
[ -x "$render" ] || die "$render: no render program (build it, or give --render)"
command -v sbatch > /dev/null || die "sbatch not found: this script submits to Slurm"
[[ "$width" =~ ^[1-9][0-9]*$ && "$height" =~ ^[1-9][0-9]*$ ]] || die "--width/--height: positive integers"
[[ "$per_task" =~ ^[1-9][0-9]*$ ]] || die "--frames-per-task: a positive integer"
if [ -n "$tiles" ] && [ -n "$frames" ]; then die "--tiles and --frames exclude each other"; fi
if [ -z "$tiles" ] && [ -z "$frames" ]; then die "give --frames A-B (animation) or --tiles CxR (still)"; fi
job_name=citygen-$(basename "${output%.*}" | tr -c 'A-Za-z0-9_\n-' '_')
work=${work:-$(dirname "$output")/farm-$job_name}
mkdir -p "$work/logs" || die "$work: cannot create"
out_dir=$(dirname "$output")
[ -w "$out_dir" ] || die "$out_dir: not writable"

# The render command every task shares, each word quoted for the task list.
base=$(printf '%q ' "$render" "$scene" --width "$width" --height "$height" -q "${render_options[@]}")
tasks="$work/tasks.txt"
: > "$tasks"
if [ -n "$frames" ]; then
  [[ "$frames" =~ ^([0-9]+)-([0-9]+)$ ]] || die "--frames: expected A-B"
  first=${BASH_REMATCH[1]} last=${BASH_REMATCH[2]}
  [ "$first" -le "$last" ] || die "--frames: A must not exceed B"
  for ((a = first; a <= last; a += per_task)); do
    b=$((a + per_task - 1 > last ? last : a + per_task - 1))
    echo "$base --fps $(printf '%q' "$fps") --frames $a-$b -o $(printf '%q' "$output")" >> "$tasks"
  done
else
  [[ "$tiles" =~ ^([1-9][0-9]*)x([1-9][0-9]*)$ ]] || die "--tiles: expected CxR, e.g. 2x2"
  columns=${BASH_REMATCH[1]} rows=${BASH_REMATCH[2]}
  [ "$columns" -le "$width" ] && [ "$rows" -le "$height" ] || die "--tiles: more tiles than pixels"
  extension=${output##*.}
  case "$extension" in
    png) canvas=(--create "${width}x${height}" 3) ;;
    # EXR tiles carry their channel names: the first tile, padded to the frame, is the canvas.
    exr) canvas=("$work/tile_0_0.exr" --crop "${width}x${height}+0+0" --fullpixels) ;;
    *) die "--tiles: OUTPUT must be .png (merged byte for byte) or .exr (pixel for pixel)" ;;
  esac
  # Tile edges at i * size / count, so uneven sizes still cover every pixel once.
  paste=()
  for ((r = 0; r < rows; ++r)); do
    for ((c = 0; c < columns; ++c)); do
      x0=$((c * width / columns)) x1=$(((c + 1) * width / columns))
      y0=$((r * height / rows)) y1=$(((r + 1) * height / rows))
      tile="$work/tile_${r}_${c}.$extension"
      echo "$base --region $x0,$y0,$x1,$y1 -o $(printf '%q' "$tile")" >> "$tasks"
      paste+=("$tile" --swap --paste "+$x0+$y0")
    done
  done
fi
count=$(wc -l < "$tasks")

sbatch_common=(--parsable --chdir "$work")
[ -n "$partition" ] && sbatch_common+=(--partition "$partition")

# Slurm runs a copy of the job script from its spool directory: name the task list by its path.
cat > "$work/task.sh" << EOF
#!/usr/bin/env bash
# One array task: line SLURM_ARRAY_TASK_ID + 1 of tasks.txt.
set -euo pipefail
line=\$(sed -n "\$((SLURM_ARRAY_TASK_ID + 1))p" $(printf '%q' "$tasks"))
[ -n "\$line" ] || { echo "no task \$SLURM_ARRAY_TASK_ID in $(printf '%q' "$tasks")" >&2; exit 1; }
echo "task \$SLURM_ARRAY_TASK_ID on \$(hostname): \$line"
eval "\$line"
EOF
chmod +x "$work/task.sh"
task_options=("${sbatch_common[@]}" --job-name "$job_name" --array "0-$((count - 1))" --cpus-per-task 1
              --output "$work/logs/task_%a.log")
[ -n "$task_time" ] && task_options+=(--time "$task_time")
array_job=$(sbatch "${task_options[@]}" "$work/task.sh")

{
  echo '#!/usr/bin/env bash'
  echo '# Runs after every task succeeded.'
  echo 'set -euo pipefail'
  if [ -n "$tiles" ]; then
    # oiiotool pastes the tiles; without its software stamp the file equals a one-machine render.
    # A clean canvas (a PNG read back would bring colour chunks along), the tiles pasted in, no
    # software stamp or date: the PNG equals a one-machine render byte for byte.
    echo "oiiotool --nosoftwareattrib $(printf '%q ' "${canvas[@]}" "${paste[@]}") --attrib DateTime '' -o $(printf '%q' "$output.merging.$extension")"
    echo "mv $(printf '%q' "$output.merging.$extension") $(printf '%q' "$output")"
    echo "echo merged $count tiles into $(printf '%q' "$output")"
  else
    echo "echo rendered frames $frames"
    if [ -n "$video" ]; then
      echo 'if command -v ffmpeg > /dev/null; then'
      echo "  ffmpeg -nostdin -loglevel error -y -framerate $(printf '%q' "$fps") -start_number $first -i $(printf '%q' "$output") -frames:v $((last - first + 1)) -c:v libx264 -pix_fmt yuv420p $(printf '%q' "$video")"
      echo "  echo encoded $(printf '%q' "$video")"
      echo 'else'
      echo '  echo "no ffmpeg on this node: frames only, no video"'
      echo 'fi'
    fi
  fi
  echo "touch $(printf '%q' "$work/merge.done")"
} > "$work/merge.sh"
chmod +x "$work/merge.sh"
merge_options=("${sbatch_common[@]}" --job-name "$job_name-merge" --dependency "afterok:$array_job"
               --kill-on-invalid-dep=yes --output "$work/logs/merge.log")
echo "render_farm: array job $array_job ($count tasks), merge job follows; logs in $work/logs"
rm -f "$work/merge.done"
merge_job=$(sbatch "${merge_options[@]}" "$work/merge.sh")
echo "render_farm: merge job $merge_job"
if [ "$wait" -eq 1 ]; then
  # Until the merge job has left the queue (ended, failed, or cancelled because a task failed);
  # only the file its last line writes says it succeeded (sbatch --wait does not, for a
  # cancelled job, and it polls slowly).
  while squeue -h -j "$merge_job" -o %T 2> /dev/null | grep -qE 'PENDING|CONFIGURING|RUNNING|COMPLETING'; do
    sleep 0.5
  done
  [ -f "$work/merge.done" ] || die "the job failed or was cancelled (logs in $work/logs)"
  echo "render_farm: done"
fi
