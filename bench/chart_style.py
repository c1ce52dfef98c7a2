"""What every chart of plot_results.py and sweep_charts.py shares: the fixed style, saving,
light-count axes, and how a measured time is drawn (its spread as an error bar, a flagged
configuration hollow and named under its chart).

A time's error bar is its interquartile range over the rounds (P_iqr_ms, or an older bench's
P_spread_ms), drawn centred on the median. A flagged row (its spread exceeds results.json's
noise.flag_limit) is drawn as a hollow marker with a black edge, never as an ordinary point, and
its configuration is added to the figure's `flagged` list, which index.html prints under the
chart.
"""

import math
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402  (after selecting the backend)
from matplotlib.lines import Line2D  # noqa: E402
from matplotlib.ticker import FixedLocator, NullLocator  # noqa: E402

from bench_data import is_flagged, light_count, method_order, method_style, number, spread  # noqa: E402

FLAGGED_LABEL = "_flagged"  # the label of a flagged row's hollow marker (kept out of legends)
FLAGGED_LEGEND = "flagged: spread over the limit"


class SkipChart(Exception):
    """Raised by a chart function when the data cannot support its chart; the message says why."""


def configure_matplotlib():
    """Fixed style and a fixed SVG id salt, so that reruns write identical files."""
    matplotlib.rcParams.update({
        "svg.hashsalt": "punctual-bench", "svg.fonttype": "path", "figure.dpi": 100,
        "savefig.dpi": 100, "font.size": 9, "axes.grid": True, "grid.alpha": 0.3,
        "axes.titlesize": 10, "legend.fontsize": 8,
    })


def panel_grid(count, width, height):
    """A figure of `count` panels of width x height inches, at most three a row (the spare cells
    hidden); returns the figure and the `count` axes in reading order."""
    ncols = min(3, count)
    nrows = math.ceil(count / ncols)
    fig, axes = plt.subplots(nrows, ncols, figsize=(width * ncols, height * nrows), squeeze=False)
    for ax in axes.flat[count:]:
        ax.set_visible(False)
    return fig, list(axes.flat[:count])


def save_chart(fig, charts_dir, name, outputs):
    """Writes charts_dir/name.png and .svg without timestamps through `outputs` (temporaries,
    renamed at its commit: output_file.py), and closes the figure even when a write fails."""
    try:
        outputs.write_with(os.path.join(charts_dir, name + ".png"), lambda f: fig.savefig(
            f, format="png", metadata={"Software": None}))
        outputs.write_with(os.path.join(charts_dir, name + ".svg"), lambda f: fig.savefig(
            f, format="svg", metadata={"Date": None, "Creator": None}))
    finally:
        plt.close(fig)


def set_count_axis(ax, counts):
    """Light counts on x: log 2 when they span a wide range, ticks at the measured counts."""
    counts = sorted(set(counts))
    if counts and counts[0] > 0 and counts[-1] / counts[0] >= 8:
        ax.set_xscale("log", base=2)
    ax.xaxis.set_major_locator(FixedLocator(counts))
    ax.xaxis.set_minor_locator(NullLocator())
    ax.set_xticklabels([str(c) for c in counts])
    ax.set_xlabel("lights (spot + point)")


def note_flagged(fig, rows):
    """Adds the configurations of the flagged `rows` to fig.flagged (in order, once each)."""
    listed = getattr(fig, "flagged", [])
    for r in rows:
        if is_flagged(r) and r.get("config", "") not in listed:
            listed.append(r.get("config", ""))
    fig.flagged = listed


def mark_flagged(ax, points, colour, marker, size=9):
    """Draws the flagged (x, y) points hollow over whatever marker is there: a white face, the
    line's colour as a thick edge, and a black ring around it."""
    if not points:
        return
    xs, ys = [p[0] for p in points], [p[1] for p in points]
    ax.plot(xs, ys, linestyle="", marker=marker, markersize=size, markerfacecolor="white",
            markeredgecolor=colour, markeredgewidth=1.8, zorder=4, label=FLAGGED_LABEL)
    ax.plot(xs, ys, linestyle="", marker="o", markersize=size + 7, markerfacecolor="none",
            markeredgecolor="black", markeredgewidth=0.8, zorder=4, label=FLAGGED_LABEL)


def flagged_handle():
    """The legend entry of the flagged markers."""
    return Line2D([], [], linestyle="", marker="o", markersize=8, markerfacecolor="white",
                  markeredgecolor="black", label=FLAGGED_LEGEND)


def add_flagged_legend(ax, **kwargs):
    """The axes' legend, with the flagged entry when the axes draw a flagged point."""
    handles, labels = ax.get_legend_handles_labels()
    if any(line.get_label() == FLAGGED_LABEL for a in ax.figure.axes for line in a.lines):
        handles.append(flagged_handle())
        labels.append(FLAGGED_LEGEND)
    if handles:
        ax.legend(handles, labels, **kwargs)


def time_line(ax, rows, x_of, column, colour, marker, label, linestyle="-"):
    """One line of `column` against x_of(row) with its spread as error bars and its flagged rows
    hollow; returns the y values drawn. Rows without x or y are left out."""
    pts = sorted((x_of(r), number(r, column), spread(r, column), is_flagged(r)) for r in rows
                 if x_of(r) is not None and number(r, column) is not None)
    if not pts:
        return []
    xs, ys = [p[0] for p in pts], [p[1] for p in pts]
    # Half the interquartile range each side, kept above 0 for a log axis.
    low = [min((p[2] or 0.0) / 2, 0.999 * p[1]) if p[1] > 0 else (p[2] or 0.0) / 2 for p in pts]
    high = [(p[2] or 0.0) / 2 for p in pts]
    ax.errorbar(xs, ys, yerr=[low, high], color=colour, marker=marker, linestyle=linestyle,
                capsize=2.5, elinewidth=0.9, label=label)
    mark_flagged(ax, [(p[0], p[1]) for p in pts if p[3]], colour, marker)
    note_flagged(ax.figure, [r for r in rows if x_of(r) is not None and number(r, column) is not None])
    return ys


def plot_per_method(ax, rows, column, methods, x_of=light_count):
    """One line per method of `column` against x_of(row) (light count by default), time columns
    with their spread as error bars and flagged rows hollow; returns the values drawn."""
    drawn = []
    for method in method_order(rows, methods):
        colour, marker = method_style(method, methods)
        own = [r for r in rows if r.get("method") == method]
        if column.endswith("_ms"):
            drawn += time_line(ax, own, x_of, column, colour, marker, method)
            continue
        pts = sorted((x_of(r), number(r, column)) for r in own
                     if x_of(r) is not None and number(r, column) is not None)
        if pts:
            ax.plot([p[0] for p in pts], [p[1] for p in pts], color=colour, marker=marker,
                    label=method)
            drawn += [p[1] for p in pts]
    return drawn


def draw_front(ax, points, front):
    """The Pareto front of `points` as a step line with its points ringed."""
    xs, ys = [points[i][0] for i in front], [points[i][1] for i in front]
    ax.plot(xs, ys, drawstyle="steps-post", color="black", linewidth=1.2, zorder=1,
            label="Pareto front")
    ax.scatter(xs, ys, s=150, facecolors="none", edgecolors="black", linewidths=1.5, zorder=3)


def time_point_errors(ax, rows, points, column, scale=1.0):
    """Error bars (the rows' spread of `column`, times `scale`) on the scattered (x, y) points of
    the rows, and the flagged ones hollow; for the Pareto charts, whose y is a time."""
    for (x, y), r in zip(points, rows):
        s = spread(r, column)
        if s:
            ax.errorbar([x], [y], yerr=[[min(s * scale / 2, 0.999 * y)], [s * scale / 2]],
                        fmt="none", ecolor="0.35", elinewidth=0.8, capsize=2, zorder=1)
    mark_flagged(ax, [p for p, r in zip(points, rows) if is_flagged(r)], "black", "o", size=7)
    note_flagged(ax.figure, rows)
