"""The Monte Carlo sizes and grids of one full-size run of paper 000's study (the notebook's parameters fill it;
:mod:`.study` runs it)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = ["Sizes"]


@dataclass(frozen=True)
class Sizes:
    """Monte Carlo sizes and grids of one full-size run (the notebook's parameters).

    Parameters
    ----------
    n_trials : int               runs per operating point
    duration_T, window_T : float run length and final steady-state window (T)
    dt : float                   sampling interval (T)
    substeps : int               midpoint sub-intervals of an integrated sample
    psi_grid, contrast_grid      Fig. 2 SNRs and Fig. 3 contrasts (the latter holds 0, 0.5 and 0.9)
    dt_points                    (psi_A, P) of the discretisation check (C000-8), over the Figs. 2-3 range
    dt_factor, dt_trials         fine step dt / dt_factor; runs of the discretisation check
    dt_duration_T : float        run length of the check (its steady window: the last third)
    grid_trials, grid_points     runs and nodes of the grid filter (only where a reading asks for it)
    lock_factor : float          out of lock: a scan's RMS error above lock_factor x the steady sigma
    acquire_by_T : float         "converges fairly quickly": within this many scans (this project's choice: 5 T)
    """

    n_trials: int = 600
    duration_T: float = 30.0
    window_T: float = 10.0
    dt: float = 0.05
    substeps: int = 5
    psi_grid: tuple = (2.0, 5.0, 10.0, 20.0, 50.0, 100.0)
    contrast_grid: tuple = (0.0, 0.25, 0.5, 0.7, 0.9)
    dt_points: tuple = ((5.0, 0.5), (20.0, 0.0), (20.0, 0.5), (20.0, 0.9), (100.0, 0.5))
    dt_factor: int = 10
    dt_trials: int = 200
    dt_duration_T: float = 15.0
    grid_trials: int = 100
    grid_points: int = 201
    lock_factor: float = 5.0
    acquire_by_T: float = 5.0

    @property
    def n_steps(self) -> int:
        return int(round(self.duration_T / self.dt))

    @property
    def steps_per_scan(self) -> int:
        return int(round(1.0 / self.dt))

    def window(self, n_columns: int | None = None):
        """Steady-state mask over the columns ``0..n_steps`` (the last ``window_T``)."""
        k = np.arange(self.n_steps + 1 if n_columns is None else n_columns)
        return k * self.dt > self.duration_T - self.window_T
