"""Tests of bench/plot_results.py on synthetic results.csv and results.json files.

    /usr/bin/python3 -m unittest bench/test_plot_results.py      (from the repository root)
"""

import contextlib
import csv
import io
import json
import os
import sys
import tempfile
import unittest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import plot_results  # noqa: E402
from matplotlib.colors import same_color  # noqa: E402  (plot_results selects the backend)

ALL_CHARTS = [chart[0] for chart in plot_results.CHARTS]
# What today's bench writes into results.json; the tests add names to these to prove that the
# script draws whatever results.json lists.
METHODS = ["brute", "per-object", "tiled", "clustered"]
FILTERS = ["hw", "tent3", "tent5", "tent7", "disk"]
PASSES = ["depth", "culling", "shadows", "forward", "tonemap"]
COLUMNS = plot_results.known_columns(PASSES)
COST = {"brute": 12.0, "per-object": 1.6, "tiled": 1.8, "clustered": 1.7, "hybrid": 1.5,
        "mystery": 2.5}
# The series the new sweeps add (docs/BENCH_RESULTS.md), and the columns of an older bench.
SWEEP_SERIES = ["scale", "scale-fixed", "range", "pixels", "triangles", "shadow-budget"]
OLD_COLUMNS = """config series method spot point shadows shadow_res shadow_filter point_layout frames
    depth_ms culling_ms shadows_ms forward_ms total_ms forward_spread_ms total_spread_ms
    tested_per_pixel affecting_per_pixel efficiency missed_energy image_error pixels_off
    shadow_misclassified shadow_false_shadow shadow_false_lit""".split()
# Charts with a line, point or bar per method.
PER_METHOD_CHARTS = ["forward_time", "total_time", "pass_time", "culling_efficiency",
                     "pareto_light_assignment"]


def row(config, series, method, spot, point, **cells):
    """A full row: a plausible default for every column, overridden by `cells`."""
    lights = spot + point
    forward = COST[method] * lights
    values = {
        "config": config, "series": series, "method": method, "spot": spot, "point": point,
        "shadows": 0, "shadow_res": 1024, "shadow_filter": "tent5", "point_layout": "cube",
        "frames": 5, "depth_ms": 4.0, "culling_ms": 0.0 if method in ("brute", "per-object")
        else 0.4 * lights, "shadows_ms": 0.0, "forward_ms": forward, "tonemap_ms": 1.5,
        "total_ms": forward + 15.0, "total_iqr_ms": 0.1 * forward, "flagged": 0, "flag_reason": "",
        "tested_per_pixel": {"brute": lights, "per-object": min(lights, 8)}.get(
            method, 0.07 * lights + 1), "affecting_per_pixel": 0.05 * lights + 0.2,
        "missed_energy": 0.006 * lights if method == "per-object" else 0.0,
        "image_error": "" if method == "brute" else (
            0.0004 * lights if method == "per-object" else 0.0),
        "pixels_off": "" if method == "brute" else (
            0.01 * lights if method == "per-object" else 0.0),
        "shadow_misclassified": "", "shadow_false_shadow": "", "shadow_false_lit": "",
        "shadow_misclassified_all": "", "shadow_misclassified_1px": "", "shadow_memory_bytes": "",
        "shadow_floor_bytes": "", "shadow_views": "", "shadow_texels_rendered": "", "shadow_filter_taps": "",
        "shadow_reduced_views": "", "shadow_format": "", "shadowed_spots": "", "shadowed_points": "",
        "width": 640, "height": 360, "pixels": 640 * 360, "scene": "synthetic",
        "scene_triangles": 20000, "light_range": 0.1, "rounds": 5, "depth_triangles": 20000,
        "forward_triangles": 20000, "depth_draws": 40, "forward_draws": 40,
    }
    values["efficiency"] = values["tested_per_pixel"] / values["affecting_per_pixel"]
    values.update(cells)
    for name in PASSES:
        values[f"{name}_iqr_ms"] = 0.1 * values[f"{name}_ms"]
    values["total_iqr_ms"] = cells.get("total_iqr_ms", 0.1 * values["forward_ms"])
    if "total_ms" not in cells:
        values["total_ms"] = sum(values[f"{p}_ms"] for p in PASSES)
    values["total_cv"] = 0.02
    return values


def sweep_rows(methods=METHODS):
    """The range, pixels, triangles and shadow-budget series: forward grows with the square of
    the range and with the pixels, depth with the triangles, shadows with the budget."""
    rows = []
    for rng in (0.05, 0.1, 0.2, 0.4):
        for m in methods:
            rows.append(row(f"range-{m}-{rng}", "range", m, 64, 32, light_range=rng,
                            forward_ms=COST[m] * 96 * (rng / 0.1) ** 2))
    for w, h in ((320, 180), (640, 360), (1280, 720), (2560, 1440)):
        for m in methods:
            rows.append(row(f"pixels-{m}-{w}", "pixels", m, 64, 32, width=w, height=h,
                            pixels=w * h, forward_ms=3e-4 * w * h * COST[m],
                            depth_ms=1e-5 * w * h, tonemap_ms=2e-6 * w * h))
    for t in (10**4, 10**5, 10**6, 10**7):
        rows.append(row(f"triangles-{t}", "triangles", "tiled", 8, 8, scene_triangles=t,
                        depth_triangles=t, forward_triangles=t, depth_ms=2e-5 * t + 0.1))
    for mib in (16, 64, 256):
        rows.append(row(f"budget-{mib}", "shadow-budget", "tiled", 64, 32, shadows=1,
                        shadow_res="auto", shadow_budget_mib=mib, shadows_ms=0.5 * mib))
    return rows


def full_rows(methods=METHODS):
    """Every series, as `punctual bench` writes it (sizes as in a full run)."""
    rows = []
    for n in (3, 6, 12, 24, 48, 96):
        for m in methods:
            rows.append(row(f"mix-{m}-{n}", "mix", m, 2 * n // 3, n // 3))
    for n in (8, 32, 64):
        for m in methods:
            rows.append(row(f"spot-{m}-{n}", "spot-only", m, n, 0))
    for n in (4, 16, 32):
        for m in methods:
            rows.append(row(f"point-{m}-{n}", "point-only", m, 0, n))
    # The scale series: thousands of lights, each count its own set (half spots); at constant
    # density culled methods stay nearly flat, at the fixed range every method grows.
    for series, flat in (("scale", True), ("scale-fixed", False)):
        for n in (16, 256, 4096):
            for m in methods:
                growth = n / 16 if m == "brute" or not flat else (n / 16) ** 0.1
                rows.append(row(f"{series}-{m}-{n}", series, m, n // 2, n // 2,
                                forward_ms=COST[m] * 16 * growth))
    for m in methods:
        for on in (0, 1):
            rows.append(row(f"shadows-{m}-{on}", "shadows", m, 64, 32, shadows=on,
                            shadows_ms=60.0 * on))
    for i, res in enumerate((256, 512, 1024, 2048)):
        for j, flt in enumerate(FILTERS):
            rows.append(row(f"sq-{res}-{flt}", "shadow-quality", "tiled", 64, 32, shadows=1,
                            shadow_res=res, shadow_filter=flt, total_ms=200 + res / 20 + 8 * j,
                            shadow_misclassified=0.04 / (i + 1) / (1 + 0.3 * j) + 0.002 * j,
                            shadow_false_shadow=100 * j + 7, shadow_false_lit=50 + i,
                            shadow_format="d16" if j % 2 else "d32", shadowed_spots=64, shadowed_points=32,
                            shadow_memory_bytes=256 * res * res * (2 + 2 * (j % 2 == 0)),
                            shadow_misclassified_1px=0.03 / (i + 1) + 0.001 * j,
                            shadow_misclassified_all=0.05 / (i + 1) + 0.001 * j))
    rows += cascade_rows()
    rows += sweep_rows(methods)
    # Whole views against virtual pages on two scenes (the shadow-memory series).
    for scene, scale in (("hall", 1.0), ("rooms", 2.0)):
        for mode, memory, marks in (("auto", 64, ""), ("virtual", 20, 200.0)):
            rows.append(row(f"sm-{scene}-{mode}", "shadow-memory", "tiled", 64, 32, shadows=1, shadow_res=mode,
                            scene=scene, scene_triangles=int(10000 * scale), light_range="",
                            shadow_memory_bytes=memory * scale * 2**20,
                            shadows_ms=100.0 * scale, shadow_marks_ms=marks,
                            shadow_misclassified=0.0001 * scale, shadow_floor_bytes=8 * scale * 2**20,
                            shadow_views=240 * scale))
    rows[0]["config"] = "mix <b>&amp;\"quoted\""  # must be escaped in the table
    return rows


def cascade_rows(counts=(1, 2, 3, 4), resolutions=(512, 1024, 2048), filters=("hw", "tent5")):
    """The cascades series: the sun's error falls with count and resolution, and costs rise."""
    rows = []
    for count in counts:
        for res in resolutions:
            for j, flt in enumerate(filters):
                error = 0.05 / count / (res / 512) + 0.002 * j
                rows.append(row(f"cascades-{count}-{res}-{flt}", "cascades", "tiled", 16, 16, shadows=1,
                                shadow_res=res, shadow_filter=flt, shadows_ms=2 * count * res / 512 + j,
                                shadow_memory_bytes=count * res * res * 2, cascades=count,
                                sun_misclassified=error / 2, sun_misclassified_1px=error,
                                **{f"sun_cascade{i}_misclassified_1px": error for i in range(count)}))
    return rows


def quick_mix_rows():
    """Only the mix series, two counts, with the statistics and error columns left empty."""
    empty = {c: "" for c in ("tested_per_pixel", "affecting_per_pixel", "efficiency",
                             "missed_energy", "image_error", "pixels_off")}
    return [row(f"q-{m}-{n}", "mix", m, 2 * n // 3, n // 3, **empty)
            for n in (3, 96) for m in METHODS]


def write_csv(folder, rows, columns=COLUMNS):
    with open(os.path.join(folder, "results.csv"), "w", newline="", encoding="utf-8") as f:
        writer = csv.DictWriter(f, fieldnames=columns, extrasaction="ignore")
        writer.writeheader()
        writer.writerows(rows)


def write_json(folder, methods=METHODS, filters=FILTERS, passes=PASSES):
    """results.json's names, as the bench writes them (None leaves a key out, as older runs do)."""
    document = {"configurations": [],
                "provenance": {"device": {"name": "Synthetic GPU", "driver_info": "test 1.0"},
                               "cpu": {"model": "Synthetic CPU", "logical_cores": 2},
                               "git_commit": "0123abc", "command_line": "punctual bench",
                               "date": "2025-01-01T00:00:00Z",
                               "scene": {"source": "synthetic", "triangles": 20000}},
                "noise": {"rounds": 5, "best_of": 3, "seed": 1, "median_cv": 0.02,
                          "frame_median_cv": 0.081, "flag_limit": 0.15, "flagged": 0}}
    for key, names in (("methods", methods), ("shadow_filters", filters),
                       ("point_layouts", ["cube", "slices"]), ("passes", passes)):
        if names is not None:
            document[key] = names
    with open(os.path.join(folder, "results.json"), "w", encoding="utf-8") as f:
        json.dump(document, f)


def names(methods=METHODS, filters=FILTERS, passes=PASSES):
    return {"methods": methods, "shadow_filters": filters, "passes": passes}


def chart(name, rows, chart_names):
    """The figure of one chart, drawn from `rows` as the CSV reader gives them (strings)."""
    _, _, function, args = next(c for c in plot_results.CHARTS if c[0] == name)
    plot_results.configure_matplotlib()
    return function([{k: str(v) for k, v in r.items()} for r in rows], chart_names, *args)


def drawn_labels(fig):
    """Every label a figure shows for its data: lines, points, bars, legends and x tick labels."""
    labels = set()
    for ax in fig.axes:
        labels.update(a.get_label() for a in ax.lines + ax.collections + ax.containers)
        labels.update(t.get_text() for t in ax.get_xticklabels())
        if ax.get_legend():
            labels.update(t.get_text() for t in ax.get_legend().get_texts())
    for legend in fig.legends:
        labels.update(t.get_text() for t in legend.get_texts())
    return labels


def legend_texts(fig):
    """The texts of the figure's legend (the first axes' one when the figure has none)."""
    legend = fig.legends[0] if fig.legends else fig.axes[0].get_legend()
    return [t.get_text() for t in legend.get_texts()]


def write_png(path):
    """A tiny valid PNG standing in for a heat map."""
    plot_results.plt.imsave(path, [[0.0, 0.5], [1.0, 0.25]], cmap="viridis")


def run(folder):
    with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(io.StringIO()):
        return plot_results.main([folder])


def snapshot(folder):
    """{relative path: bytes} of every file the script wrote."""
    names = ["index.html", "laws.json", "cost_model.json"] + [
        "charts/" + n for n in os.listdir(os.path.join(folder, "charts"))]
    files = {}
    for name in names:
        with open(os.path.join(folder, name), "rb") as f:
            files[name] = f.read()
    return files


class PlotResultsTest(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.dir = self.tmp.name

    def tearDown(self):
        self.tmp.cleanup()

    def index(self):
        with open(os.path.join(self.dir, "index.html"), encoding="utf-8") as f:
            return f.read()

    def assert_charts(self, names):
        index = self.index()
        for name in names:
            for ext in (".png", ".svg"):
                path = os.path.join(self.dir, "charts", name + ext)
                self.assertTrue(os.path.getsize(path) > 1000, path)
            self.assertIn(f'<img src="charts/{name}.png"', index)
            self.assertIn(f'<a href="charts/{name}.svg">SVG</a>', index)
        captions = [line for line in index.splitlines() if line.startswith("<figcaption><b>")]
        for caption in captions:  # every chart caption has its description
            self.assertGreater(len(caption), 150, caption)

    def test_all_series_give_every_chart_and_index(self):
        write_csv(self.dir, full_rows())
        os.makedirs(os.path.join(self.dir, "images"))
        for name in ("heatmap-tiled.png", "shadow mismatch #1.png"):
            write_png(os.path.join(self.dir, "images", name))
        self.assertEqual(run(self.dir), 0)
        self.assert_charts(ALL_CHARTS)
        index = self.index()
        self.assertNotIn("not drawn", index)
        self.assertIn('<img src="images/heatmap-tiled.png"', index)
        self.assertIn('<img src="images/shadow%20mismatch%20%231.png"', index)
        self.assertIn("<figcaption>shadow mismatch #1.png</figcaption>", index)
        self.assertIn("mix &lt;b&gt;&amp;amp;&quot;quoted&quot;", index)
        self.assertNotIn("<b>&amp;", index)
        self.assertEqual(index.split("<h2>Results</h2>")[1].count("<tr>"), len(full_rows()) + 1)

    def test_reruns_are_identical(self):
        write_csv(self.dir, full_rows())
        run(self.dir)
        first = snapshot(self.dir)
        run(self.dir)
        self.assertEqual(first.keys(), snapshot(self.dir).keys())
        for name, data in snapshot(self.dir).items():
            self.assertEqual(first[name], data, name)

    def test_mix_only_with_empty_columns_skips_charts(self):
        write_csv(self.dir, quick_mix_rows())
        self.assertEqual(run(self.dir), 0)
        self.assert_charts(["forward_time", "total_time"])
        index = self.index()
        self.assert_charts(["sweep_mix"])  # two light counts are enough for a slope
        skipped = ["culling_efficiency", "pareto_shadows", "pareto_shadow_memory",
                   "pareto_light_assignment", "pareto_cascades", "pareto_virtual_pages", "virtual_page_growth",
                   "lights_reaching"]
        skipped += [f"sweep_{s}" for s in ["spot-only", "point-only"] + SWEEP_SERIES]
        for name in skipped:
            self.assertFalse(os.path.exists(os.path.join(self.dir, "charts", name + ".png")))
            self.assertNotIn(f"charts/{name}.png", index)
        self.assertEqual(index.count("not drawn"), len(skipped))
        self.assertIn("No images in images/.", index)

    def test_skipped_chart_removes_stale_files(self):
        write_csv(self.dir, full_rows())
        run(self.dir)
        write_csv(self.dir, quick_mix_rows())
        run(self.dir)
        self.assertFalse(os.path.exists(os.path.join(self.dir, "charts", "pareto_shadows.svg")))

    def test_header_only_and_missing_columns(self):
        write_csv(self.dir, [], columns=["config", "series", "method"])
        self.assertEqual(run(self.dir), 0)
        index = self.index()
        self.assertEqual(index.count("not drawn"), len(ALL_CHARTS))
        self.assertIn("lacks the columns spot, point", index)

    def test_missing_csv_is_an_error(self):
        self.assertEqual(run(os.path.join(self.dir, "absent")), 1)

    def test_pareto_front(self):
        points = [(0.0, 10.0), (0.1, 5.0), (0.2, 6.0), (0.3, 1.0), (0.0, 12.0), (0.1, 5.0)]
        self.assertEqual(plot_results.pareto_front(points), [0, 1, 5, 3])


class NamesFromResultsJsonTest(unittest.TestCase):
    """Methods, filters and passes come from results.json: a name added there is drawn with no
    edit to the script, and folders from older benches (without the keys) still plot."""

    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.dir = self.tmp.name

    def tearDown(self):
        self.tmp.cleanup()
        plot_results.plt.close("all")

    def index(self):
        with open(os.path.join(self.dir, "index.html"), encoding="utf-8") as f:
            return f.read()

    def line_colours(self, fig):
        """{label: colour} of the lines of the figure's first axes (error-bar lines too)."""
        colours = {line.get_label(): line.get_color() for line in fig.axes[0].lines}
        colours.update({c.get_label(): c.lines[0].get_color() for c in fig.axes[0].containers
                        if c.lines and c.lines[0] is not None})
        return colours

    def test_a_bench_folder_with_results_json_draws_everything_without_notes(self):
        write_csv(self.dir, full_rows())
        write_json(self.dir)
        self.assertEqual(run(self.dir), 0)
        index = self.index()
        self.assertNotIn("not drawn", index)
        self.assertNotIn("results.json", index)
        self.assertNotIn("lacks", index)
        for name in ALL_CHARTS:
            self.assertIn(f'<img src="charts/{name}.png"', index)

    def test_a_new_method_is_drawn_in_every_per_method_chart(self):
        methods = METHODS + ["hybrid"]
        rows = full_rows(methods)
        for name in PER_METHOD_CHARTS:
            fig = chart(name, rows, names(methods))
            self.assertIn("hybrid", drawn_labels(fig), name)
        # With a style of its own (the palette's fifth), not the grey of an unlisted method.
        colour, marker = plot_results.method_style("hybrid", methods)
        self.assertEqual((colour, marker),
                         (plot_results.METHOD_COLOURS[4], plot_results.METHOD_MARKERS[4]))
        self.assertNotIn(colour, [plot_results.method_style(m, methods)[0] for m in METHODS])
        lines = self.line_colours(chart("forward_time", rows, names(methods)))
        self.assertTrue(same_color(lines["hybrid"], colour))
        # And through the command line: every chart drawn.
        write_csv(self.dir, rows)
        write_json(self.dir, methods=methods)
        self.assertEqual(run(self.dir), 0)
        self.assertNotIn("not drawn", self.index())

    def test_method_order_and_colours_follow_results_json(self):
        methods = ["clustered", "tiled", "per-object", "brute"]
        fig = chart("forward_time", full_rows(), names(methods))
        self.assertEqual(legend_texts(fig), methods)
        colours = self.line_colours(fig)
        for i, method in enumerate(methods):
            self.assertTrue(same_color(colours[method], plot_results.METHOD_COLOURS[i]), method)
        # Today's table order keeps today's colours.
        self.assertEqual([plot_results.method_style(m, METHODS)[0] for m in METHODS],
                         ["tab:red", "tab:orange", "tab:blue", "tab:green"])

    def test_a_method_missing_from_results_json_is_still_drawn(self):
        rows = full_rows(METHODS + ["mystery"])
        fig = chart("total_time", rows, names())
        self.assertEqual(legend_texts(fig), METHODS + ["mystery"])
        self.assertTrue(same_color(self.line_colours(fig)["mystery"], plot_results.OTHER_STYLE[0]))
        self.assertIn("mystery", drawn_labels(chart("pass_time", rows, names())))

    def test_a_new_pass_is_stacked_in_frame_order(self):
        passes = ["depth", "ssao", "culling", "shadows", "forward", "tonemap"]
        rows = full_rows()
        for r in rows:
            r["ssao_ms"], r["ssao_iqr_ms"] = 3.0, 0.3
        fig = chart("pass_time", rows, names(passes=passes))
        # The legend reads as the stack does, top (last pass) to bottom, then the whole frame.
        self.assertEqual(legend_texts(fig), list(reversed(passes)) + ["whole frame"])
        # Every bar holds a 3 ms segment, and its top is the sum of every pass, the new one too.
        mix, shadows = fig.axes[0], fig.axes[1]
        bars = {ax: {round(p.get_x() + p.get_width() / 2) for p in ax.patches} for ax in fig.axes}
        self.assertEqual((len(bars[mix]), len(bars[shadows])), (len(METHODS), 2 * len(METHODS)))
        for ax in (mix, shadows):
            self.assertEqual(sum(p.get_height() == 3.0 for p in ax.patches), len(bars[ax]))
        brute = next(r for r in rows if r["series"] == "mix" and r["method"] == "brute"
                     and r["spot"] + r["point"] == 96)
        top = max(p.get_y() + p.get_height() for p in mix.patches
                  if abs(p.get_x() + p.get_width() / 2) < 0.01)  # the first bar: brute
        self.assertAlmostEqual(top, sum(brute[f"{p}_ms"] for p in passes))
        # Its columns are known ones: none is reported missing, and a missing one is named.
        self.assertIn("ssao_ms", plot_results.known_columns(passes))
        self.assertIn("ssao_iqr_ms", plot_results.known_columns(passes))
        write_json(self.dir, passes=passes)
        write_csv(self.dir, rows, columns=plot_results.known_columns(passes))
        self.assertEqual(run(self.dir), 0)
        self.assertNotIn("lacks", self.index())
        write_csv(self.dir, rows,
                  columns=[c for c in plot_results.known_columns(passes) if c != "ssao_iqr_ms"])
        run(self.dir)
        self.assertIn("results.csv lacks the columns ssao_iqr_ms;", self.index())

    def test_shadow_memory_chart_marks_the_pareto_front(self):
        rows = [row(f"sq-{res}-{fmt}", "shadow-quality", "tiled", 64, 32, shadows=1, shadow_res=res,
                    shadow_format=fmt, shadow_memory_bytes=mib * 2**20, shadow_misclassified_1px=err,
                    shadow_misclassified=err, total_ms=100)
                for res, fmt, mib, err in (("auto", "d16", 40, 0.01), ("256", "d16", 32, 0.08),
                                           ("1024", "d32", 1024, 0.012), ("1024", "d16", 512, 0.009))]
        fig = chart("pareto_shadow_memory", rows, names())
        self.assertEqual(legend_texts(fig), ["d16", "d32", "Pareto front"])
        # 1024 at 32 bits is beaten by 1024 at 16 bits in both memory and accuracy.
        self.assertEqual(set(plot_results.pareto_front([(0.01, 40), (0.08, 32), (0.012, 1024), (0.009, 512)])),
                         {0, 1, 3})

    def test_virtual_page_growth_puts_each_mode_at_its_memory(self):
        # Generated lights (with a light range) at two counts and a built-in scene: each mode's points sit at
        # (floor, memory) and (views, memory), labelled by scene or light count.
        rows = []
        for spots, floor, views in ((8, 1, 36), (64, 8, 240)):
            for mode, memory in (("auto", 20 * floor), ("virtual", 2.5 * floor)):
                rows.append(row(f"sm-{spots}-{mode}", "shadow-memory", "tiled", spots, spots // 2, shadows=1,
                                shadow_res=mode, scene="built-in default scene", light_range=0.35,
                                shadow_memory_bytes=memory * 2**20,
                                shadow_floor_bytes=floor * 2**20, shadow_views=views))
        rows.append(row("sm-hall-virtual", "shadow-memory", "tiled", 0, 0, shadows=1, shadow_res="virtual",
                        scene="hall", scene_triangles="", light_range="", shadow_memory_bytes=19 * 2**20,
                        shadow_floor_bytes=7.7 * 2**20,
                        shadow_views=240))
        fig = chart("virtual_page_growth", rows, names())
        floor_panel, views_panel = fig.axes
        for ax, x_of in ((floor_panel, {8: 1, 64: 8}), (views_panel, {8: 36, 64: 240})):
            points = {}
            for collection in ax.collections:
                for x, y in collection.get_offsets():
                    points.setdefault(collection.get_label(), []).append((float(x), float(y)))
            self.assertEqual(sorted(points["auto"]), [(x_of[8], 20 * 1), (x_of[64], 20 * 8)])
            self.assertIn((x_of[64], 2.5 * 8), points["virtual"])
            labels = {t.get_text() for t in ax.texts}
            self.assertTrue({"default, 8 + 4 lights", "default, 64 + 32 lights", "hall"} <= labels, labels)
        self.assertEqual(legend_texts(fig), ["auto", "virtual", "1x the floor", "3x the floor"])

    def test_cascade_chart_marks_both_pareto_fronts(self):
        rows = cascade_rows(counts=(1, 4), resolutions=(512, 2048))
        # One row that every other beats: dearer than 4 cascades at 512 with hw, and less accurate.
        rows.append(row("cascades-worse", "cascades", "tiled", 16, 16, shadows=1, shadow_res=1024,
                        shadow_filter="tent7", shadows_ms=50, shadow_memory_bytes=2**30, cascades=2,
                        sun_misclassified_1px=0.5))
        fig = chart("pareto_cascades", rows, names())
        # Colours by count and markers by filter, in results.json's filter order, then the front.
        self.assertEqual(legend_texts(fig), ["1 cascade", "2 cascades", "4 cascades", "hw", "tent5",
                                             "tent7", "Pareto front"])
        time_panel, memory_panel = fig.axes[0], fig.axes[1]
        for ax, column, scale in ((time_panel, "shadows_ms", 1.0), (memory_panel, "shadow_memory_bytes", 2**-20)):
            points = [(r["sun_misclassified_1px"], r[column] * scale) for r in rows]
            front = plot_results.pareto_front(points)
            self.assertNotIn(len(rows) - 1, front)  # the dominated row is off the front
            line = next(line for line in ax.lines if line.get_label() == "Pareto front")
            self.assertEqual(list(line.get_xdata()), [points[i][0] for i in front])
            self.assertEqual(list(line.get_ydata()), [points[i][1] for i in front])
        # Every point is annotated with its resolution per cascade.
        self.assertEqual(sorted(t.get_text() for t in memory_panel.texts),
                         sorted(str(r["shadow_res"]) for r in rows))

    def test_cascade_chart_needs_the_sun_columns(self):
        rows = cascade_rows()
        for r in rows:
            r["sun_misclassified_1px"] = ""
        with self.assertRaises(plot_results.SkipChart):
            chart("pareto_cascades", rows, names())

    def test_shadow_filters_follow_results_json(self):
        filters = ["disk", "tent7", "tent5", "tent3", "hw", "pcss"]
        rows = full_rows() + [row("sq-1024-pcss", "shadow-quality", "tiled", 64, 32, shadows=1,
                                  shadow_res=1024, shadow_filter="pcss", total_ms=260,
                                  shadow_misclassified=0.001)]
        fig = chart("pareto_shadows", rows, names(filters=filters))
        self.assertEqual(legend_texts(fig), filters + ["Pareto front"])

    def test_an_older_folder_falls_back_to_the_csv_sorted(self):
        # The columns of an older bench: no tonemap time, spreads of forward and total only.
        old_rows = [r for r in full_rows() if r["series"] not in SWEEP_SERIES]
        for r in old_rows:
            r["forward_spread_ms"], r["total_spread_ms"] = r["forward_iqr_ms"], r["total_iqr_ms"]
        write_csv(self.dir, old_rows, columns=OLD_COLUMNS)
        # (No list forms: an older bench had none, and says nothing of them.)
        expected = {"methods": sorted(METHODS), "shadow_filters": sorted(FILTERS),
                    "passes": ["culling", "depth", "forward", "shadows"], "light_lists": []}
        header, rows = plot_results.read_results(os.path.join(self.dir, "results.csv"))
        json_path = os.path.join(self.dir, "results.json")
        # No results.json at all: no note about it.
        self.assertEqual(plot_results.read_names(json_path, header, rows), (expected, []))
        # One without the keys: the same names, and a note saying so.
        write_json(self.dir, methods=None, filters=None, passes=None)
        names, notes = plot_results.read_names(json_path, header, rows)
        self.assertEqual(names, expected)
        self.assertEqual(notes, ["results.json lacks methods, shadow_filters, passes; taken from "
                                 "results.csv, sorted."])
        self.assertEqual(run(self.dir), 0)
        index = self.index()
        for name in ("forward_time", "total_time", "pass_time", "culling_efficiency", "sweep_mix",
                     "lights_reaching", "pareto_shadows", "pareto_light_assignment"):
            self.assertIn(f'<img src="charts/{name}.png"', index)
        for series in SWEEP_SERIES:
            self.assertIn(f"the {series} series needs times", index)
        self.assertIn("results.csv is from an older bench: the error bars are its P_spread_ms", index)
        self.assertIn("results.csv lacks the columns light_range, width, height, pixels,", index)
        # Its spreads are still drawn: the forward chart's error bars span forward_spread_ms.
        fig = chart("forward_time", plot_results.read_results(
            os.path.join(self.dir, "results.csv"))[1], names)
        bars = [c for c in fig.axes[0].containers if c.get_label() == "brute"][0]
        segments = bars.lines[2][0].get_segments()
        brute96 = next(r for r in old_rows if r["series"] == "mix" and r["method"] == "brute"
                       and r["spot"] + r["point"] == 96)
        self.assertAlmostEqual(segments[-1][1][1] - segments[-1][0][1],
                               brute96["forward_spread_ms"])

    def test_an_unreadable_results_json_is_a_note(self):
        write_csv(self.dir, full_rows())
        with open(os.path.join(self.dir, "results.json"), "w", encoding="utf-8") as f:
            f.write("{ not json")
        self.assertEqual(run(self.dir), 0)
        index = self.index()
        self.assertIn("results.json could not be read", index)
        self.assertNotIn("not drawn", index)


if __name__ == "__main__":
    unittest.main()
