#!/usr/bin/python3
"""check_pages.py on synthetic pages: a broken one must show every kind of problem, a clean one
none (a checker that never fails would pass every report).

    /usr/bin/python3 tests/browser/test_check_pages.py

Needs Chromium, not punctual. Exits 77 (skipped) with one line saying why where Chromium is
missing or does not start, so CTest shows a skip rather than a pass.
"""

import os
import struct
import sys
import tempfile
import unittest
import zlib

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import check_pages  # noqa: E402  (after the path)

BROWSER = None  # one Chromium for every test, started by main()


def tiny_png():
    """A valid 2x1 PNG, written here so the test needs no file of its own."""
    def chunk(kind, data):
        crc = zlib.crc32(kind + data)
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", crc)
    pixels = b"\x00" + b"\xff\x00\x00" * 2
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", 2, 1, 8, 2, 0, 0, 0))
            + chunk(b"IDAT", zlib.compress(pixels)) + chunk(b"IEND", b""))


class CheckPagesTest(unittest.TestCase):
    def setUp(self):
        self.dir = tempfile.TemporaryDirectory(prefix="punctual-pages-")
        self.addCleanup(self.dir.cleanup)
        os.mkdir(os.path.join(self.dir.name, "sub dir"))
        self.write("sub dir/chart one.png", tiny_png())
        self.write("data.csv", b"a,b\n1,2\n")

    def write(self, name, data):
        path = os.path.join(self.dir.name, name)
        with open(path, "wb") as f:
            f.write(data if isinstance(data, bytes) else data.encode())
        return path

    def test_clean_page_passes(self):
        # Every kind of link the checker must accept: a percent-encoded path with a space,
        # a query and a fragment on a local file, a fragment-only link, a remote and a mailto
        # one (neither is followed), a console.log (not an error).
        page = self.write("clean.html", """<!doctype html><html><head><title>clean</title>
            <link rel="stylesheet" href="style.css?v=1"></head><body id="top">
            <img src="sub%20dir/chart%20one.png" alt="chart">
            <a href="data.csv">CSV</a> <a href="sub dir/chart one.png#x">PNG</a>
            <a href="#top">top</a> <a href="https://example.invalid/">web</a>
            <a href="mailto:nobody@example.invalid">mail</a>
            <script>console.log("fine"); console.warn("only a warning");</script>
            </body></html>""")
        self.write("style.css", "body { margin: 0 }")
        self.assertEqual(BROWSER.check_page(page), [])

    def test_broken_page_reports_each_problem(self):
        page = self.write("broken.html", """<!doctype html><html><head><title>broken</title>
            </head><body><img src="charts/missing.png" alt="gone">
            <a href="no-such-page.html#frag">dangling</a>
            <script>console.error("something went wrong");</script>
            <script>undefinedFunction();</script></body></html>""")
        problems = BROWSER.check_page(page)
        text = "\n".join(problems)

        def has(*words):
            return any(all(w in p for w in words) for p in problems)
        self.assertTrue(has("image", "naturalWidth 0", "charts/missing.png"), text)
        self.assertTrue(has("console.error", "something went wrong"), text)
        self.assertTrue(has("uncaught exception", "undefinedFunction"), text)
        self.assertTrue(has("missing file", "no-such-page.html"), text)
        # The failed image load reaches the browser's log as an error too.
        self.assertTrue(has("console error", "missing.png"), text)
        # The dangling link's fragment is not part of the file name reported.
        self.assertTrue(has(os.path.join(self.dir.name, "no-such-page.html") + ")"), text)

    def test_missing_page_is_reported(self):
        problems = BROWSER.check_page(os.path.join(self.dir.name, "absent.html"))
        self.assertEqual(len(problems), 1)
        self.assertIn("page missing", problems[0])

    def test_local_file_missing_ignores_other_links(self):
        here = "file://" + self.dir.name
        self.assertIsNone(check_pages.local_file_missing("#x", here + "/page.html#x"))
        web = "https://a.invalid/"
        self.assertIsNone(check_pages.local_file_missing(web, web))
        self.assertIsNone(check_pages.local_file_missing("data.csv?x=1", here + "/data.csv?x=1"))
        self.assertEqual(check_pages.local_file_missing("a%20b.png", here + "/a%20b.png"),
                         os.path.join(self.dir.name, "a b.png"))


def main():
    global BROWSER
    try:
        BROWSER = check_pages.Browser()
    except check_pages.BrowserUnavailable as e:
        print(f"skipped: {e}")
        return check_pages.SKIP
    with BROWSER:
        print(f"using {BROWSER.version}")
        result = unittest.main(exit=False, verbosity=2).result
    return 0 if result.wasSuccessful() else 1


if __name__ == "__main__":
    sys.exit(main())
