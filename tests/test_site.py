"""The static site (``python -m tvtrack site``): what it holds, offline, built from a small runs directory."""

import json
import re

import numpy as np
import pytest

from site_fixtures import built_site, runs_dir  # noqa: F401 - fixtures
from tvtrack.pipeline.site import claim_cells, recording_still, tex_to_html


def test_index_has_a_card_per_run_with_counts(built_site):
    html = (built_site / "index.html").read_text()
    for name in ("fixture_centroid", "old_schema", "broken"):
        assert f'id="{name}"' in html
    assert "(test fixture; no paper)" in html and "Run failed" in html and "parameter &#39;n_trials&#39; = 0" in html
    # fixture: 1 reproduced, robust; old schema: 1 partly, no label
    assert re.search(r'1 <span class="pill v-reproduced">reproduced</span>', html)
    assert re.search(r'1 <span class="pill l-robust">robust</span>', html)
    assert re.search(r'1 <span class="pill l-—">—</span>', html)
    assert 'href="sweeps/fixture_sweep.html"' in html and "1 failed" in html


def test_ledger_lists_every_claim_with_verdict_label_and_cell_link(built_site, runs_dir):
    html = (built_site / "ledger.html").read_text()
    claims = [c for p in (runs_dir / "reproduce").glob("*/results.json") for c in json.loads(p.read_text())["claims"]]
    assert len(claims) == 2
    rows = re.findall(r'<tr data-paper="([^"]+)" data-verdict="([^"]+)" data-label="([^"]+)">', html)
    assert sorted(rows) == [("fixture_centroid", "reproduced", "robust"), ("old_schema", "partly", "—")]
    nb = json.loads((runs_dir / "reproduce/fixture_centroid/notebook.ipynb").read_text())
    cell = claim_cells(nb, ["C900-1"])["C900-1"]
    assert "results.claim(" in "".join(next(c for c in nb["cells"] if c.get("id") == cell)["source"])
    assert f'href="notebooks/fixture_centroid.html#cell-id={cell}">C900-1</a>' in html
    assert f'id="cell-id={cell}"' in (built_site / "notebooks/fixture_centroid.html").read_text()
    assert 'href="notebooks/old_schema.html#cell-id=c1">C911-1</a>' in html


def test_pages_load_nothing_from_elsewhere(built_site):
    for page in built_site.rglob("*.html"):
        text = page.read_text()
        assert not re.search(r'<(script|link|img|iframe)[^>]+(src|href)="(https?:)?//', text), page
        assert "@import" not in text and "cdnjs" not in text and "require.js" not in text, page


def test_notebook_page_has_figures_math_and_recording(built_site):
    html = (built_site / "notebooks/fixture_centroid.html").read_text()
    assert html.count('src="data:image/png;base64,') >= 1
    assert "Centroid error per axis" in html
    assert re.search(r"<pre class=\"cmd\">python -m tvtrack view \S*/reproduce/fixture_centroid</pre>", html)
    assert 'class="still" src="../runs/fixture_centroid/recording.png"' in html
    old = (built_site / "notebooks/old_schema.html").read_text()
    assert old.count("<math") == 2 and "<mfrac>" in old and 'display="block"' in old


def test_sweep_page_has_table_and_plot(built_site):
    html = (built_site / "sweeps/fixture_sweep.html").read_text()
    assert "<td>0.09</td>" in html and 'src="fixture_sweep.png"' in html
    assert (built_site / "sweeps/fixture_sweep.png").stat().st_size > 0


def test_tex_that_cannot_be_parsed_stays_readable():
    assert tex_to_html("x^2", display=False).startswith("<math")
    assert tex_to_html(r"\frac{1}{", display=False) == r'<code class="tex">$\frac{1}{$</code>'


def test_recording_still_is_the_first_nonconstant_frame(runs_dir, tmp_path):
    from PIL import Image

    out = tmp_path / "still.png"
    assert recording_still(runs_dir / "reproduce/fixture_centroid/recording.rrd", out)
    img = Image.open(out)
    assert min(img.size) >= 320 and img.size[0] == img.size[1]          # 32 x 32 frame, enlarged
    assert len(np.unique(np.asarray(img.convert("L")))) > 10                     # a noisy spot, not a flat frame


@pytest.mark.parametrize("argv", [["site", "--help"], ["view", "--help"]])
def test_cli_has_site_and_view(argv, capsys):
    from tvtrack.pipeline.cli import main

    with pytest.raises(SystemExit) as exc:
        main(argv)
    assert exc.value.code == 0 and "usage" in capsys.readouterr().out
