#!/usr/bin/env bash
# Builds the libFuzzer targets (tests/fuzz) with clang into build-fuzz/ and runs them side by side
# for a bounded time: the glTF loader's on bytes (gltf) and on JSON built structure first
# (gltf_json: deep nesting, huge numbers, long strings), and the render options parser's:
#   scripts/fuzz.sh [SECONDS]      (default 60)
# Installs clang and its sanitizer runtimes first (install-deps.sh --fuzz). Each target starts
# from its seeds (tests/fuzz/corpus/<target>, plus data/small-room.gltf for glTF) and the inputs
# earlier runs kept in build-fuzz/corpus/<target>. A crash, sanitizer report, hang (> 20 s) or
# memory blow-up (> 2 GiB) fails the script and leaves the input in build-fuzz/crashes/: fix the
# bug and commit the input as a regression (README, "CI").
# With PUNCTUAL_CI=1 in the environment, compiler warnings are errors.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
seconds="${1:-60}"
"$root/scripts/install-deps.sh" --fuzz
werror=OFF
[ "${PUNCTUAL_CI:-0}" = 1 ] && werror=ON
build="$root/build-fuzz"
CC=clang CXX=clang++ cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release -DPUNCTUAL_FUZZ=ON \
  -DPUNCTUAL_WERROR="$werror" >/dev/null
cmake --build "$build" -j"$(nproc)"

mkdir -p "$build/corpus/gltf" "$build/corpus/gltf_json" "$build/corpus/options" "$build/crashes"
cp "$root/data/small-room.gltf" "$build/corpus/gltf/"
# The option target's dictionary: the hand-picked values, then every option and variant name the
# tables hold (printed by punctual_options_dictionary, so a new variant needs no edit here).
{ cat "$root/tests/fuzz/options.dict"; "$build/punctual_options_dictionary"; } >"$build/options.dict"

run() {  # TARGET: fuzz it for $seconds, output in build-fuzz/TARGET.log
  local target=$1
  # The first corpus folder receives new inputs; the seeds are only read.
  "$build/punctual_fuzz_$target" -max_total_time="$seconds" -timeout=20 -rss_limit_mb=2048 \
    $([ -f "$build/$target.dict" ] && echo "-dict=$build/$target.dict") -artifact_prefix="$build/crashes/$target-" -print_final_stats=1 \
    "$build/corpus/$target" "$root/tests/fuzz/corpus/$target" </dev/null >"$build/$target.log" 2>&1
}

status=0
pids=()
for target in gltf gltf_json options; do
  run "$target" &
  pids+=($!)
done
i=0
for target in gltf gltf_json options; do
  if wait "${pids[$i]}"; then
    echo "fuzz $target: $(grep -E '^stat::number_of_executed_units' "$build/$target.log" | awk '{print $2}') inputs" \
         "in ${seconds} s, no failure"
  else
    status=1
    echo "fuzz $target: FAILED (inputs in $build/crashes/); the end of $build/$target.log:" >&2
    tail -n 60 "$build/$target.log" >&2
  fi
  i=$((i + 1))
done
exit "$status"
