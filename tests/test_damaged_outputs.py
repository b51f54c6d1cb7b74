"""Output folders and run records that are not what tvtrack left: an ``-o`` that is a symbolic link, a disk that
fills up while the site is written, and run files whose content is of the wrong kind. Each is one line naming the
parameter or file, before any work or with nothing of the new output kept, and nothing of the user's is deleted."""

from __future__ import annotations

import errno
import json
import os
from pathlib import Path

import pytest

from conftest import cli_here, finished_run, minimal_claim, one_line_error

from tvtrack.pipeline import outputs
from tvtrack.pipeline import reproduce as rep
from tvtrack.pipeline import site as site_module
from tvtrack.pipeline.outputs import MARKER, replace_folder
from tvtrack.pipeline.preflight import UsageError
from tvtrack.pipeline.report import collect_runs
from tvtrack.pipeline.runfiles import DamagedRun

FULL = OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))


def earlier_site(folder: Path) -> dict[str, str]:
    """A site folder as tvtrack leaves it (its marker lists its files); returns its files and their content."""
    (folder / "claims").mkdir(parents=True)
    content = {"index.html": "earlier site", "claims/C1-1.html": "earlier page"}
    for rel, text in content.items():
        (folder / rel).write_text(text)
    (folder / MARKER).write_text(json.dumps({"kind": "site", "written_by": "tvtrack", "files": sorted(content)}))
    return content


def files_of(folder: Path) -> dict[str, str]:
    return {str(p.relative_to(folder)): p.read_text() for p in folder.rglob("*") if p.is_file() and p.name != MARKER}


def leftovers(parent: Path) -> list[str]:
    return sorted(p.name for p in parent.iterdir() if p.name.startswith((".tmp-", ".old-")))


# --- site -o: a symbolic link ---------------------------------------------------------------------------------


@pytest.mark.parametrize("target", ["empty folder", "earlier site", "nothing"])
def test_site_refuses_an_output_that_is_a_symbolic_link_and_keeps_it(tmp_path, capsys, target):
    finished_run(tmp_path / "reproduce-smoke")
    real = tmp_path / "www" / "site"
    content = {}
    if target == "empty folder":
        real.mkdir(parents=True)
    elif target == "earlier site":
        content = earlier_site(real)
    link = tmp_path / "out" / "site"
    link.parent.mkdir()
    link.symlink_to(real)
    proc = cli_here(capsys, "site", "--runs", tmp_path, "--profile", "smoke", "-o", link)
    one_line_error(proc, f"-o {link}", "symbolic link", str(real))
    assert link.is_symlink() and os.readlink(link) == str(real)
    assert leftovers(link.parent) == [] and (not real.exists() or files_of(real) == content)


def test_site_refuses_a_default_site_folder_that_is_a_symbolic_link(tmp_path, capsys):
    finished_run(tmp_path / "reproduce-smoke")
    (tmp_path / "elsewhere").mkdir()
    (tmp_path / "site-smoke").symlink_to(tmp_path / "elsewhere")
    proc = cli_here(capsys, "site", "--runs", tmp_path, "--profile", "smoke")
    one_line_error(proc, f"site folder {tmp_path / 'site-smoke'}", "symbolic link")
    assert (tmp_path / "site-smoke").is_symlink() and list((tmp_path / "elsewhere").iterdir()) == []


# --- site: a full disk ----------------------------------------------------------------------------------------


def _full_when_writing(monkeypatch, name: str) -> None:
    write_text = Path.write_text

    def full(self, *args, **kwargs):
        if self.name == name:
            raise FULL  # as write() raises it: no file name
        return write_text(self, *args, **kwargs)

    monkeypatch.setattr(Path, "write_text", full)


@pytest.mark.parametrize("earlier", [False, True], ids=["new folder", "earlier site"])
def test_a_full_disk_while_the_site_is_written_is_one_line_and_keeps_nothing_of_it(
    tmp_path, capsys, monkeypatch, earlier
):
    finished_run(tmp_path / "reproduce-smoke")
    out = tmp_path / "sites" / "s"
    content = earlier_site(out) if earlier else None
    _full_when_writing(monkeypatch, "ledger.html")
    proc = cli_here(capsys, "site", "--runs", tmp_path, "--profile", "smoke", "-o", out)
    one_line_error(proc, f"cannot write the site folder {out}", "No space left on device", status=(1,))
    assert leftovers(out.parent) == []
    assert (files_of(out) == content) if earlier else not out.exists()


def test_a_full_disk_while_the_recording_still_is_written_is_not_a_damaged_recording(tmp_path, capsys, monkeypatch):
    run = finished_run(tmp_path / "reproduce-smoke", results={"recording": "recording.rrd"})
    (run / "recording.rrd").write_bytes(b"a recording")

    def still(rrd, png):
        raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC), str(png))

    monkeypatch.setattr(site_module, "recording_still", still)
    out = tmp_path / "sites" / "s"
    proc = cli_here(capsys, "site", "--runs", tmp_path, "--profile", "smoke", "-o", out)
    line = one_line_error(proc, f"{out}/runs/p1/recording.png", "No space left on device", status=(1,))
    assert "damaged" not in line and ".tmp-" not in line
    assert leftovers(out.parent) == [] and not out.exists() and (run / "recording.rrd").is_file()


def test_a_failed_rename_puts_the_earlier_folder_back(tmp_path, monkeypatch):
    final = tmp_path / "s"
    content = earlier_site(final)
    new = tmp_path / ".tmp-s-new"
    new.mkdir()
    (new / "index.html").write_text("new site")
    outputs.mark(new, "site")
    renames = []
    replace = os.replace

    def second_fails(src, dst):
        renames.append(src)
        if len(renames) == 2:
            raise OSError(errno.EIO, os.strerror(errno.EIO), str(src))
        return replace(src, dst)

    monkeypatch.setattr(outputs.os, "replace", second_fails)
    with pytest.raises(OSError):
        replace_folder(new, final)
    assert files_of(final) == content and not list(tmp_path.glob(".old-*"))


def test_a_temporary_folder_whose_owner_file_cannot_be_written_is_removed(tmp_path, monkeypatch):
    _full_when_writing(monkeypatch, outputs.OWNER_FILE)
    with pytest.raises(OSError):
        outputs.temporary_beside(tmp_path / "s")
    assert list(tmp_path.iterdir()) == []


# --- run records of the wrong kind ----------------------------------------------------------------------------


def _replace_run_json_by_folder(run: Path) -> None:
    (run / "run.json").unlink()
    (run / "run.json").mkdir()


def _replace_run_json_by_loop(run: Path) -> None:
    (run / "run.json").unlink()
    (run / "run.json").symlink_to("run.json")


def _replace_results_by_folder(run: Path) -> None:
    (run / "results.json").unlink()
    (run / "results.json").mkdir()


def _edit(name: str, change: dict | None = None, text: tuple[str, str] | None = None):
    def apply(run: Path) -> None:
        path = run / name
        if change is not None:
            path.write_text(json.dumps({**json.loads(path.read_text()), **change}))
        if text is not None:
            path.write_text(path.read_text().replace(*text))

    return apply


DAMAGES = [
    ("run.json", _replace_run_json_by_folder, "a folder, not a file"),
    ("run.json", _replace_run_json_by_loop, "cannot be read"),
    ("run.json", _edit("run.json", {"files": "results.json"}), "'files' is a JSON str, not a list"),
    ("run.json", _edit("run.json", {"files": ["run.json", 5]}), "'files' lists 5"),
    ("run.json", _edit("run.json", text=('"runtime_s": 12.0', '"runtime_s": NaN')), "runtime_s nan"),
    ("run.json", _edit("run.json", text=('"runtime_s": 12.0', '"runtime_s": Infinity')), "runtime_s inf"),
    ("run.json", _edit("run.json", {"runtime_s": -3.0}), "runtime_s -3.0"),
    ("run.json", _edit("run.json", {"status": "failed", "error": ["x"]}), "'error' is a JSON list"),
    ("run.json", _edit("run.json", {"finished_utc": 5}), "'finished_utc' is a JSON int"),
    ("results.json", _edit("results.json", text=('"runtime_s": 10.0', '"runtime_s": NaN')), "runtime_s nan"),
    ("results.json", _edit("results.json", {"claims": [minimal_claim("C1-1"), minimal_claim("C1-1")]}), "twice"),
    ("results.json", _replace_results_by_folder, "a folder, not a file"),
    ("results.json", _edit("results.json", {"citation": 5}), "'citation' is a JSON int"),
    # integers JSON allows of any size: beyond any float, and beyond the digits Python converts
    ("run.json", _edit("run.json", text=('"runtime_s": 12.0', '"runtime_s": 1' + "0" * 400)), "(401 digits)"),
    ("results.json", _edit("results.json", text=('"runtime_s": 10.0', '"runtime_s": 1' + "0" * 400)), "401 digits"),
    ("run.json", _edit("run.json", text=('"runtime_s": 12.0', '"runtime_s": 1' + "0" * 5000)), "not JSON a record"),
    ("run.json", _edit("run.json", text=('"runtime_s": 12.0', '"runtime_s": ' + "[" * 100_000)), "not JSON a record"),
]
DAMAGE_IDS = [d[2] for d in DAMAGES]


@pytest.mark.parametrize(("name", "damage", "said"), DAMAGES, ids=DAMAGE_IDS)
def test_a_damaged_run_record_is_one_line_naming_the_file(tmp_path, name, damage, said):
    run = finished_run(tmp_path / "reproduce-smoke")
    damage(run)
    with pytest.raises(DamagedRun, match=f"{run / name}: ") as caught:
        collect_runs(run.parent, ["p1"])
    assert said in str(caught.value) and "\n" not in str(caught.value)


SITE_DAMAGES = [DAMAGES[k] for k in (0, 2, 4, 10)]


@pytest.mark.parametrize(("name", "damage", "said"), SITE_DAMAGES, ids=[d[2] for d in SITE_DAMAGES])
def test_site_stops_at_a_damaged_run_record_before_writing(tmp_path, capsys, name, damage, said):
    run = finished_run(tmp_path / "reproduce-smoke")
    damage(run)
    before = sorted(p.name for p in run.iterdir())
    out = tmp_path / "sites" / "s"
    one_line_error(cli_here(capsys, "site", "--runs", tmp_path, "--profile", "smoke", "-o", out), str(run / name), said)
    assert not out.parent.exists() and sorted(p.name for p in run.iterdir()) == before


def test_reproduce_checks_a_damaged_record_of_a_run_it_keeps_before_any_run(tmp_path):
    kept = finished_run(tmp_path / "reproduce-smoke", "000_dissector_ekf")
    _replace_run_json_by_folder(kept)
    with pytest.raises(DamagedRun, match=f"{kept / 'run.json'}: is a folder, not a file"):
        rep.check_records(
            kept.parent, ["000_dissector_ekf", "004_laser_spot_prediction"], ["004_laser_spot_prediction"]
        )


@pytest.mark.parametrize("damage", [_replace_run_json_by_folder, _edit("run.json", {"files": "results.json"})])
def test_a_damaged_run_record_deletes_nothing_of_the_run_it_replaces(tmp_path, damage):
    run = finished_run(tmp_path / "reproduce-smoke")
    damage(run)
    before = files_of(run)
    rep.check_records(run.parent, ["p1"], ["p1"])  # a run about to run again is replaced, not read
    new = tmp_path / "new"
    new.mkdir()
    (new / "run.json").write_text(json.dumps({"status": "ok", "runtime_s": 1.0, "files": ["run.json"]}))
    replace_folder(new, run, legacy_run=True)
    (old,) = run.parent.glob(".old-p1-*")
    assert files_of(old) == before  # every file kept aside (an empty folder named run.json holds none)


# --- found beside them ----------------------------------------------------------------------------------------


def test_a_file_rewritten_whole_through_a_symbolic_link_stays_a_link(tmp_path):
    (tmp_path / "real").mkdir()
    (tmp_path / "real" / "README.md").write_text("old")
    link = tmp_path / "README.md"
    link.symlink_to(tmp_path / "real" / "README.md")
    outputs.replace_text(link, "new")
    assert link.is_symlink() and (tmp_path / "real" / "README.md").read_text() == "new"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["README.md", "real"]
    assert [p.name for p in (tmp_path / "real").iterdir()] == ["README.md"]


def test_site_shows_a_figure_saved_in_a_folder_of_the_run(tmp_path, capsys):
    run = finished_run(tmp_path / "reproduce-smoke", results={"figures": [{"file": "figs/a.png", "caption": "A"}]})
    (run / "figs").mkdir()
    (run / "figs" / "a.png").write_bytes(b"a figure")
    out = tmp_path / "s"
    proc = cli_here(capsys, "site", "--runs", tmp_path, "--profile", "smoke", "-o", out)
    assert proc.returncode == 0, proc.stderr
    assert (out / "runs" / "p1" / "figs" / "a.png").read_bytes() == b"a figure"
    assert "../runs/p1/figs/a.png" in (out / "notebooks" / "p1.html").read_text()


def test_reproduce_refuses_to_replace_a_run_folder_that_is_a_symbolic_link_before_any_run(tmp_path):
    real = finished_run(tmp_path / "elsewhere")
    before = files_of(real)
    folder = tmp_path / "reproduce-smoke"
    folder.mkdir()
    (folder / "p1").symlink_to(real)
    with pytest.raises(UsageError, match=f"{folder / 'p1'}: a symbolic link"):
        rep.check_records(folder, ["p1"], ["p1"])
    assert (folder / "p1").is_symlink() and files_of(real) == before


# --- a new run a stopped reproduce left before putting it in place --------------------------------------------


def test_a_new_run_left_by_a_stopped_reproduce_is_removed_only_when_it_holds_its_own_files(tmp_path):
    """``.new-<notebook>`` is where reproduce makes a run before it replaces the earlier one; one left by a killed
    reproduce is removed before the next run, file by file as its ``run.json`` lists them. A folder of that name
    holding anything else (a user's file, no ``run.json``) is refused before any run, and nothing in it is
    deleted; an empty one simply goes."""
    own = finished_run(tmp_path, ".new-p1")
    rep.check_records(tmp_path, ["p1"], ["p1"])  # no refusal: it is a run tvtrack wrote
    assert rep.remove_new_run(own, dry_run=True) and own.is_dir()
    assert rep.remove_new_run(own) and not own.exists()

    theirs = finished_run(tmp_path, ".new-p1")
    (theirs / "notes.txt").write_text("mine")
    with pytest.raises(UsageError, match=r"\.new-p1: .*move it out of the way.*run reproduce again"):
        rep.check_records(tmp_path, ["p1"], ["p1"])
    assert not rep.remove_new_run(theirs) and (theirs / "notes.txt").read_text() == "mine"
    assert (theirs / "results.json").is_file()  # nothing of the folder went, the run's own files included

    unrecorded = tmp_path / ".new-p2"
    unrecorded.mkdir()
    (unrecorded / "results.json").write_text("{}")
    with pytest.raises(UsageError, match=r"\.new-p2"):
        rep.check_records(tmp_path, ["p2"], ["p2"])
    assert not rep.remove_new_run(unrecorded) and (unrecorded / "results.json").read_text() == "{}"

    empty = tmp_path / ".new-p3"
    empty.mkdir()
    rep.check_records(tmp_path, ["p3"], ["p3"])
    assert rep.remove_new_run(empty) and not empty.exists()


def test_a_run_json_that_links_out_of_its_folder_says_so(tmp_path):
    """A ``run.json`` that is a symbolic link to a sound record elsewhere names itself outside the folder: the line
    says a link leading out of it is not allowed, not only "no '..'"; nothing is deleted."""
    run = finished_run(tmp_path / "reproduce-smoke")
    outside = tmp_path / "elsewhere.json"
    outside.write_text((run / "run.json").read_text())
    (run / "run.json").unlink()
    (run / "run.json").symlink_to(outside)
    with pytest.raises(DamagedRun, match="no link leading out of it"):
        collect_runs(run.parent, ["p1"])
    assert outside.is_file() and (run / "run.json").is_symlink()


def test_a_stopped_reproduce_removes_only_the_new_runs_of_its_own_notebooks(tmp_path, monkeypatch):
    """Ctrl-C while the notebooks run: the ``.new-`` run of a notebook of this command goes; that of another
    notebook, which this command never checked, is left."""
    mine = finished_run(tmp_path, ".new-p1")
    other = finished_run(tmp_path, ".new-p2")

    class Pool:
        def __init__(self, *args, **kwargs):
            pass

        def submit(self, *args, **kwargs):
            raise KeyboardInterrupt

    monkeypatch.setattr(rep, "ProcessPoolExecutor", Pool)
    monkeypatch.setattr(rep, "stop_pool", lambda pool: None)
    with pytest.raises(KeyboardInterrupt, match="notebooks stopped"):
        rep._run_notebooks([Path("p1.ipynb")], "smoke", tmp_path, 1, 1, [({}, {})])
    assert not mine.exists() and (other / "run.json").is_file()
