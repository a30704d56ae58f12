"""A headless Chromium driven through the DevTools protocol over a pipe (standard library
only): open a page at a window size, wait for an element, measure the layout with JavaScript,
and take screenshots.

Chromium reads protocol messages (JSON, each ended by a NUL byte) on its file descriptor 3 and
writes them on 4 with --remote-debugging-pipe (Chrome DevTools Protocol, "Target", "Page",
"Emulation" and "Runtime" domains: https://chromedevtools.github.io/devtools-protocol/).
"""

import base64
import fcntl
import json
import os
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

#: the Debian binary first, then the other names distributions give it
BINARIES = ("chromium", "chromium-browser", "google-chrome", "google-chrome-stable")
#: switches of a quiet, self-contained headless browser (no network of its own, no updates)
SWITCHES = (
    "--headless=new",
    "--no-sandbox",
    "--disable-gpu",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
    "--no-first-run",
    "--hide-scrollbars",
)


#: the launcher: the descriptors given as its first two arguments become 3 and 4, then the
#: browser (the rest of its arguments) replaces it
LAUNCH = (
    "import os, sys; os.dup2(int(sys.argv[1]), 3); os.dup2(int(sys.argv[2]), 4); "
    "os.execv(sys.argv[3], sys.argv[3:])"
)


def chromium() -> str | None:
    """The path of an installed Chromium, or None."""
    return next((path for path in map(shutil.which, BINARIES) if path), None)


class Browser:
    """One headless Chromium with one page (a context manager)."""

    def __init__(self, binary: str, timeout: float = 60.0):
        self.timeout = timeout
        self.profile = tempfile.TemporaryDirectory(prefix="chromium-profile-")
        to_browser, self._commands = os.pipe()
        self._replies, from_browser = os.pipe()
        # a small launcher puts the pipe's ends on descriptors 3 and 4, where Chromium expects
        # them, from descriptors above 9 (a low one could be overwritten before it is moved)
        to_browser, from_browser = (self._above_nine(fd) for fd in (to_browser, from_browser))
        arguments = [
            binary,
            *SWITCHES,
            "--remote-debugging-pipe",
            f"--user-data-dir={self.profile.name}",
            "about:blank",
        ]
        self.process = subprocess.Popen(
            [sys.executable, "-c", LAUNCH, str(to_browser), str(from_browser), *arguments],
            pass_fds=(to_browser, from_browser),
            stdout=subprocess.DEVNULL,
            stderr=subprocess.DEVNULL,
        )
        os.close(to_browser)
        os.close(from_browser)
        self._buffer = b""
        self._next_id = 0
        self.events: list[dict] = []
        page = next(t for t in self.send("Target.getTargets")["targetInfos"] if t["type"] == "page")
        attached = self.send("Target.attachToTarget", targetId=page["targetId"], flatten=True)
        self.session = attached["sessionId"]
        self.send("Page.enable", session=True)

    @staticmethod
    def _above_nine(fd: int) -> int:
        """The descriptor ``fd`` moved to the lowest free number above 9."""
        moved = fcntl.fcntl(fd, fcntl.F_DUPFD, 10)
        os.close(fd)
        return moved

    def __enter__(self) -> "Browser":
        return self

    def __exit__(self, *exc) -> None:
        self.close()

    def close(self) -> None:
        """End the browser and remove its profile."""
        try:
            self.send("Browser.close")
        except (OSError, RuntimeError, TimeoutError):
            pass
        try:
            self.process.wait(timeout=10)
        except subprocess.TimeoutExpired:
            self.process.kill()
        os.close(self._commands)
        os.close(self._replies)
        self.profile.cleanup()

    def _message(self) -> dict:
        """The next message from the browser."""
        deadline = time.monotonic() + self.timeout
        while b"\0" not in self._buffer:
            if time.monotonic() > deadline:
                raise TimeoutError("Chromium did not answer")
            chunk = os.read(self._replies, 1 << 20)
            if not chunk:
                raise RuntimeError("Chromium closed its protocol pipe")
            self._buffer += chunk
        message, self._buffer = self._buffer.split(b"\0", 1)
        return json.loads(message)

    def send(self, method: str, session: bool = False, **params) -> dict:
        """Call a protocol method (on the page with ``session``) and return its result."""
        self._next_id += 1
        command = {"id": self._next_id, "method": method, "params": params}
        if session:
            command["sessionId"] = self.session
        os.write(self._commands, json.dumps(command).encode() + b"\0")
        while True:
            message = self._message()
            if message.get("id") == self._next_id:
                if "error" in message:
                    raise RuntimeError(f"{method}: {message['error']}")
                return message.get("result", {})
            self.events.append(message)

    def _wait_for_event(self, method: str) -> None:
        """Wait until the page sends the event ``method`` (one seen already counts)."""
        while not any(event.get("method") == method for event in self.events):
            self.events.append(self._message())

    def open(self, url: str, width: int, height: int) -> None:
        """Load ``url`` in a window of ``width`` × ``height`` CSS pixels."""
        self.send(
            "Emulation.setDeviceMetricsOverride",
            session=True,
            width=width,
            height=height,
            deviceScaleFactor=1,
            mobile=False,
        )
        self.events.clear()
        self.send("Page.navigate", session=True, url=url)
        self._wait_for_event("Page.loadEventFired")

    def evaluate(self, expression: str):
        """The value of a JavaScript expression on the page (a promise is awaited)."""
        result = self.send(
            "Runtime.evaluate",
            session=True,
            expression=expression,
            awaitPromise=True,
            returnByValue=True,
        )
        if "exceptionDetails" in result:
            raise RuntimeError(f"JavaScript failed: {result['exceptionDetails']}")
        return result["result"].get("value")

    def wait_for(self, selector: str) -> None:
        """Wait until an element matching the CSS ``selector`` is on the page."""
        deadline = time.monotonic() + self.timeout
        while not self.evaluate(f"document.querySelector({json.dumps(selector)}) !== null"):
            if time.monotonic() > deadline:
                raise TimeoutError(f"no element {selector!r} on the page")
            time.sleep(0.2)

    def screenshot(self, path: Path, height: int | None = None) -> Path:
        """A PNG of the window, or of its top ``height`` pixels of the page (taller than the
        window: the page laid out at the window's width)."""
        params = {"format": "png"}
        if height is not None:
            width = self.evaluate("window.innerWidth")
            params |= {
                "clip": {"x": 0, "y": 0, "width": width, "height": height, "scale": 1},
                "captureBeyondViewport": True,
            }
        data = self.send("Page.captureScreenshot", session=True, **params)["data"]
        path.write_bytes(base64.b64decode(data))
        return path
