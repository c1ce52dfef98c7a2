"""The sweeps that separate causes (docs/BENCH_RESULTS.md, Series): time per pass against the
swept variable, a line per method, with a fitted log-log slope per method and pass, and the
light-count series' second x axis, the lights that reach a pixel.

A law is the least-squares line of log(time) on log(x) over the rows with x > 0 and time > 0
(flagged rows left out), reported as its slope: "forward ∝ pixels^1.01".
"""

import math

from bench_data import (is_flagged, is_wide, light_count, method_order, method_style, number,
                        pixels, series_rows, varying_label)
from chart_style import (SkipChart, add_flagged_legend, panel_grid, plot_per_method, plt,
                         set_count_axis, time_line)
from matplotlib.ticker import FixedLocator, NullLocator

# (series, what x is on the axis, x in a law, x of a row). The light-count series use
# light_count; the others a column of the contract.
SWEEPS = [
    ("mix", "lights (spot + point)", "lights", light_count),
    ("spot-only", "spot lights", "lights", light_count),
    ("point-only", "point lights", "lights", light_count),
    ("scale", "lights (half spots), constant density", "lights", light_count),
    ("scale-fixed", "lights (half spots), fixed range", "lights", light_count),
    ("range", "light range (fraction of the scene's diagonal)", "range",
     lambda r: number(r, "light_range")),
    ("pixels", "pixels (width x height)", "pixels", pixels),
    ("triangles", "scene triangles", "triangles", lambda r: number(r, "scene_triangles")),
    ("shadow-budget", "shadow budget, MiB", "budget", lambda r: number(r, "shadow_budget_mib")),
]
# Settings besides the method that may vary inside a series: a line per combination.
LINE_FIELDS = ["method", "light_lists", "shadows", "shadow_res", "shadow_format", "shadow_filter",
               "point_layout", "cascades"]
LINE_STYLES = ["-", "--", ":", "-."]
LIGHT_PANELS = [("mix", "mix (spot:point = 2:1)"), ("spot-only", "spot lights only"),
                ("point-only", "point lights only"), ("scale", "16-8192 at constant density"),
                ("scale-fixed", "16-8192 at the fixed range")]
COUNT_SERIES = ("mix", "spot-only", "point-only", "scale", "scale-fixed")


def fit_slope(points):
    """The slope of the least-squares line of log y on log x over the (x, y) points with x > 0
    and y > 0; None with fewer than two distinct x."""
    logs = [(math.log(x), math.log(y)) for x, y in points
            if x is not None and y is not None and x > 0 and y > 0]
    if len({lx for lx, _ in logs}) < 2:
        return None
    mx = sum(lx for lx, _ in logs) / len(logs)
    my = sum(ly for _, ly in logs) / len(logs)
    sxx = sum((lx - mx) ** 2 for lx, _ in logs)
    return sum((lx - mx) * (ly - my) for lx, ly in logs) / sxx


def crossings(points_a, points_b):
    """The x values where line a's time crosses line b's: between two consecutive x that both
    lines have, where log(a / b) changes sign, interpolated linearly in log x and log time (the
    charts' axes). Each as (x, time there, the line faster below it: "a" or "b")."""
    a = {x: y for x, y in points_a if x is not None and y is not None and x > 0 and y > 0}
    b = {x: y for x, y in points_b if x is not None and y is not None and x > 0 and y > 0}
    xs = sorted(set(a) & set(b))
    found = []
    for x1, x2 in zip(xs, xs[1:]):
        d1, d2 = math.log(a[x1] / b[x1]), math.log(a[x2] / b[x2])
        if d1 == 0 or d1 * d2 >= 0:
            continue
        t = d1 / (d1 - d2)
        x = math.exp(math.log(x1) + t * (math.log(x2) - math.log(x1)))
        y = math.exp(math.log(a[x1]) + t * (math.log(a[x2]) - math.log(a[x1])))
        found.append((x, y, "a" if d1 < 0 else "b"))
    return found


# The passes whose crossings a sweep reports: the forward pass and the whole frame.
CROSSING_PASSES = ("forward", "frame")


def law_text(what, variable, slope):
    """"forward ∝ pixels^1.01"."""
    return f"{what} ∝ {variable}^{slope:.2f}"


def lines_of(rows, methods, light_lists=()):
    """[(label, method, rows, variant)]: a line per method and per combination of the other
    settings that vary inside `rows` (`variant` numbers the combination), methods in
    results.json's order; a method's list forms in `light_lists`' order (the default first)."""
    fields = [f for f in LINE_FIELDS if len({r.get(f, "") for r in rows}) > 1] or ["method"]
    if "method" not in fields:
        fields = ["method"] + fields
    keys = {}
    for r in rows:
        keys.setdefault(tuple(r.get(f, "") for f in fields), []).append(r)
    order = method_order(rows, methods)
    forms = list(light_lists)

    def variant_order(variant):
        return tuple((forms.index(v) if v in forms else len(forms), v) if f == "light_lists" else (0, v)
                     for f, v in zip(fields[1:], variant))
    variants = sorted({k[1:] for k in keys}, key=variant_order)
    result = []
    for key in sorted(keys, key=lambda k: (order.index(k[0]), variants.index(k[1:]))):
        label = varying_label(keys[key][0], rows, fields) if len(fields) > 1 else key[0]
        result.append((label, key[0], keys[key], variants.index(key[1:])))
    return result


def timed_columns(rows, passes):
    """The time columns with a positive value in `rows`: every pass in frame order, then the
    whole frame."""
    columns = [f"{p}_ms" for p in passes] + ["total_ms"]
    return [c for c in columns if any((number(r, c) or 0) > 0 for r in rows)]


def short(x):
    """A tick label: 57.6k, 3.6864M, 0.05."""
    for scale, suffix in ((1e9, "G"), (1e6, "M"), (1e3, "k")):
        if abs(x) >= scale:
            return f"{x / scale:g}{suffix}"
    return f"{x:g}"


def set_sweep_axis(ax, xs, label):
    """x: log (ticks at the measured values) when the values span a wide range, else linear."""
    xs = sorted({x for x in xs if x is not None})
    if is_wide([x for x in xs if x > 0]) and xs[0] > 0:
        ax.set_xscale("log")
        ax.xaxis.set_major_locator(FixedLocator(xs))
        ax.xaxis.set_minor_locator(NullLocator())
        ax.set_xticklabels([short(x) for x in xs], rotation=30 if len(xs) > 5 else 0)
    ax.set_xlabel(label)


def chart_sweep(rows, names, series, axis_label, variable, x_of, laws=None, crossovers=None):
    """Median GPU time of every pass (a panel each, the whole frame last) against the series'
    swept variable, a line per method (and per other setting that varies), error bars the
    interquartile range over the rounds, flagged configurations hollow. Each line's legend entry
    gives its fitted law, the least-squares slope of log time on log x over x > 0 and time > 0
    (flagged rows left out): a slope of 1 is time in proportion to x. Axes are logarithmic where
    the values span more than ten times; rows with x = 0 are left off a log axis. Where two
    methods' forward or whole-frame lines cross, a black cross marks the point, and the crossing
    is listed (laws.json's crossovers)."""
    laws = [] if laws is None else laws  # every fitted law is appended here
    crossovers = [] if crossovers is None else crossovers  # and every crossing
    rs = [r for r in series_rows(rows, series) if x_of(r) is not None]
    xs_all = [x_of(r) for r in rs]
    log_x = is_wide([x for x in xs_all if x > 0])
    if log_x:
        rs = [r for r in rs if x_of(r) > 0]
    columns = timed_columns(rs, names["passes"])
    if len({x_of(r) for r in rs}) < 2 or not columns:
        raise SkipChart(f"the {series} series needs times at two or more values of {variable}")
    fig, axes = panel_grid(len(columns), 4.6, 3.9)
    for ax, column in zip(axes, columns):
        what = column[:-len("_ms")] if column != "total_ms" else "frame"
        values = []
        lines = lines_of(rs, names["methods"], names.get("light_lists", ()))
        for label, method, own, variant in lines:
            slope = fit_slope([(x_of(r), number(r, column)) for r in own if not is_flagged(r)])
            colour, marker = method_style(method, names["methods"])
            text = label if slope is None else f"{label}: {law_text(what, variable, slope)}"
            values += time_line(ax, own, x_of, column, colour, marker, text,
                                linestyle=LINE_STYLES[variant % len(LINE_STYLES)])
            if slope is not None:
                laws.append({"series": series, "x": variable, "line": label, "method": method,
                             "pass": what, "slope": round(slope, 4),
                             "points": sum(1 for r in own if not is_flagged(r)
                                           and (x_of(r) or 0) > 0 and (number(r, column) or 0) > 0),
                             "law": law_text(what, variable, slope)})
        if what in CROSSING_PASSES:
            mark_crossings(ax, lines, x_of, column, series, variable, what, crossovers)
        if series in COUNT_SERIES:
            set_count_axis(ax, [x_of(r) for r in rs])
            ax.set_xlabel(axis_label)
        else:
            set_sweep_axis(ax, [x_of(r) for r in rs], axis_label)
        if log_x and is_wide([v for v in values if v > 0]) and min(values) > 0:
            ax.set_yscale("log")
        ax.set_title(f"{what}" if column != "total_ms" else "whole frame")
        ax.set_ylabel("median GPU ms")
        add_flagged_legend(ax, fontsize=7)
    fig.suptitle(f"the {series} series: time per pass against {variable}")
    fig.tight_layout()
    return fig


def mark_crossings(ax, lines, x_of, column, series, variable, what, crossovers):
    """Marks and lists where the lines of two methods (lines_of's, the first of each method: its
    default list form) cross in `column`, and where a method's list forms cross each other."""
    firsts = {}
    for label, method, own, variant in lines:
        firsts.setdefault(method, own)
    pairs = [(a, b, firsts[a], firsts[b]) for i, a in enumerate(firsts) for b in list(firsts)[i + 1:]]
    forms = {}
    for label, method, own, variant in lines:
        if own[0].get("light_lists", ""):
            forms.setdefault(method, []).append((f"{method} {own[0]['light_lists']}", own))
    for method_forms in forms.values():
        pairs += [(a, b, ra, rb) for i, (a, ra) in enumerate(method_forms) for b, rb in method_forms[i + 1:]]
    for a, b, rows_a, rows_b in pairs:
        points = [[(x_of(r), number(r, column)) for r in own if not is_flagged(r)] for own in (rows_a, rows_b)]
        for x, y, faster in crossings(*points):
            below, above = (a, b) if faster == "a" else (b, a)
            ax.plot([x], [y], marker="x", color="black", markersize=7, linestyle="none")
            crossovers.append({"series": series, "x": variable, "pass": what, "at": round(x, 4),
                               "faster_below": below, "faster_above": above,
                               "text": f"{what}: {below} faster below {variable} ≈ {short(x)}, "
                                       f"{above} above"})


def chart_lights_reaching(rows, names):
    """Lights tested per covered pixel against the lights that reach it (attenuation x cone > 0,
    the oracle), one panel per light-count series, a line per method. The dashed line is the
    oracle y = x: a culled method's list should follow it (it tests only the lights that
    reach), brute force lies above it (it tests every light), and a point under it misses
    lights."""
    panels = []
    for series, title in LIGHT_PANELS:
        rs = [r for r in series_rows(rows, series) if number(r, "affecting_per_pixel") is not None
              and number(r, "tested_per_pixel") is not None]
        if rs:
            panels.append((title, rs))
    if not panels:
        raise SkipChart("no rows of the light-count series with tested_per_pixel and "
                        "affecting_per_pixel")
    fig, axes = plt.subplots(1, len(panels), figsize=(4.6 * len(panels) + 0.4, 4.2),
                             squeeze=False)
    for ax, (title, rs) in zip(axes[0], panels):
        affecting = [number(r, "affecting_per_pixel") for r in rs]
        tested = plot_per_method(ax, rs, "tested_per_pixel", names["methods"],
                                 x_of=lambda r: number(r, "affecting_per_pixel"))
        lo, hi = min(affecting + tested), max(affecting + tested)
        positive = [v for v in affecting + tested if v > 0]
        if is_wide(positive):
            ax.set_xscale("log")
            ax.set_yscale("log")
            lo = min(positive)
        ax.plot([lo, hi], [lo, hi], color="black", linestyle="--", linewidth=1,
                label="oracle: tested = reaching")
        ax.set_xlabel("lights reaching a pixel (mean per covered pixel)")
        ax.set_ylabel("lights tested per covered pixel")
        ax.set_title(title)
        ax.legend()
    fig.suptitle("lights tested against lights reaching a pixel (culled methods follow the oracle)")
    fig.tight_layout()
    return fig


def sweep_chart_list():
    """(file name, title, function, extra arguments) of every sweep chart, for plot_results'
    CHARTS; chart_sweep appends its laws to its `laws` keyword argument."""
    charts = [(f"sweep_{series}", f"The {series} series: time per pass against {variable}",
               chart_sweep, (series, label, variable, x_of))
              for series, label, variable, x_of in SWEEPS]
    charts.append(("lights_reaching", "Lights tested against lights reaching a pixel",
                   chart_lights_reaching, ()))
    return charts


def laws_document(laws, crossovers=()):
    """laws.json's contents: every fitted slope, in chart order, and every crossing of two
    methods' forward or whole-frame lines."""
    return {"fit": "least squares of log(median GPU ms) on log(x), over x > 0 and time > 0, "
                   "flagged rows left out", "laws": laws,
            "crossing": "where log(a / b) changes sign between two consecutive x, interpolated in "
                        "log x (flagged rows left out)", "crossovers": list(crossovers)}
