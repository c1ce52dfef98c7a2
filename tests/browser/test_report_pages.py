#!/usr/bin/python3
"""The reports punctual writes, opened in headless Chromium (check_pages.py): the bench's
index.html and failures.html, validate's report.html (two scenes) and play's index.html.

    /usr/bin/python3 tests/browser/test_report_pages.py PATH/TO/punctual [--keep DIR]

Writes the pages into a temporary folder (or DIR, kept) with a small bench: the 2:1 mix series
(charts, images) and the failure study (failures.html's charts) at --quick and a tiny size, then
validate runs of the hall and the outdoor scene, then play along the hall's walk with its frames (and its video, where ffmpeg is installed).
Exits 0 when every page is clean, 1 with every
problem listed otherwise, and 77 (skipped) with one line saying why where Chromium is missing or
does not start; Chromium is tried first, so a skip costs no bench.
"""

import argparse
import os
import shutil
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import check_pages  # noqa: E402  (after the path)

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
PYTHON = "/usr/bin/python3"  # Debian's, with python3-matplotlib (as CMakeLists.txt's tests)
SIZE = "160x90"  # pixels mean time on lavapipe; the pages' structure does not depend on them


def run(command):
    start = time.monotonic()
    print("$ " + " ".join(command), flush=True)
    done = subprocess.run(command, cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                          text=True)
    if done.returncode != 0:
        print(done.stdout[-4000:])
        raise SystemExit(f"failed with exit status {done.returncode}: {' '.join(command)}")
    print(f"  {time.monotonic() - start:.1f} s", flush=True)


def write_pages(punctual, folder):
    """Writes the pages under FOLDER; their paths."""
    bench = os.path.join(folder, "bench")
    run([punctual, "bench", "--quick", "--series", "mix,failures", "--size", SIZE,
         "--rounds", "1", "--out-dir", bench])
    # The bench draws its own report (bench/plot_results.py and plot_failures.py).
    pages = [os.path.join(bench, "index.html"), os.path.join(bench, "failures.html")]
    # The hall (spots and points) and the outdoor scene, whose report adds the sun's mismatch
    # map and cascade picture.
    for scene in ("hall", "outdoor"):
        validate = os.path.join(folder, "validate-" + scene)
        run([punctual, "validate", "--scene", scene, "--size", SIZE, "--out-dir", validate])
        pages.append(os.path.join(validate, "report.html"))
    # A sequence: its chart (SVG) and its saved frames.
    play = os.path.join(folder, "play")
    # With its video where ffmpeg is installed (play --video needs it on PATH).
    video = ["--video"] if shutil.which("ffmpeg") else []
    run([punctual, "play", "--scene", "hall", "--fps", "0.5", "--size", SIZE, "--save-frames", *video,
         "--out-dir", play])
    pages.append(os.path.join(play, "index.html"))
    return pages


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("punctual", help="the punctual executable")
    parser.add_argument("--keep", metavar="DIR", help="write the pages into DIR and keep them")
    args = parser.parse_args()
    try:
        browser = check_pages.Browser()
    except check_pages.BrowserUnavailable as e:
        print(f"skipped: {e}")
        return check_pages.SKIP
    with browser, tempfile.TemporaryDirectory(prefix="punctual-report-pages-") as scratch:
        print(f"using {browser.version}")
        folder = os.path.abspath(args.keep) if args.keep else scratch
        os.makedirs(folder, exist_ok=True)
        pages = write_pages(os.path.abspath(args.punctual), folder)
        problems = check_pages.check_pages(browser, pages)
    if problems:
        print(f"{problems} problem(s) in the pages above")
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
