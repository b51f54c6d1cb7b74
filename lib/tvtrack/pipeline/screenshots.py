"""The README's three screenshots, taken from the runs they show: ``python -m tvtrack screenshots``.

The site is built from the paper runs (``papermill_runs/reproduce/``), then the system Chromium (driven by
Playwright, as the site's browser tests do) photographs its first screen, one claim's page with its specification
curve, and one run's recording in the Rerun web viewer (served on loopback). Nothing leaves the machine: requests
to any other host are refused.
"""

from __future__ import annotations

import io
import os
import shutil
import time
from pathlib import Path

import numpy as np

from .outputs import temporary_beside
from .paths import REPO_ROOT, RUNS_DIR, reproduce_dir
from .preflight import UsageError
from .viewer.environment import free_port
from .viewer.pixels import coloured_mask

CHROMIUM = "/usr/bin/chromium"
#: Chromium's flags measured to work for the site and Rerun's web viewer on CPU-only machines
FLAGS = [
    "--no-sandbox",
    "--disable-gpu",
    "--disable-quic",
    "--no-first-run",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
    "--use-angle=swiftshader",
    "--enable-unsafe-swiftshader",
]
LOOPBACK = {"127.0.0.1", "localhost", "::1", "[::1]"}
FIRST_SCREEN = (1400, 900)  # px, the window a reader opens the site in
VIEWER_SCREEN = (1200, 700)  # px
SCREENSHOTS = REPO_ROOT / "docs" / "screenshots"
NAMES = ("site_index.png", "site_claim.png", "web_viewer.png")
#: the order in which a claim is picked for its page: a verdict a reader most needs to see explained first
VERDICT_ORDER = ("not reproduced", "partly", "undecided", "reproduced")


def viewer_drawn(png: bytes) -> dict:
    """Coarse measures of a web-viewer screenshot: grey levels and coloured pixels in its left (image) half, and
    coloured pixels in its right (plot) half, each without the top and bottom 60 px (the viewer's bars)."""
    from PIL import Image

    img = np.asarray(Image.open(io.BytesIO(png)).convert("RGB"))
    body = img[60:-60]
    left, right = body[:, : body.shape[1] // 2], body[:, body.shape[1] // 2 :]
    grey = left[(np.ptp(left.astype(int), axis=-1) < 8)]
    return {
        "grey_levels": len(np.unique(grey[:, 0])),
        "left_colour": int(coloured_mask(left).sum()),
        "right_colour": int(coloured_mask(right).sum()),
    }


def is_drawn(seen: dict) -> bool:
    """Whether the viewer shows a recording's frame (many grey levels), its marks and its plotted lines."""
    return seen.get("grey_levels", 0) > 20 and seen.get("left_colour", 0) > 100 and seen.get("right_colour", 0) > 100


def pick_claim(source: Path, claim: str | None = None) -> tuple[str, str]:
    """``(notebook, claim id)`` whose page is photographed: ``claim`` where given (found in a run the site shows:
    one whose ``run.json`` says it finished), else the first claim in notebook order with the first verdict of
    :data:`VERDICT_ORDER` that has one. A failed run's ``results.json`` has no page on the site."""
    from .site import find_paper_runs

    found = [(r.name, str(c.get("id")), str(c.get("verdict"))) for r in find_paper_runs(source) if r.ok
             for c in r.results.get("claims", [])]  # fmt: skip
    if claim is not None:
        for nb, cid, _ in found:
            if cid == claim:
                return nb, cid
        raise UsageError(f"--claim: no claim {claim} in the finished runs of {source} (give an id such as C004-1)")
    for verdict in VERDICT_ORDER:
        for nb, cid, v in found:
            if v == verdict:
                return nb, cid
    raise UsageError(f"no finished run with claims in {source}: `make reproduce` makes them")


def pick_recording(source: Path, notebook: str | None = None) -> Path:
    """The recording shown in the viewer: ``notebook``'s, else the last notebook's that has one."""
    runs = sorted(p.parent for p in source.glob("*/recording.rrd"))
    if notebook is not None:
        runs = [r for r in runs if r.name == notebook]
        if not runs:
            raise UsageError(f"--recording: no run of {notebook} with a recording.rrd in {source}")
    if not runs:
        raise UsageError(f"no recording.rrd in any run of {source}: `make reproduce` makes them")
    return runs[-1] / "recording.rrd"


def _page(browser, viewport: tuple[int, int]):
    """A page that refuses every request to a host other than this machine."""
    from urllib.parse import urlparse

    page = browser.new_page(viewport={"width": viewport[0], "height": viewport[1]})

    def route(r):
        host = urlparse(r.request.url).hostname
        return r.continue_() if host is None or host in LOOPBACK else r.abort()

    page.route("**/*", route)
    return page


def _viewer_shot(browser, recording: Path, out: Path, wait_s: float) -> dict:
    """The recording in the web viewer, photographed once it is drawn (or at ``wait_s``, which raises)."""
    from playwright.sync_api import TimeoutError as PlaywrightTimeout

    from .webview import WebViewer

    page = _page(browser, VIEWER_SCREEN)
    with WebViewer(recording, web_port=free_port(), grpc_port=free_port()) as viewer:
        page.goto(viewer.url)
        deadline, seen, png = time.monotonic() + wait_s, {}, b""
        while time.monotonic() < deadline and not is_drawn(seen):
            try:
                png = page.screenshot(timeout=max(1000.0, (deadline - time.monotonic()) * 1000))
            except PlaywrightTimeout:
                break
            seen = viewer_drawn(png)
            time.sleep(0.5)
    page.close()
    if not is_drawn(seen):
        raise RuntimeError(f"the web viewer did not draw {recording} within {wait_s:.0f} s ({seen})")
    out.write_bytes(png)
    return seen


def _photograph(browser, site: Path, claim: tuple[str, str], recording: Path, shots: Path, wait_s: float) -> None:
    """The three pictures into ``shots``: the site's first screen, the claim's page, the recording drawn."""
    page = _page(browser, FIRST_SCREEN)
    page.goto((site / "index.html").as_uri())
    page.screenshot(path=str(shots / NAMES[0]))
    page.goto((site / "claims" / claim[0] / f"{claim[1]}.html").as_uri())
    page.screenshot(path=str(shots / NAMES[1]))
    page.close()
    _viewer_shot(browser, recording, shots / NAMES[2], wait_s)


def take_screenshots(
    runs_dir: Path = RUNS_DIR,
    out: Path = SCREENSHOTS,
    claim: str | None = None,
    recording: str | None = None,
    wait_s: float = 120.0,
    site: Path | None = None,
    browser=None,
) -> list[Path]:
    """Build the site of the paper runs in ``runs_dir`` and photograph it into ``out`` (:data:`NAMES`).

    Parameters
    ----------
    runs_dir : Path
        Runs directory holding ``reproduce/`` (the paper runs).
    out : Path
        Folder the three PNG files are written to (created; only those files are replaced, and only once all
        three are taken: a failure leaves the earlier ones as they were).
    claim : str, optional
        Claim id whose page is photographed (default: :func:`pick_claim`).
    recording : str, optional
        Notebook whose recording is shown in the web viewer (default: the last with one).
    wait_s : float
        Seconds the viewer may take to draw the recording (software rendering is slow on a loaded machine).
    site : Path, optional
        A site already built from ``runs_dir`` (default: built now into ``runs_dir/site``).
    browser : playwright.sync_api.Browser, optional
        A Chromium already launched (as the site's browser tests hold one); default: the system Chromium, launched
        and closed here.

    Returns
    -------
    list of Path
        The files written, in the order of :data:`NAMES`.
    """
    from .site import build_site

    out = Path(out)
    if out.exists() and not out.is_dir():
        raise UsageError(f"-o {out}: a file, not a folder; give the folder the three PNG files go to")
    source = reproduce_dir(None, Path(runs_dir))
    if not source.is_dir():
        raise UsageError(f"no paper runs in {source}: `make reproduce` makes them")
    notebook, cid = pick_claim(source, claim)
    rrd = pick_recording(source, recording)
    if not Path(CHROMIUM).is_file():
        raise UsageError(f"no Chromium at {CHROMIUM}: apt-get install -y chromium")
    try:
        from playwright.sync_api import sync_playwright
    except ImportError:
        raise UsageError("no Playwright here: pip install playwright==1.65.2 (it drives the system Chromium)") from None

    site = (Path(site) if site is not None else build_site(Path(runs_dir)).parent).resolve()
    shots = temporary_beside(out)  # all three are taken before any is replaced: never a half-updated set
    try:
        if browser is not None:
            _photograph(browser, site, (notebook, cid), rrd.resolve(), shots, wait_s)
        else:
            with sync_playwright() as p:
                launched = p.chromium.launch(executable_path=CHROMIUM, args=FLAGS)
                try:
                    _photograph(launched, site, (notebook, cid), rrd.resolve(), shots, wait_s)
                finally:
                    launched.close()
        out.mkdir(parents=True, exist_ok=True)
        for name in NAMES:
            os.replace(shots / name, out / name)
    finally:
        shutil.rmtree(shots, ignore_errors=True)
    return [out / n for n in NAMES]
