"""A small client for the browser tests: Debian's Chromium, headless, driven by Playwright.

    with Chromium() as chromium:
        page = chromium.open("report.html")     # waits for document.body.dataset.rendered
        page.page.evaluate(...)                 # a playwright Page
        page.console_errors, page.requests      # what the page logged and asked for

Playwright never downloads a browser here: it launches the system's Chromium
(`/usr/bin/chromium`, or $VAL3CHECK_CHROMIUM) with a fresh profile and no background
networking. Every request the page makes is recorded, and anything but the page itself is
refused. `skip_reason()` says why the browser tests cannot run (no Playwright, no Chromium);
with VAL3CHECK_REQUIRE_BROWSER=1 (.ci/run) that is a failure instead of a skip.
"""

from __future__ import annotations

import os
import shutil
import tempfile
from dataclasses import dataclass, field
from pathlib import Path

FLAGS = [
    "--headless",
    "--no-sandbox",
    "--disable-gpu",
    "--no-first-run",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
]
RENDER_TIMEOUT_MS = 30_000


def chromium_path() -> str | None:
    given = os.environ.get("VAL3CHECK_CHROMIUM")
    if given:
        return given if Path(given).is_file() else None
    found = shutil.which("chromium")
    if found:
        return found
    return "/usr/bin/chromium" if Path("/usr/bin/chromium").is_file() else None


def skip_reason() -> str | None:
    try:
        import playwright.sync_api  # noqa: F401
    except ImportError:
        return "Playwright is not installed (pip install -e '.[test]')"
    if chromium_path() is None:
        return "Chromium is not installed (Debian: apt-get install chromium; .ci/run installs it)"
    return None


def required() -> bool:
    return os.environ.get("VAL3CHECK_REQUIRE_BROWSER", "") not in ("", "0")


@dataclass
class LoadedPage:
    page: object  # playwright.sync_api.Page
    url: str
    console_errors: list[str] = field(default_factory=list)
    requests: list[str] = field(default_factory=list)
    refused: list[str] = field(default_factory=list)

    def evaluate(self, script: str, arg=None):
        return self.page.evaluate(script, arg)  # type: ignore[attr-defined]


class Chromium:
    def __init__(self, width: int = 1400, height: int = 900):
        self.size = {"width": width, "height": height}

    def __enter__(self) -> "Chromium":
        from playwright.sync_api import sync_playwright

        self._profile = tempfile.TemporaryDirectory(prefix="val3check-chromium-")
        self._pw = sync_playwright().start()
        try:
            self.context = self._pw.chromium.launch_persistent_context(
                self._profile.name, executable_path=chromium_path(), headless=True, args=FLAGS, viewport=self.size,
                offline=True)
        except Exception:
            self._pw.stop()
            self._profile.cleanup()
            raise
        return self

    def __exit__(self, *exc) -> None:
        try:
            self.context.close()
        finally:
            self._pw.stop()
            self._profile.cleanup()

    def open(self, path: str | Path, wait: bool = True) -> LoadedPage:
        """Load a local file; wait (by default) until the page says it has rendered."""
        url = Path(path).resolve().as_uri()
        page = self.context.new_page()
        loaded = LoadedPage(page, url)
        page.on("console", lambda m: loaded.console_errors.append(m.text) if m.type == "error" else None)
        page.on("pageerror", lambda e: loaded.console_errors.append(f"uncaught: {e}"))
        page.on("request", lambda r: loaded.requests.append(r.url))

        def guard(route):
            if route.request.url == url:
                route.continue_()
            else:
                loaded.refused.append(route.request.url)
                route.abort()

        page.route("**/*", guard)
        page.goto(url)
        if wait:
            # a function, not an expression: the page's policy forbids evaluating strings
            page.wait_for_function("() => document.body && document.body.dataset.rendered === '1'",
                                   timeout=RENDER_TIMEOUT_MS)
        return loaded
