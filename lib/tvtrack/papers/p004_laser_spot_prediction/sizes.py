"""The sizes of one run of paper 004's study (:mod:`.study`): paths, frames, grids, network sizes, and the
smaller size of a screen."""

from __future__ import annotations

from dataclasses import dataclass, replace

__all__ = ["StudySize", "screen_size"]


@dataclass(frozen=True)
class StudySize:
    """Sizes of one run (fixed for a notebook run; the register varies the world, not these).

    Attributes
    ----------
    n_paths, n_frames : int
        Paths per run and frames per path (the paper: 15 paths of up to 1000 images).
    eval_start : int
        First frame scored for every method (start-up excluded), frames.
    n_folds : int
        Cross-validation folds over paths.
    floor_grid, window_grid : tuple of int
        Candidates of the floor ``N_f`` and of the windows (each baseline's search starts at its
        degree + 1, :func:`.prediction_study.window_candidates`).
    fixed_floor, fixed_window : int
        The "fixed" tuning reading.
    mlp_hidden_units, rbf_centres, train_samples : int
        Network sizes and training pairs per fold.
    lag_grid : tuple of int
        Candidate lag counts of the networks when the register's "network lags" is "cross-validated"
        (:func:`.prediction_study.tune_learned_lags`).
    lag_tuning_samples : int
        Training pairs of each tuning model (at most ``train_samples``): the tuning fits ``len(lag_grid)``
        models per fold, so they are trained on fewer pairs than the final ones.
    n_mc_variance : int
        Monte Carlo series of the C004-5 variance check.
    timing_frames : int
        Full frames timed for C004-8.
    """

    n_paths: int = 15
    n_frames: int = 1000
    eval_start: int = 40
    n_folds: int = 3
    floor_grid: tuple = (3, 4, 5, 7, 10, 15, 20, 30, 50, 100, 200)
    window_grid: tuple = (4, 6, 8, 10, 15, 20, 30)
    fixed_floor: int = 10
    fixed_window: int = 10
    mlp_hidden_units: int = 16
    rbf_centres: int = 100
    train_samples: int = 4000
    n_mc_variance: int = 20000
    timing_frames: int = 200
    lag_grid: tuple = (1, 2, 4, 8, 16)
    lag_tuning_samples: int = 500


def screen_size(size: StudySize) -> StudySize:
    """The explorer's cheaper screen of the joint design (``explore(screen=...)``): the same paths and folds at
    half the frames (at least 200), a quarter of the networks' training pairs (at least 300), a quarter of the
    variance check's series and the lag grid's two ends; a joint configuration whose screened verdict is not
    decisively the default's is measured again at ``size``. A run of fewer than 400 frames (the smoke profile) is
    returned as it is: halving it would leave too few frames. Measured at paper size (32 joint configurations,
    seed 2005), the screen sent all 32 to full size, so the notebook does not screen (docs/validity/004.md)."""
    if size.n_frames < 400:
        return size
    lags = tuple(sorted({min(size.lag_grid), max(size.lag_grid)}))
    return replace(
        size,
        n_frames=max(200, size.n_frames // 2),
        train_samples=max(300, size.train_samples // 4),
        lag_tuning_samples=min(size.lag_tuning_samples, max(300, size.train_samples // 4)),
        n_mc_variance=max(1000, size.n_mc_variance // 4),
        lag_grid=lags,
        timing_frames=min(size.timing_frames, 100),
    )
