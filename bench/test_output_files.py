"""Tests of the files the bench scripts read and write: input_file.py (punctual's reader's rules:
a FIFO, a folder or a device is refused before it is opened, nothing over the cap is read),
output_file.py (temporaries renamed together), and what the scripts make of a FIFO, a folder, a
full disk or an interrupt: one line on stderr, every earlier file as it was (or every file new,
when the interrupt comes during the renames) and no temporary left.

    /usr/bin/python3 -m unittest bench/test_output_files.py      (from the repository root)
"""

import contextlib
import errno
import io
import os
import shutil
import signal
import socket
import stat
import subprocess
import sys
import tempfile
import unittest
from unittest import mock

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import input_file  # noqa: E402
import output_file  # noqa: E402
import plot_results  # noqa: E402  (selects matplotlib's backend before the Figure import)
import test_compare_runs  # noqa: E402  (its synthetic runs)
import test_plot_results  # noqa: E402  (its synthetic rows and CSV writer)
from matplotlib.figure import Figure  # noqa: E402

TIMEOUT = 120  # seconds a script may take; a FIFO opened for reading would block forever
FAILURES_V1 = """study,parameter,value,variant,metric,error,total_ms
acne,"bias scale",0,"hw","false_shadow fraction",0.5,20
acne,"bias scale",1,"hw","false_shadow fraction",0,21
tiles,"tile size (pixels)",16,"tiled","efficiency",2.1,12
tiles,"tile size (pixels)",32,"tiled","efficiency",2.6,12
"""
FAILURES_V2 = FAILURES_V1.replace("0.5,20", "0.25,20").replace("2.6,12", "3.1,12")
INDEX = "<!DOCTYPE html><html><body><h1>bench</h1></body></html>\n"


def snapshot(folder):
    """{relative path: bytes} of every regular file under `folder` (other entries: their
    type), so that a comparison also sees a file added, removed or replaced by a FIFO."""
    files = {}
    for root, dirs, names in os.walk(folder):
        for name in names + [d for d in dirs if os.path.islink(os.path.join(root, d))]:
            path = os.path.join(root, name)
            mode = os.lstat(path).st_mode
            key = os.path.relpath(path, folder)
            if stat.S_ISREG(mode):
                with open(path, "rb") as f:
                    files[key] = f.read()
            else:
                files[key] = stat.S_IFMT(mode)
    return files


def temporaries(folder):
    """Every entry under `folder` named like an output's temporary (".NAME.XXXXXXXX")."""
    return [os.path.join(root, n) for root, dirs, names in os.walk(folder)
            for n in names + dirs if n.startswith(".")]


def run_script(name, *args, hook=None):
    """The script run as `punctual bench` runs it: its status, stdout and stderr."""
    env = dict(os.environ)
    env.pop(output_file.TEST_HOOK, None)
    if hook:
        env[output_file.TEST_HOOK] = hook
    return subprocess.run([sys.executable, os.path.join(HERE, name), *args], env=env,
                          capture_output=True, text=True, timeout=TIMEOUT, check=False)


def write(path, text):
    with open(path, "w", encoding="utf-8") as f:
        f.write(text)


class ReaderTest(unittest.TestCase):
    """input_file.py: known answers, in the words of src/scene/input_file.cpp."""

    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.addCleanup(self.tmp.cleanup)
        self.dir = self.tmp.name

    def path(self, name):
        return os.path.join(self.dir, name)

    def assert_problem(self, path, problem, max_bytes=input_file.MAX_BYTES):
        with self.assertRaises(input_file.InputFileError) as caught:
            input_file.read_bytes(path, max_bytes)
        self.assertEqual((caught.exception.path, caught.exception.problem), (path, problem))
        self.assertEqual(str(caught.exception), f"{path}: {problem}")

    def test_a_regular_file_and_a_link_to_one_are_read_whole(self):
        write(self.path("a.csv"), "config\r\nx\n")
        os.symlink("a.csv", self.path("link.csv"))
        for name in ("a.csv", "link.csv"):
            self.assertEqual(input_file.read_bytes(self.path(name)), b"config\r\nx\n")
            self.assertEqual(input_file.read_text(self.path(name)), "config\r\nx\n")

    def test_a_fifo_is_refused_without_being_opened(self):
        os.mkfifo(self.path("results.csv"))
        with mock.patch.object(input_file.os, "open", wraps=os.open) as opened:
            self.assert_problem(self.path("results.csv"), "a named pipe (FIFO), not a regular file")
        opened.assert_not_called()

    def test_a_fifo_swapped_in_after_the_stat_is_refused_without_blocking(self):
        # The stat saw a regular file; by the open a FIFO is there (no writer: a blocking open
        # would wait forever). O_NONBLOCK opens it at once and fstat refuses it.
        os.mkfifo(self.path("results.csv"))
        previous = signal.signal(signal.SIGALRM, lambda *_: self.fail("the open blocked"))
        self.addCleanup(signal.signal, signal.SIGALRM, previous)
        signal.alarm(20)
        self.addCleanup(signal.alarm, 0)
        with mock.patch.object(input_file, "regular_file_problem", return_value=""):
            self.assert_problem(self.path("results.csv"), "a named pipe (FIFO), not a regular file")

    def test_what_is_not_a_regular_file(self):
        os.mkdir(self.path("folder"))
        os.symlink("absent", self.path("broken"))
        write(self.path("file"), "x")
        server = socket.socket(socket.AF_UNIX)
        self.addCleanup(server.close)
        server.bind(self.path("socket"))
        self.assert_problem(self.path("folder"), "a directory, not a regular file")
        self.assert_problem(self.path("absent"), "no such file")
        self.assert_problem(self.path("broken"), "a broken symbolic link")
        self.assert_problem(self.path("file/inside"), "no such file (a folder on its path is a file)")
        self.assert_problem(self.path("socket"), "a socket, not a regular file")
        self.assert_problem("/dev/null", "a device, not a regular file")
        self.assert_problem("", "no such file (the path is empty)")
        with self.assertRaises(input_file.InputFileError) as caught:
            input_file.read_text(self.path("absent"))
        self.assertTrue(caught.exception.absent)
        with self.assertRaises(input_file.InputFileError) as caught:
            input_file.read_text(self.path("broken"))
        self.assertFalse(caught.exception.absent)  # something is there: not an optional file's absence

    def test_the_size_cap(self):
        write(self.path("ten"), "0123456789")
        self.assertEqual(input_file.read_bytes(self.path("ten"), 10), b"0123456789")
        self.assert_problem(self.path("ten"), "10 bytes, more than the 9 punctual can read", 9)
        self.assertEqual(input_file.regular_file_problem(self.path("ten"), 9),
                         "10 bytes, more than the 9 punctual can read")
        self.assertEqual(input_file.MAX_BYTES, 256 * 2**20)

    @unittest.skipUnless(os.path.exists("/proc/self/status"), "needs /proc")
    def test_a_file_longer_than_its_stat_size_stops_at_the_cap(self):
        # /proc files report size 0: the reader reads on past st_size, never past the cap.
        self.assertEqual(os.stat("/proc/self/status").st_size, 0)
        with self.assertRaises(input_file.InputFileError) as caught:
            input_file.read_bytes("/proc/self/status", 16)
        self.assertRegex(caught.exception.problem, r"^\d+ bytes, more than the 16 punctual can read$")
        self.assertIn(b"Pid:", input_file.read_bytes("/proc/self/status"))

    def test_text_that_is_not_utf8(self):
        with open(self.path("latin1.csv"), "wb") as f:
            f.write(b"config\ncaf\xe9\n")
        with self.assertRaises(input_file.InputFileError) as caught:
            input_file.read_text(self.path("latin1.csv"))
        self.assertEqual(caught.exception.problem, "not UTF-8 text (byte 10)")


class OutputsTest(unittest.TestCase):
    """output_file.Outputs in the process: temporaries beside their targets, renamed together."""

    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.addCleanup(self.tmp.cleanup)
        self.dir = self.tmp.name
        self.targets = [os.path.join(self.dir, n) for n in ("a.svg", "b.html")]
        for target in self.targets:
            write(target, "old " + os.path.basename(target))

    def test_nothing_changes_before_the_commit_and_everything_at_it(self):
        old_mask = os.umask(0o027)
        self.addCleanup(os.umask, old_mask)
        os.chmod(self.targets[0], 0o604)
        write(os.path.join(self.dir, "stale.png"), "old chart")
        outputs = output_file.Outputs()
        for target in self.targets + [os.path.join(self.dir, "c.json")]:
            outputs.write_text(target, "new " + os.path.basename(target))
        outputs.remove(os.path.join(self.dir, "stale.png"))
        outputs.remove(os.path.join(self.dir, "absent.png"))  # nothing to remove: no error
        names = sorted(os.listdir(self.dir))
        self.assertEqual(len(names), 6)
        self.assertRegex(names[0], r"^\.a\.svg\.\w+$")
        self.assertRegex(names[1], r"^\.b\.html\.\w+$")
        self.assertRegex(names[2], r"^\.c\.json\.\w+$")
        written = snapshot(self.dir)  # the targets as they were, the temporaries new
        self.assertEqual([written[n] for n in ("a.svg", "b.html", "stale.png")],
                         [b"old a.svg", b"old b.html", b"old chart"])
        self.assertEqual([written[n] for n in names[:3]], [b"new a.svg", b"new b.html", b"new c.json"])
        outputs.commit()
        self.assertTrue(outputs.committed)
        self.assertEqual(snapshot(self.dir), {"a.svg": b"new a.svg", "b.html": b"new b.html",
                                              "c.json": b"new c.json"})
        # What open(target, "w") gives: an old file keeps its mode, a new one 0666 less the umask.
        modes = {n: stat.S_IMODE(os.stat(os.path.join(self.dir, n)).st_mode) for n in ("a.svg", "c.json")}
        self.assertEqual(modes, {"a.svg": 0o604, "c.json": 0o640})

    def test_discard_keeps_every_old_file(self):
        before = snapshot(self.dir)
        outputs = output_file.Outputs()
        outputs.write_text(self.targets[0], "new")
        outputs.remove(self.targets[1])
        outputs.discard()
        self.assertEqual(snapshot(self.dir), before)
        self.assertEqual(temporaries(self.dir), [])

    def test_a_folder_where_a_file_goes_is_refused_before_anything_is_written(self):
        os.mkdir(os.path.join(self.dir, "c.png"))
        outputs = output_file.Outputs()
        outputs.write_text(self.targets[0], "new")
        with self.assertRaises(output_file.OutputError) as caught:
            outputs.write_text(os.path.join(self.dir, "c.png"), "new")
        self.assertEqual(str(caught.exception),
                         f"{self.dir}/c.png: a directory, where a file is to be written")
        outputs.discard()
        self.assertEqual(temporaries(self.dir), [])


class ScriptInputTest(unittest.TestCase):
    """A FIFO or a folder where a script reads a file: one line, status 1, nothing written, and
    promptly (a script that opened the FIFO would block until TIMEOUT)."""

    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.addCleanup(self.tmp.cleanup)
        self.dir = self.tmp.name

    def assert_refused(self, result, program, path, problem):
        self.assertEqual((result.returncode, result.stdout), (1, ""))
        self.assertEqual(result.stderr, f"{program}: error: {path}: {problem}\n")

    def test_compare_runs_refuses_a_fifo_or_a_folder_in_a_run(self):
        a, b, out = (os.path.join(self.dir, n) for n in ("a", "b", "out"))
        test_compare_runs.write_run(a, [test_compare_runs.row("one", 1.0, 1.0, 1.0)], "A")
        test_compare_runs.write_run(b, [test_compare_runs.row("one", 2.0, 1.0, 1.0)], "B")
        for name, make, problem in (("results.csv", os.mkfifo, "a named pipe (FIFO), not a regular file"),
                                    ("results.json", os.mkfifo, "a named pipe (FIFO), not a regular file"),
                                    ("results.json", os.mkdir, "a directory, not a regular file")):
            path = os.path.join(a, name)
            saved = snapshot(a)[name]
            os.remove(path)
            make(path)
            self.assert_refused(run_script("compare_runs.py", a, b, out), "compare_runs.py", path, problem)
            self.assertFalse(os.path.exists(out))
            (os.rmdir if os.path.isdir(path) else os.remove)(path)
            with open(path, "wb") as f:
                f.write(saved)

    def test_plot_results_refuses_a_fifo_or_a_folder(self):
        test_plot_results.write_csv(self.dir, test_plot_results.quick_mix_rows())
        csv_path, json_path = (os.path.join(self.dir, n) for n in ("results.csv", "results.json"))
        os.mkdir(json_path)
        self.assert_refused(run_script("plot_results.py", self.dir), "plot_results.py", json_path,
                            "a directory, not a regular file")
        os.rmdir(json_path)
        os.remove(csv_path)
        os.mkfifo(csv_path)
        self.assert_refused(run_script("plot_results.py", self.dir), "plot_results.py", csv_path,
                            "a named pipe (FIFO), not a regular file")
        self.assertEqual(sorted(os.listdir(self.dir)), ["results.csv"])

    def test_plot_failures_refuses_a_fifo_for_its_csv_or_the_index(self):
        csv_path, index = (os.path.join(self.dir, n) for n in ("failures.csv", "index.html"))
        os.mkfifo(csv_path)
        self.assert_refused(run_script("plot_failures.py", self.dir), "plot_failures.py", csv_path,
                            "a named pipe (FIFO), not a regular file")
        os.remove(csv_path)
        write(csv_path, FAILURES_V1)
        os.mkfifo(index)
        self.assert_refused(run_script("plot_failures.py", self.dir), "plot_failures.py", index,
                            "a named pipe (FIFO), not a regular file")
        self.assertEqual(snapshot(self.dir), {"failures.csv": FAILURES_V1.encode(), "index.html": stat.S_IFIFO})
        self.assertEqual(temporaries(self.dir), [])

    def test_a_bad_failures_csv_is_one_line(self):
        csv_path = os.path.join(self.dir, "failures.csv")
        write(csv_path, "study,parameter,value,variant,metric,error\nacne,bias,zero,hw,m,0.5\n")
        self.assert_refused(run_script("plot_failures.py", self.dir), "plot_failures.py", csv_path,
                            "line 2: could not convert string to float: 'zero'")
        write(csv_path, "study,value\nacne,0\n")
        self.assert_refused(run_script("plot_failures.py", self.dir), "plot_failures.py", csv_path,
                            "no parameter column")


class CommitTest(unittest.TestCase):
    """plot_failures.py writes six files (four charts, failures.html, index.html); a signal or a
    full disk injected at each step of the commit (PUNCTUAL_BENCH_TEST_HOOK) leaves all of them
    old or all new, one line on stderr, and no temporary."""

    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory()
        cls.old = os.path.join(cls.tmp.name, "old")  # a folder after a run on FAILURES_V1
        os.mkdir(cls.old)
        write(os.path.join(cls.old, "failures.csv"), FAILURES_V1)
        write(os.path.join(cls.old, "index.html"), INDEX)
        assert run_script("plot_failures.py", cls.old).returncode == 0
        write(os.path.join(cls.old, "failures.csv"), FAILURES_V2)  # the input of the runs tested
        cls.old_files = snapshot(cls.old)
        new = os.path.join(cls.tmp.name, "new")
        shutil.copytree(cls.old, new)
        assert run_script("plot_failures.py", new).returncode == 0
        cls.new_files = snapshot(new)

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def run_with(self, hook):
        folder = os.path.join(self.tmp.name, "run-" + hook.replace(":", "-"))
        shutil.copytree(self.old, folder)
        return folder, run_script("plot_failures.py", folder, hook=hook)

    def test_the_runs_differ(self):
        self.assertEqual(len(self.new_files), len(self.old_files))
        changed = [n for n in self.new_files if self.new_files[n] != self.old_files[n]]
        self.assertEqual(sorted(changed), ["charts/failure-acne.png", "charts/failure-acne.svg",
                                           "charts/failure-tiles.png", "charts/failure-tiles.svg"])

    def test_a_fault_before_the_renames_leaves_every_old_file(self):
        cases = [("write:0:INT", 130), ("written:0:INT", 130), ("written:2:TERM", 143),
                 ("write:3:QUIT", 131), ("write:5:INT", 130), ("written:5:HUP", 129),
                 ("written:1:ENOSPC", 1)]
        for hook, status in cases:
            with self.subTest(hook=hook):
                folder, result = self.run_with(hook)
                self.assertEqual((result.returncode, result.stdout), (status, ""))
                if status == 1:
                    self.assertEqual(result.stderr, f"plot_failures.py: error: {folder}/charts/"
                                     "failure-acne.svg: no space left on the device\n")
                else:
                    self.assertEqual(result.stderr, "plot_failures.py: interrupted; no file was changed\n")
                self.assertEqual(temporaries(folder), [])
                self.assertEqual(snapshot(folder), self.old_files)

    def test_a_signal_during_the_renames_completes_every_new_file(self):
        for hook, status in (("rename:0:INT", 130), ("rename:3:HUP", 129), ("rename:5:TERM", 143)):
            with self.subTest(hook=hook):
                folder, result = self.run_with(hook)
                self.assertEqual((result.returncode, result.stdout), (status, ""))
                self.assertEqual(result.stderr,
                                 "plot_failures.py: interrupted; every file was already written\n")
                self.assertEqual(temporaries(folder), [])
                self.assertEqual(snapshot(folder), self.new_files)

    def test_compare_runs_is_all_or_nothing_too(self):
        a, b, out = (os.path.join(self.tmp.name, "cmp-" + n) for n in ("a", "b", "out"))
        test_compare_runs.write_run(a, [test_compare_runs.row("one", 1.0, 1.0, 1.0)], "A")
        test_compare_runs.write_run(b, [test_compare_runs.row("one", 2.0, 1.0, 1.0)], "B")
        self.assertEqual(run_script("compare_runs.py", a, b, out).returncode, 0)
        before = snapshot(out)
        test_compare_runs.write_run(b, [test_compare_runs.row("one", 4.0, 1.0, 1.0)], "B")
        result = run_script("compare_runs.py", a, b, out, hook="written:1:INT")
        self.assertEqual((result.returncode, result.stderr), (130, "compare_runs.py: interrupted; no file was changed\n"))
        self.assertEqual(snapshot(out), before)
        os.mkdir(os.path.join(out, ".compare.csv.keep"))  # not ours: left alone
        result = run_script("compare_runs.py", a, b, out, hook="rename:1:INT")
        self.assertEqual(result.returncode, 130)
        self.assertEqual(temporaries(out), [os.path.join(out, ".compare.csv.keep")])
        self.assertNotEqual(snapshot(out)["compare.csv"], before["compare.csv"])


class PlotResultsFaultTest(unittest.TestCase):
    """plot_results.py's charts when savefig fails halfway through a chart (a truncated SVG was
    the issue): the run says so in one line and every earlier chart is as it was."""

    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.addCleanup(self.tmp.cleanup)
        self.dir = self.tmp.name
        test_plot_results.write_csv(self.dir, test_plot_results.quick_mix_rows())
        self.assertEqual(self.main(), 0)
        # The next run would draw one light count only: other charts, and sweep_mix skipped
        # (its old files are removed only at the commit).
        test_plot_results.write_csv(self.dir, test_plot_results.quick_mix_rows()[:4])
        self.before = snapshot(self.dir)
        self.assertIn("charts/sweep_mix.svg", self.before)

    def main(self):
        self.stderr = io.StringIO()
        with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(self.stderr):
            return plot_results.main([self.dir])

    def failing_savefig(self, error):
        """Figure.savefig that writes the first two files, then half a file and raises."""
        real, calls = Figure.savefig, []

        def savefig(fig, f, **kwargs):
            calls.append(kwargs.get("format"))
            if len(calls) < 3:
                return real(fig, f, **kwargs)
            f.write(b"\x89PNG truncated")
            raise error
        return mock.patch.object(Figure, "savefig", savefig)

    def test_an_interrupt_in_savefig_changes_no_file(self):
        with self.failing_savefig(KeyboardInterrupt()):
            self.assertEqual(self.main(), 130)
        self.assertEqual(self.stderr.getvalue(), "plot_results.py: interrupted; no file was changed\n")
        self.assertEqual(temporaries(self.dir), [])
        self.assertEqual(snapshot(self.dir), self.before)

    def test_a_full_disk_in_savefig_changes_no_file(self):
        with self.failing_savefig(OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))):
            self.assertEqual(self.main(), 1)
        self.assertEqual(self.stderr.getvalue(), f"plot_results.py: error: {self.dir}/charts/"
                         "total_time.png: no space left on the device\n")
        self.assertEqual(temporaries(self.dir), [])
        self.assertEqual(snapshot(self.dir), self.before)

    def test_sigint_while_drawing_and_sigterm_while_renaming(self):
        result = run_script("plot_results.py", self.dir, hook="written:3:INT")
        self.assertEqual((result.returncode, result.stdout), (130, ""))
        self.assertEqual(result.stderr, "plot_results.py: interrupted; no file was changed\n")
        self.assertEqual(snapshot(self.dir), self.before)
        result = run_script("plot_results.py", self.dir, hook="rename:2:TERM")
        self.assertEqual((result.returncode, result.stdout), (143, ""))
        self.assertEqual(result.stderr, "plot_results.py: interrupted; every file was already written\n")
        after = snapshot(self.dir)
        self.assertNotIn("charts/sweep_mix.svg", after)  # skipped now: the stale chart went too
        self.assertNotEqual(after["index.html"], self.before["index.html"])
        self.assertEqual(temporaries(self.dir), [])


if __name__ == "__main__":
    unittest.main()
