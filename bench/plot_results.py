#!/usr/bin/python3
"""Charts and an HTML index for the results of `punctual bench --out-dir DIR`.

    /usr/bin/python3 bench/plot_results.py DIR

reads DIR/results.csv and writes DIR/charts/<name>.png and .svg for every chart the data allows,
then DIR/index.html with every chart, every DIR/images/*.png and the CSV as a table. A chart whose
series or columns are missing or empty is skipped with a note in index.html, so the few rows of
`--quick` work too. Output is deterministic: rerunning on the same CSV gives identical files.

Nothing here names the methods, shadow filters or passes: DIR/results.json says them
("methods" and "shadow_filters" in table order, "passes" in frame order), and the script draws
whatever it lists, a method's colour and marker taken from a fixed palette by its position. The
per-pass columns of results.csv are P_ms and P_spread_ms for every pass P. Without those keys (a
folder from an older bench) the names come from the CSV itself, sorted.

Needs Debian's /usr/bin/python3 with python3-matplotlib (no other packages).
"""

import argparse
import csv
import html
import json
import math
import os
import sys
import urllib.parse

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402  (after selecting the backend)
from matplotlib.lines import Line2D  # noqa: E402
from matplotlib.ticker import FixedLocator, MaxNLocator, NullLocator, PercentFormatter  # noqa: E402

# The columns every row has besides the per-pass times (see pass_columns).
LEADING_COLUMNS = """config series method spot point shadows shadow_res shadow_format shadow_filter
    point_layout shadowed_spots shadowed_points frames""".split()
TRAILING_COLUMNS = """total_ms total_spread_ms tested_per_pixel affecting_per_pixel efficiency
    missed_energy image_error pixels_off shadow_views shadow_memory_bytes shadow_texels_rendered
    shadow_filter_taps shadow_reduced_views shadow_misclassified shadow_misclassified_all
    shadow_misclassified_1px shadow_false_shadow shadow_false_lit cascades sun_misclassified
    sun_misclassified_1px sun_cascade0_misclassified_1px sun_cascade1_misclassified_1px
    sun_cascade2_misclassified_1px sun_cascade3_misclassified_1px scene_triangles objects
    objects_in_view camera_triangles camera_draws shadow_draws shadow_draws_max shadow_triangles
    peak_rss_bytes device_bytes""".split()
# Method styles by position in results.json's "methods": the first four keep the colours the
# charts have always had (brute, per-object, tiled, clustered). Grey and "x" are left out: they
# mark a method that results.json does not list.
METHOD_COLOURS = ["tab:red", "tab:orange", "tab:blue", "tab:green", "tab:purple", "tab:brown",
                  "tab:pink", "tab:olive", "tab:cyan"]
METHOD_MARKERS = ["o", "s", "^", "D", "v", "P", "*", "h"]  # 8 against 9 colours: 72 pairs
OTHER_STYLE = ("tab:gray", "x")  # a method in the rows that results.json does not list
# Pass colours by position in "passes" (a palette apart from the methods').
PASS_COLOURS = ["#66c2a5", "#fc8d62", "#8da0cb", "#e78ac3", "#a6d854", "#ffd92f", "#e5c494",
                "#b3b3b3"]
PASS_HATCHES = [None, "//", "xx", ".."]  # beyond the palette, the colours repeat with a hatch
# Errors are measured against brute force, so its own error cells are empty; it is drawn at 0.
REFERENCE_METHOD = "brute"
LIGHT_SERIES = [("mix", "mix (spot:point = 2:1)"), ("spot-only", "spot lights only"),
                ("point-only", "point lights only")]
WIDE_RATIO = 10.0  # a log axis once the largest value is this many times the smallest


class SkipChart(Exception):
    """Raised by a chart function when the data cannot support its chart; the message says why."""


# ----------------------------------------------------------------------------------- data access

NAME_KEYS = ("methods", "shadow_filters", "passes")


def pass_columns(passes):
    """The per-pass columns of results.csv: P_ms then P_spread_ms, for every pass in order."""
    return [f"{p}_ms" for p in passes] + [f"{p}_spread_ms" for p in passes]


def known_columns(passes):
    """Every column a row of results.csv should have, for these passes."""
    return LEADING_COLUMNS + pass_columns(passes) + TRAILING_COLUMNS


def passes_in_header(header):
    """Pass names of the P_ms columns in `header` (not total_ms, not the spreads), sorted."""
    return sorted(c[:-len("_ms")] for c in header
                  if c.endswith("_ms") and not c.endswith("_spread_ms") and c != "total_ms")


def read_names(path, header, rows):
    """{"methods", "shadow_filters", "passes": names in order} from results.json, and notes.

    A key that results.json lacks (an older bench), or the whole file when it is absent or
    unreadable, falls back to what results.csv holds, sorted: the methods and filters of the rows,
    the passes of the P_ms columns. The notes say which keys fell back and why."""
    document, notes = {}, []
    try:
        with open(path, encoding="utf-8") as f:
            document = json.load(f)
    except FileNotFoundError:
        pass
    except (OSError, ValueError) as err:
        notes.append(f"results.json could not be read ({err}); names come from results.csv.")
    if not isinstance(document, dict):
        document = {}
    fallback = {"methods": sorted({r.get("method", "") for r in rows} - {""}),
                "shadow_filters": sorted({r.get("shadow_filter", "") for r in rows} - {""}),
                "passes": passes_in_header(header)}
    names, fell_back = {}, []
    for key in NAME_KEYS:
        listed = document.get(key)
        if isinstance(listed, list) and all(isinstance(n, str) for n in listed):
            names[key] = list(listed)
        else:
            names[key] = fallback[key]
            fell_back.append(key)
    if document and fell_back:
        notes.append(f"results.json lacks {', '.join(fell_back)}; taken from results.csv, sorted.")
    return names, notes


def read_results(path):
    """Returns (header, rows) of the CSV; rows are dicts of strings, missing cells are ''."""
    with open(path, newline="", encoding="utf-8") as f:
        reader = csv.DictReader(f)
        header = list(reader.fieldnames or [])
        rows = [{k: (v or "").strip() for k, v in row.items() if k is not None} for row in reader]
    return header, rows


def number(row, column):
    """The cell as a finite float, or None when it is empty, missing or not a number."""
    try:
        value = float(row.get(column) or "")
    except ValueError:
        return None
    return value if math.isfinite(value) else None


def light_count(row):
    """Spot plus point lights of a row (0 for missing counts)."""
    return int((number(row, "spot") or 0) + (number(row, "point") or 0))


def series_rows(rows, series):
    """The rows of one series, in file order."""
    return [r for r in rows if r.get("series") == series]


def method_order(rows, methods):
    """The methods present in `rows`: those of `methods` in its order, then any others sorted."""
    return ordered((r.get("method", "") for r in rows), methods)


def method_style(method, methods):
    """(colour, marker) of a method: by its position in `methods`, OTHER_STYLE when absent."""
    if method not in methods:
        return OTHER_STYLE
    i = methods.index(method)
    return METHOD_COLOURS[i % len(METHOD_COLOURS)], METHOD_MARKERS[i % len(METHOD_MARKERS)]


def ordered(present, names):
    """`present` values in the order of `names`, then any others sorted."""
    present = set(present)
    return [n for n in names if n in present] + sorted(present - set(names))


def is_wide(values):
    """True when the positive values span more than WIDE_RATIO (and none is <= 0)."""
    values = [v for v in values if v is not None]
    return bool(values) and min(values) > 0 and max(values) / min(values) > WIDE_RATIO


def varying_label(row, rows, fields):
    """A label made of those `fields` whose values differ between `rows`."""
    varying = [f for f in fields if len({r.get(f, "") for r in rows}) > 1] or fields[:1]
    return " ".join(row.get(f, "") for f in varying)


def pareto_front(points):
    """Indices of the non-dominated (x, y) points, both lower-is-better, sorted by x then y: no
    other point is at least as good in both and better in one. Equal points are all kept."""
    order = sorted(range(len(points)), key=lambda i: (points[i][0], points[i][1]))
    front, best_y = [], math.inf
    for i in order:
        x, y = points[i]
        if y < best_y or (front and points[front[-1]] == (x, y)):
            front.append(i)
            best_y = min(best_y, y)
    return front


# ------------------------------------------------------------------------------- chart helpers

def configure_matplotlib():
    """Fixed style and a fixed SVG id salt, so that reruns write identical files."""
    matplotlib.rcParams.update({
        "svg.hashsalt": "punctual-bench", "svg.fonttype": "path", "figure.dpi": 100,
        "savefig.dpi": 100, "font.size": 9, "axes.grid": True, "grid.alpha": 0.3,
        "axes.titlesize": 10, "legend.fontsize": 8,
    })


def save_chart(fig, charts_dir, name):
    """Writes charts_dir/name.png and .svg without timestamps, and closes the figure."""
    fig.savefig(os.path.join(charts_dir, name + ".png"), metadata={"Software": None})
    fig.savefig(os.path.join(charts_dir, name + ".svg"), metadata={"Date": None, "Creator": None})
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


def plot_per_method(ax, rows, column, methods):
    """One line per method of `column` against light count; returns the values drawn."""
    drawn = []
    for method in method_order(rows, methods):
        pts = sorted((light_count(r), number(r, column)) for r in rows
                     if r.get("method") == method and number(r, column) is not None)
        if pts:
            colour, marker = method_style(method, methods)
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


# ---------------------------------------------------------------------------------------- charts

def chart_pass_time(rows, names, column, what):
    """Median GPU time (forward pass, or whole frame) against light count, one line per method,
    one panel per light series (mix, spot-only, point-only). It shows how each method scales with
    the number of lights: brute force grows linearly, culled lists with the lights that actually
    reach pixels."""
    panels = [(s, t, series_rows(rows, s)) for s, t in LIGHT_SERIES]
    panels = [(s, t, rs) for s, t, rs in panels if any(number(r, column) is not None for r in rs)]
    if not any(s == "mix" for s, _, _ in panels):
        raise SkipChart(f"no {column} values in the mix series")
    fig, axes = plt.subplots(1, len(panels), figsize=(4.2 * len(panels) + 0.6, 4.0), sharey=True,
                             squeeze=False)
    values = []
    for ax, (_, title, rs) in zip(axes[0], panels):
        values += plot_per_method(ax, rs, column, names["methods"])
        set_count_axis(ax, [light_count(r) for r in rs if number(r, column) is not None])
        ax.set_title(title)
    if is_wide(values):
        axes[0][0].set_yscale("log")
    axes[0][0].set_ylabel(f"{what}: median GPU ms")
    axes[0][0].legend()
    fig.suptitle(f"{what} time against light count")
    fig.tight_layout()
    return fig


def chart_culling_efficiency(rows, names):
    """Culling efficiency (lights tested / lights affecting each pixel, 1 = perfect) against
    light count for the mix series, and next to it the two per-pixel counts it is made of. It
    shows how much wasted shading work each light list leaves as the lights get denser."""
    rs = [r for r in series_rows(rows, "mix") if number(r, "efficiency") is not None]
    if not rs:
        raise SkipChart("no efficiency values in the mix series")
    fig, (left, right) = plt.subplots(1, 2, figsize=(10, 4.0))
    values = plot_per_method(left, rs, "efficiency", names["methods"])
    left.axhline(1.0, color="black", linestyle=":", linewidth=1, label="perfect (1)")
    if is_wide(values + [1.0]):
        left.set_yscale("log")
    left.set_ylabel("efficiency = tested / affecting")
    left.set_title("culling efficiency (lower is better)")
    left.legend()
    tested = plot_per_method(right, rs, "tested_per_pixel", names["methods"])
    # Exact counts, the same for every method at one light count.
    affecting = {light_count(r): number(r, "affecting_per_pixel") for r in rs
                 if number(r, "affecting_per_pixel") is not None}
    if affecting:
        xs = sorted(affecting)
        right.plot(xs, [affecting[x] for x in xs], color="black", linestyle="--",
                   label="affecting (exact)")
    if is_wide(tested + list(affecting.values())):
        right.set_yscale("log")
    right.set_ylabel("lights per covered pixel (mean)")
    right.set_title("lights tested and lights affecting")
    if tested or affecting:
        right.legend()
    for ax in (left, right):
        set_count_axis(ax, [light_count(r) for r in rs])
    fig.suptitle("light culling efficiency, mix series (spot:point = 2:1)")
    fig.tight_layout()
    return fig


def finish_shadow_pareto(fig, ax, points, front, error, cost, title, legend):
    """The shadow Pareto charts' common end: the front, a log cost axis when the costs are wide, a
    percent error axis, labels (both lower is better), title and legend."""
    draw_front(ax, points, front)
    if is_wide([p[1] for p in points]):
        ax.set_yscale("log")
    ax.xaxis.set_major_formatter(PercentFormatter(xmax=1.0))
    ax.set_xlabel(f"{error} (lower is better)")
    ax.set_ylabel(f"{cost} (lower is better)")
    ax.set_title(title)
    ax.legend(title=legend)
    fig.tight_layout()
    return fig


def chart_shadow_pareto(rows, names):
    """Whole-frame time against the fraction of shadow tests misclassified (outside the edge
    band, against the Embree reference), one point per shadow resolution and filter. The Pareto
    front marks the settings no other setting beats in both speed and accuracy."""
    rs = [r for r in series_rows(rows, "shadow-quality")
          if number(r, "total_ms") is not None and number(r, "shadow_misclassified") is not None]
    if not rs:
        raise SkipChart("no shadow-quality rows with both total_ms and shadow_misclassified")
    points = [(number(r, "shadow_misclassified"), number(r, "total_ms")) for r in rs]
    front = pareto_front(points)
    fig, ax = plt.subplots(figsize=(8, 5.2))
    filters = ordered((r.get("shadow_filter", "") for r in rs), names["shadow_filters"])
    cmap = plt.get_cmap("tab10")
    for k, flt in enumerate(filters):
        pts = [p for p, r in zip(points, rs) if r.get("shadow_filter", "") == flt]
        ax.scatter([p[0] for p in pts], [p[1] for p in pts], color=cmap(k % 10), zorder=2,
                   label=flt or "(no filter)")
    fields = ["shadow_res", "shadow_filter", "point_layout", "method", "spot", "point"]
    for (x, y), r in zip(points, rs):
        ax.annotate(varying_label(r, rs, fields), (x, y), xytext=(5, 4),
                    textcoords="offset points", fontsize=7)
    return finish_shadow_pareto(fig, ax, points, front, "shadow tests misclassified outside the edge band",
                                "whole frame: median GPU ms",
                                "shadow quality: speed against accuracy (resolution x filter)", "filter")


def chart_shadow_memory(rows, names):
    """Shadow memory against the fraction of shadow tests misclassified outside an edge band one
    screen pixel wide (against the Embree reference), one point per resolution mode (auto or a
    fixed N) and depth format. The band's width is fixed on screen, so a coarse map cannot hide
    its error in a band that widens with its texels. The Pareto front marks the settings that no
    other beats in both memory and accuracy."""
    rs = [r for r in series_rows(rows, "shadow-quality")
          if number(r, "shadow_memory_bytes") is not None and number(r, "shadow_misclassified_1px") is not None]
    if not rs:
        raise SkipChart("no shadow-quality rows with shadow_memory_bytes and shadow_misclassified_1px")
    points = [(number(r, "shadow_misclassified_1px"), number(r, "shadow_memory_bytes") / 2**20) for r in rs]
    front = pareto_front(points)
    fig, ax = plt.subplots(figsize=(8, 5.2))
    formats = ordered((r.get("shadow_format", "") for r in rs), ["d16", "d32"])
    cmap = plt.get_cmap("tab10")
    for k, fmt in enumerate(formats):
        pts = [p for p, r in zip(points, rs) if r.get("shadow_format", "") == fmt]
        ax.scatter([p[0] for p in pts], [p[1] for p in pts], color=cmap(k % 10), zorder=2, label=fmt or "(unknown)")
    for (x, y), r in zip(points, rs):
        label = r.get("shadow_res", "")
        if r.get("shadowed_spots") and r.get("shadowed_points"):
            label += f" ({r['shadowed_spots']}+{r['shadowed_points']} lights)"
        ax.annotate(label, (x, y), xytext=(5, 4), textcoords="offset points", fontsize=7)
    return finish_shadow_pareto(fig, ax, points, front, "shadow tests misclassified outside a 1-pixel edge band",
                                "shadow memory, MiB", "shadow memory against accuracy (resolution x depth format)",
                                "format")


CASCADE_MARKERS = ["o", "s", "^", "D", "v", "P"]  # by filter, in results.json's filter order


def chart_cascade_pareto(rows, names):
    """The sun's cascades on the outdoor scene (the cascades series): the shadow stage's median GPU
    time (left) and the shadow memory (right) against the share of the sun's shadow tests
    misclassified outside an edge band one screen pixel wide (against Embree), one point per
    cascade count (colour), filter (marker) and resolution per cascade (label). The Pareto front
    of each panel marks the settings that no other beats in both cost and accuracy."""
    rs = [r for r in series_rows(rows, "cascades")
          if all(number(r, c) is not None for c in ("sun_misclassified_1px", "shadows_ms",
                                                   "shadow_memory_bytes", "cascades"))]
    if not rs:
        raise SkipChart("no cascades rows with sun_misclassified_1px, shadows_ms, shadow_memory_bytes and "
                        "cascades")
    counts = sorted({int(number(r, "cascades")) for r in rs})
    filters = ordered((r.get("shadow_filter", "") for r in rs), names["shadow_filters"])
    cmap = plt.get_cmap("viridis")
    colour = {c: cmap(k / max(len(counts) - 1, 1) * 0.85) for k, c in enumerate(counts)}
    marker = {f: CASCADE_MARKERS[k % len(CASCADE_MARKERS)] for k, f in enumerate(filters)}
    panels = [("shadows_ms", 1.0, "shadow stage: median GPU ms"),
              ("shadow_memory_bytes", 2.0 ** -20, "shadow memory, MiB")]
    fig, axes = plt.subplots(1, 2, figsize=(13, 5.2))
    for ax, (column, scale, cost) in zip(axes, panels):
        points = [(number(r, "sun_misclassified_1px"), number(r, column) * scale) for r in rs]
        for (x, y), r in zip(points, rs):
            ax.scatter([x], [y], color=colour[int(number(r, "cascades"))],
                       marker=marker[r.get("shadow_filter", "")], s=40, zorder=2)
            ax.annotate(r.get("shadow_res", ""), (x, y), xytext=(5, 4), textcoords="offset points",
                        fontsize=7)
        draw_front(ax, points, pareto_front(points))
        if is_wide([p[1] for p in points]):
            ax.set_yscale("log")
        ax.xaxis.set_major_formatter(PercentFormatter(xmax=1.0))
        ax.set_xlabel("sun's shadow tests misclassified outside a 1-pixel edge band (lower is better)")
        ax.set_ylabel(f"{cost} (lower is better)")
    axes[0].set_title("shadow stage time against accuracy")
    axes[1].set_title("shadow memory against accuracy")
    handles = [Line2D([], [], linestyle="", marker="o", color=colour[c],
                      label=f"{c} cascade{'s' if c > 1 else ''}") for c in counts]
    handles += [Line2D([], [], linestyle="", marker=marker[f], color="black", label=f or "(no filter)")
                for f in filters]
    handles += [Line2D([], [], color="black", linewidth=1.2, label="Pareto front")]
    fig.legend(handles=handles, loc="center right", title="count, filter")
    fig.suptitle("the sun's cascades: cost against accuracy (count x resolution x filter; labels: "
                 "texels a side per cascade)")
    fig.tight_layout(rect=(0, 0, 1 - 1.6 / fig.get_figwidth(), 1))
    return fig


def assignment_error_column(rows):
    """image_error when the non-brute rows have any, else pixels_off, else None."""
    for column in ("image_error", "pixels_off"):
        if any(number(r, column) is not None for r in rows if r.get("method") != REFERENCE_METHOD):
            return column
    return None


def chart_assignment_pareto(rows, names):
    """Whole-frame time against image error versus brute force, one panel per light count of the
    mix series, one point per method. Brute force is the reference (error 0 when its cell is
    empty); tiled and clustered should sit on 0 as well, and per-object's capped lists show as
    error. The Pareto front marks the methods nothing beats in both speed and accuracy."""
    mix = series_rows(rows, "mix")
    column = assignment_error_column(mix)
    if column is None:
        raise SkipChart("no image_error or pixels_off values in the mix series")

    def error(r):
        value = number(r, column)
        return 0.0 if value is None and r.get("method") == REFERENCE_METHOD else value

    rs = [r for r in mix if number(r, "total_ms") is not None and error(r) is not None]
    counts = sorted({light_count(r) for r in rs})
    ncols = min(3, len(counts))
    nrows = math.ceil(len(counts) / ncols)
    fig, axes = plt.subplots(nrows, ncols, figsize=(4.3 * ncols, 3.8 * nrows), squeeze=False)
    for ax in axes.flat[len(counts):]:
        ax.set_visible(False)
    for ax, count in zip(axes.flat, counts):
        group = [r for m in method_order(rs, names["methods"]) for r in rs
                 if light_count(r) == count and r.get("method") == m]
        points = [(error(r), number(r, "total_ms")) for r in group]
        for (x, y), r in zip(points, group):
            colour, marker = method_style(r.get("method"), names["methods"])
            ax.scatter([x], [y], color=colour, marker=marker, s=45, zorder=2,
                       label=r.get("method", ""))
        draw_front(ax, points, pareto_front(points))
        if is_wide([p[1] for p in points]):
            ax.set_yscale("log")
        spots, pts = group[0].get("spot", ""), group[0].get("point", "")
        ax.set_title(f"{count} lights ({spots} spot + {pts} point)")
        ax.xaxis.set_major_locator(MaxNLocator(4))
        ax.set_xlabel(("mean abs. error per channel" if column == "image_error"
                       else "fraction of pixels off by > 2/255") + " vs brute")
        ax.set_ylabel("whole frame: median GPU ms")
    legend = {}
    for ax in axes.flat[:len(counts)]:
        legend.update(zip(*reversed(ax.get_legend_handles_labels())))
    fig.legend(legend.values(), legend.keys(), loc="lower center", ncol=len(legend))
    fig.suptitle("light assignment: speed against accuracy (lower is better on both axes)")
    margin = 0.4 / fig.get_figheight()  # room for the title above and the legend below
    fig.tight_layout(rect=(0, margin, 1, 1 - margin / 2))
    return fig


def pass_stack(ax, bars, passes, total_label):
    """Stacked bars, one per (label, row) of `bars`, a segment per pass in frame order, with the
    whole frame's time as a black tick; returns the legend handles of the passes drawn."""
    handles = {}
    for x, (_, r) in enumerate(bars):
        bottom = 0.0
        for k, name in enumerate(passes):
            value = number(r, f"{name}_ms") or 0.0
            bar = ax.bar(x, value, bottom=bottom, width=0.7, edgecolor="black", linewidth=0.4,
                         color=PASS_COLOURS[k % len(PASS_COLOURS)],
                         hatch=PASS_HATCHES[k // len(PASS_COLOURS) % len(PASS_HATCHES)],
                         label=name)
            handles.setdefault(name, bar)
            bottom += value
        total = number(r, "total_ms")
        if total is not None:
            tick = ax.scatter([x], [total], marker="_", s=500, color="black", zorder=3,
                              label=total_label)
            handles.setdefault(total_label, tick)
    ax.set_xticks(range(len(bars)))
    ax.set_xticklabels([label for label, _ in bars], rotation=30, ha="right")
    return handles


def chart_pass_breakdown(rows, names):
    """Median GPU time of every pass, stacked in frame order, one bar per method: at the largest
    light count of the mix series, and in the shadows series with shadows off and on. It shows
    where each method spends the frame, and what the shadow pass adds; the black tick is the
    whole frame (first to last timestamp), so the gap above a bar is time between passes."""
    passes = names["passes"]
    if not any(number(r, f"{p}_ms") is not None for p in passes for r in rows):
        raise SkipChart("no per-pass time columns (results.json \"passes\" and P_ms columns)")
    panels = []
    mix = [r for r in series_rows(rows, "mix") if number(r, "total_ms") is not None]
    if mix:
        count = max(light_count(r) for r in mix)
        largest = [r for r in mix if light_count(r) == count]
        bars = [(m, r) for m in method_order(largest, names["methods"])
                for r in largest if r.get("method") == m]
        panels.append((f"mix series, {count} lights", bars))
    shadow = [r for r in series_rows(rows, "shadows") if number(r, "total_ms") is not None]
    if shadow:
        bars = []
        for m in method_order(shadow, names["methods"]):
            own = sorted((r for r in shadow if r.get("method") == m),
                         key=lambda r: number(r, "shadows") or 0)  # off, then on
            bars += [(f"{m}, shadows {'on' if number(r, 'shadows') else 'off'}", r) for r in own]
        count = max(light_count(r) for r in shadow)
        panels.append((f"shadows series, {count} lights", bars))
    if not panels:
        raise SkipChart("no mix or shadows rows with total_ms")
    widths = [len(bars) for _, bars in panels]
    fig, axes = plt.subplots(1, len(panels), figsize=(2.0 + 0.55 * sum(widths) + 1.2 * len(panels),
                                                      4.6), squeeze=False, sharey=True,
                             gridspec_kw={"width_ratios": widths})
    handles = {}
    for ax, (title, bars) in zip(axes[0], panels):
        for name, handle in pass_stack(ax, bars, passes, "whole frame").items():
            handles.setdefault(name, handle)
        ax.set_title(title)
    axes[0][0].set_ylabel("median GPU ms")
    # Legend top to bottom as the stack reads: the last pass on top.
    entries = ([n for n in reversed(passes) if n in handles] +
               [n for n in handles if n not in passes])
    fig.legend([handles[n] for n in entries], entries, loc="center right", title="pass")
    fig.suptitle("GPU time per pass (stacked in frame order)")
    fig.tight_layout(rect=(0, 0, 1 - 1.3 / fig.get_figwidth(), 1))
    return fig


# (file name, title, function, extra arguments); the function's docstring is the caption.
CHARTS = [
    ("forward_time", "Forward pass time against light count", chart_pass_time,
     ("forward_ms", "forward pass")),
    ("total_time", "Whole-frame time against light count", chart_pass_time,
     ("total_ms", "whole frame")),
    ("pass_time", "GPU time per pass", chart_pass_breakdown, ()),
    ("culling_efficiency", "Culling efficiency against light count", chart_culling_efficiency, ()),
    ("pareto_shadows", "Shadows: speed against accuracy", chart_shadow_pareto, ()),
    ("pareto_shadow_memory", "Shadows: memory against accuracy", chart_shadow_memory, ()),
    ("pareto_light_assignment", "Light assignment: speed against accuracy",
     chart_assignment_pareto, ()),
    ("pareto_cascades", "The sun's cascades: cost against accuracy", chart_cascade_pareto, ()),
]


def draw_charts(rows, names, charts_dir):
    """Draws every chart; returns [(name, title, caption, skip reason or None)]."""
    os.makedirs(charts_dir, exist_ok=True)
    done = []
    for name, title, function, args in CHARTS:
        caption = " ".join((function.__doc__ or "").split())
        try:
            fig = function(rows, names, *args)
        except SkipChart as reason:
            for ext in (".png", ".svg"):  # never leave a stale chart from an earlier run
                stale = os.path.join(charts_dir, name + ext)
                if os.path.exists(stale):
                    os.remove(stale)
            done.append((name, title, caption, str(reason)))
            continue
        save_chart(fig, charts_dir, name)
        done.append((name, title, caption, None))
    return done


# ------------------------------------------------------------------------------------ index.html

STYLE = """body { font-family: sans-serif; margin: 1.5em; max-width: 1400px; }
figure { display: inline-block; margin: 0.6em; vertical-align: top; } .skipped { color: #a33; }
figure img { max-width: 100%; border: 1px solid #ccc; } figcaption { max-width: 60em; }
table { border-collapse: collapse; font-size: 0.75em; } th { background: #eee; }
th, td { border: 1px solid #bbb; padding: 2px 5px; text-align: right; }
td:first-child, th:first-child { text-align: left; }"""


def href(path):
    """A relative URL for an attribute: percent-encoded, then HTML-escaped."""
    return html.escape(urllib.parse.quote(path), quote=True)


def list_images(out_dir):
    """Sorted file names of DIR/images/*.png (empty when the folder is absent)."""
    folder = os.path.join(out_dir, "images")
    names = os.listdir(folder) if os.path.isdir(folder) else []
    return sorted(f for f in names
                  if f.lower().endswith(".png") and os.path.isfile(os.path.join(folder, f)))


def render_index(header, rows, charts, images, notes):
    """The text of index.html: charts (or why each was skipped), images, the CSV as a table."""
    e = html.escape
    out = ["<!DOCTYPE html>", '<html lang="en"><head><meta charset="utf-8">',
           "<title>punctual bench results</title>", f"<style>\n{STYLE}\n</style></head><body>",
           "<h1>punctual bench results</h1>",
           f"<p>{len(rows)} configurations from <a href=\"results.csv\">results.csv</a>. "
           "Times are median GPU ms over the timed frames.</p>"]
    out += [f'<p class="skipped">{e(n)}</p>' for n in notes]
    out.append("<h2>Charts</h2>")
    for name, title, caption, skipped in charts:
        if skipped:
            out.append(f'<p class="skipped"><b>{e(title)}</b>: not drawn: {e(skipped)}.</p>')
            continue
        out += [f'<figure id="{e(name)}"><img src="{href("charts/" + name + ".png")}" '
                f'alt="{e(title)}">',
                f"<figcaption><b>{e(title)}</b>. {e(caption)} "
                f'(<a href="{href("charts/" + name + ".svg")}">SVG</a>)</figcaption></figure>']
    out.append("<h2>Images</h2>")
    if not images:
        out.append('<p class="skipped">No images in images/.</p>')
    for name in images:
        out.append(f'<figure><img src="{href("images/" + name)}" alt="{e(name)}">'
                   f"<figcaption>{e(name)}</figcaption></figure>")
    out += ["<h2>Results</h2>", "<table>",
            "<tr>" + "".join(f"<th>{e(c)}</th>" for c in header) + "</tr>"]
    for row in rows:
        out.append("<tr>" + "".join(f"<td>{e(row.get(c, ''))}</td>" for c in header) + "</tr>")
    out += ["</table>", "</body></html>", ""]
    return "\n".join(out)


def main(argv=None):
    """Command line entry point; returns the exit status."""
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("out_dir", metavar="DIR", help="folder holding results.csv (from "
                        "`punctual bench --out-dir DIR`); charts/ and index.html go there too")
    args = parser.parse_args(argv)
    csv_path = os.path.join(args.out_dir, "results.csv")
    try:
        header, rows = read_results(csv_path)
    except OSError as err:
        print(f"plot_results: error: {csv_path}: {err.strerror or err}", file=sys.stderr)
        return 1
    names, notes = read_names(os.path.join(args.out_dir, "results.json"), header, rows)
    missing = [c for c in known_columns(names["passes"]) if c not in header]
    if missing:
        notes.append(f"results.csv lacks the columns {', '.join(missing)}; they count as empty.")
    configure_matplotlib()
    charts = draw_charts(rows, names, os.path.join(args.out_dir, "charts"))
    index = render_index(header, rows, charts, list_images(args.out_dir), notes)
    with open(os.path.join(args.out_dir, "index.html"), "w", encoding="utf-8") as f:
        f.write(index)
    for name, title, _, skipped in charts:
        print(f"{'skipped' if skipped else 'wrote'} charts/{name}: {skipped or title}")
    print(f"wrote {os.path.join(args.out_dir, 'index.html')}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
