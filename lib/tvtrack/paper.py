"""One declared object per paper: :class:`Paper` holds what a notebook reads of its paper package.

A paper package declares ``PAPER = Paper(...)`` in its ``paper.py``, from what its modules already hold: the
citation, every notebook parameter's rule (:class:`tvtrack.parameters.ParamRule`, with a unit where it has one),
the register and which claims read which entries, the claims with their statements and rules, the run-size class
and how the notebook's parameters fill it, the measurement functions the explorer calls (each with the claims it
measures) and the recording module. What was written separately is derived from it:

- :meth:`Paper.validate`: the parameters cell's checks (every rule, then the constraints between parameters);
- :meth:`Paper.sizes`: one full-size run's sizes from validated parameters;
- :meth:`Paper.parameters`: a typed declaration per parameter (rule, unit, paper value, smoke value), the paper
  value read from the notebook's ``parameters`` cell and the smoke value from its smoke profile, so that neither
  is written twice;
- :meth:`Paper.smoke_profile` and :meth:`Paper.paper_profile`: every parameter at the smoke or paper size;
- :meth:`Paper.rule`: a claim's rule (``tvtrack.results.Results.claim`` takes it from the exploration).

:func:`tvtrack.contract.check_paper` runs a ``Paper`` at smoke size. The core never imports a paper: a ``Paper``
is built by the package and handed to the core.
"""

from __future__ import annotations

import json
import tomllib
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from pathlib import Path
from types import ModuleType
from typing import Any

from .parameters import COMMON_RULES, ParamRule, cell_literals, validate_parameters
from .register import Register
from .verdicts import Rule

__all__ = ["Measurement", "Paper", "Parameter", "notebook_defaults"]


@dataclass(frozen=True)
class Parameter:
    """One notebook parameter or run size, declared.

    Attributes
    ----------
    rule : ParamRule
        Its allowed values (the range, or the allowed options).
    unit : str
        Its unit (``""`` for a count, a switch or a name).
    paper : Any
        Its value in the paper profile (the notebook's ``parameters`` cell).
    smoke : Any
        Its value in the smoke profile (the paper value where the smoke profile leaves it).
    """

    rule: ParamRule
    unit: str = ""
    paper: Any = None
    smoke: Any = None


@dataclass(frozen=True)
class Measurement:
    """A measurement function the notebook explores with, and the claims it measures.

    Attributes
    ----------
    function : callable
        ``function(config, seed, **{keyword: sizes}) -> {claim id: measured}``, or with ``batched``
        ``function(configs, seeds, **{keyword: sizes}) -> [dict, ...]`` (the :func:`tvtrack.explore.explore`
        signatures).
    claims : tuple of str
        The claim ids its output holds at the register's default.
    keyword : str
        The name under which it takes the run sizes.
    sizes : callable, optional
        ``sizes(params, paper_sizes) -> value`` passed as ``keyword``, where the function takes other sizes than
        the paper's (``None``: :meth:`Paper.sizes`).
    batched : bool
        Whether it measures a batch of configurations at once.
    """

    function: Callable
    claims: tuple[str, ...]
    keyword: str = "sizes"
    sizes: Callable[[Mapping, Any], Any] | None = None
    batched: bool = False

    def run(self, config: Mapping, seed: int, sizes: Any) -> dict:
        """``{claim id: measured}`` of one run at ``config`` drawing from ``numpy.random.default_rng(seed)``."""
        if self.batched:
            return self.function([dict(config)], [seed], **{self.keyword: sizes})[0]
        return self.function(dict(config), seed, **{self.keyword: sizes})


def notebook_defaults(notebook: Path) -> dict[str, Any]:
    """``{name: value}`` of a notebook's first code cell (its ``parameters`` cell; literal values only).

    Raises
    ------
    ValueError
        When the first code cell is not tagged ``parameters``.
    """
    cells = [c for c in json.loads(Path(notebook).read_text())["cells"] if c["cell_type"] == "code"]
    if not cells or "parameters" not in cells[0].get("metadata", {}).get("tags", []):
        raise ValueError(f"{Path(notebook).name}: the first code cell is not tagged 'parameters'")
    source = cells[0]["source"]
    return cell_literals("".join(source) if isinstance(source, list) else source)


@dataclass(frozen=True, eq=False)
class Paper:
    """One paper, declared: what its notebook, the report, the site and the tests read of its package.

    Attributes
    ----------
    name : str
        The notebook's stem, ``NNN_short_name``.
    citation : str
        The paper's full citation (authors, title, venue, year).
    home : Path
        The package's folder; the notebook and its smoke profile are found from it (``home.parents[3]`` is the
        repository root).
    rules : mapping
        ``{notebook parameter: ParamRule}`` (the :data:`tvtrack.parameters.COMMON_RULES` are added).
    register : Register
        Every choice the paper left unstated, with its default.
    depends : mapping
        ``{claim id: [register entry names]}``: the entries that can change what a claim measures.
    claims : mapping
        ``{claim id: {"statement": str, "paper_value": str}}``: what the paper says, in its words.
    claim_rules : mapping
        ``{claim id: tvtrack.verdicts.Rule}`` at the default sizes (claim rules only).
    Sizes : type
        The class of one full-size run's sizes.
    build_sizes : callable
        ``build_sizes(params) -> Sizes``: the sizes from validated parameters.
    measurements : mapping
        ``{name: Measurement}``: the measurement functions the notebook explores with.
    recording : module
        The Rerun layout of one trial and ``VIEWER_EXPECTATIONS``.
    units : mapping
        ``{parameter: unit}`` of the parameters that have one.
    consistency : callable, optional
        ``consistency(params)`` raises one ``ValueError`` naming the parameters of a combination not allowed.
    rules_at : callable, optional
        ``rules_at(sizes) -> {claim id: Rule}`` where a rule reads the run's sizes (a grid, a time).
    """

    name: str
    citation: str
    home: Path
    rules: Mapping[str, ParamRule]
    register: Register
    depends: Mapping[str, Any]
    claims: Mapping[str, Mapping[str, str]]
    claim_rules: Mapping[str, Rule]
    Sizes: type
    build_sizes: Callable[[Mapping], Any]
    measurements: Mapping[str, Measurement]
    recording: ModuleType
    units: Mapping[str, str] = field(default_factory=dict)
    consistency: Callable[[Mapping], None] | None = None
    rules_at: Callable[[Any], Mapping[str, Rule]] | None = None

    @property
    def root(self) -> Path:
        """The repository root the package lives in."""
        return Path(self.home).resolve().parents[3]

    @property
    def notebook(self) -> Path:
        """The paper's notebook."""
        return self.root / "notebooks" / f"{self.name}.ipynb"

    @property
    def smoke_file(self) -> Path:
        """The smoke profile (TOML)."""
        return self.root / "papermill_runs" / "profiles" / f"{self.name}.smoke.toml"

    def parameters(self) -> dict[str, Parameter]:
        """Every parameter with a rule, declared: rule, unit, paper value and smoke value."""
        paper = notebook_defaults(self.notebook)
        smoke = tomllib.loads(self.smoke_file.read_text()) if self.smoke_file.is_file() else {}
        return {
            k: Parameter(rule, self.units.get(k, ""), paper.get(k), smoke.get(k, paper.get(k)))
            for k, rule in {**COMMON_RULES, **self.rules}.items()
        }

    def paper_profile(self) -> dict[str, Any]:
        """Every parameter of the notebook's ``parameters`` cell at its paper value."""
        return notebook_defaults(self.notebook)

    def smoke_profile(self) -> dict[str, Any]:
        """Every parameter of the notebook at its smoke value (the paper value where the profile leaves it)."""
        smoke = tomllib.loads(self.smoke_file.read_text()) if self.smoke_file.is_file() else {}
        return self.paper_profile() | smoke

    def validate(self, values: Mapping[str, Any]) -> dict[str, Any]:
        """The parameters cell's checks: every rule, then the constraints between parameters.

        Returns
        -------
        dict
            ``{name: value}`` of every parameter with a rule, normalised.

        Raises
        ------
        ValueError
            One line naming the first parameter (or combination) not allowed and what is allowed.
        """
        params = validate_parameters(values, self.rules)
        if self.consistency is not None:
            self.consistency(params)
        return params

    def sizes(self, params: Mapping[str, Any]) -> Any:
        """One full-size run's sizes (a :attr:`Sizes`) from validated parameters."""
        return self.build_sizes(params)

    def rule(self, claim_id: str, sizes: Any = None) -> Rule:
        """The rule that decides ``claim_id`` (at ``sizes`` where the paper's rules read them).

        Raises
        ------
        KeyError
            Naming the claim when the paper declares no rule for it.
        """
        rules = self.rules_at(sizes) if sizes is not None and self.rules_at is not None else self.claim_rules
        if claim_id not in rules:
            raise KeyError(f"{self.name}: no rule for claim {claim_id!r}; rules: {', '.join(rules)}")
        return rules[claim_id]
