#!/usr/bin/env bash
# Configures and builds punctual (Release) into build/. Installs missing packages first.
# With PUNCTUAL_CI=1 in the environment (.ci/run sets it), compiler warnings are errors.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/scripts/install-deps.sh"
werror=OFF
[ "${PUNCTUAL_CI:-0}" = 1 ] && werror=ON
cmake -S "$root" -B "$root/build" -DCMAKE_BUILD_TYPE=Release -DPUNCTUAL_WERROR="$werror" >/dev/null
cmake --build "$root/build" -j"$(nproc)"
