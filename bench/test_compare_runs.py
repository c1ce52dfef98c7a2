"""Tests of bench/compare_runs.py: two synthetic runs compared side by side.

    /usr/bin/python3 -m unittest bench/test_compare_runs.py      (from the repository root)
"""

import contextlib
import csv
import io
import json
import os
import subprocess
import sys
import tempfile
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import compare_runs  # noqa: E402

SCRIPT = os.path.join(HERE, "compare_runs.py")
PASSES = ["depth", "culling", "forward"]
COLUMNS = (["config", "series", "method"] + [f"{p}_ms" for p in PASSES] + ["total_ms"] +
           ["tested_per_pixel", "forward_triangles", "shadow_draws"])


def row(config, depth, culling, forward, tested=3.5, triangles=20000, draws=12):
    return {"config": config, "series": "mix", "method": "tiled", "depth_ms": depth,
            "culling_ms": culling, "forward_ms": forward,
            "total_ms": depth + culling + forward, "tested_per_pixel": tested,
            "forward_triangles": triangles, "shadow_draws": draws}


def write_run(folder, rows, device):
    os.makedirs(folder, exist_ok=True)
    with open(os.path.join(folder, "results.csv"), "w", newline="", encoding="utf-8") as f:
        writer = csv.DictWriter(f, fieldnames=COLUMNS)
        writer.writeheader()
        writer.writerows(rows)
    with open(os.path.join(folder, "results.json"), "w", encoding="utf-8") as f:
        json.dump({"passes": PASSES, "configurations": [],
                   "provenance": {"device": {"name": device}, "git_commit": "abc123"}}, f)


def read_bytes(path):
    with open(path, "rb") as f:
        return f.read()


def compare(*args):
    """compare_runs.main, its progress line kept off the test's output."""
    with contextlib.redirect_stdout(io.StringIO()):
        return compare_runs.main(list(args))


def run_script(*args):
    return subprocess.run([sys.executable, SCRIPT, *args], capture_output=True, text=True,
                          check=False)


class CompareRunsTest(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.a = os.path.join(self.tmp.name, "a")
        self.b = os.path.join(self.tmp.name, "b")
        self.out = os.path.join(self.tmp.name, "out")
        write_run(self.a, [row("only-a", 1, 1, 1), row("one", 2.0, 1.0, 10.0),
                           row("two", 4.0, 0.5, 8.0)], "llvmpipe")
        # B: twice as slow on "one", the same on "two" but with other triangles; "only-b" extra.
        write_run(self.b, [row("two", 4.0, 0.5, 8.0, triangles=20004), row("only-b", 1, 1, 1),
                           row("one", 4.0, 2.0, 20.0)], "Some GPU")

    def tearDown(self):
        self.tmp.cleanup()

    def read_csv(self):
        with open(os.path.join(self.out, "compare.csv"), newline="", encoding="utf-8") as f:
            return list(csv.DictReader(f))

    def test_ratios_and_differing_counters(self):
        self.assertEqual(compare(self.a, self.b, self.out), 0)
        rows = self.read_csv()
        self.assertEqual([r["config"] for r in rows], ["one", "two"])  # in both, A's order
        one, two = rows
        for p in PASSES + ["total"]:
            self.assertEqual(one[f"{p}_ratio"], "2", p)
            self.assertEqual(two[f"{p}_ratio"], "1", p)
        self.assertEqual((one["forward_ms_a"], one["forward_ms_b"]), ("10.0", "20.0"))
        self.assertEqual(one["counters_differing"], "")
        self.assertEqual(two["counters_differing"], "forward_triangles")
        self.assertEqual((two["forward_triangles_a"], two["forward_triangles_b"]),
                         ("20000", "20004"))
        with open(os.path.join(self.out, "compare.html"), encoding="utf-8") as f:
            page = f.read()
        self.assertEqual(page.count('<td class="differ">'), 1)
        self.assertIn('<td class="differ">20000 ≠ 20004</td>', page)
        self.assertIn("<tr><td>device.name</td><td>llvmpipe</td><td>Some GPU</td></tr>", page)
        self.assertIn("2 configurations in both (of 3 in A, 3 in B)", page)

    def test_a_counter_within_the_tolerance_matches(self):
        write_run(self.b, [row("one", 2.0, 1.0, 10.0, tested=3.5 * (1 + 1e-6)),
                           row("two", 4.0, 0.5, 8.0, tested=3.6)], "Some GPU")
        self.assertEqual(compare(self.a, self.b, self.out), 0)
        self.assertEqual([r["counters_differing"] for r in self.read_csv()],
                         ["", "tested_per_pixel"])

    def test_output_is_deterministic(self):
        self.assertEqual(compare(self.a, self.b, self.out), 0)
        first = {n: read_bytes(os.path.join(self.out, n))
                 for n in ("compare.csv", "compare.html")}
        self.assertEqual(compare(self.a, self.b, self.out), 0)
        for name, data in first.items():
            self.assertEqual(read_bytes(os.path.join(self.out, name)), data, name)
        self.assertEqual(sorted(os.listdir(self.out)), ["compare.csv", "compare.html"])

    def assert_one_line_error(self, args, path, problem):
        result = run_script(*args)
        self.assertEqual(result.returncode, 1)
        self.assertEqual(result.stderr, f"compare_runs.py: error: {path}: {problem}\n")
        self.assertEqual(result.stdout, "")
        self.assertFalse(os.path.exists(self.out))

    def test_a_missing_folder_is_one_line_and_writes_nothing(self):
        absent = os.path.join(self.tmp.name, "absent")
        self.assert_one_line_error([self.a, absent, self.out], absent, "no such folder")
        self.assert_one_line_error([absent, self.b, self.out], absent, "no such folder")

    def test_unreadable_results_are_one_line_and_write_nothing(self):
        os.remove(os.path.join(self.b, "results.csv"))
        path = os.path.join(self.b, "results.csv")
        self.assert_one_line_error([self.a, self.b, self.out], path, "no such file")
        os.mkdir(path)  # a folder where the CSV should be
        result = run_script(self.a, self.b, self.out)
        self.assertEqual(result.returncode, 1)
        self.assertEqual(len(result.stderr.splitlines()), 1)
        self.assertTrue(result.stderr.startswith(f"compare_runs.py: error: {path}: "))
        os.rmdir(path)
        with open(path, "w", encoding="utf-8") as f:
            f.write("name,value\nx,1\n")
        self.assert_one_line_error([self.a, self.b, self.out], path, "no config column")
        with open(path, "w", encoding="utf-8") as f:
            f.write("config,total_ms\nx,1\nx,2\n")
        self.assert_one_line_error([self.a, self.b, self.out], path,
                                   "configuration 'x' appears twice")

    def test_an_error_leaves_an_earlier_comparison_alone(self):
        self.assertEqual(compare(self.a, self.b, self.out), 0)
        before = read_bytes(os.path.join(self.out, "compare.csv"))
        with open(os.path.join(self.b, "results.json"), "w", encoding="utf-8") as f:
            f.write("{ not json")
        result = run_script(self.a, self.b, self.out)
        self.assertEqual(result.returncode, 1)
        self.assertEqual(result.stderr, "compare_runs.py: error: "
                         f"{os.path.join(self.b, 'results.json')}: not valid JSON\n")
        self.assertEqual(read_bytes(os.path.join(self.out, "compare.csv")), before)
        self.assertEqual(sorted(os.listdir(self.out)), ["compare.csv", "compare.html"])

    def test_usage(self):
        result = run_script(self.a)
        self.assertEqual(result.returncode, 2)
        self.assertEqual(len(result.stderr.splitlines()), 1)


if __name__ == "__main__":
    unittest.main()
