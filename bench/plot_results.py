#!/usr/bin/python3
"""Charts and an HTML index for the results of `punctual bench --out-dir DIR`.

    /usr/bin/python3 bench/plot_results.py DIR

reads DIR/results.csv (and results.json) and writes DIR/charts/<name>.png and .svg for every
chart the data allows, DIR/laws.json (every sweep's fitted log-log slopes), DIR/cost_model.json
(each pass's fitted cost per unit of its counters) and DIR/index.html: the run's provenance and
noise, every chart with its fitted laws and flagged configurations, the laws and the cost model
as tables, every DIR/images/*.png and the CSV as a table. A chart whose series or columns are
missing or empty is skipped with a note in index.html, so the few rows of `--quick` work too.
Output is deterministic: rerunning on the same CSV gives identical files.

The files are read by input_file.py's rules (punctual's own reader's: a FIFO or a folder where
a file should be is refused, never opened) and written together by output_file.py: every chart,
JSON file and index.html goes to a temporary, and all are renamed at the end, so a run that
fails leaves the folder as it was. Bad input or a write error is one line `plot_results.py:
error: <file>: <problem>` on stderr and status 1; an interrupt one line and status 128 + the
signal (130 for Ctrl-C).

Nothing here names the methods, shadow filters or passes: DIR/results.json says them
("methods" and "shadow_filters" in table order, "passes" in frame order), and the script draws
whatever it lists, a method's colour and marker taken from a fixed palette by its position. The
columns are docs/BENCH_RESULTS.md's (bench_data.py reads them): every time chart draws the
interquartile range over the rounds (P_iqr_ms; an older folder's P_spread_ms) as error bars, and
a flagged configuration (its spread over results.json's noise.flag_limit) hollow, named under
its chart. Without results.json's keys (a folder from an older bench) the names come from the
CSV itself, sorted.

The modules: bench_data.py (reading, columns), chart_style.py (what every chart shares),
sweep_charts.py (the sweeps and their laws), shadow_page_charts.py (virtual pages against whole
views), cost_model.py (the fit), bench_report.py
(index.html). Needs Debian's /usr/bin/python3 with python3-matplotlib (no other packages).
"""

import argparse
import json
import os
import sys

PROGRAM = "plot_results.py"
if __name__ == "__main__":
    # Before the slow imports below: an interrupt there is one line, not a traceback.
    import output_file
    output_file.exit_quietly_on_interrupt(PROGRAM)

from bench_data import (METHOD_COLOURS, METHOD_MARKERS, OTHER_STYLE, flag_limit,  # noqa: F401
                        is_flagged, is_wide, known_columns, light_count, mark_flags, method_order,
                        method_style, number, ordered, pareto_front, read_document, read_names,
                        read_results, series_rows, varying_label)
from chart_style import (FLAGGED_LEGEND, SkipChart, add_flagged_legend, configure_matplotlib,
                         draw_front, flagged_handle, panel_grid, plot_per_method, plt, save_chart,
                         set_count_axis, time_point_errors)
from matplotlib.lines import Line2D
from matplotlib.ticker import MaxNLocator, PercentFormatter
import bench_report
import cost_model
import output_file
import shadow_page_charts
import sweep_charts

# Pass colours by position in "passes" (a palette apart from the methods').
PASS_COLOURS = ["#66c2a5", "#fc8d62", "#8da0cb", "#e78ac3", "#a6d854", "#ffd92f", "#e5c494",
                "#b3b3b3"]
PASS_HATCHES = [None, "//", "xx", ".."]  # beyond the palette, the colours repeat with a hatch
# Errors are measured against brute force, so its own error cells are empty; it is drawn at 0.
REFERENCE_METHOD = "brute"
LIGHT_SERIES = [("mix", "mix (spot:point = 2:1)"), ("spot-only", "spot lights only"),
                ("point-only", "point lights only")]


# ---------------------------------------------------------------------------------------- charts

def chart_pass_time(rows, names, column, what):
    """Median GPU time (forward pass, or whole frame) against light count, one line per method,
    one panel per light series (mix, spot-only, point-only), error bars the interquartile range
    over the rounds, flagged configurations hollow. It shows how each method scales with the
    number of lights: brute force grows linearly, culled lists with the lights that actually
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
    add_flagged_legend(axes[0][0])
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
    add_flagged_legend(ax, title=legend)
    fig.tight_layout()
    return fig


def chart_shadow_pareto(rows, names):
    """Whole-frame time against the fraction of shadow tests misclassified (outside the edge
    band, against the Embree reference), one point per shadow resolution and filter. The Pareto
    front marks the settings no other setting beats in both speed and accuracy. Error bars: the
    interquartile range over the rounds; flagged configurations hollow."""
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
    time_point_errors(ax, rs, points, "total_ms")
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
    of each panel marks the settings that no other beats in both cost and accuracy. Error bars:
    the interquartile range over the rounds; flagged configurations hollow."""
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
        if column == "shadows_ms":
            time_point_errors(ax, rs, points, column)
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
    if getattr(fig, "flagged", None):
        handles.append(flagged_handle())
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
    error. The Pareto front marks the methods nothing beats in both speed and accuracy. Error
    bars: the interquartile range over the rounds; flagged configurations hollow."""
    mix = series_rows(rows, "mix")
    column = assignment_error_column(mix)
    if column is None:
        raise SkipChart("no image_error or pixels_off values in the mix series")

    def error(r):
        value = number(r, column)
        return 0.0 if value is None and r.get("method") == REFERENCE_METHOD else value

    rs = [r for r in mix if number(r, "total_ms") is not None and error(r) is not None]
    counts = sorted({light_count(r) for r in rs})
    fig, axes = panel_grid(len(counts), 4.3, 3.8)
    for ax, count in zip(axes, counts):
        group = [r for m in method_order(rs, names["methods"]) for r in rs
                 if light_count(r) == count and r.get("method") == m]
        points = [(error(r), number(r, "total_ms")) for r in group]
        for (x, y), r in zip(points, group):
            colour, marker = method_style(r.get("method"), names["methods"])
            ax.scatter([x], [y], color=colour, marker=marker, s=45, zorder=2,
                       label=r.get("method", ""))
        time_point_errors(ax, group, points, "total_ms")
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
    for ax in axes:
        legend.update(zip(*reversed(ax.get_legend_handles_labels())))
    if getattr(fig, "flagged", None):
        legend[FLAGGED_LEGEND] = flagged_handle()
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
            time_point_errors(ax, [r], [(x, total)], "total_ms")
            if is_flagged(r):
                handles.setdefault(FLAGGED_LEGEND, flagged_handle())
    ax.set_xticks(range(len(bars)))
    ax.set_xticklabels([label for label, _ in bars], rotation=30, ha="right")
    return handles


def chart_pass_breakdown(rows, names):
    """Median GPU time of every pass, stacked in frame order, one bar per method: at the largest
    light count of the mix series, and in the shadows series with shadows off and on. It shows
    where each method spends the frame, and what the shadow pass adds; the black tick is the
    whole frame (first to last timestamp), so the gap above a bar is time between passes; its
    error bar is the interquartile range over the rounds, a flagged configuration's ringed."""
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
] + sweep_charts.sweep_chart_list() + [
    ("pareto_shadows", "Shadows: speed against accuracy", chart_shadow_pareto, ()),
    ("pareto_shadow_memory", "Shadows: memory against accuracy", chart_shadow_memory, ()),
    ("pareto_light_assignment", "Light assignment: speed against accuracy",
     chart_assignment_pareto, ()),
    ("pareto_cascades", "The sun's cascades: cost against accuracy", chart_cascade_pareto, ()),
    ("pareto_virtual_pages", "Virtual shadow pages against whole views", shadow_page_charts.chart_virtual_pages, ()),
    ("virtual_page_growth", "Shadow memory against the pairs shaded and the views",
     shadow_page_charts.chart_virtual_page_growth, ()),
]


def draw_charts(rows, names, charts_dir, outputs):
    """Draws every chart into `outputs` (written at its commit); returns ([{name, title,
    caption, skipped (the reason or None), flagged (configurations drawn hollow), laws,
    crossovers}], every law fitted, every crossing found)."""
    os.makedirs(charts_dir, exist_ok=True)
    done, laws, crossovers = [], [], []
    for name, title, function, args in CHARTS:
        caption = " ".join((function.__doc__ or "").split())
        entry = {"name": name, "title": title, "caption": caption, "skipped": None,
                 "flagged": [], "laws": [], "crossovers": []}
        own, crossed = [], []
        try:
            if function is sweep_charts.chart_sweep:
                fig = function(rows, names, *args, laws=own, crossovers=crossed)
            else:
                fig = function(rows, names, *args)
        except SkipChart as reason:
            for ext in (".png", ".svg"):  # never leave a stale chart from an earlier run
                stale = os.path.join(charts_dir, name + ext)
                if os.path.lexists(stale):
                    outputs.remove(stale)
            entry["skipped"] = str(reason)
            done.append(entry)
            continue
        entry["flagged"] = list(getattr(fig, "flagged", []))
        entry["laws"] = own
        entry["crossovers"] = crossed
        laws += own
        crossovers += crossed
        save_chart(fig, charts_dir, name, outputs)
        done.append(entry)
    return done, laws, crossovers


def json_text(document):
    """`document` as indented JSON with a final newline."""
    return json.dumps(document, indent=1, ensure_ascii=False) + "\n"


def main(argv=None):
    """Command line entry point; returns the exit status. Bad input, a write error or an
    interrupt is one line on stderr (status 1, or 128 + the signal) and changes no file."""
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("out_dir", metavar="DIR", help="folder holding results.csv (from "
                        "`punctual bench --out-dir DIR`); charts/ and index.html go there too")
    args = parser.parse_args(argv)
    return output_file.run_script(PROGRAM, lambda outputs: write_report(args.out_dir, outputs))


def write_report(out_dir, outputs):
    """Reads DIR's results, writes every chart, laws.json, cost_model.json and index.html into
    `outputs` and commits them together; returns 0."""
    header, rows = read_results(os.path.join(out_dir, "results.csv"))
    document, notes = read_document(os.path.join(out_dir, "results.json"))
    names, more = read_names(None, header, rows, document)
    notes += more
    missing = [c for c in known_columns(names["passes"]) if c not in header]
    old_spreads = [f"{p}_iqr_ms" for p in names["passes"] + ["total"]
                   if f"{p}_iqr_ms" in missing and f"{p}_spread_ms" in header]
    if old_spreads:
        notes.append("results.csv is from an older bench: the error bars are its P_spread_ms "
                     "columns, not interquartile ranges.")
    if missing:
        notes.append(f"results.csv lacks the columns {', '.join(missing)}; they count as empty.")
    limit = flag_limit(document)
    mark_flags(rows, limit)
    configure_matplotlib()
    charts, laws, crossovers = draw_charts(rows, names, os.path.join(out_dir, "charts"), outputs)
    model = cost_model.fit_cost_model(rows, names["passes"])
    outputs.write_text(os.path.join(out_dir, "laws.json"),
                       json_text(sweep_charts.laws_document(laws, crossovers)))
    outputs.write_text(os.path.join(out_dir, "cost_model.json"),
                       json_text(cost_model.model_document(model)))
    index = bench_report.render_index(header, rows, charts, bench_report.list_images(out_dir),
                                      notes, document, limit, laws, cost_model.model_document(model))
    outputs.write_text(os.path.join(out_dir, "index.html"), index)
    outputs.commit()
    for chart in charts:
        print(f"{'skipped' if chart['skipped'] else 'wrote'} charts/{chart['name']}: "
              f"{chart['skipped'] or chart['title']}")
    print(f"wrote {os.path.join(out_dir, 'index.html')}, laws.json, cost_model.json")
    return 0


if __name__ == "__main__":
    sys.exit(main())
