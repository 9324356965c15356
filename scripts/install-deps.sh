#!/usr/bin/env bash
# Installs the Debian 12 packages citygen builds with. Idempotent: does nothing when all
# are present. Runs as root without prompts (uses sudo when not root).
set -euo pipefail

PACKAGES=(
  cmake g++ make pkg-config ccache bzip2
  libosmium2-dev libprotozero-dev libexpat1-dev zlib1g-dev libbz2-dev
  libgeographiclib-dev libcgal-dev
  libflatbuffers-dev flatbuffers-compiler libcli11-dev
  libgtest-dev libgmock-dev libtbb-dev
  libembree-dev libopenimageio-dev
  # render --export-gltf (Debian ships tinygltf as a shared library).
  libtinygltf-dev
  # OpenImageIO's CMake config refers to its command-line tools; without them find_package fails.
  openimageio-tools
  # tests/bench/parse_bench.sh compares with `osmium fileinfo -e` and reads peak memory with GNU time.
  osmium-tool time
  # scripts/check-sanitizers.sh: clang with ASan, UBSan and libFuzzer (the runtimes are in
  # libclang-rt-14-dev).
  clang libclang-rt-14-dev
  # The render farm's test starts a single-node Slurm (tests/farm); ffmpeg encodes farm videos.
  slurm-wlm munge ffmpeg
  # The glTF export's test imports it with Blender; its glTF importer needs numpy.
  blender python3-numpy
)

missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
[ ${#missing[@]} -eq 0 ] && exit 0

SUDO=""
[ "$(id -u)" -ne 0 ] && SUDO="sudo"
echo "installing: ${missing[*]}" >&2
$SUDO apt-get update -qq
DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq "${missing[@]}" >/dev/null
