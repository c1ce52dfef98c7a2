"""Every file a bench script writes, and how a run ends: all of a run's files change together or
none does, and an interrupt or a write error is one line on stderr, never a traceback.

A script's outputs (charts, pages, JSON) go through one Outputs. Each is written to a temporary
beside its target (tempfile.mkstemp, named ".NAME.XXXXXXXX" so that a listing hides it), given
the mode a plain open() would (the old file's, else 0666 less the umask) and fsync'ed; nothing
is renamed yet. When the run has written everything, commit() renames every temporary over its
target with the ending signals blocked, so an interrupt then is held until every rename is done
(all new); an interrupt or an error before it removes every temporary (all old). A reader of
the folder never sees a truncated chart, nor a page pointing at a chart of another run.

run_script() runs a script's body with that Outputs: it turns SIGTERM, SIGHUP and SIGQUIT into
an interrupt like SIGINT's (the signals punctual's own commit holds, src/core/deferred_signals.h),
and maps an interrupt to one line and status 128 + the signal (130 for Ctrl-C), bad
input (InputFileError) or a write error (OutputError, OSError) to `<script>.py: error: <file>:
<problem>` and status 1. Any other exception is a bug: its temporaries are removed and its
traceback shown.

PUNCTUAL_BENCH_TEST_HOOK=STEP:INDEX:ACTION (for the tests only) sends SIGINT (INT), SIGTERM
(TERM), SIGHUP (HUP) or SIGQUIT (QUIT) to the script, or raises ENOSPC (ENOSPC), at one step of the commit: "write" before
the INDEX-th temporary is created, "written" once it holds its bytes (before the fsync), "rename"
before the INDEX-th rename (signals blocked).
"""

import contextlib
import errno
import os
import signal
import stat
import sys
import tempfile
import threading

from input_file import InputFileError

# The signals that end a process from the keyboard, a closed terminal or a supervisor.
SIGNALS = (signal.SIGINT, signal.SIGTERM, signal.SIGHUP, signal.SIGQUIT)
TEST_HOOK = "PUNCTUAL_BENCH_TEST_HOOK"

_started = False  # whether run_script has begun (for the import-time interrupt message)


class Interrupted(KeyboardInterrupt):
    """One of SIGNALS arrived; a KeyboardInterrupt, so nothing catches it by accident."""

    def __init__(self, signum=signal.SIGINT):
        super().__init__(signal.Signals(signum).name)
        self.signum = int(signum)


class OutputError(Exception):
    """An output that cannot be written: its path and the problem, for the one-line message."""

    def __init__(self, path, problem):
        super().__init__(f"{path}: {problem}")
        self.path = path
        self.problem = problem


def output_problem(error):
    """The phrase of an errno from creating, writing or renaming an output."""
    phrases = {errno.ENOSPC: "no space left on the device", errno.EDQUOT: "over the disk quota",
               errno.EROFS: "a read-only file system", errno.EACCES: "permission denied",
               errno.EPERM: "permission denied", errno.ENOENT: "no such file or folder",
               errno.ENOTDIR: "a folder on its path is a file",
               errno.EISDIR: "a directory, not a file",
               errno.EEXIST: "there already, and not a folder"}  # os.makedirs on a file
    return phrases.get(error) or (os.strerror(error) if error else "write error")


def new_file_mode():
    """0666 less the umask: the mode open(path, "w") gives a new file (mkstemp's is 0600, which
    would hide a chart from a web server or another user). os.umask is the only portable way
    to read the mask, and sets it; it is put straight back (the scripts have one thread)."""
    mask = os.umask(0o022)
    os.umask(mask)
    return 0o666 & ~mask


def target_mode(target, new_mode):
    """The mode open(target, "w") would leave: an existing regular file's own permissions (it
    truncates the file and keeps them), else `new_mode`."""
    try:
        info = os.stat(target)
    except OSError:
        return new_mode
    return stat.S_IMODE(info.st_mode) & 0o777 if stat.S_ISREG(info.st_mode) else new_mode


@contextlib.contextmanager
def signals_blocked():
    """SIGNALS held (not lost) for the block: they are delivered when it ends."""
    previous = signal.pthread_sigmask(signal.SIG_BLOCK, SIGNALS)
    try:
        yield
    finally:
        signal.pthread_sigmask(signal.SIG_SETMASK, previous)


def fault_hook(step, index):
    """The tests' fault at this step, when PUNCTUAL_BENCH_TEST_HOOK names it (see the module)."""
    spec = os.environ.get(TEST_HOOK, "")
    parts = spec.split(":")
    if len(parts) != 3 or parts[0] != step or parts[1] != str(index):
        return
    if parts[2] == "ENOSPC":
        raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))
    os.kill(os.getpid(), signal.Signals["SIG" + parts[2]])


class Outputs:
    """The files of one run: each written to a temporary beside its target; commit() renames
    them all over their targets (and removes the stale ones), discard() removes the
    temporaries. `committed` says whether the targets hold the new files."""

    def __init__(self):
        self._pending = []  # [(temporary, target)] in the order written
        self._stale = []  # targets to remove at the commit (a chart no longer drawn)
        self._mode = new_file_mode()
        self.committed = False

    def write_bytes(self, target, data):
        self.write_with(target, lambda f: f.write(data))

    def write_text(self, target, text):
        """`text` as UTF-8, its line ends as given (as open(newline="") would write them)."""
        self.write_bytes(target, text.encode("utf-8"))

    def write_with(self, target, write):
        """Calls write(f) with `f` a binary file on a new temporary for `target` (savefig
        writes there), then makes it durable. An OSError becomes OutputError(target, ...)."""
        folder, name = os.path.split(target)
        if os.path.isdir(target) and not os.path.islink(target):
            raise OutputError(target, "a directory, where a file is to be written")
        fault_hook("write", len(self._pending))
        try:
            # Held signals: a temporary is on the list from the moment it exists, so an
            # interrupt can never leave one behind.
            with signals_blocked():
                fd, temporary = tempfile.mkstemp(prefix="." + name + ".", dir=folder or ".")
                self._pending.append((temporary, target))
            with os.fdopen(fd, "wb") as f:
                os.fchmod(f.fileno(), target_mode(target, self._mode))
                write(f)
                fault_hook("written", len(self._pending) - 1)
                f.flush()
                os.fsync(f.fileno())  # its bytes on disk before a rename can expose them
        except OSError as err:
            raise OutputError(target, output_problem(err.errno)) from None

    def remove(self, target):
        """Removes `target` at the commit, not before (an interrupt keeps it)."""
        if os.path.isdir(target) and not os.path.islink(target):
            raise OutputError(target, "a directory, where a file is to be removed")
        self._stale.append(target)

    def commit(self):
        """Renames every temporary over its target and removes the stale targets, with
        SIGNALS held until all is done. Only a failing rename (a disk error) can
        stop it halfway; the error then says how many targets were already replaced."""
        with signals_blocked():
            for done, (temporary, target) in enumerate(self._pending):
                try:
                    fault_hook("rename", done)
                    os.replace(temporary, target)
                except OSError as err:
                    self._pending = self._pending[done:]
                    self.discard()
                    replaced = f" ({done} files before it were replaced)" if done else ""
                    raise OutputError(target, output_problem(err.errno) + replaced) from None
            self._pending = []
            for target in self._stale:
                with contextlib.suppress(FileNotFoundError):
                    os.remove(target)
            self._stale = []
            self.committed = True

    def discard(self):
        """Removes every temporary not yet renamed; the targets keep their old contents."""
        with signals_blocked():
            for temporary, _ in self._pending:
                with contextlib.suppress(FileNotFoundError):
                    os.remove(temporary)
            self._pending = []
            self._stale = []


def _interrupt(signum, frame):
    # Further signals are ignored from here: the cleanup that follows is short and must end.
    for s in SIGNALS:
        signal.signal(s, signal.SIG_IGN)
    raise Interrupted(signum)


def exit_quietly_on_interrupt(program):
    """For a script's first lines, before its slow imports (matplotlib): an interrupt exits
    with one line and 128 + the signal, no traceback. Nothing is written before run_script."""
    def handler(signum, frame):
        what = "interrupted" if _started else "interrupted before writing anything"
        with contextlib.suppress(OSError):  # a closed terminal (SIGHUP): the line is lost
            os.write(2, f"{program}: {what}\n".encode())
        os._exit(128 + signum)
    for s in _caught_signals():
        signal.signal(s, handler)


def _caught_signals():
    """SIGNALS, less those the parent set to be ignored (nohup, a background job of
    a shell script): an ignored signal stays ignored, as Python itself leaves SIGINT."""
    return [s for s in SIGNALS if signal.getsignal(s) is not signal.SIG_IGN]


def _say(line):
    """The run's one line on stderr; on a closed terminal (SIGHUP) it is lost, quietly."""
    with contextlib.suppress(OSError):
        print(line, file=sys.stderr, flush=True)


def _error_line(program, err):
    """The one line of an expected failure: an InputFileError, OutputError or OSError."""
    if isinstance(err, (InputFileError, OutputError)):
        return f"{program}: error: {err}"
    where = err.filename if err.filename is not None else "?"
    return f"{program}: error: {where}: {output_problem(err.errno)}"


def run_script(program, body):
    """Runs body(outputs) -> exit status, with an Outputs that body commits once it has
    written everything. Returns the status; an interrupt or an error is one line on stderr
    (the module says which), every temporary is removed, and the targets are all old, or all
    new when the interrupt came during or after the commit."""
    global _started
    _started = True
    outputs = Outputs()
    handle = threading.current_thread() is threading.main_thread()
    previous = [(s, signal.signal(s, _interrupt)) for s in _caught_signals()] if handle else []
    try:
        return body(outputs)
    except KeyboardInterrupt as err:  # Interrupted, or a KeyboardInterrupt raised by hand
        _stop_signals(handle)
        outputs.discard()
        what = ("every file was already written" if outputs.committed
                else "no file was changed")
        _say(f"{program}: interrupted; {what}")
        return 128 + getattr(err, "signum", signal.SIGINT)
    except (InputFileError, OutputError, OSError) as err:
        _stop_signals(handle)
        outputs.discard()
        _say(_error_line(program, err))
        return 1
    finally:
        outputs.discard()  # a bug's exception: no temporary left behind either
        for s, handler in previous:
            signal.signal(s, handler)


def _stop_signals(handle):
    """Ignores SIGNALS while a failed run cleans up (a second Ctrl-C must not cut
    the cleanup short); run_script's finally puts the handlers back."""
    if handle:
        for s in SIGNALS:
            signal.signal(s, signal.SIG_IGN)
