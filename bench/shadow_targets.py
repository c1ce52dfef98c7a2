#!/usr/bin/python3
"""Issue 11's shadow targets on the default scene, measured in one run:

    /usr/bin/python3 bench/shadow_targets.py [--punctual build/punctual] [--size 1280x720]
                                             [--rounds 3] [--out-dir DIR]

A is the former default (`--shadow-res 1024 --shadowed 32,8 --shadow-format d32`), B the default
(auto resolution, every light, 16 bits). Times are medians over interleaved rounds (A and B
alternate, the order flipping every round), each round a `render --frames 3` whose stats give the
median of three frames per pass. Accuracy comes from one `validate --edge-band-px 1` per setting:
the share of shadow tests misclassified outside a one-pixel edge band, and over every pixel,
both on the lights A and B both shadow (by scene light index) and on all of each one's lights.
Prints a Markdown table; with --out-dir keeps every stats and report file there.
"""

import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile

SETTINGS = {
    "A": ["--shadow-res", "1024", "--shadowed", "32,8", "--shadow-format", "d32"],
    "B": [],
}


def run(punctual, args):
    result = subprocess.run([punctual] + args, capture_output=True, text=True)
    if result.returncode != 0:
        sys.exit(f"shadow_targets: punctual {' '.join(args)} failed: {result.stderr.strip()}")
    return result


def render_stats(punctual, size, name, folder, round_index):
    path = os.path.join(folder, f"stats-{name}-{round_index}.json")
    run(punctual, ["render", "--size", size, "--frames", "3", "--stats", path] + SETTINGS[name])
    with open(path, encoding="utf-8") as f:
        return json.load(f)


def validation(punctual, size, name, folder):
    out = os.path.join(folder, f"validate-{name}")
    run(punctual, ["validate", "--size", size, "--edge-band-px", "1", "--out-dir", out] + SETTINGS[name])
    with open(os.path.join(out, "report.json"), encoding="utf-8") as f:
        return {light["scene_light"]: light for light in json.load(f)["lights"]}


def misclassified(lights, keys):
    """(outside the band, every pixel) misclassified shares over the lights `keys`."""
    outside = sum(lights[k]["outside_edge_band"]["compared"] for k in keys)
    wrong_outside = sum(lights[k]["outside_edge_band"]["false_shadow"] + lights[k]["outside_edge_band"]["false_lit"]
                        for k in keys)
    compared = sum(lights[k]["compared"] for k in keys)
    wrong = sum(lights[k]["false_shadow"] + lights[k]["false_lit"] for k in keys)
    return wrong_outside / max(outside, 1), wrong / max(compared, 1)


def spread(values):
    return (max(values) - min(values)) / 2 if values else 0.0


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--punctual", default="build/punctual")
    parser.add_argument("--size", default="1280x720")
    parser.add_argument("--rounds", type=int, default=3)
    parser.add_argument("--out-dir")
    args = parser.parse_args(argv)
    folder = args.out_dir or tempfile.mkdtemp(prefix="shadow-targets-")
    os.makedirs(folder, exist_ok=True)

    times = {name: {"shadows": [], "forward": [], "total": []} for name in SETTINGS}
    stats = {}
    for r in range(args.rounds):
        for name in (["A", "B"] if r % 2 == 0 else ["B", "A"]):
            s = render_stats(args.punctual, args.size, name, folder, r)
            stats[name] = s
            for part in ("shadows", "forward", "total"):
                times[name][part].append(s["gpu_ms"][part])
    lights = {name: validation(args.punctual, args.size, name, folder) for name in SETTINGS}
    shared = sorted(set(lights["A"]) & set(lights["B"]))

    print(f"default scene, {args.size}, {args.rounds} interleaved rounds (median of rounds, +- half the range)\n")
    print("| | A: 1024, 32+8 lights, d32 | B: auto, every light, d16 | B / A |")
    print("|---|---:|---:|---:|")
    memory = {n: stats[n]["shadows"]["memory_bytes"] / 2**20 for n in SETTINGS}
    print(f"| shadow memory (MiB) | {memory['A']:.1f} | {memory['B']:.1f} | {memory['B'] / memory['A']:.3f} |")
    texels = {n: stats[n]["shadows"]["texels_rendered"] / 2**20 for n in SETTINGS}
    print(f"| texels rendered (Mi) | {texels['A']:.1f} | {texels['B']:.1f} | {texels['B'] / texels['A']:.3f} |")
    views = {n: stats[n]["shadows"]["views_rendered"] for n in SETTINGS}
    print(f"| views rendered | {views['A']} | {views['B']} | |")
    print(f"| views reduced by the budget | {len(stats['A']['shadows']['reduced'])} | "
          f"{len(stats['B']['shadows']['reduced'])} | |")
    for part in ("shadows", "forward", "total"):
        a, b = statistics.median(times["A"][part]), statistics.median(times["B"][part])
        print(f"| {part} ms | {a:.1f} +- {spread(times['A'][part]):.1f} | {b:.1f} +- {spread(times['B'][part]):.1f} | "
              f"{b / a:.2f} |")
    for label, keys in ((f"the {len(shared)} lights both shadow", shared), ("each one's own lights", None)):
        a = misclassified(lights["A"], keys or sorted(lights["A"]))
        b = misclassified(lights["B"], keys or sorted(lights["B"]))
        print(f"| misclassified outside a 1-px band, {label} | {100 * a[0]:.3f}% | {100 * b[0]:.3f}% | "
              f"{b[0] / max(a[0], 1e-12):.2f} |")
        print(f"| misclassified over every pixel, {label} | {100 * a[1]:.3f}% | {100 * b[1]:.3f}% | "
              f"{b[1] / max(a[1], 1e-12):.2f} |")
    print(f"\nB's tiers: {stats['B']['shadows']['tiers']}; files in {folder}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
