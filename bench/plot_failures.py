#!/usr/bin/python3
"""Charts of the bench's failure study: for each known failure, the error against the parameter
that provokes it, one line per variant (filter, layout or method).

Usage: /usr/bin/python3 bench/plot_failures.py DIR   (reads DIR/failures.csv; writes
DIR/charts/failure-<study>.png and .svg and DIR/failures.html, and adds the charts to
DIR/index.html when plot_results.py has written one; run it after plot_results.py)

Files are read by input_file.py's rules and written together by output_file.py, as
plot_results.py's: a run that fails (one line on stderr: `plot_failures.py: error: <file>:
<problem>` and status 1, or an interrupt and 128 + the signal) leaves every file as it was.
"""
import csv
import html
import io
import os
import sys
import textwrap
from collections import OrderedDict

PROGRAM = "plot_failures.py"
if __name__ == "__main__":
    # Before the slow imports below: an interrupt there is one line, not a traceback.
    import output_file
    output_file.exit_quietly_on_interrupt(PROGRAM)

import matplotlib  # noqa: E402

matplotlib.use("Agg")
matplotlib.rcParams["svg.hashsalt"] = "punctual"  # identical SVGs run after run
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.ticker import FixedLocator, NullLocator  # noqa: E402

import output_file  # noqa: E402
from input_file import InputFileError, read_text  # noqa: E402

WIDE_RATIO = 10.0  # a log x axis once the largest value is this many times the smallest, as plot_results


def read_studies(path):
    """Rows of failures.csv grouped by study, then by variant, in file order. Raises
    InputFileError when the file cannot be read (input_file.py's rules) or a row is bad."""
    studies = OrderedDict()
    reader = csv.DictReader(io.StringIO(read_text(path), newline=""))
    try:
        for row in reader:
            study = studies.setdefault(row["study"], {"parameter": row["parameter"], "metric": row["metric"],
                                                      "variants": OrderedDict()})
            study["variants"].setdefault(row["variant"], []).append((float(row["value"]), float(row["error"])))
    except KeyError as err:
        raise InputFileError(path, f"no {err.args[0]} column") from None
    except (TypeError, ValueError, csv.Error) as err:
        # TypeError: a short row's missing cell is None, which float() refuses.
        raise InputFileError(path, f"line {reader.line_num}: {err}") from None
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


def plot_study(name, study, charts, outputs):
    """One chart (study_figure) as charts/failure-NAME.png and .svg, written into `outputs`
    (renamed at its commit: output_file.py); returns the PNG's name."""
    fig = study_figure(name, study)
    base = os.path.join(charts, "failure-" + name)
    try:
        outputs.write_with(base + ".png", lambda f: fig.savefig(
            f, format="png", dpi=100, metadata={"Software": None}))
        outputs.write_with(base + ".svg", lambda f: fig.savefig(
            f, format="svg", metadata={"Date": None}))
    finally:
        plt.close(fig)
    return "failure-" + name + ".png"


MARK_BEGIN = "<!-- failure study: begin -->"
MARK_END = "<!-- failure study: end -->"


def add_to_index(folder, sections, outputs):
    """Puts the failure charts into DIR/index.html (replacing an earlier copy), so the index
    shows every chart of the bench; False when there is no index.html (plot_results.py has not
    run). index.html is read by input_file.py's rules: a FIFO there is an error, not a hang."""
    index = os.path.join(folder, "index.html")
    try:
        page = read_text(index)
    except InputFileError as err:
        if err.absent:
            return False
        raise
    if MARK_BEGIN in page and MARK_END in page:
        # The block's own line end goes with it, so that a rerun writes the same bytes.
        end = page.index(MARK_END) + len(MARK_END)
        page = page[:page.index(MARK_BEGIN)] + page[end + page.startswith("\n", end):]
    block = MARK_BEGIN + "\n<h2>Where methods fail</h2>\n" + "\n".join(sections) + "\n" + MARK_END + "\n"
    at = page.rfind("</body>")
    page = page[:at] + block + page[at:] if at >= 0 else page + block
    outputs.write_text(index, page)
    return True


def write_failures(folder, outputs):
    """Reads DIR/failures.csv and writes its charts, failures.html and index.html's section
    into `outputs` (not committed); returns the number of studies."""
    studies = read_studies(os.path.join(folder, "failures.csv"))
    charts = os.path.join(folder, "charts")
    os.makedirs(charts, exist_ok=True)
    parts = ["<!DOCTYPE html><html><head><meta charset='utf-8'><title>Where methods fail</title></head><body>",
             "<h1>Where methods fail</h1>"]
    sections = []
    for name, study in studies.items():
        image = plot_study(name, study, charts, outputs)
        sections.append("<h3>%s</h3><img src='charts/%s' alt='%s'>" % (html.escape(name), image, html.escape(name)))
    parts.extend(sections)
    parts.append("</body></html>\n")
    outputs.write_text(os.path.join(folder, "failures.html"), "\n".join(parts))
    add_to_index(folder, sections, outputs)
    return len(studies)


def main(folder):
    """Writes DIR's failure charts and pages, all together (output_file.Outputs); returns the
    number of studies. Raises on bad input or a write error, leaving every file as it was."""
    outputs = output_file.Outputs()
    try:
        count = write_failures(folder, outputs)
        outputs.commit()
    finally:
        outputs.discard()
    return count


def command(argv):
    """Command line entry point; returns the exit status. Bad input, a write error or an
    interrupt is one line on stderr (status 1, or 128 + the signal) and changes no file."""
    if len(argv) != 1:
        print(f"{PROGRAM}: error: usage: {PROGRAM} DIR", file=sys.stderr)
        return 2

    def body(outputs):
        count = write_failures(argv[0], outputs)
        outputs.commit()
        print("wrote %d failure charts" % count)
        return 0

    return output_file.run_script(PROGRAM, body)


if __name__ == "__main__":
    sys.exit(command(sys.argv[1:]))
