"""A real headless Chromium, driven over the Chrome DevTools Protocol, for the page's tests and
for the screenshot in docs/ (``python -m tests.page.chromium FOLDER PNG``).

Debian's ``chromium`` draws WebGL without a GPU with SwiftShader. In CI (``CI=true``) a missing
browser fails the tests that need one; elsewhere they are skipped with the reason.
"""

from __future__ import annotations

import base64
import contextlib
import itertools
import json
import os
import shutil
import signal
import subprocess
import sys
import tempfile
import time
import urllib.request
import weakref
from pathlib import Path
from typing import Any

from tests.executables import require

NAMES = ("chromium", "chromium-browser", "google-chrome", "google-chrome-stable")
FLAGS = (
    "--headless",
    "--use-angle=swiftshader",
    "--enable-unsafe-swiftshader",
    "--disable-gpu-sandbox",
    "--no-first-run",
    "--no-default-browser-check",
    "--disable-background-timer-throttling",
    "--disable-renderer-backgrounding",
    "--hide-scrollbars",
)
WAIT = 60.0  # seconds a page may take to be ready, or a check to play: a bound, not a timing


def find_chromium() -> str | None:
    """The browser: ``$MJCFBUILD_CHROMIUM``, else the first of NAMES on PATH."""
    explicit = os.environ.get("MJCFBUILD_CHROMIUM")
    if explicit:
        return shutil.which(explicit)
    return next((path for name in NAMES if (path := shutil.which(name))), None)


def require_chromium() -> str:
    """The browser for a test; without one the test is skipped, or fails in CI (``CI=true``,
    where .ci/run installs it)."""
    return require(
        find_chromium(), "no chromium on PATH (apt-get install chromium, or set MJCFBUILD_CHROMIUM)"
    )


class Browser:
    """One headless Chromium with one page, closed with :meth:`close`."""

    def __init__(self, executable: str, width: int = 1280, height: int = 800) -> None:
        from websockets.sync.client import connect

        self.profile = tempfile.TemporaryDirectory(prefix="mjcfbuild-chromium-")
        args = [
            executable,
            *FLAGS,
            f"--window-size={width},{height}",
            f"--user-data-dir={self.profile.name}",
            "--remote-debugging-port=0",
            "about:blank",
        ]
        # The pages are our own local files. Chromium's sandbox refuses to run as root, and
        # where unprivileged user namespaces are off (Ubuntu 24.04's AppArmor) it cannot start.
        args.insert(1, "--no-sandbox")
        self.process = subprocess.Popen(
            args, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, start_new_session=True
        )
        # Ended when this Python exits even if nobody called close (a script that failed).
        weakref.finalize(self, _end, self.process)
        self._ids = itertools.count(1)
        self._stack = contextlib.ExitStack()
        try:
            port = self._port()
            with urllib.request.urlopen(f"http://127.0.0.1:{port}/json/list", timeout=10) as r:
                targets = json.load(r)
            page = next(t for t in targets if t.get("type") == "page")
            self.socket = self._stack.enter_context(
                connect(page["webSocketDebuggerUrl"], max_size=None, open_timeout=10)
            )
        except BaseException:
            self._stop()
            raise
        self.requests: list[str] = []  # every URL the page asked for, in order
        self.send("Page.enable")
        self.send("Runtime.enable")
        self.send("Network.enable")

    def _port(self) -> int:
        """The debugging port Chromium chose, from the file it writes in its profile."""
        marker = Path(self.profile.name) / "DevToolsActivePort"
        deadline = time.monotonic() + WAIT
        while time.monotonic() < deadline:
            if self.process.poll() is not None:
                raise RuntimeError(f"chromium exited with {self.process.returncode}")
            try:
                return int(marker.read_text().splitlines()[0])
            except (OSError, IndexError, ValueError):
                time.sleep(0.05)
        raise RuntimeError("chromium did not open its debugging port")

    def send(self, method: str, **params: Any) -> dict:
        """Call a DevTools method and return its result (of the events in between, only the
        requests' URLs are kept)."""
        ident = next(self._ids)
        self.socket.send(json.dumps({"id": ident, "method": method, "params": params}))
        while True:
            message = json.loads(self.socket.recv(timeout=WAIT))
            if message.get("method") == "Network.requestWillBeSent":
                self.requests.append(message["params"]["request"]["url"])
            if message.get("id") == ident:
                if "error" in message:
                    raise RuntimeError(f"{method}: {message['error']}")
                return dict(message.get("result", {}))

    def evaluate(self, expression: str) -> Any:
        """The value of a JavaScript expression in the page (promises awaited)."""
        result = self.send(
            "Runtime.evaluate", expression=expression, returnByValue=True, awaitPromise=True
        )
        if "exceptionDetails" in result:
            details = result["exceptionDetails"]
            raise RuntimeError(details.get("exception", {}).get("description") or str(details))
        return result["result"].get("value")

    def wait_for(self, expression: str, timeout: float = WAIT) -> Any:
        """Poll ``expression`` until it is truthy; its value."""
        deadline = time.monotonic() + timeout
        while True:
            value = self.evaluate(expression)
            if value:
                return value
            if time.monotonic() > deadline:
                raise TimeoutError(f"still false after {timeout:g} s: {expression}")
            time.sleep(0.1)

    def open(self, path: Path) -> str:
        """Load a local file and wait until the page says it is ready (or failed); its state."""
        self.requests.clear()
        self.send("Page.navigate", url=path.resolve().as_uri())
        state: str = self.wait_for(
            "document.readyState === 'complete' && document.body"
            " && ['ready', 'error'].includes(document.body.dataset.state)"
            " && document.body.dataset.state"
        )
        return state

    def screenshot(self) -> bytes:
        """A PNG of the window."""
        return base64.b64decode(self.send("Page.captureScreenshot", format="png")["data"])

    def close(self) -> None:
        """Close the connection and end the browser."""
        try:
            self._stack.close()
        finally:
            self._stop()

    def _stop(self) -> None:
        _end(self.process)
        # The browser's helper processes may still be writing into the profile as they go
        # (seen on a loaded CI machine: "Directory not empty: 'Default'"): retry a moment.
        for attempt in range(50):
            try:
                self.profile.cleanup()
                return
            except OSError:
                if attempt == 49:
                    raise
                time.sleep(0.1)


def _end(process: subprocess.Popen) -> None:
    """Terminate the browser (and wait for it), killing it if it does not go."""
    if process.poll() is None:
        process.terminate()
        try:
            process.wait(timeout=10)
        except subprocess.TimeoutExpired:
            process.kill()
            process.wait()
    # Its renderer, GPU and crash-handler processes share its session (start_new_session):
    # end those left too, so none writes into the profile being removed.
    with contextlib.suppress(ProcessLookupError, PermissionError):
        os.killpg(process.pid, signal.SIGKILL)


def main(argv: list[str]) -> int:
    """Screenshot a built report page: ``python -m tests.page.chromium OUTPUT_FOLDER PNG
    [CHECK]``, after playing CHECK (the id of its button: hold, stand, menagerie) if given."""
    folder, picture = Path(argv[0]), Path(argv[1])
    executable = find_chromium()
    if executable is None:
        print("no chromium found (apt-get install chromium)", file=sys.stderr)
        return 2
    browser = Browser(executable)
    try:
        if browser.open(folder / "report" / "index.html") != "ready":
            print(browser.evaluate("window.mjcfbuildPage.error"), file=sys.stderr)
            return 1
        if len(argv) > 2:
            browser.evaluate(f"document.getElementById({json.dumps(argv[2])}).click()")
            browser.wait_for(
                "['pass', 'fail'].includes(document.getElementById('result').className)"
            )
        picture.write_bytes(browser.screenshot())
    finally:
        browser.close()
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
