#!/usr/bin/python3
"""Charts of the bench's failure study: for each known failure, the error against the parameter
that provokes it, one line per variant (filter, layout or method).

Usage: /usr/bin/python3 bench/plot_failures.py DIR   (reads DIR/failures.csv; writes
DIR/charts/failure-<study>.png and .svg and DIR/failures.html, and adds the charts to
DIR/index.html when plot_results.py has written one; run it after plot_results.py)
"""
import csv
import html
import os
import sys
import textwrap
from collections import OrderedDict

import matplotlib

matplotlib.use("Agg")
matplotlib.rcParams["svg.hashsalt"] = "punctual"  # identical SVGs run after run
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.ticker import FixedLocator, NullLocator  # noqa: E402

WIDE_RATIO = 10.0  # a log x axis once the largest value is this many times the smallest, as plot_results


def read_studies(path):
    """Rows of failures.csv grouped by study, then by variant, in file order."""
    studies = OrderedDict()
    with open(path, newline="") as f:
        for row in csv.DictReader(f):
            study = studies.setdefault(row["study"], {"parameter": row["parameter"], "metric": row["metric"],
                                                      "variants": OrderedDict()})
            study["variants"].setdefault(row["variant"], []).append((float(row["value"]), float(row["error"])))
    return studies


LINE_STYLES = ["-", "--", ":", "-."]
MARKERS = ["o", "s", "^", "D"]


def variant_styles(variants):
    """{variant: plot keyword arguments}. Variants named "GROUP: PART" (a blend and a region of the
    frame, say) take a colour per group and a line style and marker per part, so that lines
    lying on one another stay told apart; other variants take the colour cycle's next colour."""
    parts = [v.split(": ", 1) for v in variants]
    if not all(len(p) == 2 for p in parts):
        return {v: {"marker": "o"} for v in variants}
    groups = list(dict.fromkeys(p[0] for p in parts))
    kinds = list(dict.fromkeys(p[1] for p in parts))
    colours = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    return {v: {"color": colours[groups.index(g) % len(colours)],
                "linestyle": LINE_STYLES[kinds.index(k) % len(LINE_STYLES)],
                "marker": MARKERS[kinds.index(k) % len(MARKERS)]}
            for v, (g, k) in zip(variants, parts)}


def study_figure(name, study):
    """Error (y) against the provoking parameter (x), a line per variant of the CSV, in file
    order: the variants (filters, layouts, methods) are whatever failures.csv holds, so a new
    one is drawn with no edit here (styled by variant_styles). x is logarithmic when its positive
    values span more than WIDE_RATIO."""
    fig, ax = plt.subplots(figsize=(6.4, 4.0))
    styles = variant_styles(list(study["variants"]))
    for variant, points in study["variants"].items():
        points.sort()
        ax.plot([p[0] for p in points], [p[1] for p in points], label=variant, **styles[variant])
    values = sorted({p[0] for points in study["variants"].values() for p in points})
    if values and values[0] > 0 and values[-1] / values[0] > WIDE_RATIO:
        # Parameters that double or grow geometrically (view depths, heights): a log axis with a
        # tick at every measured value, so the near end is not squeezed into one corner.
        ax.set_xscale("log")
        ax.xaxis.set_major_locator(FixedLocator(values))
        ax.xaxis.set_minor_locator(NullLocator())
        ax.set_xticklabels(["%g" % v for v in values])
    if all(p[1] >= 0 for points in study["variants"].values() for p in points):
        ax.set_ylim(bottom=0)  # errors from zero, so that a small difference does not look large
    ax.set_title(name)
    ax.set_xlabel(study["parameter"])
    ax.set_ylabel("\n".join(textwrap.wrap(study["metric"], 48)))  # long metrics on two or three lines
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    return fig


def plot_study(name, study, charts):
    """One chart (study_figure) as charts/failure-NAME.png and .svg; returns the PNG's name."""
    fig = study_figure(name, study)
    base = os.path.join(charts, "failure-" + name)
    fig.savefig(base + ".png", dpi=100, metadata={"Software": None})
    fig.savefig(base + ".svg", metadata={"Date": None})
    plt.close(fig)
    return "failure-" + name + ".png"


MARK_BEGIN = "<!-- failure study: begin -->"
MARK_END = "<!-- failure study: end -->"


def add_to_index(folder, sections):
    """Puts the failure charts into DIR/index.html (replacing an earlier copy), so the index
    shows every chart of the bench."""
    index = os.path.join(folder, "index.html")
    if not os.path.exists(index):
        return False
    with open(index) as f:
        page = f.read()
    if MARK_BEGIN in page:
        page = page[:page.index(MARK_BEGIN)] + page[page.index(MARK_END) + len(MARK_END):]
    block = MARK_BEGIN + "\n<h2>Where methods fail</h2>\n" + "\n".join(sections) + "\n" + MARK_END + "\n"
    at = page.rfind("</body>")
    page = page[:at] + block + page[at:] if at >= 0 else page + block
    with open(index, "w") as f:
        f.write(page)
    return True


def main(folder):
    studies = read_studies(os.path.join(folder, "failures.csv"))
    charts = os.path.join(folder, "charts")
    os.makedirs(charts, exist_ok=True)
    parts = ["<!DOCTYPE html><html><head><meta charset='utf-8'><title>Where methods fail</title></head><body>",
             "<h1>Where methods fail</h1>"]
    sections = []
    for name, study in studies.items():
        image = plot_study(name, study, charts)
        sections.append("<h3>%s</h3><img src='charts/%s' alt='%s'>" % (html.escape(name), image, html.escape(name)))
    parts.extend(sections)
    parts.append("</body></html>\n")
    with open(os.path.join(folder, "failures.html"), "w") as f:
        f.write("\n".join(parts))
    add_to_index(folder, sections)
    return len(studies)


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit("usage: plot_failures.py DIR")
    print("wrote %d failure charts" % main(sys.argv[1]))
