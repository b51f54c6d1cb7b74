"""Validation of a notebook's parameters, done once, right after the ``parameters`` cell.

Every notebook declares what each parameter may be, then calls :func:`validate_parameters`.
A bad value raises a :class:`ValueError` that names the parameter, its value and the
allowed range before any simulation starts::

    params = validate_parameters(globals(), {
        "seed": Integer(0, 2**32 - 1),
        "n_trials": Integer(1, 100_000),
        "sigma_px": Real(0.0, 10.0, low_open=True),
        "rerun_mode": OneOf("file", "off"),
        "output_dir": OutputDir(),
    })
"""

from __future__ import annotations

import abc
import ast
import math
import numbers
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Mapping

__all__ = [
    "ParamRule",
    "Integer",
    "Real",
    "OneOf",
    "Boolean",
    "OutputDir",
    "RealList",
    "IntegerList",
    "OneOfList",
    "SchedulerAddress",
    "validate_parameters",
    "COMMON_RULES",
    "cell_literals",
]


class ParamRule(abc.ABC):
    """One parameter's allowed values."""

    @abc.abstractmethod
    def check(self, value: Any) -> Any:
        """Return the normalised value, or raise ``TypeError`` if it is not allowed."""

    @abc.abstractmethod
    def describe(self) -> str:
        """The allowed values in words, e.g. ``"an integer in [1, 100]"``."""


def _interval(low, high, low_open, high_open) -> str:
    left = "(" if low_open or low is None else "["
    right = ")" if high_open or high is None else "]"
    lo = "-inf" if low is None else f"{low:g}"
    hi = "inf" if high is None else f"{high:g}"
    return f"{left}{lo}, {hi}{right}"


def _within(x, low, high, low_open, high_open) -> bool:
    if low is not None and (x < low or (low_open and x == low)):
        return False
    if high is not None and (x > high or (high_open and x == high)):
        return False
    return True


@dataclass(frozen=True)
class Integer(ParamRule):
    """An integer in ``[low, high]`` (either bound may be ``None``)."""

    low: int | None = None
    high: int | None = None

    def check(self, value):
        if isinstance(value, bool) or not isinstance(value, numbers.Integral):
            raise TypeError("an integer")
        if not _within(value, self.low, self.high, False, False):
            raise TypeError
        return int(value)

    def describe(self) -> str:
        return f"an integer in {_interval(self.low, self.high, False, False)}"


@dataclass(frozen=True)
class Real(ParamRule):
    """A finite real number in an interval; ``low_open``/``high_open`` exclude the bounds."""

    low: float | None = None
    high: float | None = None
    low_open: bool = False
    high_open: bool = False

    def check(self, value):
        if isinstance(value, bool) or not isinstance(value, numbers.Real) or not math.isfinite(value):
            raise TypeError
        if not _within(value, self.low, self.high, self.low_open, self.high_open):
            raise TypeError
        return float(value)

    def describe(self) -> str:
        return f"a real number in {_interval(self.low, self.high, self.low_open, self.high_open)}"


@dataclass(frozen=True)
class OneOf(ParamRule):
    """One of a fixed set of values."""

    options: tuple

    def __init__(self, *options):
        object.__setattr__(self, "options", tuple(options))

    def check(self, value):
        if value not in self.options:
            raise TypeError
        return value

    def describe(self) -> str:
        return "one of " + ", ".join(repr(o) for o in self.options)


@dataclass(frozen=True)
class Boolean(ParamRule):
    """``True`` or ``False``."""

    def check(self, value):
        if not isinstance(value, bool):
            raise TypeError
        return value

    def describe(self) -> str:
        return "True or False"


@dataclass(frozen=True)
class RealList(ParamRule):
    """A non-empty list of reals, each in the interval, with a length in ``[min_len, max_len]``."""

    low: float | None = None
    high: float | None = None
    low_open: bool = False
    high_open: bool = False
    min_len: int = 1
    max_len: int | None = None

    def check(self, value):
        if isinstance(value, (str, bytes)) or not hasattr(value, "__len__"):
            raise TypeError
        if len(value) < self.min_len or (self.max_len is not None and len(value) > self.max_len):
            raise TypeError
        item = Real(self.low, self.high, self.low_open, self.high_open)
        return [item.check(v) for v in value]

    def describe(self) -> str:
        size = f"{self.min_len}..{self.max_len if self.max_len is not None else 'any'}"
        return f"a list of {size} real numbers, each in {_interval(self.low, self.high, self.low_open, self.high_open)}"


@dataclass(frozen=True)
class IntegerList(ParamRule):
    """A non-empty list of integers, each in ``[low, high]``."""

    low: int | None = None
    high: int | None = None
    min_len: int = 1
    max_len: int | None = None

    def check(self, value):
        if isinstance(value, (str, bytes)) or not hasattr(value, "__len__"):
            raise TypeError
        if len(value) < self.min_len or (self.max_len is not None and len(value) > self.max_len):
            raise TypeError
        item = Integer(self.low, self.high)
        return [item.check(v) for v in value]

    def describe(self) -> str:
        size = f"{self.min_len}..{self.max_len if self.max_len is not None else 'any'}"
        return f"a list of {size} integers, each in {_interval(self.low, self.high, False, False)}"


@dataclass(frozen=True)
class OneOfList(ParamRule):
    """A list of distinct values, each one of a fixed set (e.g. which figures to compute)."""

    options: tuple
    min_len: int = 1

    def __init__(self, *options, min_len: int = 1):
        object.__setattr__(self, "options", tuple(options))
        object.__setattr__(self, "min_len", min_len)

    def check(self, value):
        if isinstance(value, (str, bytes)) or not hasattr(value, "__len__") or len(value) < self.min_len:
            raise TypeError
        if any(v not in self.options for v in value) or len(set(value)) != len(value):
            raise TypeError
        return list(value)

    def describe(self) -> str:
        return f"a list of at least {self.min_len} distinct values from " + ", ".join(repr(o) for o in self.options)


@dataclass(frozen=True)
class OutputDir(ParamRule):
    """A directory path (string); created if missing."""

    def check(self, value):
        if not isinstance(value, (str, Path)) or str(value).strip() == "":
            raise TypeError
        path = Path(value)
        if path.exists() and not path.is_dir():
            raise TypeError
        path.mkdir(parents=True, exist_ok=True)
        return str(path)

    def describe(self) -> str:
        return "a directory path (a non-empty string; an existing non-directory is refused)"


@dataclass(frozen=True)
class SchedulerAddress(ParamRule):
    """A Dask scheduler address ``tcp://HOST:PORT`` (or ``HOST:PORT``), or ``""`` for this machine. Only its form
    is checked here; whether a scheduler answers is checked when the notebook connects
    (:func:`tvtrack.explore.executor_for`)."""

    def check(self, value):
        if not isinstance(value, str):
            raise TypeError
        if value.strip():
            from .executors import SchedulerError, parse_scheduler_address

            try:
                parse_scheduler_address(value)
            except SchedulerError:
                raise TypeError from None
        return value.strip()

    def describe(self) -> str:
        return '"" (this machine) or a Dask scheduler address tcp://HOST:PORT'


#: Rules for the parameters every notebook has (see docs/contributing.md, "Writing a notebook").
COMMON_RULES: dict[str, ParamRule] = {
    "seed": Integer(0, 2**63 - 1),
    "n_trials": Integer(1, 10_000_000),
    "output_dir": OutputDir(),
    "rerun_mode": OneOf("file", "off", "notebook"),
}


def validate_parameters(namespace: Mapping[str, Any], rules: Mapping[str, ParamRule]) -> dict[str, Any]:
    """Check every parameter against its rule and return them as a plain dict.

    Parameters
    ----------
    namespace : mapping
        Where the parameters live (a notebook passes ``globals()``).
    rules : mapping of str to Rule
        The notebook's own rules; :data:`COMMON_RULES` are added for the common parameters
        unless the notebook overrides them.

    Returns
    -------
    dict
        ``{name: value}`` for every rule, in the rules' order, with integers and reals normalised.

    Raises
    ------
    ValueError
        On the first parameter that is missing or outside its allowed range, naming the
        parameter, its value and the allowed range.
    """
    merged = {**COMMON_RULES, **rules}
    checked: dict[str, Any] = {}
    for name, rule in merged.items():
        if name not in namespace:
            raise ValueError(f"parameter {name!r} is missing; it must be {rule.describe()}")
        value = namespace[name]
        try:
            checked[name] = rule.check(value)
        except (TypeError, ValueError):
            raise ValueError(f"parameter {name!r} = {value!r} is out of range; it must be {rule.describe()}") from None
    return checked


def cell_literals(source: str) -> dict[str, Any]:
    """``{name: value}`` of every assignment in a notebook's ``parameters`` cell: the literal value, or ``None``
    where the value is not a Python literal."""
    out = {}
    for node in ast.parse(source).body:
        if isinstance(node, ast.Assign):
            for target in node.targets:
                if isinstance(target, ast.Name):
                    try:
                        out[target.id] = ast.literal_eval(node.value)
                    except ValueError:
                        out[target.id] = None
    return out
