"""Tests of bench/plot_failures.py on a synthetic failures.csv: one chart per study, the
failures page, and an idempotent section in index.html."""
import os
import sys
import tempfile
import unittest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import plot_failures  # noqa: E402

CSV = """study,parameter,value,variant,metric,error,total_ms
acne-vs-bias,"bias scale (x 1,1,1,0)",0,"hw","false_shadow fraction",0.5,20
acne-vs-bias,"bias scale (x 1,1,1,0)",1,"hw","false_shadow fraction",0,21
acne-vs-bias,"bias scale (x 1,1,1,0)",0,"tent5","false_shadow fraction",0.49,30
tile-depth-discontinuities,"tile size (pixels)",16,"tiled","efficiency",2.1,12
tile-depth-discontinuities,"tile size (pixels)",16,"clustered","efficiency",1.3,13
"""


class PlotFailuresTest(unittest.TestCase):
    def test_charts_page_and_index_section(self):
        with tempfile.TemporaryDirectory() as folder:
            with open(os.path.join(folder, "failures.csv"), "w") as f:
                f.write(CSV)
            with open(os.path.join(folder, "index.html"), "w") as f:
                f.write("<html><body><h1>bench</h1></body></html>\n")
            self.assertEqual(plot_failures.main(folder), 2)
            plot_failures.main(folder)  # a second run must not add a second section
            for study in ("acne-vs-bias", "tile-depth-discontinuities"):
                for ext in ("png", "svg"):
                    self.assertTrue(os.path.exists(os.path.join(folder, "charts", "failure-%s.%s" % (study, ext))))
            with open(os.path.join(folder, "failures.html")) as f:
                self.assertIn("failure-acne-vs-bias.png", f.read())
            with open(os.path.join(folder, "index.html")) as f:
                index = f.read()
            self.assertEqual(index.count(plot_failures.MARK_BEGIN), 1)
            self.assertIn("failure-tile-depth-discontinuities.png", index)
            self.assertTrue(index.rstrip().endswith("</html>"))

    def test_variants_become_lines_in_value_order(self):
        with tempfile.TemporaryDirectory() as folder:
            path = os.path.join(folder, "failures.csv")
            with open(path, "w") as f:
                f.write(CSV)
            studies = plot_failures.read_studies(path)
            self.assertEqual(list(studies["acne-vs-bias"]["variants"]), ["hw", "tent5"])
            self.assertEqual(studies["acne-vs-bias"]["variants"]["hw"], [(0.0, 0.5), (1.0, 0.0)])

    def test_every_variant_of_the_csv_is_drawn(self):
        # A variant no script names (a new filter) is a line like the others, in file order.
        extra = 'acne-vs-bias,"bias scale (x 1,1,1,0)",1,"pcss","false_shadow fraction",0.1,40\n'
        with tempfile.TemporaryDirectory() as folder:
            path = os.path.join(folder, "failures.csv")
            with open(path, "w") as f:
                f.write(CSV + extra)
            studies = plot_failures.read_studies(path)
        fig = plot_failures.study_figure("acne-vs-bias", studies["acne-vs-bias"])
        try:
            ax = fig.axes[0]
            self.assertEqual([line.get_label() for line in ax.lines], ["hw", "tent5", "pcss"])
            self.assertEqual([t.get_text() for t in ax.get_legend().get_texts()], ["hw", "tent5", "pcss"])
        finally:
            plot_failures.plt.close(fig)

    def test_a_wide_parameter_gets_a_log_axis_with_its_values_as_ticks(self):
        # The perspective-aliasing studies' view depths span 2.5 to 180 m; resolutions 512-2048 do not.
        wide = "".join('perspective,"view depth (m)",%g,"1 cascade","misclassified",%g,90\n' % (v, 0.01 / v)
                       for v in (2.5, 5, 10, 20, 40, 80, 180))
        narrow = "".join('seams,"resolution",%d,"hard: inside","misclassified",0.001,90\n' % v
                         for v in (512, 1024, 2048))
        with tempfile.TemporaryDirectory() as folder:
            path = os.path.join(folder, "failures.csv")
            with open(path, "w") as f:
                f.write(CSV.splitlines()[0] + "\n" + wide + narrow)
            studies = plot_failures.read_studies(path)
        for name, scale, ticks in (("perspective", "log", ["2.5", "5", "10", "20", "40", "80", "180"]),
                                   ("seams", "linear", None)):
            fig = plot_failures.study_figure(name, studies[name])
            try:
                ax = fig.axes[0]
                self.assertEqual(ax.get_xscale(), scale, name)
                if ticks:
                    self.assertEqual([t.get_text() for t in ax.get_xticklabels()], ticks)
            finally:
                plot_failures.plt.close(fig)

    def test_group_and_part_variants_share_colours_and_line_styles(self):
        variants = ["hard: split band", "hard: inside", "soft: split band", "soft: inside"]
        styles = plot_failures.variant_styles(variants)
        self.assertEqual(styles["hard: split band"]["color"], styles["hard: inside"]["color"])
        self.assertNotEqual(styles["hard: split band"]["color"], styles["soft: split band"]["color"])
        self.assertEqual(styles["hard: inside"]["linestyle"], styles["soft: inside"]["linestyle"])
        self.assertNotEqual(styles["soft: split band"]["linestyle"], styles["soft: inside"]["linestyle"])
        # Plain names keep the colour cycle.
        self.assertEqual(plot_failures.variant_styles(["hw", "tent5: wide"]), {"hw": {"marker": "o"},
                                                                              "tent5: wide": {"marker": "o"}})


if __name__ == "__main__":
    unittest.main()
