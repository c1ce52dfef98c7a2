#!/usr/bin/python3
"""Charts of the bench's failure study: for each known failure, the error against the parameter
that provokes it, one line per variant (filter, layout or method).

Usage: /usr/bin/python3 bench/plot_failures.py DIR   (reads DIR/failures.csv; writes
DIR/charts/failure-<study>.png and .svg, and DIR/failures.html)
"""
import csv
import html
import os
import sys
from collections import OrderedDict

import matplotlib

matplotlib.use("Agg")
matplotlib.rcParams["svg.hashsalt"] = "punctual"  # identical SVGs run after run
import matplotlib.pyplot as plt  # noqa: E402


def read_studies(path):
    """Rows of failures.csv grouped by study, then by variant, in file order."""
    studies = OrderedDict()
    with open(path, newline="") as f:
        for row in csv.DictReader(f):
            study = studies.setdefault(row["study"], {"parameter": row["parameter"], "metric": row["metric"],
                                                      "variants": OrderedDict()})
            study["variants"].setdefault(row["variant"], []).append((float(row["value"]), float(row["error"])))
    return studies


def plot_study(name, study, charts):
    """One chart: error (y) against the provoking parameter (x), a line per variant."""
    fig, ax = plt.subplots(figsize=(6.4, 4.0))
    for variant, points in study["variants"].items():
        points.sort()
        ax.plot([p[0] for p in points], [p[1] for p in points], marker="o", label=variant)
    ax.set_title(name)
    ax.set_xlabel(study["parameter"])
    ax.set_ylabel(study["metric"])
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    base = os.path.join(charts, "failure-" + name)
    fig.savefig(base + ".png", dpi=100, metadata={"Software": None})
    fig.savefig(base + ".svg", metadata={"Date": None})
    plt.close(fig)
    return "failure-" + name + ".png"


def main(folder):
    studies = read_studies(os.path.join(folder, "failures.csv"))
    charts = os.path.join(folder, "charts")
    os.makedirs(charts, exist_ok=True)
    parts = ["<!DOCTYPE html><html><head><meta charset='utf-8'><title>Where methods fail</title></head><body>",
             "<h1>Where methods fail</h1>"]
    for name, study in studies.items():
        image = plot_study(name, study, charts)
        parts.append("<h2>%s</h2><img src='charts/%s' alt='%s'>" % (html.escape(name), image, html.escape(name)))
    parts.append("</body></html>\n")
    with open(os.path.join(folder, "failures.html"), "w") as f:
        f.write("\n".join(parts))
    return len(studies)


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit("usage: plot_failures.py DIR")
    print("wrote %d failure charts" % main(sys.argv[1]))
