"""What a reader would miss in a figure: a numeric axis without a label, an image without a colour bar saying its
values and unit. :meth:`tvtrack.results.Results.save_figure` records the problems beside the figure (the notebook
tests fail on any), so every figure a notebook shows keeps labelled axes and units."""

from __future__ import annotations

import re

__all__ = ["figure_problems"]


def _numeric(ticks) -> bool:
    """Whether an axis' drawn tick labels are numbers (mathtext such as ``10^{1}`` included): such an axis needs
    a label and its unit; text ticks (categories) say what they are."""
    texts = [t.get_text() for t in ticks if t.get_text()]
    clean = [re.sub(r"mathdefault|times|[$\\{}^ ]", "", t).replace("\u2212", "-") for t in texts]
    return bool(clean) and all(re.fullmatch(r"[-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?%?", t) for t in clean)


def figure_problems(fig) -> list[str]:
    """What a reader would miss in a figure, read after it is drawn (saved): a panel showing data whose numeric x
    or y axis has no label (an axis shared with a labelled one, or with no ticks or text ticks, needs none), and
    a single-channel image without a colour bar whose label says what its values are and in what unit.

    Returns
    -------
    list of str
        One line per problem, naming the panel by its title (else its number); empty where none.
    """
    problems = []
    for i, ax in enumerate(fig.axes):
        if hasattr(ax, "_colorbar") or not ax.axison or not ax.has_data():
            continue
        name = ax.get_title() or f"panel {i + 1}"
        for axis, ticks, shared in (
            ("x", ax.get_xticklabels(), ax.get_shared_x_axes()),
            ("y", ax.get_yticklabels(), ax.get_shared_y_axes()),
        ):
            labelled = [getattr(o, f"get_{axis}label")() for o in shared.get_siblings(ax)]
            if not any(labelled) and _numeric(ticks):
                problems.append(f"{name}: its {axis} axis has no label")
        for im in ax.images:
            cb = im.colorbar
            if im.get_array().ndim == 2 and (cb is None or not (cb.ax.get_ylabel() or cb.ax.get_xlabel())):
                problems.append(f"{name}: an image without a colour bar saying its values and unit")
    return problems
