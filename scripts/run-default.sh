#!/usr/bin/env bash
# The main job: builds, renders the built-in default scene (the hall) at 1280x720 and prints the
# per-pass timing table. Writes out/default.png and out/default-stats.json. Then compares every
# light-list method on the hall (1280x720) and on the outdoor scene (640x360: its 32 lights, sun
# cascades and simple geometry take 8 to 15 s there, and at this size its shadow views fit the
# default budget, so it prints no warning). The hall's render and compare get --shadow-budget 80
# (MiB): its whole shadow demand at a texel per pixel at 1280x720 is 79 MiB (atlas and drawing
# square), so no view is reduced; the default budget, 64 MiB (the budget issue's ceiling), trims
# 115 views by a tier there and warns (bench/RESULTS.md, "Frames in motion, fifth part"). Options
# given to the script come after it, and a later --shadow-budget wins.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/scripts/build.sh"
mkdir -p "$root/out"
"$root/build/punctual" render --shadow-budget 80 --out "$root/out/default.png" --stats "$root/out/default-stats.json" "$@"
echo
echo "Every light-list method on the default scene, side by side:"
"$root/build/punctual" compare --shadow-budget 80
echo
echo "Every light-list method on the outdoor scene (--scene outdoor), side by side:"
"$root/build/punctual" compare --scene outdoor --size 640x360
