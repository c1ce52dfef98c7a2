#!/usr/bin/python3
"""Opens HTML pages in headless Chromium and reports what a reader would see broken.

    /usr/bin/python3 tests/browser/check_pages.py PAGE.html...

For every page: no console error (console.error/assert, an uncaught exception, or a browser log
entry of level error, which is where a resource that failed to load shows up), every <img> loaded
(naturalWidth > 0), and every local link (<a>/<link>/<area> href, <img>/<script>/... src that is
relative or file://) names a file that exists. Prints each problem as "PAGE: WHAT: URL" and exits
1 if there is any, 0 if none, and 77 (CTest's SKIP_RETURN_CODE) with one line saying why where
Chromium is missing or does not start.

Chromium is Debian's `chromium` package (or $PUNCTUAL_CHROMIUM), driven through the Chrome
DevTools Protocol over a pipe (--remote-debugging-pipe: the browser reads commands on fd 3 and
writes replies and events on fd 4, each a JSON text ended by a NUL byte). A pipe rather than a
port: nothing listens on the network, and no client library beyond Python's standard library is
needed.
"""

import fcntl
import json
import os
import pathlib
import select
import shutil
import subprocess
import sys
import tempfile
import time
import urllib.parse

SKIP = 77  # CTest's SKIP_RETURN_CODE for these tests (CMakeLists.txt)

FLAGS = [
    "--headless=new",
    "--no-sandbox",  # CI and this machine run as root, where Chromium's sandbox refuses to start
    "--disable-gpu",
    "--disable-dev-shm-usage",  # containers often have a tiny /dev/shm
    "--no-first-run",
    "--no-default-browser-check",
    "--disable-extensions",
    "--disable-background-networking",  # nothing may reach the network
    "--disable-component-update",
    "--disable-sync",
    "--mute-audio",
    "--allow-file-access-from-files",
    "--remote-debugging-pipe",
]

# Runs in the page once it has loaded (and waits for that too, should the load event have been
# another document's): waits for every image to finish (loaded or failed, lazy
# ones made eager so none waits for a scroll that never comes, 20 s at most), then lists the
# images and every element that names another file, with the attribute as written and the URL
# the browser resolved it to.
PAGE_SCRIPT = r"""
(async () => {
  if (document.readyState !== "complete")
    await new Promise(done => addEventListener("load", done, {once: true}));
  const images = Array.from(document.images);
  for (const img of images) if (img.loading === "lazy") img.loading = "eager";
  const settled = images.map(img => img.complete ? null : new Promise(done => {
    img.addEventListener("load", done, {once: true});
    img.addEventListener("error", done, {once: true});
  }));
  await Promise.race([Promise.all(settled), new Promise(done => setTimeout(done, 20000))]);
  const links = [];
  for (const el of document.querySelectorAll("a[href], link[href], area[href]"))
    links.push({tag: el.localName, attr: el.getAttribute("href"), url: el.href});
  for (const el of document.querySelectorAll(
      "img[src], script[src], iframe[src], source[src], video[src], audio[src], embed[src]"))
    links.push({tag: el.localName, attr: el.getAttribute("src"), url: el.src});
  return {
    url: location.href,
    images: images.map(img => ({attr: img.getAttribute("src"), url: img.currentSrc || img.src,
                                complete: img.complete, width: img.naturalWidth})),
    links: links,
  };
})()
"""


class BrowserUnavailable(Exception):
    """Chromium is not installed or did not start: the tests skip."""


class CdpError(Exception):
    """A DevTools command failed, or the browser stopped answering."""


def find_chromium():
    if os.environ.get("PUNCTUAL_CHROMIUM"):
        return shutil.which(os.environ["PUNCTUAL_CHROMIUM"])
    for name in ("chromium", "chromium-browser", "google-chrome"):
        path = shutil.which(name)
        if path:
            return path
    return None


class Browser:
    """One headless Chromium, each page checked in a tab of its own."""

    def __init__(self, start_timeout=60.0):
        exe = find_chromium()
        if not exe:
            raise BrowserUnavailable(
                f"PUNCTUAL_CHROMIUM={os.environ['PUNCTUAL_CHROMIUM']} not found"
                if os.environ.get("PUNCTUAL_CHROMIUM") else
                "no chromium on PATH (Debian's chromium package, scripts/install-deps.sh)")
        self._dir = tempfile.TemporaryDirectory(prefix="punctual-chromium-")
        self._log_path = os.path.join(self._dir.name, "chromium.log")
        to_browser_r, self._to_browser = os.pipe()
        self._from_browser, from_browser_w = os.pipe()

        def pipe_fds():  # in the child: our ends of the pipes become its fds 3 and 4
            # Copies above 4 first, so dup2 cannot close one end while placing the other.
            r = fcntl.fcntl(to_browser_r, fcntl.F_DUPFD, 10)
            w = fcntl.fcntl(from_browser_w, fcntl.F_DUPFD, 10)
            os.dup2(r, 3)
            os.dup2(w, 4)
            os.close(r)
            os.close(w)

        self._buffer = b""
        self._next_id = 0
        self._events = []
        self.last_counts = (0, 0)  # images and local links of the page checked last
        with open(self._log_path, "wb") as log:
            # os.pipe()'s fds are close-on-exec, so only the dup2 copies (3 and 4) reach Chromium.
            self._proc = subprocess.Popen(
                [exe, *FLAGS, "--user-data-dir=" + os.path.join(self._dir.name, "profile"),
                 "about:blank"],
                stdin=subprocess.DEVNULL, stdout=log, stderr=subprocess.STDOUT,
                preexec_fn=pipe_fds, close_fds=False)
        os.close(to_browser_r)
        os.close(from_browser_w)
        try:
            version = self.send("Browser.getVersion", timeout=start_timeout)
        except CdpError as e:
            self.close()
            raise BrowserUnavailable(f"{exe} did not start ({e}); its output: {self.log_tail()}")
        self.version = version.get("product", "?")

    def log_tail(self, chars=600):
        try:
            with open(self._log_path, "rb") as f:
                text = f.read().decode("utf-8", "replace")
        except OSError:
            return "(none)"
        return " ".join(text[-chars:].split()) or "(none)"

    # ------------------------------------------------------------------------------ protocol
    def _read_message(self, deadline):
        while b"\0" not in self._buffer:
            left = deadline - time.monotonic()
            if left <= 0:
                return None
            ready, _, _ = select.select([self._from_browser], [], [], left)
            if not ready:
                return None
            chunk = os.read(self._from_browser, 1 << 20)
            if not chunk:
                raise CdpError("the browser closed its pipe (exited?)")
            self._buffer += chunk
        message, self._buffer = self._buffer.split(b"\0", 1)
        return json.loads(message)

    def send(self, method, params=None, session=None, timeout=30.0):
        """Sends one command and returns its result; events read meanwhile are kept."""
        self._next_id += 1
        message = {"id": self._next_id, "method": method, "params": params or {}}
        if session:
            message["sessionId"] = session
        data = json.dumps(message).encode() + b"\0"
        try:
            while data:
                data = data[os.write(self._to_browser, data):]
        except OSError as e:
            raise CdpError(f"{method}: cannot write to the browser ({e})") from e
        deadline = time.monotonic() + timeout
        while True:
            reply = self._read_message(deadline)
            if reply is None:
                raise CdpError(f"{method}: no answer in {timeout:g} s")
            if reply.get("id") == self._next_id:
                if "error" in reply:
                    raise CdpError(f"{method}: {reply['error'].get('message', reply['error'])}")
                return reply.get("result", {})
            if "method" in reply:
                self._events.append(reply)

    def wait_event(self, method, session, timeout):
        """Reads until the event METHOD arrives for SESSION; False on timeout."""
        deadline = time.monotonic() + timeout
        while True:
            if any(e["method"] == method and e.get("sessionId") == session for e in self._events):
                return True
            event = self._read_message(deadline)
            if event is None:
                return False
            if "method" in event:
                self._events.append(event)

    def drain(self, seconds):
        """Keeps the events that arrive within SECONDS (late console messages)."""
        deadline = time.monotonic() + seconds
        while (event := self._read_message(deadline)) is not None:
            if "method" in event:
                self._events.append(event)

    # ---------------------------------------------------------------------------------- pages
    def check_page(self, path, timeout=60.0):
        """The problems a reader of the page at PATH would see, as "WHAT: DETAIL" strings."""
        page = pathlib.Path(path).resolve()
        if not page.is_file():
            return [f"page missing: {page}"]
        target = self.send("Target.createTarget", {"url": "about:blank"})["targetId"]
        session = None
        try:
            session = self.send("Target.attachToTarget",
                                {"targetId": target, "flatten": True})["sessionId"]
            for domain in ("Page", "Runtime", "Log"):
                self.send(domain + ".enable", session=session)
            problems = []
            navigation = self.send("Page.navigate", {"url": page.as_uri()}, session)
            if navigation.get("errorText"):
                return [f"navigation failed: {navigation['errorText']}"]
            if not self.wait_event("Page.loadEventFired", session, timeout):
                problems.append(f"no load event in {timeout:g} s")
            found = self.send("Runtime.evaluate", {"expression": PAGE_SCRIPT, "awaitPromise": True,
                                                    "returnByValue": True}, session, timeout)
            if "exceptionDetails" in found:
                problems.append("the checking script failed: "
                                + found["exceptionDetails"].get("text", "?"))
                found = {"result": {"value": {"url": page.as_uri(), "images": [], "links": []}}}
            self.drain(0.3)
            problems += self._console_errors(session)
            value = found["result"]["value"]
            shown = urllib.parse.unquote(urllib.parse.urlsplit(value["url"]).path)
            if shown != str(page):  # compared decoded: Chromium and Python escape differently
                problems.append(f"checked {value['url']} instead (the page did not load)")
            local = [link for link in value["links"] if link["url"].startswith("file:")]
            self.last_counts = (len(value["images"]), len(local))
            for img in value["images"]:
                if not img["width"]:
                    why = "failed to load" if img["complete"] else "still loading after 20 s"
                    problems.append(f"image {why} (naturalWidth 0): {img['attr'] or img['url']}")
            for link in value["links"]:
                missing = local_file_missing(link["attr"], link["url"])
                if missing:
                    problems.append(f"<{link['tag']}> names a missing file: {link['attr']} "
                                    f"({missing})")
            return problems
        finally:
            self._events = [e for e in self._events if e.get("sessionId") != session]
            try:
                self.send("Target.closeTarget", {"targetId": target})
            except CdpError:
                pass

    def _console_errors(self, session):
        errors = []
        for event in self._events:
            if event.get("sessionId") != session:
                continue
            p = event.get("params", {})
            method = event["method"]
            if method == "Runtime.consoleAPICalled" and p.get("type") in ("error", "assert"):
                text = " ".join(str(a.get("value", a.get("description", a.get("type", ""))))
                                for a in p.get("args", []))
                errors.append(f"console.{p['type']}: {text}")
            elif method == "Runtime.exceptionThrown":
                d = p.get("exceptionDetails", {})
                text = d.get("exception", {}).get("description") or d.get("text", "?")
                errors.append(f"uncaught exception: {text}")
            elif method == "Log.entryAdded" and p.get("entry", {}).get("level") == "error":
                entry = p["entry"]
                errors.append(f"console error ({entry.get('source', '?')}): {entry.get('text', '')}"
                              + (f" {entry['url']}" if entry.get("url") else ""))
        return errors

    def close(self):
        if self._proc.poll() is None:
            try:
                self.send("Browser.close", timeout=10)
            except CdpError:
                pass
            try:
                self._proc.wait(timeout=10)
            except subprocess.TimeoutExpired:
                self._proc.kill()
                self._proc.wait()
        for fd in (self._to_browser, self._from_browser):
            try:
                os.close(fd)
            except OSError:
                pass
        self._dir.cleanup()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()


def local_file_missing(attr, url):
    """The path a local link points to when no such file exists, else None. Links elsewhere
    (http, mailto, data...) and fragment-only ones ("#name", this page) are not checked."""
    if attr is None or attr.strip().startswith("#"):
        return None
    parts = urllib.parse.urlsplit(url)
    if parts.scheme != "file":
        return None
    path = urllib.parse.unquote(parts.path)  # ?query and #fragment are not part of the file
    return None if os.path.exists(path) else path


def check_pages(browser, pages):
    """Checks PAGES in BROWSER and prints what it finds; the number of problems."""
    count = 0
    for page in pages:
        problems = browser.check_page(page)
        for problem in problems:
            print(f"{page}: {problem}")
        if not problems:
            images, links = browser.last_counts
            print(f"{page}: ok ({images} images, {links} local links)")
        count += len(problems)
    return count


def main(argv):
    if not argv or argv[0] in ("-h", "--help"):
        print(__doc__.strip())
        return 0 if argv else 2
    try:
        browser = Browser()
    except BrowserUnavailable as e:
        print(f"skipped: {e}")
        return SKIP
    with browser:
        return 1 if check_pages(browser, argv) else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
