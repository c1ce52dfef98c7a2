#!/usr/bin/python3
"""Issue 11's shadow targets on the default scene, measured in one run:

    /usr/bin/python3 bench/shadow_targets.py [--punctual build/punctual] [--size 1280x720]
                                             [--rounds 3] [--out-dir DIR]

A is the former default (`--shadow-res 1024 --shadowed 32,8 --shadow-format d32`), B the default
(auto resolution, every light, 16 bits). A0 is A as the issue measured it, with the design notes'
per-tap compares and their bias (`--shadow-receiver-plane off --shadow-bias 1,1,1,0`); A and B use
today's receiver-plane compares. Times are medians over interleaved rounds (A and B
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

import output_file
from input_file import InputFileError, read_text

PROGRAM = "shadow_targets.py"

SETTINGS = {
    "A0": ["--shadow-res", "1024", "--shadowed", "32,8", "--shadow-format", "d32", "--shadow-receiver-plane", "off",
           "--shadow-bias", "1,1,1,0"],
    "A": ["--shadow-res", "1024", "--shadowed", "32,8", "--shadow-format", "d32"],
    "B": [],
}
ORDER = ["A0", "A", "B"]


def run(punctual, args):
    result = subprocess.run([punctual] + args, capture_output=True, text=True)
    if result.returncode != 0:
        sys.exit(f"shadow_targets: punctual {' '.join(args)} failed: {result.stderr.strip()}")
    return result


def render_stats(punctual, size, name, folder, round_index):
    path = os.path.join(folder, f"stats-{name}-{round_index}.json")
    run(punctual, ["render", "--size", size, "--frames", "3", "--stats", path] + SETTINGS[name])
    return read_json(path)


def read_json(path):
    """A JSON file punctual wrote, read by input_file.py's rules (never blocks on a FIFO)."""
    try:
        return json.loads(read_text(path))
    except ValueError as err:
        raise InputFileError(path, f"not valid JSON ({err})") from None


def validation(punctual, size, name, folder):
    out = os.path.join(folder, f"validate-{name}")
    run(punctual, ["validate", "--size", size, "--edge-band-px", "1", "--out-dir", out] + SETTINGS[name])
    return {light["scene_light"]: light for light in read_json(os.path.join(out, "report.json"))["lights"]}


def misclassified(lights, keys):
    """((wrong, compared) outside the band, (wrong, compared) over every pixel) on the lights `keys`."""
    outside = sum(lights[k]["outside_edge_band"]["compared"] for k in keys)
    wrong_outside = sum(lights[k]["outside_edge_band"]["false_shadow"] + lights[k]["outside_edge_band"]["false_lit"]
                        for k in keys)
    compared = sum(lights[k]["compared"] for k in keys)
    wrong = sum(lights[k]["false_shadow"] + lights[k]["false_lit"] for k in keys)
    return (wrong_outside, outside), (wrong, compared)


def share(pair):
    """'0.002% (60)': the misclassified share and count."""
    wrong, compared = pair
    return f"{100 * wrong / max(compared, 1):.3f}% ({wrong})"


def ratio(b, a):
    return f"{b / a:.2f}" if a else ("1" if b == a else "A: none")


def spread(values):
    return (max(values) - min(values)) / 2 if values else 0.0


def main(argv=None):
    """Command line entry point; returns the exit status. An unreadable stats or report file
    is one line `shadow_targets.py: error: <file>: <problem>` (status 1), an interrupt one
    line (status 128 + the signal): output_file.run_script. It writes no file itself."""
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--punctual", default="build/punctual")
    parser.add_argument("--size", default="1280x720")
    parser.add_argument("--rounds", type=int, default=3)
    parser.add_argument("--out-dir")
    args = parser.parse_args(argv)
    return output_file.run_script(PROGRAM, lambda outputs: measure(args))


def measure(args):
    """Runs the renders and validations and prints the table; returns 0."""
    folder = args.out_dir or tempfile.mkdtemp(prefix="shadow-targets-")
    os.makedirs(folder, exist_ok=True)

    times = {name: {"shadows": [], "forward": [], "total": []} for name in SETTINGS}
    stats = {}
    for r in range(args.rounds):
        for name in (ORDER if r % 2 == 0 else ORDER[::-1]):
            s = render_stats(args.punctual, args.size, name, folder, r)
            stats[name] = s
            for part in ("shadows", "forward", "total"):
                times[name][part].append(s["gpu_ms"][part])
    lights = {name: validation(args.punctual, args.size, name, folder) for name in SETTINGS}
    shared = sorted(set(lights["A"]) & set(lights["B"]))

    print(f"default scene, {args.size}, {args.rounds} interleaved rounds (median of rounds, +- half the range)\n")
    print("| | A0: A with the notes' compares | A: 1024, 32+8 lights, d32 | B: auto, every light, d16 | B / A | B / A0 |")
    print("|---|---:|---:|---:|---:|---:|")

    def row(label, values, fmt):
        cells = " | ".join(fmt(values[n]) for n in ORDER)
        print(f"| {label} | {cells} | {ratio(values['B'], values['A'])} | {ratio(values['B'], values['A0'])} |")

    row("shadow memory (MiB)", {n: stats[n]["shadows"]["memory_bytes"] / 2**20 for n in SETTINGS}, lambda v: f"{v:.1f}")
    row("texels rendered (Mi)", {n: stats[n]["shadows"]["texels_rendered"] / 2**20 for n in SETTINGS}, lambda v: f"{v:.1f}")
    print("| views rendered | " + " | ".join(str(stats[n]["shadows"]["views_rendered"]) for n in ORDER) + " | | |")
    print("| views reduced by the budget | " + " | ".join(str(len(stats[n]["shadows"]["reduced"])) for n in ORDER) + " | | |")
    for part in ("shadows", "forward", "total"):
        medians = {n: statistics.median(times[n][part]) for n in SETTINGS}
        cells = " | ".join(f"{medians[n]:.1f} +- {spread(times[n][part]):.1f}" for n in ORDER)
        print(f"| {part} ms | {cells} | {ratio(medians['B'], medians['A'])} | {ratio(medians['B'], medians['A0'])} |")
    for label, keys in ((f"the {len(shared)} lights both shadow", shared), ("each one's own lights", None)):
        counts = {n: misclassified(lights[n], keys or sorted(lights[n])) for n in SETTINGS}
        for index, where in ((0, "outside a 1-px band"), (1, "over every pixel")):
            cells = " | ".join(share(counts[n][index]) for n in ORDER)
            fractions = {n: counts[n][index][0] / max(counts[n][index][1], 1) for n in SETTINGS}
            print(f"| misclassified {where}, {label} | {cells} | {ratio(fractions['B'], fractions['A'])} | "
                  f"{ratio(fractions['B'], fractions['A0'])} |")
    print(f"\nB's tiers: {stats['B']['shadows']['tiers']}; files in {folder}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
