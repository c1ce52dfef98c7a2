#!/usr/bin/env bash
# Shadow caching along the hall's walk (issue 34's "caching saves"): `punctual play --scene hall`
# at 1280x720 and 10 fps with --shadow-cache off, on and redraw, its lamps still (--moving-lights
# 0), a quarter of them swaying (0.25) and the walk's own sixth, and a fixed 1024 with still lamps.
# Each run's frames.csv goes to bench/results/shadow-cache/CONFIG (or OUT_DIR/CONFIG), and
# summary.json beside them holds per run the shadow stage's p50, p95 and largest time per frame,
# the p50 as a share of the same lamps' off, the views kept, drawn and moved, the fresh layouts,
# the shadow memory and the cache's CPU time; and, frame by frame, whether on's frames are
# redraw's bit for bit, and how many pixels on's differ from off's (their squares lie elsewhere).
# The lifting runs (issue 34's mixed caching) keep the lamps still and lift a quarter of the props
# (--moving-casters 0.25): off, on and mixed, with their frames compared the same way. The
# virtual runs cache virtual pages (--shadow-res virtual): off and on, lamps still (virtual-*)
# and a quarter swaying (virtualquarter-*), with the pages kept and drawn.
# Extra arguments go to every play (e.g. --fps 5 --size 640x360). RUNS="lifting-off lifting-on
# lifting-mixed" plays only those; their rows and comparisons replace the stored summary's, the
# others' stay (one stored run per series).
#   [RUNS="..."] scripts/shadow-cache.sh [BUILD_DIR [OUT_DIR [PLAY OPTIONS...]]]
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
binary="${1:-$root/build}/punctual"
out="${2:-$root/bench/results/shadow-cache}"
shift $(( $# > 2 ? 2 : $# ))
[ -x "$binary" ] || { echo "shadow-cache: no $binary; build first (scripts/build.sh)" >&2; exit 1; }
frames="$(mktemp -d)"
trap 'rm -rf "$frames"' EXIT
mkdir -p "$out"
# CONFIG and its play options; the first word names the lamps (the off run it is compared with).
configs=(
  "still-off|--moving-lights 0 --shadow-cache off"
  "still-on|--moving-lights 0 --shadow-cache on"
  "still-redraw|--moving-lights 0 --shadow-cache redraw"
  "quarter-off|--moving-lights 0.25 --shadow-cache off"
  "quarter-on|--moving-lights 0.25 --shadow-cache on"
  "sixth-off|--shadow-cache off"
  "sixth-on|--shadow-cache on"
  "fixed1024-off|--moving-lights 0 --shadow-res 1024 --shadow-cache off"
  "fixed1024-on|--moving-lights 0 --shadow-res 1024 --shadow-cache on"
  "lifting-off|--moving-lights 0 --moving-casters 0.25 --shadow-cache off"
  "lifting-on|--moving-lights 0 --moving-casters 0.25 --shadow-cache on"
  "lifting-mixed|--moving-lights 0 --moving-casters 0.25 --shadow-cache mixed"
  "virtual-off|--moving-lights 0 --shadow-res virtual --shadow-cache off"
  "virtual-on|--moving-lights 0 --shadow-res virtual --shadow-cache on"
  "virtualquarter-off|--moving-lights 0.25 --shadow-res virtual --shadow-cache off"
  "virtualquarter-on|--moving-lights 0.25 --shadow-res virtual --shadow-cache on"
)
for entry in "${configs[@]}"; do
  name="${entry%%|*}"
  if [ -n "${RUNS:-}" ] && [[ " $RUNS " != *" $name "* ]]; then continue; fi
  read -r -a options <<< "${entry#*|}"
  echo "shadow-cache: $name" >&2
  "$binary" play --scene hall --size 1280x720 --fps 10 "${options[@]}" "$@" --save-frames \
    --out-dir "$frames/$name" > /dev/null
  mkdir -p "$out/$name"
  cp "$frames/$name/frames.csv" "$out/$name/frames.csv"
done
/usr/bin/python3 - "$frames" "$out" "$(git -C "$root" rev-parse --short HEAD 2>/dev/null || echo unknown)" <<'PY'
import glob, json, os, statistics, sys
import matplotlib.image as mpimg
import numpy as np

frames_dir, out_dir, version = sys.argv[1], sys.argv[2], sys.argv[3]
runs = sorted(os.listdir(frames_dir))

def percentile(values, p):
    values = sorted(values)
    rank = (len(values) - 1) * p / 100.0
    low = int(rank)
    if low + 1 >= len(values):
        return values[-1]
    return values[low] + (rank - low) * (values[low + 1] - values[low])

summary_path = os.path.join(out_dir, "summary.json")
summary = json.load(open(summary_path)) if os.path.exists(summary_path) else {"device": None, "runs": {}}
for run in runs:
    document = json.load(open(os.path.join(frames_dir, run, "frames.json")))
    summary["device"] = document["device"]
    shadows = [f["gpu_ms"]["shadows"] for f in document["frames"]]
    cache = [f["stats"]["shadows"].get("cache", {}) for f in document["frames"]]
    row = {"frames": len(shadows),
           "shadow_ms": {"p50": percentile(shadows, 50), "p95": percentile(shadows, 95), "max": max(shadows)},
           "total_ms_p50": document["summary"]["total"]["p50"],
           "shadow_memory_bytes_p50": statistics.median(f["stats"]["shadows"]["memory_bytes"] for f in document["frames"]),
           "views_rendered": sum(f["stats"]["shadows"]["views_rendered"] for f in document["frames"])}
    if cache[0]:
        for key in ("kept_views", "drawn_views", "moved_views", "laid_out", "over_static_views", "static_stored_views",
                    "kept_pages", "drawn_pages"):
            row[key] = sum(c.get(key, 0) for c in cache)
        row["dynamic_casters"] = cache[-1].get("dynamic_casters", 0)
        row["static_texels_p50"] = statistics.median(c.get("static_texels", 0) for c in cache)
        row["check_ms_p50"] = statistics.median(c["check_ms"] for c in cache)
        row["atlas_texels_p50"] = statistics.median(c["atlas_texels"] for c in cache)
        row["packed_texels_p50"] = statistics.median(c["packed_texels"] for c in cache)
    row["pages_allocated"] = sum(f["stats"]["shadows"].get("pages", {}).get("allocated", 0)
                                 for f in document["frames"])
    row["shadow_draws"] = sum(f["stats"]["geometry"]["shadow_draws"]["total"] for f in document["frames"])
    summary["runs"][run] = row
for run, row in summary["runs"].items():
    lamps = run.rsplit("-", 1)[0]
    off = summary["runs"].get(lamps + "-off")
    if off and run != lamps + "-off":
        row["shadow_p50_of_off"] = row["shadow_ms"]["p50"] / off["shadow_ms"]["p50"]
        row["memory_of_off"] = row["shadow_memory_bytes_p50"] / off["shadow_memory_bytes_p50"]

def pngs(run):
    return sorted(glob.glob(os.path.join(frames_dir, run, "frame-*.png")))

def compare(a_run, b_run):
    same, differing_pixels, frames = 0, 0, 0
    for a, b in zip(pngs(a_run), pngs(b_run)):
        frames += 1
        if open(a, "rb").read() == open(b, "rb").read():
            same += 1
            continue
        differing_pixels += int(np.count_nonzero(np.abs(mpimg.imread(a) - mpimg.imread(b)).max(axis=2)))
    return {"frames": frames, "identical_frames": same, "differing_pixels": differing_pixels}

comparisons = {"still_on_vs_redraw": ("still-on", "still-redraw"), "still_on_vs_off": ("still-on", "still-off"),
               "quarter_on_vs_off": ("quarter-on", "quarter-off"), "lifting_on_vs_off": ("lifting-on", "lifting-off"),
               "lifting_mixed_vs_off": ("lifting-mixed", "lifting-off"), "virtual_on_vs_off": ("virtual-on", "virtual-off"),
               "virtualquarter_on_vs_off": ("virtualquarter-on", "virtualquarter-off")}
for key, (a, b) in comparisons.items():
    if a in runs and b in runs:
        summary[key] = compare(a, b)
summary.setdefault("commits", {})
for run in summary["runs"]:  # rows stored before the commits were kept per run
    summary["commits"].setdefault(run, summary.get("commit", "unknown"))
for run in runs:
    summary["commits"][run] = version
summary.pop("commit", None)
json.dump(summary, open(summary_path, "w"), indent=1)
print(f"{'run':18} {'p50':>8} {'p95':>8} {'max':>8} {'of off':>7} {'kept':>6} {'drawn':>6} {'over':>6} {'moved':>6} "
      f"{'fresh':>5} {'pages':>8} {'p.kept':>8} {'p.drawn':>8} {'draws':>7} {'MiB':>7} {'check':>6}")
for run, r in summary["runs"].items():
    print(f"{run:18} {r['shadow_ms']['p50']:8.2f} {r['shadow_ms']['p95']:8.2f} {r['shadow_ms']['max']:8.2f} "
          f"{r.get('shadow_p50_of_off', 1.0):7.3f} {r.get('kept_views', 0):6} {r.get('drawn_views', r['views_rendered']):6} "
          f"{r.get('over_static_views', 0):6} {r.get('moved_views', 0):6} {r.get('laid_out', 0):5} "
          f"{r.get('pages_allocated', 0):8} {r.get('kept_pages', 0):8} {r.get('drawn_pages', 0):8} "
          f"{r.get('shadow_draws', 0):7} {r['shadow_memory_bytes_p50'] / 2**20:7.1f} {r.get('check_ms_p50', 0.0):6.2f}")
for key in comparisons:
    if key not in summary:
        continue
    c = summary[key]
    print(f"{key}: {c['identical_frames']} of {c['frames']} frames identical, {c['differing_pixels']} pixels differ")
PY
