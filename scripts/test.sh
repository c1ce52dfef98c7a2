#!/usr/bin/env bash
# Builds and runs the whole test suite (CTest: unit tests and GPU tests with validation on).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/scripts/build.sh"
cd "$root/build"
ctest --output-on-failure -j"$(nproc)" "$@"
