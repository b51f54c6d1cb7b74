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
from .numbers import setting

__all__ = [
    "leaves_operating_point",
    "ENTRY_KINDS",
    "WORLD_KINDS",
    "READING_KINDS",
    "SETTING_KINDS",
    "SIDES",
    "SIDE_PHRASES",
    "side_of",
    "Entry",
    "Register",
    "project",
    "with_kinds",
    "guard",
    "Undeclared",
    "UndeclaredEntry",
]

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
#: Kinds that vary the simulated world, the figure's operating point or the scale a quantity is summarised on
#: (every kind :func:`side_of` files as a world): a claim measured over none of them cannot be labelled
#: ``robust`` (:func:`tvtrack.verdicts.label_parts`).
WORLD_KINDS = ("regime", "operating point", "model", "scale")
#: Kinds that are readings of the paper itself (an ambiguous sentence, a statistic, a comparator the paper
#: names): a flip under one says the paper's claim is ambiguous. Every other kind (:data:`WORLD_KINDS` and
#: ``scale``) is a world beyond the paper: a flip there says the claim does not extend to it.
READING_KINDS = ("reading", "statistic", "comparator")
#: Kinds that are settings of the paper's own experiment the paper never printed (a rotation-rate law, a drift
#: spread, a track geometry): neither an ambiguous passage of the text nor a world beyond the paper. A flip under
#: one says the paper's claim depends on something it did not report.
SETTING_KINDS = ("unreported setting",)
#: The sides a flip can be on: an entry's side is one of the first three (:func:`side_of`); a flip that changes
#: entries of several sides and that no subset of them isolates is ``"unattributed"``.
SIDES = ("reading", "setting", "world", "unattributed")
#: Each side in plain words, for the report.
SIDE_PHRASES = {
    "reading": "a reading of the paper's text",
    "setting": "a setting of the paper's own experiment that the paper never printed",
    "world": "a world beyond the paper",
}
#: Who added an entry: the notebook's author, or the adversarial pass hunting for a flip.
ORIGINS = ("author", "adversarial")


def side_of(kind: str) -> str:
    """``"reading"`` for a reading of the paper (:data:`READING_KINDS`), ``"setting"`` for an unreported setting
    of its own experiment (:data:`SETTING_KINDS`), ``"world"`` for a world beyond it (every other kind)."""
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
        """``"reading"``, ``"setting"`` or ``"world"`` (:func:`side_of`)."""
        return side_of(self.kind)

    def phrase(self, value: Any) -> str:
        """``value`` in plain words: its phrase, else ``"<title> = <value>"``."""
        if value in self.phrases:
            return self.phrases[value]
        return setting(self.title or self.name, value)

    @property
    def alternatives(self) -> tuple:
        """The defensible values other than the default."""
        return tuple(v for v in self.values if v != self.default)

    @property
    def operating_values(self) -> tuple:
        """The values that keep the paper's operating point (:attr:`values` less :attr:`off_operating_point`):
        those a joint design combines (:func:`tvtrack.explore.joint_sample`)."""
        return tuple(v for v in self.values if v not in self.off_operating_point)

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
        parts = [self[k].phrase(v) if k in self else setting(k, v) for k, v in changed.items()]
        return " and ".join(parts) or "the default reading"

    def project(self, config: Mapping[str, Any], names: Iterable[str]) -> dict:
        """The default overridden by ``config`` only on the entries ``names`` (:func:`project`)."""
        return project(config, names, self.default())

    def guard(self, config: Mapping[str, Any], allowed: Iterable[str]) -> dict:
        """``config`` with every entry outside ``allowed`` an :class:`Undeclared` sentinel (:func:`guard`)."""
        return guard(config, allowed)

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
        """The register as a Markdown table in a reader's words: each entry by its title, its kind with what the kind
        means (:data:`SIDE_PHRASES`), its default and other values by their phrases (:meth:`Entry.phrase`), why,
        and who added it; then the pinned joint conditions by :meth:`describe`. The code's names appear only
        where an entry has no title or phrase of its own."""
        rows = [
            "| entry | kind | default | other defensible values | why | added by |",
            "| --- | --- | --- | --- | --- | --- |",
        ]
        for e in self.entries:
            alts = "; ".join(md_escape(e.phrase(v)) for v in e.alternatives) or "-"
            rows.append(
                f"| {md_escape(e.title or e.name)} | {e.kind} ({SIDE_PHRASES[e.side]}) | {md_escape(e.phrase(e.default))}"
                f" | {alts} | {md_escape(e.why)} | {e.origin} |"
            )
        if self.pinned:
            rows.append("")
            rows.append("Joint conditions pinned (they flipped a claim before; measured every run):")
            rows += [f"- {md_escape(self.describe(p))}" for p in self.pinned]
        return "\n".join(rows)

    def _repr_markdown_(self) -> str:
        return self.to_markdown()


def leaves_operating_point(changed: Mapping[str, Any], off: Mapping[str, Iterable[Any]]) -> bool:
    """Whether a configuration's ``changed`` entries set one to a value that leaves the operating point the paper
    states: ``off`` maps an entry's name to its ``off_operating_point`` values (:class:`Entry`; a record's
    register carries them as lists, so values are compared as written, 8 and 8.0 alike)."""

    def same(a: Any, b: Any) -> bool:
        return a == b or repr(a) == repr(b)

    return any(any(same(v, o) for o in off.get(k) or ()) for k, v in changed.items())


def project(config: Mapping[str, Any], names: Iterable[str], default: Mapping[str, Any]) -> dict:
    """``default`` overridden by ``config`` only on the entries ``names``: the configuration a claim that declares
    ``names`` (its ``DEPENDS``) is measured at, so that no claim is measured in a world it does not declare."""
    keep = set(names)
    return {k: (config[k] if k in keep and k in config else v) for k, v in default.items()}


class UndeclaredEntry(LookupError):
    """A measurement used a register entry that the claims it was asked for do not declare."""


class Undeclared:
    """Stands for the value of a register entry the claims asked for do not declare (:func:`guard`): every use of
    it (comparison, hashing, truth, conversion, arithmetic, iteration, attribute access) raises
    :class:`UndeclaredEntry` naming the entry; ``repr`` is harmless (for error messages), and copying a guarded
    configuration (``dict(cfg)``, ``{**cfg}``, ``copy.deepcopy``, pickling) does not use the value."""

    def __init__(self, name: str):
        object.__setattr__(self, "_undeclared_name", name)

    def _raise(self, *_args, **_kwargs):
        name = object.__getattribute__(self, "_undeclared_name")
        raise UndeclaredEntry(
            f"register entry {name!r} was read by a measurement, but no claim it was asked for declares it in its "
            "DEPENDS: add it to DEPENDS of the claims that read it, or stop reading it"
        )

    def __getattr__(self, attr: str):
        if attr.startswith("__") and attr.endswith("__"):  # copy, pickle and numpy probe dunders: no use of the value
            raise AttributeError(attr)
        self._raise()

    def __setattr__(self, attr: str, value: Any):
        self._raise()

    def __repr__(self) -> str:
        return f"<undeclared register entry {object.__getattribute__(self, '_undeclared_name')!r}>"

    def __reduce__(self):
        return (Undeclared, (object.__getattribute__(self, "_undeclared_name"),))

    def __deepcopy__(self, memo):
        return self

    def __copy__(self):
        return self

    __eq__ = __ne__ = __lt__ = __le__ = __gt__ = __ge__ = _raise
    __hash__ = __bool__ = __len__ = __iter__ = __contains__ = __getitem__ = __call__ = _raise
    __str__ = __format__ = __float__ = __int__ = __index__ = __complex__ = __round__ = __array__ = _raise
    __add__ = __radd__ = __sub__ = __rsub__ = __mul__ = __rmul__ = __truediv__ = __rtruediv__ = _raise
    __floordiv__ = __rfloordiv__ = __mod__ = __rmod__ = __pow__ = __rpow__ = __neg__ = __pos__ = __abs__ = _raise
    __and__ = __rand__ = __or__ = __ror__ = __xor__ = __rxor__ = __invert__ = __matmul__ = __rmatmul__ = _raise


def guard(config: Mapping[str, Any], allowed: Iterable[str]) -> dict:
    """A plain dict of ``config`` in which every entry not in ``allowed`` is an :class:`Undeclared` sentinel: a
    measurement that uses such an entry raises :class:`UndeclaredEntry` naming it (copying the dict does not)."""
    keep = set(allowed)
    return {k: (v if k in keep else Undeclared(k)) for k, v in config.items()}


def with_kinds(entries: Iterable[Entry], kinds: Mapping[str, tuple[str, str]]) -> list[Entry]:
    """``entries`` with each one's kind from ``kinds`` and the line of the paper that decides it appended to its
    ``why`` (a paper package's ``kinds.KINDS``: ``{entry name: (kind, line)}``).

    Three kinds: a reading of an ambiguous passage (``reading``, ``statistic``, ``comparator``), an unreported
    setting of the paper's own experiment, or a world beyond the paper (``regime``, ``model``, ``operating point``,
    ``scale``); ``tests/test_declared_entries.py`` checks that each entry's words say its own kind and no other.
    """
    from dataclasses import replace

    return [replace(e, kind=kinds[e.name][0], why=f"{e.why.rstrip('. ')}. Kind: {kinds[e.name][1]}") for e in entries]
