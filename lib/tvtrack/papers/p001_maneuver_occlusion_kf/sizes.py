"""The run sizes of notebook 001: the keys of the ``sizes`` dict the notebook builds from its parameters and
passes to every measurement function of :mod:`.study`, and the register defaults a measurement projects each
claim's configuration onto (:func:`declared`).

This module imports the register only inside :func:`declared`, and nothing of the study, so the measurements can
read the register (whose entries name the study's values) without an import circle."""

from __future__ import annotations

from typing import Any, TypedDict

__all__ = ["Sizes", "declared"]


class Sizes(TypedDict, total=False):
    """Monte Carlo sizes and grids of one full-size run (a plain dict at run time).

    Keys
    ----
    n_trials : runs per condition; n_fa_runs, fa_duration_s : false-alarm runs and their length (s);
    sigma_eps : measurement noise (elements, the paper's 1); n_train, n_tradeoff_trials, train_seed : comparator tuning runs, trade-off runs and their seed;
    kb3_grid : the gain bounds of Fig. 4 (frames); loss_grid_s : loss start times (s); n_fig4_trials : runs per
    Fig. 4 point; grids : the comparators' tuning grids; defaults : the register's defaults; prediction_rms : the
    C001-9 tolerance (elements), set after the Fig. 4 study. The delay limit of C001-2 (``roc_delay_s``), its step
    (``step_dv``) and restart C's prior (``restart_accel_var``) are register entries, not sizes; what a
    measurement may read besides the register is listed in :data:`.register.RUN_SIZES`,
    :data:`.register.FIXED_BY_PAPER` and :data:`.register.PROJECT_GRIDS`.
    """

    n_trials: int
    n_fa_runs: int
    fa_duration_s: float
    sigma_eps: float
    n_train: int
    n_tradeoff_trials: int
    train_seed: int
    kb3_grid: Any
    loss_grid_s: Any
    n_fig4_trials: int
    grids: dict
    defaults: dict
    prediction_rms: float


def declared(args: tuple, kwargs: dict) -> tuple[dict, dict]:
    """``(DEPENDS, default)`` of a measurement called with ``sizes`` (positional after the seed, or by name): the
    default is the notebook's (``sizes["defaults"]``), else the register's (:func:`tvtrack.projection.as_declared`)."""
    from .register import DEPENDS, build_register

    sizes = kwargs.get("sizes", args[0] if args else {})
    return DEPENDS, sizes.get("defaults") or build_register().default()
