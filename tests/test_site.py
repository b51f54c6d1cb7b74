"""The static site (``python -m tvtrack site``): what it holds, offline, built from a small runs directory."""

import json
import re
from pathlib import Path

import numpy as np
import pytest

from site_fixtures import built_site, explored_site, runs_dir  # noqa: F401 - fixtures
from tvtrack.pipeline.site import claim_cells, tex_to_html
from tvtrack.pipeline.stills import recording_still


def test_index_has_a_card_per_run_with_counts(built_site):  # noqa: F811 - pytest fixture from site_fixtures
    html = (built_site / "index.html").read_text()
    for name in ("fixture_centroid", "old_schema", "broken"):
        assert f'id="{name}"' in html
    assert "(test fixture; no paper)" in html and "Run failed" in html and "parameter &#39;n_trials&#39; = 0" in html
    # fixture: 1 reproduced, unexplored (it varies no simulated world); old schema: 1 partly, no label
    assert re.search(
        r'1 <span class="pill v-reproduced" title="reproduced: the whole 95 % [^"]+">reproduced</span>', html
    )
    assert re.search(r'1 <span class="pill l-unexplored" title="unexplored: [^"]+">unexplored</span>', html)
    assert re.search(
        r'1 <span class="pill l-provisional" title="provisional: too few configurations explored[^"]+">provisional</span>',
        html,
    )
    assert re.search(r'1 <span class="pill l-—" title="—: no label: the claim is not checkable[^"]*">—</span>', html)
    assert 'href="sweeps/fixture_sweep.html"' in html and "1 failed" in html


def test_ledger_lists_every_claim_with_verdict_label_and_cell_link(built_site, runs_dir):  # noqa: F811 - pytest fixture from site_fixtures
    html = (built_site / "ledger.html").read_text()
    claims = [c for p in (runs_dir / "reproduce").glob("*/results.json") for c in json.loads(p.read_text())["claims"]]
    assert len(claims) == 4
    rows = re.findall(r'<tr data-paper="([^"]+)" data-verdict="([^"]+)" data-label="([^"]+)">', html)
    assert sorted(rows) == [
        ("fixture_centroid", "reproduced", "provisional"),  # a design too small for a share
        ("new_schema", "not reproduced", "depends"),
        ("new_schema", "undecided", "unexplored"),
        ("old_schema", "partly", "—"),
    ]
    nb = json.loads((runs_dir / "reproduce/fixture_centroid/notebook.ipynb").read_text())
    cell = claim_cells(nb, ["C900-1"])["C900-1"]
    assert "results.claim(" in "".join(next(c for c in nb["cells"] if c.get("id") == cell)["source"])
    assert f'href="notebooks/fixture_centroid.html#cell-id={cell}">C900-1</a>' in html
    assert f'id="cell-id={cell}"' in (built_site / "notebooks/fixture_centroid.html").read_text()
    assert 'href="notebooks/old_schema.html#cell-id=c1">C911-1</a>' in html


def test_pages_load_nothing_from_elsewhere(built_site):  # noqa: F811 - pytest fixture from site_fixtures
    for page in built_site.rglob("*.html"):
        text = page.read_text()
        assert not re.search(r'<(script|link|img|iframe)[^>]+(src|href)="(https?:)?//', text), page
        assert "@import" not in text and "cdnjs" not in text and "require.js" not in text, page


def test_notebook_page_has_figures_math_and_recording(built_site):  # noqa: F811 - pytest fixture from site_fixtures
    html = (built_site / "notebooks/fixture_centroid.html").read_text()
    assert html.count('src="data:image/png;base64,') >= 1
    assert "Centroid error per axis" in html
    assert re.search(r"<pre class=\"cmd\">python -m tvtrack view \S*/reproduce/fixture_centroid</pre>", html)
    assert 'class="still" src="../runs/fixture_centroid/recording.png"' in html
    old = (built_site / "notebooks/old_schema.html").read_text()
    assert old.count("<math") == 2 and "<mfrac>" in old and 'display="block"' in old
    # a run from before the verdict standard shows no figure inline: the page adds its saved figures
    assert '<img alt="An old figure." src="../runs/old_schema/old.png"' in old
    assert (built_site / "runs/old_schema/old.png").is_file()
    assert "Figures saved by this run" not in html


def test_sweep_page_has_table_and_plot(built_site):  # noqa: F811 - pytest fixture from site_fixtures
    html = (built_site / "sweeps/fixture_sweep.html").read_text()
    assert "<td>0.09</td>" in html and 'src="fixture_sweep.png"' in html
    assert (built_site / "sweeps/fixture_sweep.png").stat().st_size > 0


def test_tex_that_cannot_be_parsed_stays_readable():
    assert tex_to_html("x^2", display=False).startswith("<math")
    assert tex_to_html(r"\frac{1}{", display=False) == r'<code class="tex">$\frac{1}{$</code>'


def test_recording_still_is_the_first_nonconstant_frame(runs_dir, tmp_path):  # noqa: F811 - pytest fixture from site_fixtures
    from PIL import Image

    out = tmp_path / "still.png"
    assert recording_still(runs_dir / "reproduce/fixture_centroid/recording.rrd", out)
    img = Image.open(out)
    assert min(img.size) >= 320 and img.size[0] == img.size[1]  # 32 x 32 frame, enlarged
    assert len(np.unique(np.asarray(img.convert("L")))) > 10  # a noisy spot, not a flat frame


@pytest.mark.parametrize("argv", [["site", "--help"], ["view", "--help"]])
def test_cli_has_site_and_view(argv, capsys):
    from tvtrack.pipeline.cli import main

    with pytest.raises(SystemExit) as exc:
        main(argv)
    assert exc.value.code == 0 and "usage" in capsys.readouterr().out


def test_view_command_prints_a_loopback_url_and_stops_on_ctrl_c(runs_dir):  # noqa: F811 - pytest fixture from site_fixtures
    import os
    import signal
    import subprocess
    import sys
    import urllib.request

    from tvtrack.pipeline.viewer import free_port

    web, grpc = free_port(), free_port()
    proc = subprocess.Popen(
        [
            sys.executable,
            "-m",
            "tvtrack",
            "view",
            str(runs_dir / "reproduce/fixture_centroid"),
            "--port",
            str(web),
            "--grpc-port",
            str(grpc),
            "--no-browser",
        ],
        stdout=subprocess.PIPE,
        text=True,
        env={**os.environ, "PYTHONPATH": os.pathsep.join(sys.path)},
    )
    try:
        lines = [proc.stdout.readline() for _ in range(2)]
        url = lines[1].removeprefix("open ").strip()
        assert url == (f"http://127.0.0.1:{web}/?url=rerun%2Bhttp%3A%2F%2F127.0.0.1%3A{grpc}%2Fproxy"), lines
        assert urllib.request.urlopen(url, timeout=10).status == 200
        children = subprocess.run(
            ["pgrep", "-f", "--", f"web-viewer-port {web}"], capture_output=True, text=True
        ).stdout
        assert children.split()
        proc.send_signal(signal.SIGINT)
        assert proc.wait(20) == 0 and "stopped" in proc.stdout.read()
        alive = [
            pid
            for pid in children.split()
            if Path(f"/proc/{pid}/stat").is_file() and Path(f"/proc/{pid}/stat").read_text().split()[2] != "Z"
        ]
        assert alive == []
    finally:
        proc.kill()


def test_view_refuses_a_taken_port(runs_dir):  # noqa: F811 - pytest fixture from site_fixtures
    import socket

    from tvtrack.pipeline.preflight import UsageError
    from tvtrack.pipeline.webview import WebViewer

    with socket.socket() as taken:
        taken.bind(("127.0.0.1", 0))
        taken.listen()
        with pytest.raises(UsageError, match=f"--port {taken.getsockname()[1]}: something already listens"):
            WebViewer(runs_dir / "reproduce/fixture_centroid", web_port=taken.getsockname()[1]).start()
    with pytest.raises(UsageError, match="no recording at"):
        WebViewer(runs_dir / "reproduce/old_schema")


def test_site_refuses_to_replace_a_folder_it_did_not_build(runs_dir, tmp_path):  # noqa: F811 - pytest fixture from site_fixtures
    from tvtrack.pipeline.preflight import UsageError
    from tvtrack.pipeline.site import build_site

    precious = tmp_path / "precious"
    precious.mkdir()
    (precious / "thesis.tex").write_text("keep me")
    with pytest.raises(UsageError, match="not a site built here"):
        build_site(runs_dir, precious)
    assert (precious / "thesis.tex").read_text() == "keep me"


def test_index_leads_with_the_first_screen_and_the_pictures(built_site):  # noqa: F811 - pytest fixture from site_fixtures
    html = (built_site / "index.html").read_text()
    first = html[html.index('id="first-screen"') : html.index('class="cards"')]
    rows = re.findall(r'<tr data-verdict="([^"]+)" data-label="([^"]+)">', first)
    assert rows == [("not reproduced", "depends"), ("undecided", "unexplored")]  # the robust/unrecorded ones are not
    assert "&lt;= 2 px" in first and "2.6 [2.4, 2.8]" in first
    assert 'id="forest" src="forest.png"' in html and 'id="robustness" src="robustness.png"' in html
    for name in ("forest.png", "robustness.png"):
        assert (built_site / name).stat().st_size > 1000
    assert html.index('id="first-screen"') < html.index('id="forest"') < html.index('class="cards"')
    assert 'id="profile">profile shown:\n    <strong>paper</strong>' in html


def test_generated_text_is_html_escaped_everywhere(built_site):  # noqa: F811 - pytest fixture from site_fixtures
    for page in ("index.html", "ledger.html"):
        html = (built_site / page).read_text()
        assert "sigma*2 &lt;b&gt;not bold&lt;/b&gt; &amp; small." in html, page
        assert "<b>not bold</b>" not in html and "<em>2" not in html


def test_ledger_is_compact_with_the_rule_behind_a_click(built_site):  # noqa: F811 - pytest fixture from site_fixtures
    html = (built_site / "ledger.html").read_text()
    row = html[html.index('data-paper="new_schema" data-verdict="not reproduced"') :]
    row = row[: row.index("</tr>")]
    details = row[row.index('<details class="rule">') :]
    assert "error in [0, 2] px" in details
    assert "Under another reading of the paper&#39;s text it is reproduced: motion = gentle*2." in details
    assert "covers:</strong> depends over 6 readings x 3 replicates: motion, noise" in details
    assert "error in [0, 2] px" not in row[: row.index('<details class="rule">')]


def test_a_smoke_site_says_so_and_reads_the_smoke_runs(runs_dir, tmp_path):  # noqa: F811 - pytest fixture from site_fixtures
    from tvtrack.pipeline.site import build_site

    index = build_site(runs_dir, profile="smoke")
    assert index == runs_dir / "site-smoke" / "index.html"
    html = index.read_text()
    assert "<strong>smoke</strong> (not the paper-scale numbers)" in html
    assert 'id="old_schema"' in html and 'id="fixture_centroid"' not in html
    assert "profile smoke" in html


def test_index_opens_with_the_paragraph_the_glossary_and_tooltips(explored_site):  # noqa: F811
    from tvtrack.results import GLOSSARY

    html = (explored_site / "index.html").read_text()
    short = html[html.index('id="in-short"') : html.index('id="first-screen"')]
    assert (
        '<p id="summary">Of 5 claims checked, 2 hold, 0 hold in part and 1 does not; the runs could not decide 1'
        in short
    )
    glossary = short[short.index('id="glossary"') :]
    for word in GLOSSARY:  # every verdict and label word defined right there
        assert f">{word}</span></dt><dd>" in glossary, word
    assert (
        '<dt><span class="term" title="flip: a change (another reading, setting or world) flips a verdict only'
        in glossary
    )
    assert "flip</span></dt><dd>decisive the other way, from no fewer runs than the default needed</dd>" in glossary
    pills = re.findall(
        r'<span class="pill [^"]*"( title="[^"]*")?>', html + (explored_site / "ledger.html").read_text()
    )
    assert pills and all(t.startswith(' title="') and len(t) > 20 for t in pills)
    # the smoke-size record is never shown as robust; the first screen gives each claim its sentence
    ledger = (explored_site / "ledger.html").read_text()
    assert '<tr data-paper="001_explored" data-verdict="reproduced" data-label="provisional">' in ledger
    assert "too few configurations to label" in ledger[ledger.index('data-label="provisional"') :][:3000]
    row = html[html.index('<tr data-verdict="not reproduced" data-label="depends">') :]
    assert (
        "Under another reading of the paper&#39;s text it is reproduced: sigma read as the SD of the raw velocity "
        "increments." in row[: row.index("</tr>")]
    )
    assert 'href="claims/001_explored/C001-3.html"' in row[: row.index("</tr>")]


def test_each_claim_has_a_page_with_its_specification_curve(explored_site):  # noqa: F811
    from PIL import Image

    page = (explored_site / "claims/001_explored/C001-3.html").read_text()
    assert 'id="specification-curve" src="C001-3.png"' in page
    assert Image.open(explored_site / "claims/001_explored/C001-3.png").size[0] > 400
    # one count of configurations on the page: the sentence's share is the caption's
    summary = page[page.index('id="claim-summary"') :]
    assert "29 agree, 3 flip and 0 stay undecided of 32 explored configurations." in summary[: summary.index("</p>")]
    caption = page[page.index("<figcaption") :]
    assert (
        "29 agree with the default, 3 flip and 0 stay undecided of the 32 explored configurations"
        in caption[: caption.index("</fig")]
    )
    assert (
        "(a reading of the paper&#39;s text: reproduced)" in page and "(a world beyond the paper: reproduced)" in page
    )
    assert (
        "29 agree, 3 flip and 0 stay undecided of 32 explored configurations (agree: 95 % CI 75-98 %)" in page
        and "what the paper&#39;s sigma is the SD of (0.81)" in page
    )
    assert 'href="../../notebooks/001_explored.html#cell-id=e0"' in page
    assert "paper_sigma" not in page
    vector = (explored_site / "claims/001_explored/C001-7.html").read_text()
    assert "falls from 216300 px to 0.178 px over 9 points" in vector and "7839" not in vector
    undecided = (explored_site / "claims/001_explored/C004-3b.html").read_text()
    assert "About 7 independent replicates are projected to decide it." in undecided
    nothing = (explored_site / "claims/001_explored/C001-6.html").read_text()
    assert "no specification curve" in nothing


def test_a_smoke_site_never_calls_a_claim_robust(tmp_path):
    """The smoke site said "none of them is called robust" above "labels: 6 robust": a smoke design small enough
    that every combination fits is not flagged provisional by the explorer, yet at the smoke profile the paragraph,
    the counts and every chip say provisional."""
    import copy
    import json

    from record_fixtures import SMOKE
    from site_fixtures import make_explored_runs
    from tvtrack.pipeline.site import build_site

    root = make_explored_runs(tmp_path)
    (root / "reproduce").rename(root / "reproduce-smoke")
    run = root / "reproduce-smoke" / "001_explored"
    record = json.loads((run / "run.json").read_text()) | {"profile": "smoke"}
    (run / "run.json").write_text(json.dumps(record))
    results = json.loads((run / "results.json").read_text())
    robust = copy.deepcopy(SMOKE)
    robust["robustness"]["provisional"] = False
    results["claims"] = [c for c in results["claims"] if c["id"] != robust["id"]] + [robust]
    (run / "results.json").write_text(json.dumps(results))
    site = build_site(root, profile="smoke").parent
    for page in ["index.html", "ledger.html", *(str(p.relative_to(site)) for p in site.glob("claims/*/*.html"))]:
        html = re.sub(r'<aside id="glossary".*?</aside>', "", (site / page).read_text(), flags=re.S)  # the words
        assert not re.search(r'class="pill[^"]*"[^>]*>robust<', html), page
        assert 'data-label="robust"' not in html, page
    index = (site / "index.html").read_text()
    assert "none of them is called robust" in index and "These are smoke-size runs" in index


def test_each_paper_card_says_what_holds_what_does_not_and_why_then_its_limitations(explored_site):  # noqa: F811
    html = (explored_site / "index.html").read_text()
    card = html[html.index('id="001_explored"') :]
    card = card[: card.index("</article>")]
    assert "The paper makes 5 claims checked here; 4 can be measured. 2 claims hold (C001-7 and C001-5)." in card
    assert "it holds under a reading of the paper&#39;s text: sigma read as the SD of the raw velocity" in card
    assert "<strong>Limitations.</strong> C001-6 is not checkable: the recording of the real aircraft" in card
    assert "1 claim comes from a design too small to label: none is called robust." in card


def test_a_claim_holding_in_part_with_a_part_undecided_shows_its_label_scoped_on_the_site(tmp_path):
    """The ledger row and the claim's page say "in its decided parts only" beside a robust label of a claim that
    holds in part while one part is undecided, as the report's line does."""
    import copy

    from record_fixtures import DEPENDS
    from site_fixtures import make_explored_runs

    from tvtrack.pipeline.site import build_site

    claim = copy.deepcopy(DEPENDS)
    claim.update(id="C001-9", verdict="partly")
    rob = claim["robustness"]
    rob.update(label="robust", provisional=False)
    held = rob["parts"]["claim"] | {"verdict": "reproduced", "label": "robust", "flips": []}
    rob["parts"] = {
        "held": held,
        "failed": held | {"verdict": "not reproduced"},
        "open": held | {"verdict": "undecided", "label": "-"},
    }
    site = build_site(make_explored_runs(tmp_path, [claim])).parent
    ledger = (site / "ledger.html").read_text()
    page = next((site / "claims").rglob("C001-9.html")).read_text()
    for text in (ledger, page):
        assert "in its decided parts only" in text
