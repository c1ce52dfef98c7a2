"""Tests of bench/plot_results.py on synthetic results.csv files.

    cd /work/main && /usr/bin/python3 -m unittest bench/test_plot_results.py
"""

import contextlib
import csv
import io
import os
import sys
import tempfile
import unittest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import plot_results  # noqa: E402

ALL_CHARTS = [chart[0] for chart in plot_results.CHARTS]
METHODS = ["brute", "per-object", "tiled", "clustered"]
COST = {"brute": 12.0, "per-object": 1.6, "tiled": 1.8, "clustered": 1.7}


def row(config, series, method, spot, point, **cells):
    """A full row: a plausible default for every column, overridden by `cells`."""
    lights = spot + point
    forward = COST[method] * lights
    values = {
        "config": config, "series": series, "method": method, "spot": spot, "point": point,
        "shadows": 0, "shadow_res": 1024, "shadow_filter": "tent5", "point_layout": "cube",
        "frames": 5, "depth_ms": 4.0, "culling_ms": 0.0 if method in ("brute", "per-object")
        else 0.4 * lights, "shadows_ms": 0.0, "forward_ms": forward, "total_ms": forward + 15.0,
        "forward_spread_ms": 0.1 * forward, "total_spread_ms": 0.1 * forward,
        "tested_per_pixel": {"brute": lights, "per-object": min(lights, 8)}.get(
            method, 0.07 * lights + 1), "affecting_per_pixel": 0.05 * lights + 0.2,
        "missed_energy": 0.006 * lights if method == "per-object" else 0.0,
        "image_error": "" if method == "brute" else (
            0.0004 * lights if method == "per-object" else 0.0),
        "pixels_off": "" if method == "brute" else (
            0.01 * lights if method == "per-object" else 0.0),
        "shadow_misclassified": "", "shadow_false_shadow": "", "shadow_false_lit": "",
    }
    values["efficiency"] = values["tested_per_pixel"] / values["affecting_per_pixel"]
    values.update(cells)
    return values


def full_rows():
    """Every series, as `punctual bench` writes it (sizes as in a full run)."""
    rows = []
    for n in (3, 6, 12, 24, 48, 96):
        for m in METHODS:
            rows.append(row(f"mix-{m}-{n}", "mix", m, 2 * n // 3, n // 3))
    for n in (8, 32, 64):
        for m in METHODS:
            rows.append(row(f"spot-{m}-{n}", "spot-only", m, n, 0))
    for n in (4, 16, 32):
        for m in METHODS:
            rows.append(row(f"point-{m}-{n}", "point-only", m, 0, n))
    for m in METHODS:
        for on in (0, 1):
            rows.append(row(f"shadows-{m}-{on}", "shadows", m, 64, 32, shadows=on,
                            shadows_ms=60.0 * on))
    for i, res in enumerate((256, 512, 1024, 2048)):
        for j, flt in enumerate(("hw", "tent3", "tent5", "tent7", "disk")):
            rows.append(row(f"sq-{res}-{flt}", "shadow-quality", "tiled", 64, 32, shadows=1,
                            shadow_res=res, shadow_filter=flt, total_ms=200 + res / 20 + 8 * j,
                            shadow_misclassified=0.04 / (i + 1) / (1 + 0.3 * j) + 0.002 * j,
                            shadow_false_shadow=100 * j + 7, shadow_false_lit=50 + i))
    rows[0]["config"] = "mix <b>&amp;\"quoted\""  # must be escaped in the table
    return rows


def quick_mix_rows():
    """Only the mix series, two counts, with the statistics and error columns left empty."""
    empty = {c: "" for c in ("tested_per_pixel", "affecting_per_pixel", "efficiency",
                             "missed_energy", "image_error", "pixels_off")}
    return [row(f"q-{m}-{n}", "mix", m, 2 * n // 3, n // 3, **empty)
            for n in (3, 96) for m in METHODS]


def write_csv(folder, rows, columns=plot_results.COLUMNS):
    with open(os.path.join(folder, "results.csv"), "w", newline="", encoding="utf-8") as f:
        writer = csv.DictWriter(f, fieldnames=columns, extrasaction="ignore")
        writer.writeheader()
        writer.writerows(rows)


def write_png(path):
    """A tiny valid PNG standing in for a heat map."""
    plot_results.plt.imsave(path, [[0.0, 0.5], [1.0, 0.25]], cmap="viridis")


def run(folder):
    with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(io.StringIO()):
        return plot_results.main([folder])


def snapshot(folder):
    """{relative path: bytes} of every file the script wrote."""
    names = ["index.html"] + ["charts/" + n for n in os.listdir(os.path.join(folder, "charts"))]
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
        self.assertEqual(index.count("<tr>"), len(full_rows()) + 1)

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
        for name in ("culling_efficiency", "pareto_shadows", "pareto_light_assignment"):
            self.assertFalse(os.path.exists(os.path.join(self.dir, "charts", name + ".png")))
            self.assertNotIn(f"charts/{name}.png", index)
        self.assertEqual(index.count("not drawn"), 3)
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


if __name__ == "__main__":
    unittest.main()
