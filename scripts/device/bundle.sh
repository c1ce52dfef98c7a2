#!/usr/bin/env bash
# Packs .gpu/ for a lent GPU machine (offline, x86-64): the shared bundler's binaries and runtime
# packages, plus the packages this build also loads (libwebp7, libdraco7, libmeshoptimizer2d) and
# the GL vendor-neutral dispatch libraries the NVIDIA Vulkan driver needs (without them the loader
# finds its manifest but reports VK_ERROR_INCOMPATIBLE_DRIVER), and scripts/device/run.sh.
# Run from the project root after a Release build:
#   bash scripts/device/bundle.sh [BUILD_DIR]
# then, on the machine, `bash .gpu/run.sh` with .gpu carried. Needs ../shared/tools/gpu-bundle.sh.
set -euo pipefail
build=${1:-build}
shared=../shared/tools/gpu-bundle.sh
[ -f "$shared" ] || { echo "device bundle: no $shared" >&2; exit 1; }
bash "$shared" "$build"
extra=(libwebp7 libdraco7 libmeshoptimizer2d libglvnd0 libegl1 libgl1 libglx0 libopengl0 libgles2)
(cd .gpu/debs && apt-get download "${extra[@]}" >/dev/null 2>&1) ||
  { apt-get update -qq && (cd .gpu/debs && apt-get download "${extra[@]}" >/dev/null); }
cp "$(dirname "${BASH_SOURCE[0]}")/run.sh" .gpu/run.sh
missing=$(ldd "$build/punctual" | grep -c "not found" || true)
[ "$missing" = 0 ] || { echo "device bundle: $build/punctual has unresolved libraries here" >&2; exit 1; }
echo "device bundle: .gpu is $(du -sh .gpu | cut -f1)"
