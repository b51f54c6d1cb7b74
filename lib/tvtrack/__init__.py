"""tvtrack: a small library for reproducing papers on optical / television target tracking.

Modules are named for what they do:

- :mod:`tvtrack.parameters`  validating a notebook's parameters before any work starts
- :mod:`tvtrack.montecarlo`  seeded generators and Monte Carlo summaries (trials on the leading axis)
- :mod:`tvtrack.results`     the ``results.json`` every run writes (metrics, claims with verdicts)
- :mod:`tvtrack.record`      Rerun recordings (images, gates, truth, estimates, series, blueprints)
- :mod:`tvtrack.render`      pixel-integrated scene rendering and sensor read-out
- :mod:`tvtrack.measure`     gates and measurements inside them (centroids)
- :mod:`tvtrack.filters`     batched Kalman and polynomial (growing-memory) filters
- :mod:`tvtrack.pipeline.runner`, :mod:`tvtrack.pipeline.sweep`, :mod:`tvtrack.pipeline.report`  running notebooks and sweeps
"""

__version__ = "0.1.0"
