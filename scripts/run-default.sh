#!/usr/bin/env bash
# The main job: builds, renders the built-in default scene at 1280x720 and prints the per-pass
# timing table. Writes out/default.png and out/default-stats.json.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/scripts/build.sh"
mkdir -p "$root/out"
"$root/build/punctual" render --out "$root/out/default.png" --stats "$root/out/default-stats.json" "$@"
echo
echo "Every light-list method on the default scene, side by side:"
"$root/build/punctual" compare
