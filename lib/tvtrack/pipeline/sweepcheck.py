"""The checks a sweep spec passes before any run: its top-level keys, its tables and the seeds it names.

Each refusal is one line naming the spec file and the key (:class:`.preflight.UsageError`).
"""

from __future__ import annotations

from pathlib import Path

from .preflight import UsageError, parameter_defaults
from .runner import find_notebook

__all__ = [
    "SEED_MAX",
    "SEED_RULE",
    "SEED_HOWTO",
    "check_top_level",
    "spec_table",
    "seed_refused",
    "check_given_seeds",
    "notebook_seed",
]

#: The notebooks' seed rule (``COMMON_RULES["seed"]`` of :mod:`tvtrack.parameters`; the pipeline imports no core
#: module, and a test holds the two equal).
SEED_MAX = 2**63 - 1
SEED_RULE = "an integer in [0, 2**63-1]"
SEED_HOWTO = (
    "vary seeds either with a [grid] (or [zip]) list `seed = [...]` and repeats = 1, or with repeats = N "
    "(seeds base, base+1, ..., the base from [fixed] seed)"
)


def check_top_level(raw: dict, path: Path) -> tuple[Path, int]:
    """The spec's notebook and ``repeats``, checked: the notebook a name or path (a string), the profile a name,
    ``repeats`` an integer >= 1, no ``seed`` outside ``[fixed]``/``[grid]``/``[zip]``."""
    if "notebook" not in raw:
        raise UsageError(f"{path}: 'notebook' is required")
    nb_name = raw["notebook"]
    if not isinstance(nb_name, str) or not nb_name.strip():
        raise UsageError(
            f"{path}: 'notebook' = {nb_name!r}; it must be a notebook's name in notebooks/ or a path relative to "
            'the spec (a non-empty string, e.g. notebook = "004_laser_spot_prediction")'
        )
    if "profile" in raw and not isinstance(raw["profile"], str):
        raise UsageError(f"{path}: 'profile' = {raw['profile']!r}; it must be a profile's name (a string)")
    if "seed" in raw:
        raise UsageError(
            f"{path}: 'seed' = {raw['seed']!r} at the top level sets no seed; put a base seed in [fixed] "
            f"(seed = {raw['seed']!r}), or {SEED_HOWTO}"
        )
    repeats = raw.get("repeats", 1)
    if isinstance(repeats, bool) or not isinstance(repeats, int) or repeats < 1:
        raise UsageError(f"{path}: 'repeats' = {repeats!r}; it must be an integer >= 1")
    local = path.parent / nb_name
    return (find_notebook(local) if local.exists() else find_notebook(nb_name)), repeats


def spec_table(raw: dict, key: str, path: Path) -> dict:
    """The spec's table ``key`` (empty when absent); one line naming the key when it is not a table."""
    value = raw.get(key, {})
    if not isinstance(value, dict):
        raise UsageError(
            f"{path}: '{key}' = {value!r}; it must be a table: a line [{key}], then one `name = value` a line"
        )
    return value


def seed_refused(seed) -> bool:
    """Whether ``seed`` breaks the notebooks' seed rule (:data:`tvtrack.parameters.COMMON_RULES`)."""
    return isinstance(seed, bool) or not isinstance(seed, int) or not 0 <= seed <= SEED_MAX


def check_given_seeds(fixed: dict, grid: dict, zipped: dict, path: Path) -> None:
    """Refuse a seed the spec names (``[fixed]``, or a ``[grid]``/``[zip]`` list) that is no integer in
    ``[0, 2**63-1]``, in one line naming the table."""
    given = [("[fixed]", fixed["seed"])] if "seed" in fixed else []
    given += [(table, v) for table, t in (("[grid]", grid), ("[zip]", zipped)) for v in t.get("seed", [])]
    for table, seed in given:
        if seed_refused(seed):
            raise UsageError(f"{path}: {table} seed: {seed!r} is not {SEED_RULE}; no run started")


def notebook_seed(notebook: Path, where: str = "") -> object:
    """The ``seed`` default of the notebook's ``parameters`` cell (0 where it assigns none), as written: a value that
    is no integer in [0, 2**63-1] is refused by the caller (:func:`seed_refused`), naming it.

    Raises
    ------
    UsageError
        The cell computes the seed (``seed = 2**3``) or sets it to ``None``: a sweep numbers its seeds from a base it
        reads before any run.
    """
    defaults = parameter_defaults(notebook)
    if "seed" in defaults and defaults["seed"] is None:
        raise UsageError(
            f"{where}the parameters cell of {notebook.stem} sets no literal integer seed (seed = None, or a computed "
            "value), and a sweep numbers its seeds from a base it reads before any run: give it in [fixed] (seed = 0)"
        )
    return defaults.get("seed", 0)
