"""Known-answer tests of the fits and flags behind bench/plot_results.py: the sweeps' log-log
slopes (sweep_charts.py), the cost model (cost_model.py) and flagged configurations.

    /usr/bin/python3 -m unittest bench/test_bench_fits.py      (from the repository root)
"""

import json
import os
import random
import sys
import tempfile
import unittest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import bench_data  # noqa: E402
import chart_style  # noqa: E402
import cost_model  # noqa: E402
import sweep_charts  # noqa: E402
import test_plot_results as synthetic  # noqa: E402  (its synthetic rows and CSV writer)

NAMES = synthetic.names()
SIZES = ((320, 180), (640, 360), (1280, 720), (2560, 1440))


def strings(rows):
    """Rows as the CSV reader gives them."""
    return [{k: str(v) for k, v in r.items()} for r in rows]


def pixel_rows(law=lambda p: 3e-6 * p):
    """The pixels series, forward = law(pixels) for every method, depth fixed."""
    return [synthetic.row(f"px-{m}-{w}", "pixels", m, 64, 32, width=w, height=h, pixels=w * h,
                          forward_ms=law(w * h), depth_ms=2.0)
            for w, h in SIZES for m in ("tiled", "clustered")]


class SlopeTest(unittest.TestCase):
    def test_fit_slope_known_answers(self):
        self.assertAlmostEqual(sweep_charts.fit_slope([(p, 3 * p) for p in (1, 10, 100)]), 1.0)
        self.assertAlmostEqual(sweep_charts.fit_slope([(x, 2 * x ** 0.5) for x in (4, 9, 25)]), 0.5)
        self.assertAlmostEqual(sweep_charts.fit_slope([(x, 7.0) for x in (1, 2, 3)]), 0.0)
        # x = 0 and time = 0 are left out; one x alone has no slope.
        self.assertAlmostEqual(sweep_charts.fit_slope([(0, 5), (2, 4), (4, 16), (8, 0)]), 2.0)
        self.assertIsNone(sweep_charts.fit_slope([(3, 1), (3, 2), (0, 1)]))

    def test_crossings_known_answers(self):
        # a = x (slope 1), b = 4 sqrt(x) (slope 1/2): equal at x = 16. Between 4 and 64 in log
        # space the difference log(a / b) = log(x) / 2 - log 4 is linear in log x, so the
        # interpolation is exact: x = 16, time 16, a faster below.
        a = [(x, float(x)) for x in (1, 4, 64, 256)]
        b = [(x, 4.0 * x ** 0.5) for x in (1, 4, 64, 256)]
        (x, y, faster), = sweep_charts.crossings(a, b)
        self.assertAlmostEqual(x, 16.0)
        self.assertAlmostEqual(y, 16.0)
        self.assertEqual(faster, "a")
        self.assertEqual(sweep_charts.crossings(b, a)[0][2], "b")
        # Lines that never cross, touch at a shared point only, or share fewer than two x.
        self.assertEqual(sweep_charts.crossings([(1, 1), (2, 2)], [(1, 3), (2, 5)]), [])
        self.assertEqual(sweep_charts.crossings([(1, 1), (2, 2)], [(1, 1), (2, 3)]), [])
        self.assertEqual(sweep_charts.crossings([(1, 1), (2, 2)], [(2, 1), (3, 5)]), [])

    def test_count_sweep_marks_where_brute_force_stops_winning(self):
        # Brute force's forward pass grows with the lights, tiled's barely: they cross once, and
        # the crossing is listed with the faster line on each side.
        rows = [synthetic.row(f"s-{m}-{n}", "scale", m, n // 2, n // 2,
                              forward_ms=(n / 16.0 if m == "brute" else 4.0 * (n / 16.0) ** 0.1))
                for n in (16, 64, 256, 1024) for m in ("brute", "tiled")]
        crossed = []
        _, _, function, args = next(c for c in synthetic.plot_results.CHARTS if c[0] == "sweep_scale")
        function(strings(rows), NAMES, *args, laws=[], crossovers=crossed)
        forward = [c for c in crossed if c["pass"] == "forward"]
        self.assertEqual(len(forward), 1)
        self.assertEqual((forward[0]["faster_below"], forward[0]["faster_above"]), ("brute", "tiled"))
        # 16 x (4^(1/0.9)) lights: brute n/16 meets 4 (n/16)^0.1 at (n/16)^0.9 = 4.
        self.assertAlmostEqual(forward[0]["at"], 16.0 * 4.0 ** (1 / 0.9), places=2)

    def test_list_forms_are_lines_of_their_own_and_cross_within_their_method(self):
        # Tiled in two list forms (masks, the default, first) beside brute force, which has none:
        # a line each, labelled by method and form; the forms' laws apart; the crossing of
        # tiled's own forms listed under their names, and the crossings between methods taken
        # from the default form. Indices: 2 (n/16)^0.1 + n/1024; masks: 4 (n/16)^0.1.
        def forward(m, form, n):
            if m == "brute":
                return n / 16.0
            return 4.0 * (n / 16.0) ** 0.1 if form == "masks" else 3.0 * (n / 16.0) ** 0.1 + n / 1024.0
        rows = [synthetic.row(f"s-{m}-{form}-{n}", "scale", m, n // 2, n // 2, light_lists=form,
                              forward_ms=forward(m, form, n))
                for n in (16, 64, 256, 1024, 4096) for m, form in (("brute", ""), ("tiled", "indices"), ("tiled", "masks"))]
        names = dict(NAMES, light_lists=["masks", "indices"])
        lines = sweep_charts.lines_of(strings(rows), names["methods"], names["light_lists"])
        self.assertEqual([label for label, *_ in lines], ["brute", "tiled masks", "tiled indices"])
        laws, crossed = [], []
        _, _, function, args = next(c for c in synthetic.plot_results.CHARTS if c[0] == "sweep_scale")
        function(strings(rows), names, *args, laws=laws, crossovers=crossed)
        forward_laws = {law["line"]: law["slope"] for law in laws if law["pass"] == "forward"}
        self.assertAlmostEqual(forward_laws["tiled masks"], 0.1, places=3)
        self.assertGreater(forward_laws["tiled indices"], 0.1)
        forward = [c for c in crossed if c["pass"] == "forward"]
        within = [c for c in forward if c["faster_below"].startswith("tiled ")]
        self.assertEqual(len(within), 1)
        self.assertEqual((within[0]["faster_below"], within[0]["faster_above"]), ("tiled indices", "tiled masks"))
        # Between methods: brute force against tiled's masks line (n / 16 = 4 (n / 16)^0.1).
        between = [c for c in forward if c["faster_below"] == "brute"]
        self.assertEqual(len(between), 1)
        self.assertAlmostEqual(between[0]["at"], 16.0 * 4.0 ** (1 / 0.9), places=2)

    def test_pixels_sweep_reports_slope_one(self):
        laws = []
        _, _, function, args = next(c for c in synthetic.plot_results.CHARTS
                                    if c[0] == "sweep_pixels")
        fig = function(strings(pixel_rows()), NAMES, *args, laws=laws)
        forward = [w for w in laws if w["pass"] == "forward"]
        self.assertEqual([w["line"] for w in forward], ["tiled", "clustered"])
        for w in forward:
            self.assertEqual((w["slope"], w["points"], w["x"]), (1.0, 4, "pixels"))
            self.assertEqual(w["law"], "forward ∝ pixels^1.00")
        depth = [w for w in laws if w["pass"] == "depth"]
        self.assertEqual([w["slope"] for w in depth], [0.0, 0.0])
        panel = next(ax for ax in fig.axes if ax.get_title() == "forward")
        self.assertIn("tiled: forward ∝ pixels^1.00",
                      [t.get_text() for t in panel.get_legend().get_texts()])
        self.assertEqual(panel.get_xscale(), "log")  # 320x180 to 2560x1440: 64 times

    def test_a_quadratic_law_and_flagged_rows_left_out_of_the_fit(self):
        rows = pixel_rows(lambda p: 1e-9 * p ** 2)
        # A flagged outlier at a fifth size would bend the slope if it were fitted.
        rows.append(synthetic.row("px-tiled-noisy", "pixels", "tiled", 64, 32, width=5120,
                                  height=2880, pixels=5120 * 2880, forward_ms=1.0, depth_ms=2.0,
                                  flagged=1, flag_reason="total_iqr_ms > 0.15 x total_ms"))
        laws = []
        fig = sweep_charts.chart_sweep(strings(rows), NAMES, "pixels", "pixels", "pixels",
                                       bench_data.pixels, laws=laws)
        slopes = {w["line"]: w for w in laws if w["pass"] == "forward"}
        self.assertEqual(slopes["tiled"]["slope"], 2.0)
        self.assertEqual(slopes["tiled"]["points"], 4)
        self.assertEqual(fig.flagged, ["px-tiled-noisy"])
        panel = next(ax for ax in fig.axes if ax.get_title() == "forward")
        hollow = [line for line in panel.lines if line.get_label() == chart_style.FLAGGED_LABEL]
        self.assertTrue(hollow)
        self.assertEqual(list(hollow[0].get_xdata()), [5120 * 2880])
        self.assertEqual(list(hollow[0].get_ydata()), [1.0])
        self.assertEqual(hollow[0].get_markerfacecolor(), "white")
        legend = [t.get_text() for t in panel.get_legend().get_texts()]
        self.assertIn(chart_style.FLAGGED_LEGEND, legend)

    def test_lights_reaching_draws_the_oracle(self):
        fig = synthetic.chart("lights_reaching", synthetic.full_rows(), NAMES)
        mix = fig.axes[0]
        oracle = next(line for line in mix.lines if line.get_label().startswith("oracle"))
        xs, ys = list(oracle.get_xdata()), list(oracle.get_ydata())
        self.assertEqual(xs, ys)
        brute = next(c for c in mix.lines if c.get_label() == "brute")
        reaching = list(brute.get_xdata())
        self.assertTrue(all(t > a for t, a in zip(brute.get_ydata(), reaching)))


class CostModelTest(unittest.TestCase):
    COSTS_NS = {"frame": 5e5, "pixel": 2.0, "light test": 0.3, "shadow lookup": 1.1,
                "filter tap": 0.2, "triangle": 5.0, "draw": 1000.0}

    def rows(self):
        rng = random.Random(1)
        rows = []
        for k in range(40):
            w, h = rng.choice(SIZES)
            r = {"config": f"r{k}", "series": "synthetic", "method": "tiled", "width": w,
                 "height": h, "pixels": w * h, "tested_per_pixel": rng.uniform(0, 20),
                 "shadow_lookups_per_pixel": rng.uniform(0, 8),
                 "filter_taps_per_pixel": rng.uniform(0, 40),
                 "forward_triangles": rng.randint(10**4, 10**6),
                 "forward_draws": rng.randint(10, 2000), "depth_triangles": rng.randint(10**4, 10**6),
                 "depth_draws": rng.randint(10, 2000), "spot": 64, "point": 32, "flagged": 0}
            c = self.COSTS_NS
            p = r["pixels"]
            forward_ns = (c["frame"] + c["pixel"] * p + c["light test"] * p * r["tested_per_pixel"]
                          + c["shadow lookup"] * p * r["shadow_lookups_per_pixel"]
                          + c["filter tap"] * p * r["filter_taps_per_pixel"]
                          + c["triangle"] * r["forward_triangles"] + c["draw"] * r["forward_draws"])
            r["forward_ms"] = forward_ns * 1e-6
            r["depth_ms"] = (3.0 * r["depth_triangles"] + 0.5 * p) * 1e-6  # no fixed cost
            r["total_ms"] = r["forward_ms"] + r["depth_ms"]
            rows.append(r)
        return rows

    def test_known_unit_costs_are_recovered(self):
        model = cost_model.fit_cost_model(strings(self.rows()), ["depth", "forward"])
        document = cost_model.model_document(model)
        fits = {f["pass"]: f for f in document["passes"]}
        forward = {t["term"]: t["ns"] for t in fits["forward"]["terms"]}
        self.assertEqual(set(forward), set(self.COSTS_NS))
        for term, ns in self.COSTS_NS.items():
            self.assertAlmostEqual(forward[term] / ns, 1.0, places=4, msg=term)
        depth = {t["term"]: t["ns"] for t in fits["depth"]["terms"]}
        self.assertAlmostEqual(depth["triangle"], 3.0, places=4)
        self.assertAlmostEqual(depth["pixel"], 0.5, places=4)
        self.assertAlmostEqual(depth["frame"], 0.0, places=2)  # never negative
        self.assertAlmostEqual(depth["draw"], 0.0, places=4)
        self.assertEqual((fits["forward"]["rows"], fits["forward"]["r2"]), (40, 1.0))
        self.assertEqual(document["total"]["r2"], 1.0)
        json.dumps(document)  # no function left in it

    def test_flagged_rows_and_missing_counters_are_left_out(self):
        rows = self.rows()
        rows[0]["forward_ms"] *= 100  # an outlier, flagged
        rows[0]["flagged"] = 1
        for r in rows:
            r["forward_draws"] = ""
        fit = cost_model.fit_pass(strings(rows), "forward", cost_model.MODELS["forward"])
        self.assertEqual(fit["rows"], 39)
        self.assertEqual(fit["not_in_data"], ["forward_draws"])
        self.assertNotIn("draw", [t["term"] for t in fit["terms"]])

    def test_nnls_keeps_costs_non_negative(self):
        a = [[1, 0], [0, 1], [1, 1]]
        b = [2, -3, -1]  # the unconstrained solution has a negative second cost
        x = cost_model.nnls(a, b)
        self.assertGreaterEqual(min(x), 0.0)
        self.assertAlmostEqual(x[0], 0.5)
        self.assertAlmostEqual(x[1], 0.0)


class FlaggedTest(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.dir = self.tmp.name

    def tearDown(self):
        self.tmp.cleanup()

    def test_mark_flags_applies_the_limit_when_the_bench_left_it_empty(self):
        rows = [{"total_ms": "10", "total_iqr_ms": "1.6", "flagged": ""},
                {"total_ms": "10", "total_iqr_ms": "1.4"},
                {"total_ms": "10", "total_iqr_ms": "9", "flagged": "0"},  # the bench's word holds
                {"total_ms": "10"}]
        bench_data.mark_flags(rows, 0.15)
        self.assertEqual([bench_data.is_flagged(r) for r in rows], [True, False, False, False])
        self.assertEqual(rows[3].get("flagged"), None)
        self.assertEqual(bench_data.flag_limit({"noise": {"flag_limit": 0.3}}), 0.3)
        self.assertEqual(bench_data.flag_limit({}), bench_data.FLAG_LIMIT)

    def test_flagged_rows_are_hollow_and_listed(self):
        rows = synthetic.full_rows()
        noisy = next(r for r in rows if r["series"] == "mix" and r["method"] == "tiled"
                     and r["spot"] + r["point"] == 24)
        noisy.update(flagged=1, flag_reason="total_iqr_ms > 0.15 x total_ms", config="noisy-tiled-24")
        fig = synthetic.chart("forward_time", rows, NAMES)
        self.assertEqual(fig.flagged, ["noisy-tiled-24"])
        hollow = [line for line in fig.axes[0].lines if line.get_label() == chart_style.FLAGGED_LABEL]
        self.assertEqual([(list(h.get_xdata()), list(h.get_ydata())) for h in hollow][0],
                         ([24], [noisy["forward_ms"]]))
        self.assertIn(chart_style.FLAGGED_LEGEND, synthetic.legend_texts(fig))
        synthetic.write_csv(self.dir, rows)
        synthetic.write_json(self.dir)
        self.assertEqual(synthetic.run(self.dir), 0)
        with open(os.path.join(self.dir, "index.html"), encoding="utf-8") as f:
            index = f.read()
        noise = index.split("<h2>Noise</h2>")[1].split("<h2>")[0]
        self.assertIn("<b>1</b> flagged", noise)
        self.assertIn("<li>noisy-tiled-24: total", noise)
        self.assertIn("best_of 3", noise)
        self.assertIn("frame to frame (every single timed frame) 0.081", noise)
        forward = index.split('<figure id="forward_time">')[1].split("</figure>")[0]
        self.assertIn("Flagged (drawn hollow, spread over the limit): noisy-tiled-24", forward)
        self.assertIn("Synthetic GPU", index.split("<h2>Provenance</h2>")[1])
        for name in ("laws.json", "cost_model.json"):
            with open(os.path.join(self.dir, name), encoding="utf-8") as f:
                self.assertTrue(json.load(f))


if __name__ == "__main__":
    unittest.main()
