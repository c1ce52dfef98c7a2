#!/usr/bin/env bash
# Installs what punctual needs from Debian's packages, only what is missing. Safe to rerun.
#   scripts/install-deps.sh           what building, running and testing need
#   scripts/install-deps.sh --fuzz    also what the fuzz targets need (scripts/fuzz.sh, CI)
set -euo pipefail

packages=(
  build-essential cmake pkg-config
  mesa-vulkan-drivers libvulkan-dev vulkan-validationlayers  # Vulkan: lavapipe, headers/loader, validation
  glslang-tools                                              # GLSL -> SPIR-V at build time
  libglm-dev libembree-dev libtbb-dev libtinygltf-dev libstb-dev nlohmann-json3-dev libgtest-dev
  libtinyexr-dev                                             # OpenEXR output of `punctual validate --export-exr`
  libwebp-dev                                                # EXT_texture_webp textures
  libpng-dev                                                 # huge PNG textures decoded row by row at a reduced size
  libdraco-dev                                               # glTF geometry compressed with KHR_draco_mesh_compression
  libmeshoptimizer-dev                                       # glTF buffer views compressed with EXT_meshopt_compression
  python3-matplotlib                                         # charts in bench/
  chromium                                                   # the browser test opens the HTML reports (tests/browser)
  ffmpeg                                                     # play --video encodes the frames (H.264)
)
# The sanitizer build (scripts/test-sanitized.sh) needs nothing more: GCC's ASan and UBSan
# runtimes come with build-essential.
if [ "${1:-}" = --fuzz ]; then
  packages+=(
    clang                # libFuzzer is clang's (-fsanitize=fuzzer); GCC has no equivalent
    libclang-rt-14-dev   # clang's libFuzzer, ASan and UBSan runtimes (only recommended by clang)
  )
elif [ $# -gt 0 ]; then
  echo "usage: $0 [--fuzz]" >&2
  exit 2
fi

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi
echo "installing: ${missing[*]}" >&2
sudo_cmd=()
[ "$(id -u)" -eq 0 ] || sudo_cmd=(sudo)
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -qq
"${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
