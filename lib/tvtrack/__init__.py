"""tvtrack: a small library for reproducing papers on optical / television target tracking.

Three rooms (``tests/test_layout.py`` keeps them apart):

- the core, by role: :mod:`tvtrack.render` and :mod:`tvtrack.measure` (what the camera sees, gates and
  centroids), :mod:`tvtrack.filters` (Kalman with the one Joseph update, EKF, grid, IMM, alpha-beta,
  growing-memory, variable-dimension), :mod:`tvtrack.detect` (innovation detectors), :mod:`tvtrack.bounds`
  (Cramer-Rao bounds), :mod:`tvtrack.montecarlo` (seeded generators, intervals;
  re-exports :mod:`tvtrack.coverage` and :mod:`tvtrack.counts`), :mod:`tvtrack.register`
  (what a paper left unstated), :mod:`tvtrack.explore` (claims over the register and independent replicates),
  :mod:`tvtrack.verdicts` (rules and part-level labels), :mod:`tvtrack.results` (``results.json``, the
  claims table), :mod:`tvtrack.parameters`, :mod:`tvtrack.recordings` (Rerun) and :mod:`tvtrack.plotting`;
- one package per paper, :mod:`tvtrack.papers` (model, algorithms, register, study, plots, recording);
- the machinery: :mod:`tvtrack.pipeline` runs notebooks with papermill (runner, preflight, sweep,
  reproduce, report, site, viewer, cli).
"""

__version__ = "0.1.0"
