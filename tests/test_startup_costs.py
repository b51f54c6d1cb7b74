"""What a run pays before its own work: compiled kernels kept between processes (:mod:`tvtrack.jit`) and the
notebook tooling imported without the parsers it never uses (:mod:`tvtrack.pipeline.lean_imports`)."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

from tvtrack import jit

pytestmark = pytest.mark.skipif(not jit.available(), reason="numba is not installed")

KERNEL_MODULE = "from tvtrack.jit import njit\n\n\n@njit\ndef plus_one(x):\n    return x + 1.0\n"
CALL = (
    "import json, kern, tvtrack.jit as j\n"
    "y = kern.plus_one(1.0)\n"
    "s = kern.plus_one.stats\n"
    "print(json.dumps({'y': y, 'hits': len(s.cache_hits), 'misses': len(s.cache_misses), 'path': s.cache_path,"
    " 'folder': str(j.cache_folder())}))\n"
)


def _call(tmp_path: Path, cache: str | None) -> dict:
    env = {k: v for k, v in os.environ.items() if k != jit.CACHE_ENV}
    if cache is not None:
        env[jit.CACHE_ENV] = cache
    env["PYTHONPATH"] = os.pathsep.join([str(tmp_path), *sys.path])
    out = subprocess.run(
        [sys.executable, "-c", CALL], capture_output=True, text=True, env=env, check=True, cwd=tmp_path
    )
    return json.loads(out.stdout)


def test_a_kernel_compiled_in_one_process_is_loaded_by_the_next(tmp_path):
    (tmp_path / "kern.py").write_text(KERNEL_MODULE)
    cache = tmp_path / "cache"
    first, second = _call(tmp_path, str(cache)), _call(tmp_path, str(cache))
    assert first["y"] == second["y"] == 2.0
    assert (first["hits"], first["misses"]) == (0, 1)  # compiled, and written
    assert (second["hits"], second["misses"]) == (1, 0)  # loaded, not compiled
    folder = Path(first["folder"])
    assert folder.parent == cache and folder.name == jit.source_digest()
    assert Path(first["path"]).is_relative_to(folder)


def test_without_the_variable_every_process_compiles_and_nothing_is_written(tmp_path):
    (tmp_path / "kern.py").write_text(KERNEL_MODULE)
    for _ in range(2):
        out = _call(tmp_path, None)
        assert (out["hits"], out["misses"], out["path"], out["folder"]) == (0, 1, None, "None")
    assert sorted(p.name for p in tmp_path.iterdir() if p.name != "__pycache__") == ["kern.py"]


def test_only_the_cache_folders_tvtrack_made_are_ever_removed(tmp_path):
    # TVTRACK_JIT_CACHE may name a folder with other things in it (a user's ~/.cache): every subfolder unused for a
    # day was removed, a user's own included
    import time

    base = tmp_path / "cache"
    keep = base / jit.source_digest()
    ours, theirs, lookalike, linked = (
        base / "0123456789abcdef",
        base / "my_backup",
        base / "fedcba9876543210",
        base / "aaaaaaaaaaaaaaaa",
    )
    for folder in (keep, ours, theirs, lookalike, tmp_path / "elsewhere"):
        folder.mkdir(parents=True)
        (folder / "thesis.tex").write_text("x")
    for folder in (keep, ours, tmp_path / "elsewhere"):
        (folder / jit._MARKER).write_text("")
    linked.symlink_to(tmp_path / "elsewhere", target_is_directory=True)
    old = time.time() - 3 * 86_400
    for folder in (ours, theirs, lookalike, linked, tmp_path / "elsewhere"):
        os.utime(folder, (old, old), follow_symlinks=False)
    jit._prune(base, keep)
    assert sorted(p.name for p in base.iterdir()) == sorted([keep.name, theirs.name, lookalike.name, linked.name])
    assert (theirs / "thesis.tex").is_file() and (tmp_path / "elsewhere" / "thesis.tex").is_file()


def test_the_folder_a_process_keeps_its_kernels_in_is_marked_as_tvtrack_s(tmp_path):
    (tmp_path / "kern.py").write_text(KERNEL_MODULE)
    folder = Path(_call(tmp_path, str(tmp_path / "cache"))["folder"])
    assert (folder / jit._MARKER).is_file()


def test_an_edit_anywhere_in_the_package_names_a_new_folder(tmp_path):
    """numba checks only the cached function's own file: a callee edited in another file would run stale code.
    The folder is named by every source file of the package, so any edit compiles afresh."""
    (tmp_path / "a.py").write_text("x = 1\n")
    (tmp_path / "sub").mkdir()
    (tmp_path / "sub" / "b.py").write_text("y = 2\n")
    before = jit.source_digest(tmp_path)
    assert jit.source_digest(tmp_path) == before
    (tmp_path / "sub" / "b.py").write_text("y = 3\n")
    edited = jit.source_digest(tmp_path)
    (tmp_path / "c.py").write_text("")
    added = jit.source_digest(tmp_path)
    assert len({before, edited, added}) == 3


def test_notebook_tooling_is_imported_without_the_iri_parsers_and_still_validates():
    code = (
        "import sys\n"
        "from tvtrack.pipeline import lean_imports\n"
        "pm, nbf = lean_imports.papermill(), lean_imports.nbformat()\n"
        "assert 'rfc3987_syntax' not in sys.modules, 'the parsers were built'\n"
        f"nb = nbf.read({str(Path(__file__).parent / 'fixtures' / 'fixture_centroid.ipynb')!r}, as_version=4)\n"
        "nbf.validate(nb)\n"
        "bad = nbf.from_dict({**nb, 'cells': [{'cell_type': 'code'}]})\n"
        "try:\n    nbf.validate(bad)\nexcept nbf.ValidationError:\n    print('refused')\n"
        "import rfc3987_syntax  # importable again afterwards\n"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "refused", out.stderr


def test_the_core_imports_without_scipy_stats_or_optimize():
    """scipy.stats (0.4 s to import) loads at the first interval that needs it (a quantile's order statistics here;
    the Student-t mean interval calls scipy.special alone), and scipy.optimize (about 1 s, with scipy.linalg) at the
    first trend whose runs to decide are solved for, not when a notebook's import cell, the preflight that checks
    its parameters or a command that reads a record imports the core."""
    code = (
        "import sys\n"
        "import tvtrack.results, tvtrack.labels, tvtrack.verdicts, tvtrack.explore, tvtrack.montecarlo\n"
        "import tvtrack.pipeline.cli\n"
        "assert 'scipy.stats' not in sys.modules, 'imported with the core'\n"
        "assert 'scipy.optimize' not in sys.modules, 'scipy.optimize imported with the core'\n"
        "import numpy as np\n"
        "print(tvtrack.montecarlo.quantile_ci(np.random.default_rng(0).normal(size=10), 0.5).ci_high > -5)\n"
        "assert 'scipy.stats' in sys.modules\n"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert out.returncode == 0 and out.stdout.strip() == "True", out.stderr
