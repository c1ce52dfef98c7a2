"""The one way the bench scripts read an input file, with the rules of punctual's own reader
(src/scene/input_file.cpp), so that both languages accept and refuse the same files in the same
words.

Only regular files are read. A directory, a FIFO, a device or a socket is refused after a stat(),
before anything is opened: opening a FIFO blocks until some other process writes to it, possibly
forever, and a device may never end. The open itself is non-blocking (a FIFO swapped in between
the stat and the open cannot block it either), and the descriptor opened is checked again with
fstat(), since the path may name something else by then. Nothing larger than a cap is read: a
file over it is refused by its size, and one that grows past it while being read is refused too.

A problem raises InputFileError, whose path and problem (a short phrase: "no such file", "a
named pipe (FIFO), not a regular file", ...) make the scripts' one-line error message.
"""

import errno
import os
import stat

# Generous caps, never reached by a real bench: a full run's results.json is about 1.2 MiB and
# its results.csv 120 KiB (bench/results/full). The scripts hold a file's text and then its
# parsed rows, some ten times the file, so 256 MiB bounds the memory a wrong file (a disk image
# put in the folder, a runaway log) can take to a few GiB, while a bench two hundred times
# larger than today's still reads.
MAX_BYTES = 256 * 2**20
CHUNK = 65536  # bytes read at a time past the size stat() announced


class InputFileError(Exception):
    """An input file that cannot be read: its path and the problem, for the one-line message
    `<script>.py: error: <path>: <problem>`."""

    def __init__(self, path, problem):
        super().__init__(f"{path}: {problem}")
        self.path = path
        self.problem = problem

    @property
    def absent(self):
        """True when nothing is at the path (an optional file may be absent; a broken
        symbolic link is not absent: something is there)."""
        return self.problem == "no such file"


def type_problem(mode):
    """What a stat() mode is, when it is not a regular file; "" for a regular file."""
    if stat.S_ISREG(mode):
        return ""
    if stat.S_ISDIR(mode):
        return "a directory, not a regular file"
    if stat.S_ISFIFO(mode):
        return "a named pipe (FIFO), not a regular file"
    if stat.S_ISCHR(mode) or stat.S_ISBLK(mode):
        return "a device, not a regular file"
    if stat.S_ISSOCK(mode):
        return "a socket, not a regular file"
    return "not a regular file"


def errno_problem(error):
    """The phrase of an errno from stat() or open(), as punctual's reader words it."""
    phrases = {errno.ENOENT: "no such file", errno.EACCES: "permission denied",
               errno.ENOTDIR: "no such file (a folder on its path is a file)",
               errno.ELOOP: "too many levels of symbolic links",
               errno.ENAMETOOLONG: "the path is too long"}
    return phrases.get(error) or os.strerror(error)


def size_problem(size, max_bytes):
    return f"{size} bytes, more than the {max_bytes} punctual can read"


def read_problem(error):
    if error == errno.EISDIR:
        return "a directory, not a regular file"
    return "read error: " + os.strerror(error)


def regular_file_problem(path, max_bytes=MAX_BYTES):
    """The problem read_bytes would report before opening anything (stat only), or "" when
    `path` names a regular file (or a symbolic link to one) of at most `max_bytes`."""
    if not path:
        return "no such file (the path is empty)"
    try:
        info = os.stat(path)
    except ValueError:  # a NUL byte in the path: no file can have that name
        return "no such file (the path holds a NUL byte)"
    except OSError as err:
        if err.errno == errno.ENOENT:
            try:
                os.lstat(path)
                return "a broken symbolic link"
            except OSError:
                pass
        return errno_problem(err.errno)
    problem = type_problem(info.st_mode)
    if problem:
        return problem
    if info.st_size > max_bytes:
        return size_problem(info.st_size, max_bytes)
    return ""


def _read_open(fd, size, max_bytes):
    """The bytes of the open descriptor: the `size` fstat() announced, then on to the end of
    the file (st_size is a hint: a file may grow or shrink while it is read), never past
    `max_bytes`. Returns (bytes, problem)."""
    data = bytearray()
    try:
        while len(data) < size:
            chunk = os.read(fd, size - len(data))
            if not chunk:
                return bytes(data), ""  # it shrank
            data += chunk
        while True:
            chunk = os.read(fd, CHUNK)
            if not chunk:
                return bytes(data), ""
            if len(data) + len(chunk) > max_bytes:
                return b"", size_problem(len(data) + len(chunk), max_bytes)
            data += chunk
    except OSError as err:
        return b"", read_problem(err.errno)


def read_bytes(path, max_bytes=MAX_BYTES):
    """The whole regular file at `path`; raises InputFileError (path, problem) when it is not a
    regular file of at most `max_bytes` or cannot be read. Never blocks on anything but the
    disk."""
    path = os.fspath(path)
    # stat first, so that a FIFO is never opened at all.
    problem = regular_file_problem(path, max_bytes)
    if problem:
        raise InputFileError(path, problem)
    # The path may have been replaced between the stat and the open: O_NONBLOCK keeps even a
    # FIFO swapped in from blocking the open, and fstat checks what was really opened.
    try:
        fd = os.open(path, os.O_RDONLY | os.O_NONBLOCK | os.O_CLOEXEC | os.O_NOCTTY)
    except OSError as err:
        raise InputFileError(path, errno_problem(err.errno)) from None
    try:
        try:
            info = os.fstat(fd)
        except OSError as err:
            raise InputFileError(path, errno_problem(err.errno)) from None
        problem = type_problem(info.st_mode)
        if not problem and info.st_size > max_bytes:
            problem = size_problem(info.st_size, max_bytes)
        data = b""
        if not problem:
            data, problem = _read_open(fd, info.st_size, max_bytes)
    finally:
        os.close(fd)
    if problem:
        raise InputFileError(path, problem)
    return data


def read_text(path, max_bytes=MAX_BYTES):
    """The regular file at `path` as UTF-8 text, its line ends untouched (give the text to
    io.StringIO(text, newline="") for the csv module, as open(newline="") would); raises
    InputFileError as read_bytes does, and when the bytes are not UTF-8."""
    data = read_bytes(path, max_bytes)
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError as err:
        raise InputFileError(path, f"not UTF-8 text (byte {err.start})") from None
