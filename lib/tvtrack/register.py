"""The register of what a paper left unstated.

Every notebook keeps one :class:`Register`: the readings of ambiguous sentences, the regimes of the
simulated world the paper does not pin (motion, geometry, spectra, noise and photon models, frame rate,
horizon), the operating points of the figures the claims come from, the statistics and the comparators.
Each :class:`Entry` has its default, every defensible value and one line saying why those values are
defensible. The explorer (:mod:`tvtrack.explore`) measures each claim over the register; a claim's label
says which entries it was measured over.

Example
-------
>>> from tvtrack.register import Entry, Register
>>> reg = Register([
...     Entry("motion", "regime", "gentle", ("gentle", "fast"), "the paper never says how the object moves"),
...     Entry("alpha", "reading", 1e-3, (1e-3, 1e-2), "per-test false-alarm rate; the paper gives none"),
... ])
>>> reg.default()
{'motion': 'gentle', 'alpha': 0.001}
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, Iterable, Mapping, Sequence

from .markdown import md_escape

__all__ = ["ENTRY_KINDS", "WORLD_KINDS", "READING_KINDS", "SETTING_KINDS", "side_of", "Entry", "Register"]

#: What an entry can be.
ENTRY_KINDS = (
    "reading",
    "regime",
    "operating point",
    "model",
    "statistic",
    "comparator",
    "scale",
    "unreported setting",
)
#: Kinds that vary the simulated world or the figure's operating point: a claim measured over none of
#: them cannot be labelled ``robust`` (:func:`tvtrack.verdicts.label_parts`).
WORLD_KINDS = ("regime", "operating point", "model")
#: Kinds that are readings of the paper itself (an ambiguous sentence, a statistic, a comparator the paper
#: names): a flip under one says the paper's claim is ambiguous. Every other kind (:data:`WORLD_KINDS` and
#: ``scale``) is a world beyond the paper: a flip there says the claim does not extend to it.
READING_KINDS = ("reading", "statistic", "comparator")
#: Kinds that are settings of the paper's own experiment the paper never printed (a rate law, a spread, where in
#: its stated error band its data sat): neither an ambiguous sentence nor a world beyond the paper. A flip under
#: one says the claim depends on something the paper did not report.
SETTING_KINDS = ("unreported setting",)
#: Who added an entry: the notebook's author, or the adversarial pass hunting for a flip.
ORIGINS = ("author", "adversarial")


def side_of(kind: str) -> str:
    """``"reading"`` for a reading of the paper (:data:`READING_KINDS`), ``"setting"`` for an unreported setting
    of its own experiment (:data:`SETTING_KINDS`), ``"world"`` for a world beyond it."""
    if kind in READING_KINDS:
        return "reading"
    return "setting" if kind in SETTING_KINDS else "world"


@dataclass(frozen=True)
class Entry:
    """One thing the paper left unstated.

    Attributes
    ----------
    name : str
        Identifier, used as the key in a configuration (``"motion"``).
    kind : str
        One of :data:`ENTRY_KINDS`.
    default : Any
        The value the notebook's headline uses.
    values : tuple
        Every defensible value, the default among them (JSON-able scalars or strings).
    why : str
        One line: why these values are defensible (a quote of the paper, a physical range, a textbook).
    origin : str
        ``"author"`` or ``"adversarial"`` (added by the adversarial pass while trying to flip a label).
    title : str
        What the entry is, in plain words a domain reader understands without the code ("time at which the
        estimate is scored"); default: the name.
    phrases : mapping value -> str
        Each value in plain words ("scored at the end of the integration interval (the paper's filtering
        error)"); a value without a phrase reads ``"<title> = <value>"``.
    off_operating_point : tuple
        Values (never the default) at which the world leaves an operating point the paper states and the default
        world is calibrated to (e.g. a wander so fast that the paper's filter errs outside the paper's own
        1-2 px), where re-calibrating the world to it is not meaningful: a flip there says the claim does not
        extend beyond the paper's operating point. Empty: every value keeps it (or the paper states none). The
        record carries it (:meth:`to_dict`).
    """

    name: str
    kind: str
    default: Any
    values: tuple
    why: str
    origin: str = "author"
    title: str = ""
    phrases: Mapping[Any, str] | None = field(default=None, compare=False)
    off_operating_point: tuple = ()

    def __post_init__(self):
        object.__setattr__(self, "values", tuple(self.values))
        object.__setattr__(self, "off_operating_point", tuple(self.off_operating_point))
        off = [v for v in self.off_operating_point if v not in self.values or v == self.default]
        if off:
            raise ValueError(
                f"register entry {self.name!r}: off_operating_point {off} must be values other than the default "
                f"{self.default!r} among {list(self.values)}"
            )
        if not self.name or not isinstance(self.name, str):
            raise ValueError(f"register entry name must be a non-empty string, got {self.name!r}")
        if self.kind not in ENTRY_KINDS:
            raise ValueError(f"register entry {self.name!r}: kind {self.kind!r} must be one of {ENTRY_KINDS}")
        if self.origin not in ORIGINS:
            raise ValueError(f"register entry {self.name!r}: origin {self.origin!r} must be one of {ORIGINS}")
        if self.default not in self.values:
            raise ValueError(f"register entry {self.name!r}: default {self.default!r} is not among {list(self.values)}")
        if not self.why.strip():
            raise ValueError(f"register entry {self.name!r} needs a line saying why its values are defensible")
        phrases = dict(self.phrases or {})
        stray = [k for k in phrases if k not in self.values]
        if stray:
            raise ValueError(f"register entry {self.name!r}: phrases for values not among {list(self.values)}: {stray}")
        object.__setattr__(self, "phrases", phrases)

    @property
    def side(self) -> str:
        """``"reading"`` (a reading of the paper), ``"setting"`` (an unreported setting of its experiment) or
        ``"world"`` (a world beyond it): :func:`side_of`."""
        return side_of(self.kind)

    def phrase(self, value: Any) -> str:
        """``value`` in plain words: its phrase, else ``"<title> = <value>"``."""
        if value in self.phrases:
            return self.phrases[value]
        v = f"{value:g}" if isinstance(value, float) else str(value)
        return f"{self.title or self.name} = {v}"

    @property
    def alternatives(self) -> tuple:
        """The defensible values other than the default."""
        return tuple(v for v in self.values if v != self.default)

    def to_dict(self) -> dict:
        off = {"off_operating_point": list(self.off_operating_point)} if self.off_operating_point else {}
        return {
            "name": self.name,
            "kind": self.kind,
            "default": self.default,
            "values": list(self.values),
            "why": self.why,
            "origin": self.origin,
            "title": self.title or self.name,
            "side": self.side,
            "phrases": {str(v): self.phrase(v) for v in self.values},
            **off,
        }


class Register:
    """An ordered collection of :class:`Entry` with unique names.

    Parameters
    ----------
    entries : iterable of Entry
    pinned : iterable of mapping {entry name: value}, optional
        Joint conditions that flipped a claim before (a joint sample of an earlier run, or the adversarial
        pass): :func:`tvtrack.explore.explore` measures every one of them each time, so that a label never
        becomes ``robust`` because a random joint sample happened to miss a known flip. Each names at least
        two entries, with values among their defensible values.
    """

    def __init__(self, entries: Iterable[Entry], pinned: Iterable[Mapping[str, Any]] = ()):
        self.entries: list[Entry] = list(entries)
        names = [e.name for e in self.entries]
        dup = sorted({n for n in names if names.count(n) > 1})
        if dup:
            raise ValueError(f"register entries named more than once: {dup}")
        for e in self.entries:
            if not isinstance(e, Entry):
                raise TypeError(f"a register holds Entry objects, got {type(e).__name__}")
        self.pinned: list[dict] = [dict(p) for p in pinned]
        for p in self.pinned:
            if len(p) < 2:
                raise ValueError(f"a pinned joint condition names at least two entries, got {p}")
            self.check(p)

    def __iter__(self):
        return iter(self.entries)

    def __len__(self) -> int:
        return len(self.entries)

    def __contains__(self, name: str) -> bool:
        return any(e.name == name for e in self.entries)

    def __getitem__(self, name: str) -> Entry:
        for e in self.entries:
            if e.name == name:
                return e
        raise KeyError(f"no register entry {name!r}; entries: {self.names}")

    @property
    def names(self) -> list[str]:
        return [e.name for e in self.entries]

    def default(self) -> dict:
        """The default configuration ``{name: default}``."""
        return {e.name: e.default for e in self.entries}

    def subset(self, names: Sequence[str]) -> "Register":
        """The entries named, in register order."""
        unknown = set(names) - set(self.names)
        if unknown:
            raise KeyError(f"no register entries {sorted(unknown)}; entries: {self.names}")
        keep = set(names)
        return Register((e for e in self.entries if e.name in keep), [p for p in self.pinned if set(p) <= keep])

    def with_pinned(self, *conditions: Mapping[str, Any]) -> "Register":
        """A new register with joint ``conditions`` pinned (see the class)."""
        return Register(self.entries, [*self.pinned, *conditions])

    def describe(self, changed: Mapping[str, Any]) -> str:
        """A configuration's changes from the default in plain words, joined by " and " (they hold together;
        entries of other registers are named as they are, no change reads as the default reading)."""
        parts = [self[k].phrase(v) if k in self else f"{k} = {v}" for k, v in changed.items()]
        return " and ".join(parts) or "the default reading"

    def check(self, config: Mapping[str, Any]) -> dict:
        """``config`` completed with defaults, each value checked to be defensible."""
        unknown = set(config) - set(self.names)
        if unknown:
            raise KeyError(f"configuration names unknown register entries {sorted(unknown)}")
        out = self.default()
        for k, v in config.items():
            if v not in self[k].values:
                raise ValueError(f"register entry {k!r}: {v!r} is not among {list(self[k].values)}")
            out[k] = v
        return out

    def to_dict(self) -> list[dict]:
        return [e.to_dict() for e in self.entries]

    def to_markdown(self) -> str:
        """The register as a Markdown table (name, kind, default, other values, why, origin)."""
        rows = [
            "| entry | kind | default | other defensible values | why | added by |",
            "| --- | --- | --- | --- | --- | --- |",
        ]
        for e in self.entries:
            alts = ", ".join(_md(v) for v in e.alternatives) or "-"
            rows.append(f"| `{e.name}` | {e.kind} | {_md(e.default)} | {alts} | {md_escape(e.why)} | {e.origin} |")
        if self.pinned:
            rows.append("")
            rows.append("Joint conditions pinned (they flipped a claim before; measured every run):")
            rows += [f"- {md_escape(', '.join(f'{k} = {v}' for k, v in p.items()))}" for p in self.pinned]
        return "\n".join(rows)

    def _repr_markdown_(self) -> str:
        return self.to_markdown()


def _md(v: Any) -> str:
    return md_escape(f"{v:g}" if isinstance(v, float) else str(v))
