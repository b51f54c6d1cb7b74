"""What a reader would miss in a figure: a numeric axis without a label, an image without a colour bar saying its
values and unit. :meth:`tvtrack.results.Results.save_figure` records the problems beside the figure (the notebook
tests fail on any), so every figure a notebook shows keeps labelled axes and units."""

from __future__ import annotations

import re

__all__ = ["figure_problems"]


#: A tick label that is a number once mathtext is stripped: ``-0.5``, ``1e+06``, ``20%``, ``10^-1``, ``2x10^3``.
_NUMBER = re.compile(r"[-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?%?|([-+]?(\d+\.?\d*)x)?10\^[-+]?\d+")


def _numeric(ticks) -> bool:
    """Whether an axis' drawn tick labels are numbers (mathtext such as ``10^{-1}`` included): such an axis needs
    a label and its unit; text ticks (categories) say what they are."""
    texts = [t.get_text() for t in ticks if t.get_text()]
    clean = [re.sub(r"mathdefault|[$\\{} ]", "", t).replace("times", "x").replace("\u2212", "-") for t in texts]
    return bool(clean) and all(_NUMBER.fullmatch(t) for t in clean)


def _panels(fig) -> list:
    """Every axes of ``fig`` with its inset axes (``ax.child_axes``), in drawing order."""
    out = []
    for ax in fig.axes:
        out += [ax, *(c for c in getattr(ax, "child_axes", []) if c not in fig.axes)]
    return out


def _colour_mapped(ax) -> list:
    """What maps values to colours in ``ax``: single-channel images (not truth masks) and collections drawn from
    an array through a colour map (pcolormesh, contourf, hexbin, scatter with ``c=`` values; not contour lines,
    which draw a level, often labelled inline)."""
    images = [im for im in ax.images if im.get_array().ndim == 2 and im.get_array().dtype.kind != "b"]
    return images + [c for c in ax.collections if c.get_array() is not None and getattr(c, "filled", True)]


def _labelled_bar(mappable) -> bool:
    cb = mappable.colorbar
    return cb is not None and bool(cb.ax.get_ylabel() or cb.ax.get_xlabel() or cb.ax.get_title())


def figure_problems(fig) -> list[str]:
    """What a reader would miss in a figure, read after it is drawn (saved): a panel showing data whose visible
    numeric x or y axis has no label (an axis shared with a labelled one, or with no ticks or text ticks, needs
    none), and colours mapped from values (an image, a mesh, filled contours, coloured points) without a colour
    bar whose label or title says what they are and in what unit. Inset axes are panels too.

    Returns
    -------
    list of str
        One line per problem, naming the panel by its title (else its number); empty where none.
    """
    problems = []
    for i, ax in enumerate(_panels(fig)):
        if hasattr(ax, "_colorbar") or not ax.axison or not ax.has_data():
            continue
        name = ax.get_title() or f"panel {i + 1}"
        for axis, part, ticks, shared in (
            ("x", ax.xaxis, ax.get_xticklabels(), ax.get_shared_x_axes()),
            ("y", ax.yaxis, ax.get_yticklabels(), ax.get_shared_y_axes()),
        ):
            labelled = [getattr(o, f"get_{axis}label")() for o in shared.get_siblings(ax)]
            if part.get_visible() and not any(labelled) and _numeric(ticks):
                problems.append(f"{name}: its {axis} axis has no label")
        if any(not _labelled_bar(m) for m in _colour_mapped(ax)):
            problems.append(f"{name}: colours mapped from values without a colour bar saying what they are")
    return problems
