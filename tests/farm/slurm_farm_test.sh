#!/usr/bin/env bash
# The farm end to end on a single-node Slurm started here (scripts/farm/local_slurm.sh): 4 frames
# of an orbit (2 array tasks of 2 frames) and a 2x2 tiled still of the tiny fixture, through
# scripts/farm/render_farm.sh, must equal local renders byte for byte. Every daemon started is
# stopped by PID at the end. Exit 77 (ctest: skipped) only when Slurm cannot run on this machine.
#   tests/farm/slurm_farm_test.sh BUILD_BIN_DIR
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
bin=$(cd "${1:-$root/build/bin}" && pwd)
work=$(mktemp -d /tmp/citygen-farm-XXXXXX)
cleanup() {
  "$root/scripts/farm/local_slurm.sh" stop "$work/slurm" || true
  rm -rf "$work"
}
trap cleanup EXIT
fail() { echo "slurm_farm_test: FAIL: $*" >&2; exit 1; }
now() { date +%s.%N; }
since() { awk -v a="$1" -v b="$(now)" 'BEGIN { printf "%.1f", b - a }'; }

"$bin/osmparse" "$root/tests/data/tiny_roundabout.osm" -q -o "$work/tiny.scene"
size=(--width 64 --height 40)

start=$(now)
set +e
env_line=$("$root/scripts/farm/local_slurm.sh" start "$work/slurm")
status=$?
set -e
if [ $status -eq 77 ]; then echo "slurm_farm_test: SKIPPED (Slurm cannot run here, see above)"; exit 77; fi
[ $status -eq 0 ] || { tail -n 20 "$work"/slurm/*.log "$work"/slurm/*.out >&2 || true; fail "local Slurm did not start"; }
eval "$env_line"
echo "slurm started in $(since "$start") s"

start=$(now)
mkdir -p "$work/farm" "$work/local"
# Both submitted at once, as a user would; each waits for its own merge job.
"$root/scripts/farm/render_farm.sh" "$work/tiny.scene" "$work/farm/orbit_%03d.png" --render "$bin/render" \
  "${size[@]}" --fps 1 --frames 0-3 --frames-per-task 2 --wait --video "$work/farm/orbit.mp4" \
  -- --orbit --orbit-seconds 4 --spp 2 &
animation=$!
"$root/scripts/farm/render_farm.sh" "$work/tiny.scene" "$work/farm/still.png" --render "$bin/render" \
  "${size[@]}" --tiles 2x2 --wait -- --spp 2 --denoise &
still=$!
wait $animation || fail "farm animation"
wait $still || fail "farm tiles"
echo "farm jobs (4 frames in 2 tasks + merge, 4 tiles + merge) took $(since "$start") s"

"$bin/render" "$work/tiny.scene" "${size[@]}" -q --fps 1 --orbit --orbit-seconds 4 --spp 2 -o "$work/local/orbit_%03d.png"
"$bin/render" "$work/tiny.scene" "${size[@]}" -q --spp 2 --denoise -o "$work/local/still.png"
for name in orbit_000.png orbit_001.png orbit_002.png orbit_003.png still.png; do
  [ -f "$work/farm/$name" ] || fail "the farm did not write $name"
  cmp "$work/farm/$name" "$work/local/$name" || fail "$name differs between the farm and one machine"
done
[ -f "$work/farm/orbit_004.png" ] && fail "frame 4 was not asked for"
if command -v ffmpeg > /dev/null; then
  [ -s "$work/farm/orbit.mp4" ] || fail "ffmpeg is here but no video was encoded"
  frames=$(ffprobe -v error -count_frames -select_streams v:0 -show_entries stream=nb_read_frames -of csv=p=0 \
    "$work/farm/orbit.mp4")
  [ "$frames" = 4 ] || fail "the video has $frames frames, not 4"
fi
pids=$(cat "$work"/slurm/*.started.pid)
"$root/scripts/farm/local_slurm.sh" stop "$work/slurm"
for pid in $pids; do
  if kill -0 "$pid" 2> /dev/null && ! grep -q '^State:[[:space:]]*Z' "/proc/$pid/status" 2> /dev/null; then
    fail "daemon $pid still runs after stop"
  fi
done
echo "slurm_farm_test: 5 files byte-identical to local renders; daemons stopped"
