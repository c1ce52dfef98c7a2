#!/usr/bin/env bash
# Builds punctual with AddressSanitizer and UndefinedBehaviorSanitizer (PUNCTUAL_SANITIZE) into
# build-asan/ and runs the whole test suite there: any sanitizer report, leak included, fails the
# test that caused it. Installs missing packages first. Arguments go to ctest (e.g. -R gltf).
# With PUNCTUAL_CI=1 in the environment, compiler warnings are errors.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/scripts/install-deps.sh"
werror=OFF
[ "${PUNCTUAL_CI:-0}" = 1 ] && werror=ON
# Release, as the suite is long; cmake/Sanitizers.cmake adds the line tables reports need.
cmake -S "$root" -B "$root/build-asan" -DCMAKE_BUILD_TYPE=Release -DPUNCTUAL_SANITIZE=ON \
  -DPUNCTUAL_WERROR="$werror" >/dev/null
cmake --build "$root/build-asan" -j"$(nproc)"
cd "$root/build-asan"
ctest --output-on-failure -j"$(nproc)" "$@"
