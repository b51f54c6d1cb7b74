"""``python -m tvtrack screenshots`` without a browser: which runs it photographs, its bad input (one line on
stderr, exit 2, before any work) and what it leaves when a photograph fails (the browser itself is driven in
tests/test_site_browser.py)."""

from __future__ import annotations

import json
import sys
import types
from pathlib import Path

import pytest

from tvtrack.pipeline import screenshots
from tvtrack.pipeline.cli import build_parser, main
from tvtrack.pipeline.paths import REPO_ROOT
from tvtrack.pipeline.preflight import UsageError


def _run(folder: Path, status: str, claims: list[dict], recording: bool = True) -> None:
    folder.mkdir(parents=True)
    (folder / "run.json").write_text(json.dumps({"notebook": folder.name, "profile": "paper", "status": status,
                                                  "runtime_s": 1.0, "finished_utc": "2026-12-01T00:00:00Z"}))  # fmt: skip
    (folder / "results.json").write_text(json.dumps({"citation": "A paper", "seed": 1, "runtime_s": 1.0,
                                                      "claims": claims}))  # fmt: skip
    if recording:
        (folder / "recording.rrd").write_bytes(b"rrd")


def _claim(cid: str, verdict: str) -> dict:
    return {"id": cid, "statement": "s", "paper_value": "1", "verdict": verdict, "measured": 1.0}


@pytest.fixture
def runs(tmp_path) -> Path:
    """A runs folder: a finished run whose claim holds, and a failed run that left a results.json whose claim
    does not (the site builds no page for it)."""
    _run(tmp_path / "reproduce" / "100_done", "ok", [_claim("C100-1", "reproduced")])
    _run(tmp_path / "reproduce" / "200_failed", "failed", [_claim("C200-1", "not reproduced")])
    return tmp_path


def test_the_default_output_is_the_clones_docs_screenshots_wherever_the_command_runs():
    assert build_parser().parse_args(["screenshots"]).output == str(REPO_ROOT / "docs" / "screenshots")
    assert screenshots.SCREENSHOTS == REPO_ROOT / "docs" / "screenshots"


def test_only_a_finished_runs_claims_are_photographed(runs):
    """A failed run's claim has no page on the site: it is neither picked nor accepted as --claim."""
    source = runs / "reproduce"
    assert screenshots.pick_claim(source) == ("100_done", "C100-1")
    with pytest.raises(UsageError, match="^--claim: no claim C200-1 in the finished runs"):
        screenshots.pick_claim(source, "C200-1")


def test_no_playwright_is_one_line_and_exit_2_before_any_work(runs, monkeypatch, capsys):
    monkeypatch.setattr(screenshots, "CHROMIUM", sys.executable)  # a file that exists
    monkeypatch.setitem(sys.modules, "playwright.sync_api", None)  # `import` raises ImportError
    out = runs / "shots"
    assert main(["screenshots", "--runs", str(runs), "-o", str(out)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and err.startswith("error: no Playwright here: pip install playwright"), err
    assert not out.exists() and not (runs / "site").exists()


class _Page:
    def route(self, *_):
        pass

    def goto(self, url):
        self.url = url

    def screenshot(self, path):
        Path(path).write_bytes(b"new " + self.url.encode())

    def close(self):
        pass


class _Browser:
    def new_page(self, **_):
        return _Page()

    def close(self):
        pass


class _Playwright:
    chromium = types.SimpleNamespace(launch=lambda **_: _Browser())

    def __enter__(self):
        return self

    def __exit__(self, *_):
        return False


def test_a_failed_photograph_leaves_every_earlier_screenshot_as_it_was(runs, tmp_path, monkeypatch):
    """The viewer does not draw: the command fails, and the README's three pictures are still the earlier set
    (not two new ones beside an old one); no temporary folder is left."""
    monkeypatch.setattr(screenshots, "CHROMIUM", sys.executable)
    monkeypatch.setitem(sys.modules, "playwright.sync_api", types.SimpleNamespace(sync_playwright=_Playwright))

    def no_drawing(browser, recording, out, wait_s):
        raise RuntimeError(f"the web viewer did not draw {recording} within {wait_s:.0f} s")

    monkeypatch.setattr(screenshots, "_viewer_shot", no_drawing)
    out = tmp_path / "docs" / "screenshots"
    out.mkdir(parents=True)
    for name in screenshots.NAMES:
        (out / name).write_bytes(b"old")
    site = tmp_path / "site"
    with pytest.raises(RuntimeError, match="did not draw"):
        screenshots.take_screenshots(runs, out, site=site)
    assert [(out / n).read_bytes() for n in screenshots.NAMES] == [b"old"] * 3
    assert sorted(p.name for p in out.parent.iterdir()) == ["screenshots"]

    monkeypatch.setattr(screenshots, "_viewer_shot", lambda browser, rrd, path, wait_s: path.write_bytes(b"drawn"))
    paths = screenshots.take_screenshots(runs, out, site=site)
    assert paths == [out / n for n in screenshots.NAMES]
    assert [p.read_bytes() for p in paths] == [
        b"new " + (site / "index.html").as_uri().encode(),
        b"new " + (site / "claims" / "100_done" / "C100-1.html").as_uri().encode(),
        b"drawn",
    ]
    assert sorted(p.name for p in out.parent.iterdir()) == ["screenshots"]


def test_an_output_that_is_a_file_is_refused_before_any_photograph(runs, tmp_path, monkeypatch):
    taken = []
    monkeypatch.setattr(screenshots, "CHROMIUM", sys.executable)
    monkeypatch.setattr(_Page, "screenshot", lambda self, path: taken.append(path))
    monkeypatch.setitem(sys.modules, "playwright.sync_api", types.SimpleNamespace(sync_playwright=_Playwright))
    monkeypatch.setattr(screenshots, "_viewer_shot", lambda *a: taken.append(a))
    out = tmp_path / "shots.png"
    out.write_bytes(b"a picture of the user's")
    with pytest.raises(UsageError, match=r"^-o .*shots\.png: a file, not a folder"):
        screenshots.take_screenshots(runs, out, site=tmp_path / "site")
    assert taken == [] and out.read_bytes() == b"a picture of the user's"
