#!/usr/bin/env bash
# The hall's walk (`punctual play --scene hall`) once per light-list method, each into
# bench/results/walk/METHOD (or OUT_DIR/METHOD), then one line per method: the median, p95, p99
# and largest total GPU time per frame over the walk (issue 34's tails). Extra arguments go to
# play (e.g. --size 1280x720 --fps 5).
#   scripts/walk-tails.sh [BUILD_DIR [OUT_DIR [PLAY OPTIONS...]]]
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
binary="${1:-$root/build}/punctual"
out="${2:-$root/bench/results/walk}"
shift $(( $# > 2 ? 2 : $# ))
[ -x "$binary" ] || { echo "walk-tails: no $binary; build first (scripts/build.sh)" >&2; exit 1; }
source "$root/scripts/lib/variants.sh"
methods=($(variants --culling))
[ ${#methods[@]} -gt 1 ] || { echo "walk-tails: no methods in render --help" >&2; exit 1; }
mkdir -p "$out"
printf '%-12s %9s %9s %9s %9s\n' method p50_ms p95_ms p99_ms max_ms
for method in "${methods[@]}"; do
  "$binary" play --scene hall --culling "$method" --size 640x360 --fps 10 "$@" --out-dir "$out/$method" > /dev/null
  /usr/bin/python3 - "$out/$method/frames.json" "$method" <<'PY'
import json, sys
total = json.load(open(sys.argv[1]))["summary"]["total"]
print(f"{sys.argv[2]:12} {total['p50']:9.2f} {total['p95']:9.2f} {total['p99']:9.2f} {total['max']:9.2f}")
PY
done
