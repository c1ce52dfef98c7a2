#!/usr/bin/env bash
# Renders every light-list method (in every list form), shadow filter and point-shadow layout on the default scene,
# the shipped small room and (where ../shared is present) the Cornell box, and prints one line
# per image: "<scene> <variant> <sha256>". Run it before and after a change that must not change
# behaviour and diff the two outputs: every line must match (images are bit-identical run to run).
#   scripts/image-hashes.sh [BUILD_DIR] > before.txt
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
binary="${1:-$root/build}/punctual"
[ -x "$binary" ] || { echo "image-hashes: no $binary; build first (scripts/build.sh)" >&2; exit 1; }
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

# The variants, from `punctual render --help` (which prints the tables): a new method or filter is
# hashed without an edit here.
source "$root/scripts/lib/variants.sh"
methods=($(variants --culling))
filters=($(variants --shadow-filter))
forms=($(variants --light-lists))
[ ${#methods[@]} -gt 1 ] && [ ${#filters[@]} -gt 1 ] || { echo "image-hashes: no variants in render --help" >&2; exit 1; }

scenes=("default:" "small-room:$root/data/small-room.gltf")
cornell="$root/../shared/data/cornell-box/cornellBox.gltf"
[ -f "$cornell" ] && scenes+=("cornell-box:$cornell")

hash_render() {  # NAME SCENE_PATH ARGS...
  local name=$1 scene=$2
  shift 2
  local args=(render --size 320x180 --out "$work/image.png" "$@")
  [ -n "$scene" ] && args+=("$scene")
  "$binary" "${args[@]}" >/dev/null
  echo "$name $(sha256sum "$work/image.png" | cut -d' ' -f1)"
  if [ -f "$work/heat.png" ]; then
    echo "$name-heatmap $(sha256sum "$work/heat.png" | cut -d' ' -f1)"
    rm -f "$work/heat.png"
  fi
}

for entry in "${scenes[@]}"; do
  scene_name=${entry%%:*}
  scene_path=${entry#*:}
  for method in "${methods[@]}"; do
    hash_render "$scene_name $method shadows-off" "$scene_path" --culling "$method" --shadows off \
      --heatmap "$work/heat.png"
    hash_render "$scene_name $method shadows-auto" "$scene_path" --culling "$method"
    # The list forms past the first (the default, hashed above); the same image by design.
    for form in "${forms[@]:1}"; do
      hash_render "$scene_name $method lists-$form shadows-off" "$scene_path" --culling "$method" \
        --light-lists "$form" --shadows off --heatmap "$work/heat.png"
    done
  done
  # Point shadows in a cube array need one fixed resolution for every face; slices take auto too.
  for filter in "${filters[@]}"; do
    hash_render "$scene_name tiled $filter-cube-512" "$scene_path" --shadow-filter "$filter" \
      --point-shadow-layout cube --shadow-res 512
    hash_render "$scene_name tiled $filter-slices" "$scene_path" --shadow-filter "$filter" \
      --point-shadow-layout slices
  done
done
