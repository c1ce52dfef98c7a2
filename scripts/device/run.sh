#!/usr/bin/env bash
# Runs on the lent GPU machine from the project root, .gpu/ carried (scripts/device/bundle.sh):
# the methods bench (the culling targets' ratios), the default frame, the GPU tests in 4 shards
# and `compare`. Unpacks the packages into a private prefix, never into /. Writes into $OUT
# res.tgz (snapshotted after each step, so a run cut short still returns what it finished).
# About 2 minutes on an H200.
set -uo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
G=$PWD/.gpu
OUT=${OUT:-/tmp/gpu-out}; mkdir -p "$OUT"
# The GPU tests call the CLI by the absolute path compiled into them.
bp=$(cat "$G/binary-path"); root=${bp%/build/punctual}
[ -e "$root" ] || { mkdir -p "$(dirname "$root")"; ln -s "$PWD" "$root"; }
mkdir -p "$(dirname "$bp")"; [ -e "$bp" ] || cp "$G/bin/punctual" "$bp"
R=/tmp/gpu-root; mkdir -p "$R"
for f in "$G"/debs/*.deb; do dpkg -x "$f" "$R"; done
export LD_LIBRARY_PATH="$R/usr/lib/x86_64-linux-gnu${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
export VK_LAYER_PATH="$R/usr/share/vulkan/explicit_layer.d"
icd=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
[ -f "$icd" ] && export VK_DRIVER_FILES="$icd"
P="$G/bin/punctual"
S=/tmp/gpu-results; mkdir -p "$S"
snap() { tar czf "$OUT/res.tgz.tmp" -C "$S" --exclude=images . && mv "$OUT/res.tgz.tmp" "$OUT/res.tgz"; }
{ nvidia-smi -L; nvidia-smi --query-gpu=name,driver_version,clocks.sm,clocks.max.sm --format=csv; "$P" devices; } 2>&1 | tee "$S/devices.txt"
"$P" devices >/dev/null 2>&1 || { echo "no Vulkan device: stop"; exit 1; }
# A warm-up bench first: the clocks of an idle GPU start low (its first rounds came out 4x slower).
timeout 60 "$P" bench --series methods --rounds 1 --out-dir /tmp/gpu-warm >/dev/null 2>&1
timeout 90 "$P" bench --series methods --out-dir "$S/methods" >"$S/methods.log" 2>&1; echo "methods exit $?" | tee -a "$S/methods.log"
tail -2 "$S/methods.log"; snap
timeout 45 "$P" render --frames 5 --out "$S/default.png" --stats "$S/default-stats.json" >"$S/render.txt" 2>&1
echo "render exit $?" | tee -a "$S/render.txt"; snap
for i in 0 1 2 3; do
  GTEST_TOTAL_SHARDS=4 GTEST_SHARD_INDEX=$i timeout 200 "$G/bin/punctual_gpu_tests" --gtest_brief=1 >"$S/gpu-tests-$i.txt" 2>&1 &
done
wait
for i in 0 1 2 3; do grep -E "^\[  (PASSED|FAILED|SKIPPED) " "$S/gpu-tests-$i.txt"; done; snap
timeout 45 "$P" compare >"$S/compare.txt" 2>&1; echo "compare exit $?" | tee -a "$S/compare.txt"; snap
