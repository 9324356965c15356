#!/usr/bin/env bash
# Installs the Debian 12 packages citygen needs for one purpose, by profile (each includes the
# ones before it):
#   runtime  what osmparse and render need to build and run (scripts/demo.sh)
#   test     + what the test suite needs (GoogleTest) and the hand-run benchmarks in tests/bench
#   ci       + sanitizers and fuzzers, the Slurm farm test, the Blender glTF test (.ci/run)
# Usage: scripts/install-deps.sh [PROFILE]      (default: test)
#        scripts/install-deps.sh --list PROFILE   prints the profile's packages, one a line
# Idempotent: does nothing when all are present, and runs `apt-get update` only when something
# is missing. Runs as root without prompts (uses sudo when not root).
set -euo pipefail

RUNTIME=(
  # The compiler and the build: CMake generates Makefiles.
  g++ make cmake
  # Reading OSM: libosmium is header-only and needs protozero (PBF), expat (XML), zlib and
  # bzip2 (.osm.bz2, like the bundled example) at build time.
  libosmium2-dev libprotozero-dev libexpat1-dev zlib1g-dev libbz2-dev
  # Projecting coordinates (osmparse) and exact footprint geometry and roof skeletons (CGAL).
  libgeographiclib-dev libcgal-dev
  # Elevation rasters for osmparse --dem (SRTM .hgt, GeoTIFF, VRT; reprojection).
  libgdal-dev
  # The scene format: the FlatBuffers library and flatc, which generates its code at build time.
  libflatbuffers-dev flatbuffers-compiler
  # Both programs' command lines.
  libcli11-dev
  # Threads (osmparse's parallel stages, render's tiles) and the ray tracer.
  libtbb-dev libembree-dev
  # osmparse's allocator, TCMalloc: twice glibc malloc's speed on a large city's small rings.
  libgoogle-perftools-dev
  # render writes PNG/EXR. OpenImageIO's CMake config checks that its command-line tools exist
  # (its targets file lists /usr/bin/iconvert, idiff, ...), so find_package fails without them.
  libopenimageio-dev openimageio-tools
  # render --export-gltf (Debian ships tinygltf as a shared library).
  libtinygltf-dev
  # render --serve, the viewer: a small HTTP server (cpp-httplib: one header and a library, no
  # framework; Boost.Beast would bring Boost for the same job) and a JSON library for its API.
  libcpp-httplib-dev nlohmann-json3-dev
)
TEST=(
  # Every test binary is a GoogleTest executable; some use GMock matchers.
  libgtest-dev libgmock-dev
  # Rebuilds after a change (CMake uses it when present); no help to a first build.
  ccache
  # tests/bench/parse_bench.sh (run by hand, not by ctest) compares with `osmium export`
  # and reads peak memory with GNU time.
  osmium-tool time
)
CI=(
  # scripts/check-sanitizers.sh: clang with ASan, UBSan and libFuzzer (the runtimes are in
  # libclang-rt-14-dev, only a recommendation of clang).
  clang libclang-rt-14-dev
  # tests/farm/slurm_farm_test.sh starts a single-node Slurm (munge authenticates its daemons);
  # the farm encodes its videos with ffmpeg, and the test checks the video when ffmpeg is there.
  slurm-wlm munge ffmpeg
  # tests/blender/blender_gltf_test.sh imports render's glTF with Blender, whose importer needs numpy.
  blender python3-numpy
  # tests/render/viewer/browser: the viewer's page driven in headless Chromium by puppeteer-core
  # (from npm, pinned in its package-lock.json; installed below).
  # (npm comes with nodejs from NodeSource, as on our machines; with Debian's nodejs it is a
  # package of its own, installed below if missing.)
  chromium nodejs
)

usage() { echo "usage: $0 [runtime|test|ci]   or   $0 --list runtime|test|ci" >&2; exit 2; }

# packages PROFILE LAYER: prints the packages of one layer (runtime, test, ci) if PROFILE includes it.
packages() {
  local profile=$1 layer=$2
  case "$profile:$layer" in
    runtime:runtime|test:runtime|test:test|ci:runtime|ci:test|ci:ci) ;;
    *) return 0 ;;
  esac
  case $layer in
    runtime) printf '%s\n' "${RUNTIME[@]}" ;;
    test) printf '%s\n' "${TEST[@]}" ;;
    ci) printf '%s\n' "${CI[@]}" ;;
  esac
}

list=0
if [ "${1:-}" = --list ]; then list=1; shift; fi
profile=${1:-test}
case $profile in runtime|test|ci) ;; *) usage ;; esac
[ $# -le 1 ] || usage

if [ $list = 1 ]; then
  for layer in runtime test ci; do packages "$profile" "$layer"; done
  exit 0
fi

missing() {
  local p
  for p in "$@"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || echo "$p"
  done
}
# The browser test's npm packages (ci profile), once the Debian ones are there.
browser_dir="$(cd "$(dirname "$0")/.." && pwd)/tests/render/viewer/browser"
install_browser_packages() {
  [ "$profile" = ci ] || return 0
  [ -d "$browser_dir/node_modules/puppeteer-core" ] && return 0
  if ! command -v npm >/dev/null; then
    ${SUDO:-$([ "$(id -u)" -ne 0 ] && echo sudo)} apt-get install -y -qq npm >/dev/null
  fi
  echo "install-deps (ci): npm ci in tests/render/viewer/browser" >&2
  (cd "$browser_dir" && npm ci --no-audit --no-fund --loglevel=error >/dev/null)
}
mapfile -t missing_lean < <(missing $(packages "$profile" runtime) $(packages "$profile" test))
mapfile -t missing_ci < <(missing $(packages "$profile" ci))
if [ ${#missing_lean[@]} -eq 0 ] && [ ${#missing_ci[@]} -eq 0 ]; then
  install_browser_packages
  exit 0
fi

SUDO=""
[ "$(id -u)" -ne 0 ] && SUDO="sudo"
export DEBIAN_FRONTEND=noninteractive
echo "install-deps ($profile): installing ${missing_lean[*]} ${missing_ci[*]}" >&2
$SUDO apt-get update -qq
# The build and test packages are named in full above, so their recommendations (documentation,
# GUIs, other compilers) are left out. The ci extras keep theirs: Blender, Slurm and clang are
# run as whole tools and tested with what Debian recommends beside them.
if [ ${#missing_lean[@]} -gt 0 ]; then
  $SUDO apt-get install -y -qq --no-install-recommends "${missing_lean[@]}" >/dev/null
fi
if [ ${#missing_ci[@]} -gt 0 ]; then
  $SUDO apt-get install -y -qq "${missing_ci[@]}" >/dev/null
fi
install_browser_packages
