"""tvtrack: a small library for reproducing papers on optical / television target tracking.

Two layers. The science never imports the machinery (``tests/test_layout.py`` checks it):

- the science: :mod:`tvtrack.scenes`, :mod:`tvtrack.render` and :mod:`tvtrack.sensors` (what the camera
  sees), :mod:`tvtrack.measure` (gates and centroids), :mod:`tvtrack.filters` (Kalman, polynomial and
  tracking-loop filters), :mod:`tvtrack.detect`, :mod:`tvtrack.estimate`, :mod:`tvtrack.bounds`,
  :mod:`tvtrack.montecarlo` (seeded generators, intervals), :mod:`tvtrack.verdicts` (acceptance rules
  and robustness records), :mod:`tvtrack.results` (``results.json``) and :mod:`tvtrack.record`
  (Rerun recordings), with the paper-specific modules beside them;
- the machinery: :mod:`tvtrack.pipeline` runs notebooks with papermill (runner, preflight, sweep,
  reproduce, report, site, viewer, cli).
"""

__version__ = "0.1.0"
