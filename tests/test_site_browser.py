"""The site and the web viewer, checked in a real browser: headless Debian Chromium driven by Playwright.

Skipped (with the install command) when Chromium or Playwright is missing, unless
``TVTRACK_REQUIRE_BROWSER=1`` (set by ``.ci/run``), which makes a missing browser a failure.
The README's screenshots are taken from the paper runs by ``python -m tvtrack screenshots`` (tested here on the
fixture runs).
"""

from __future__ import annotations

import os
import re
import shutil
import time
from pathlib import Path
from urllib.parse import urlparse

import pytest

from conftest import NOTEBOOK_NAMES
from load import wall_budget
from site_fixtures import make_explored_runs, make_runs_dir
from tvtrack.pipeline.screenshots import CHROMIUM, FIRST_SCREEN, FLAGS, LOOPBACK, is_drawn, viewer_drawn

INSTALL = "apt-get install -y chromium && pip install playwright==1.65.2 (Playwright never downloads a browser here)"


def _browser_problem() -> str | None:
    try:
        import playwright.sync_api  # noqa: F401
    except ImportError:
        return f"Playwright is not installed ({INSTALL})"
    if not Path(CHROMIUM).is_file():
        return f"no Chromium at {CHROMIUM} ({INSTALL})"
    return None


@pytest.fixture(scope="module")
def browser():
    problem = _browser_problem()
    if problem:
        if os.environ.get("TVTRACK_REQUIRE_BROWSER") == "1":
            pytest.fail(f"TVTRACK_REQUIRE_BROWSER=1 but {problem}")
        pytest.skip(problem)
    from playwright.sync_api import sync_playwright

    with sync_playwright() as p:
        b = p.chromium.launch(executable_path=CHROMIUM, args=FLAGS)
        yield b
        b.close()


class Watched:
    """A page whose console errors and non-loopback requests are recorded (and the requests refused)."""

    def __init__(self, browser, viewport=(1200, 800)):
        self.context = browser.new_context(viewport={"width": viewport[0], "height": viewport[1]})
        self.errors, self.outside = [], []
        self.context.route("**/*", self._route)
        self.page = self.context.new_page()
        self.page.on("console", lambda m: m.type == "error" and self.errors.append(m.text))
        self.page.on("pageerror", lambda e: self.errors.append(str(e)))

    def _route(self, route):
        url = urlparse(route.request.url)
        if url.scheme in ("http", "https", "ws", "wss") and url.hostname not in LOOPBACK:
            self.outside.append(route.request.url)
            return route.abort()
        return route.continue_()

    def open(self, url: str):
        self.page.goto(url, wait_until="load")
        return self.page

    def images_decoded(self) -> list[tuple[str, int]]:
        return self.page.evaluate("Array.from(document.images).map(i => [i.src.slice(0, 60), i.naturalWidth])")

    def close(self):
        self.context.close()


@pytest.fixture(scope="module")
def smoke_site(tmp_path_factory, smoke_run, fixture_runs):
    """The site built from the fixture runs plus every notebook's smoke run (shared with the other tests)."""
    from tvtrack.pipeline.site import build_site

    root = make_runs_dir(tmp_path_factory.mktemp("browser-runs"), fixture_runs)
    for name in NOTEBOOK_NAMES:
        shutil.copytree(smoke_run(name).run_dir, root / "reproduce" / name)
    t0 = time.process_time()  # CPU seconds: a loaded machine stretches the wall time, not the work
    index = build_site(root)
    return index.parent, time.process_time() - t0


def _assert_first_screen(page):
    """The paragraph and the glossary lie wholly on the first screen (no scrolling), every verdict and label chip
    has its meaning as a tooltip, and the page is no wider than the window."""
    width, height = FIRST_SCREEN
    assert page.evaluate("window.scrollY") == 0
    for sel in ("#summary", "#glossary"):
        box = page.locator(sel).bounding_box()
        assert box and box["y"] >= 0 and box["y"] + box["height"] <= height, (sel, box)
        assert page.locator(sel).is_visible()
    assert page.locator("#summary").inner_text().startswith("Of ")
    terms = page.locator("#glossary dt").all_inner_texts()
    assert {"reproduced", "not reproduced", "undecided", "robust", "depends", "limited", "provisional"} <= set(terms)
    titles = page.locator(".pill").evaluate_all("ps => ps.map(p => p.getAttribute('title') || '')")
    assert titles and all(len(t) > 20 for t in titles), [t for t in titles if len(t) <= 20]
    assert page.evaluate("document.documentElement.scrollWidth") <= width


def test_first_screen_glossary_tooltips_and_claim_pages_in_browser(browser, tmp_path_factory, fixture_runs):
    """The acceptance at 1400 x 900: the paragraph and glossary without scrolling, tooltips on every chip
    (shown on hover), no horizontal scroll, and a claim page that shows its specification curve."""
    from tvtrack.pipeline.site import build_site

    root = make_explored_runs(make_runs_dir(tmp_path_factory.mktemp("first-screen-runs"), fixture_runs))
    site = build_site(root).parent
    w = Watched(browser, viewport=FIRST_SCREEN)
    try:
        page = w.open((site / "index.html").as_uri())
        _assert_first_screen(page)
        chip = page.locator("#glossary .pill.l-depends").first
        assert "a setting of its experiment that the paper never printed, changes the verdict" in chip.get_attribute(
            "title"
        )
        page.click('#first a:has-text("C001-3")')
        assert page.url.endswith("claims/001_explored/C001-3.html")
        curve = page.locator("#specification-curve")
        # the page is there once the click returns, its image maybe not yet (a loaded machine): wait for it to load
        page.wait_for_function(
            "() => { const i = document.querySelector('#specification-curve'); return i && i.complete && i.naturalWidth > 400; }",
            timeout=1000 * wall_budget(15),
        )
        assert curve.bounding_box()["width"] > 400
        assert "it is reproduced: sigma read as the SD" in page.locator("#claim-summary").inner_text()
        assert page.evaluate("document.documentElement.scrollWidth") <= FIRST_SCREEN[0]
        page = w.open((site / "ledger.html").as_uri())
        assert page.evaluate("document.documentElement.scrollWidth") <= FIRST_SCREEN[0]
        titles = page.locator(".pill").evaluate_all("ps => ps.map(p => p.getAttribute('title') || '')")
        assert titles and all(len(t) > 20 for t in titles)
        assert w.errors == [], w.errors
        assert w.outside == [], w.outside
    finally:
        w.close()


def test_site_in_browser(browser, smoke_site):
    site, build_s = smoke_site
    assert build_s < 60, f"site build took {build_s:.0f} CPU s"
    w = Watched(browser, viewport=FIRST_SCREEN)
    try:
        page = w.open((site / "index.html").as_uri())
        cards = page.locator("article.card").count()
        assert cards == len(NOTEBOOK_NAMES) + 4  # + fixture_centroid, old_schema, new_schema, broken
        images = w.images_decoded()
        assert images and all(width > 0 for _, width in images), images
        _assert_first_screen(page)
        w.page.set_viewport_size({"width": 1200, "height": 800})

        ok_notebooks = [
            n for n in [*NOTEBOOK_NAMES, "fixture_centroid"] if (site / "notebooks" / f"{n}.html").is_file()
        ]
        for name in (ok_notebooks[0], "old_schema"):
            page = w.open((site / "notebooks" / f"{name}.html").as_uri())
            images = w.images_decoded()
            assert all(width > 0 for _, width in images), (name, images)
        assert page.locator("math").count() == 2 and page.locator("math").first.bounding_box()["width"] > 0
        page = w.open((site / "notebooks" / "fixture_centroid.html").as_uri())
        assert len(w.images_decoded()) >= 2  # the figure inline and the recording's still

        page = w.open((site / "ledger.html").as_uri())
        rows = page.locator("#ledger tbody tr[data-paper]")
        visible = page.locator("#ledger tbody tr[data-paper]:visible")
        total = rows.count()
        assert total >= 2 and visible.count() == total
        page.select_option("#f-verdict", "partly")
        assert (
            visible.count()
            == sum(1 for v in rows.evaluate_all("rs => rs.map(r => r.dataset.verdict)") if v == "partly")
            >= 1
        )
        page.select_option("#f-label", "—")
        assert "C911-1" in visible.first.inner_text()
        page.select_option("#f-verdict", "")
        page.select_option("#f-label", "")
        page.fill("#f-text", "centroid error is below")
        assert visible.count() == 1 and "C900-1" in visible.first.inner_text()
        page.fill("#f-text", "")
        page.click("th:has-text('claim')")
        ids = [t.strip() for t in page.locator("#ledger tbody tr td:nth-child(2)").all_inner_texts()]
        # natural order, as the page's localeCompare(numeric) gives it: C004-3 < C004-3b < C004-10
        assert ids == sorted(ids, key=lambda s: [int(x) if i % 2 else x for i, x in enumerate(re.split(r"(\d+)", s))])
        page = w.open((site / "ledger.html").as_uri() + "#paper=old_schema")
        assert visible.count() == 1
        assert w.errors == [], w.errors
        assert w.outside == [], w.outside
    finally:
        w.close()


@pytest.fixture(scope="module")
def fixture_site(tmp_path_factory, fixture_runs):
    """The site of the fixture runs alone (no paper notebook runs): first screen, pictures, ledger, sweep."""
    from tvtrack.pipeline.site import build_site

    return build_site(make_runs_dir(tmp_path_factory.mktemp("fixture-site-runs"), fixture_runs)).parent


def test_first_screen_forest_plot_and_compact_ledger_in_browser(browser, fixture_site):
    w = Watched(browser, viewport=(1280, 800))
    try:
        page = w.open((fixture_site / "index.html").as_uri())
        # the first screen: the profile, then the claims that do not reproduce or are undecided, one row each
        assert "profile shown: paper" in page.locator("#profile").inner_text()
        first = page.locator("#first tbody tr")
        assert first.count() == 2
        row = first.first.inner_text()
        assert "C912-1" in row and "sigma*2 <b>not bold</b> & small." in row and "2.6 [2.4, 2.8]" in row
        assert "not reproduced" in row and "depends" in row
        assert page.locator("#first b").count() == 0 and page.locator("#first em").count() == 0  # text, not markup
        assert page.locator("#first").bounding_box()["y"] < 800  # on the first screen
        # the forest plot and the robustness picture, decoded, after the first screen and before the cards
        for pic in ("#forest", "#robustness"):
            assert page.locator(pic).evaluate("i => i.complete && i.naturalWidth") > 300, pic
        boxes = [page.locator(s).bounding_box()["y"] for s in ("#first", "#forest", "article.card >> nth=0")]
        assert boxes == sorted(boxes)
        assert page.evaluate("document.documentElement.scrollWidth") <= 1280

        page = w.open((fixture_site / "ledger.html").as_uri())
        # compact: no wider than the window, no row taller than a screen; the rule opens with a click
        assert page.evaluate("document.documentElement.scrollWidth") <= 1280
        heights = page.locator("#ledger tbody tr").evaluate_all("rs => rs.map(r => r.getBoundingClientRect().height)")
        assert max(heights) < 300, heights
        rule = page.locator('tr[data-paper="new_schema"][data-verdict="not reproduced"] details.rule')
        assert not rule.locator("p").first.is_visible()
        rule.locator("summary").click()
        assert rule.locator("p").first.is_visible() and "error in [0, 2] px" in rule.inner_text()
        assert "covers: depends over 6 readings x 3 replicates" in rule.inner_text()
        page.select_option("#f-verdict", "undecided")
        assert page.locator("#ledger tbody tr[data-paper]:visible").count() == 1

        page = w.open((fixture_site / "sweeps" / "fixture_sweep.html").as_uri())
        assert page.evaluate("document.documentElement.scrollWidth") <= 1280  # the table scrolls in its box
        assert w.errors == [], w.errors
        assert w.outside == [], w.outside
    finally:
        w.close()


class RecordedBrowser:
    """The module's browser, whose pages record the non-loopback requests they make (the screenshots' own route
    refuses them)."""

    def __init__(self, browser):
        self.browser, self.outside = browser, []

    def new_page(self, **kwargs):
        page = self.browser.new_page(**kwargs)
        page.on("request", self._seen)
        return page

    def _seen(self, request):
        url = urlparse(request.url)
        if url.scheme in ("http", "https", "ws", "wss") and url.hostname not in LOOPBACK:
            self.outside.append(request.url)


def test_the_readme_screenshots_are_taken_from_the_runs_the_site_shows(browser, smoke_site, tmp_path, monkeypatch):
    """``python -m tvtrack screenshots``: the site's first screen, the page of the first claim that does not
    reproduce (the reader's first question) and a run's recording drawn in the web viewer, as PNG files of the
    stated sizes; a claim no run has is one line naming the option.

    The viewer's picture is also the check of :class:`tvtrack.pipeline.webview.WebViewer` in a browser (003's smoke
    recording; drawing it takes ~20 s on an idle 2-core machine, so it is drawn once): it serves on this machine,
    its own server answered (alive when the picture was taken), and what it asks for on the internet (fonts, an
    examples manifest, its latest release, telemetry) is refused and not needed to draw the recording."""
    import json

    from PIL import Image
    from tvtrack.pipeline import webview
    from tvtrack.pipeline.preflight import UsageError
    from tvtrack.pipeline.screenshots import NAMES, VIEWER_SCREEN, pick_claim, take_screenshots

    viewers = []

    class KeptViewer(webview.WebViewer):
        def __exit__(self, *exc):
            viewers.append((urlparse(self.url).hostname, self.process.poll() is None))
            return super().__exit__(*exc)

    monkeypatch.setattr(webview, "WebViewer", KeptViewer)
    recorded = RecordedBrowser(browser)

    site, _ = smoke_site
    root = site.parent
    notebook, cid = pick_claim(root / "reproduce")
    records = {
        c["id"]: c["verdict"]
        for p in (root / "reproduce").glob("*/results.json")
        for c in json.loads(p.read_text()).get("claims", [])
    }
    assert records[cid] == "not reproduced"  # smoke runs and fixtures hold some: the first is photographed
    paths = take_screenshots(
        root,
        tmp_path / "shots",
        recording="003_rotating_marker_tracker",
        wait_s=max(120.0, wall_budget(90)),
        site=site,
        browser=recorded,
    )  # the module's Chromium: a second Playwright may not start inside the first one's event loop
    assert viewers == [("127.0.0.1", True)]
    hosts = {"fonts.googleapis.com", "fonts.gstatic.com", "app.rerun.io", "tel.rerun.io", "api.github.com"}
    assert all(urlparse(u).hostname in hosts for u in recorded.outside), recorded.outside
    assert [p.name for p in paths] == list(NAMES)
    sizes = [Image.open(p).size for p in paths]
    assert sizes == [FIRST_SCREEN, FIRST_SCREEN, VIEWER_SCREEN]
    assert is_drawn(viewer_drawn(paths[2].read_bytes()))
    assert paths[0].read_bytes() != paths[1].read_bytes()
    with pytest.raises(UsageError, match="--claim: no claim C999-1"):
        pick_claim(root / "reproduce", "C999-1")
