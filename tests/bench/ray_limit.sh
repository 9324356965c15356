#!/usr/bin/env bash
# Ray-limit benchmark (issue 25 §4), run by hand (never from ctest): Monaco's automatic view by
# day and by night, stored and procedural geometry; for each, the render's rays/s against a
# replay of the same rays through Embree with no shading (tests/bench/ray_limit.cpp), median of
# RUNS interleaved render/replay pairs. PACKETS=1 also replays the shadow rays in packets.
#
#   tests/bench/ray_limit.sh        (SIZE=960x540 SPP=4 RUNS=3 by default; THREADS=N;
#                                    BIN=path/to/bin to measure another build; OSM=file.osm.bz2
#                                    for another extract; any further
#                                    arguments go to every ray_limit run, e.g. --camera ...)
set -euo pipefail
cd "$(dirname "$0")/../.."
size=${SIZE:-960x540}
width=${size%x*}
height=${size#*x}
spp=${SPP:-4}
runs=${RUNS:-3}
threads=${THREADS:-0}
bin=${BIN:-build/bin}
packets=()
[ "${PACKETS:-0}" = 1 ] && packets=(--packets)

if [ -z "${BIN:-}" ]; then
  cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DCITYGEN_BUILD_TESTS=ON > /dev/null
  cmake --build build -j2 --target osmparse ray_limit > /dev/null
fi
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$bin/osmparse" "${OSM:-../shared/data/osm/monaco.osm.bz2}" -o "$work/monaco.scene" -q

echo "| geometry | time | view | rays recorded | render Mrays/s | replay Mrays/s | render / replay |"
echo "|---|---|---|---|---|---|---|"
for mode in stored procedural; do
  mode_flag=()
  [ "$mode" = procedural ] && mode_flag=(--procedural)
  for time in day night; do
    "$bin/ray_limit" "$work/monaco.scene" --width "$width" --height "$height" --spp "$spp" --time "$time" \
      --repeat "$runs" --threads "$threads" "${mode_flag[@]}" "${packets[@]}" "$@"
  done
done
