"""One package per paper: its model, algorithms, study (measurement) functions, register, claims, plots,
recording layout and parameter rules, exporting the names of the paper contract (:mod:`tvtrack.contract`).
Packages here import the core (``tvtrack.*``) and never each other; the core and the pipeline never import them
(``tests/test_layout.py``).

``TVTRACK_PAPER_PATH`` (folders separated by ``os.pathsep``) adds folders where further paper packages live, e.g.
a paper ``python -m tvtrack new`` wrote into another tree (``tests/test_new_paper.py``)."""

import os

__path__ = [*__path__, *(p for p in os.environ.get("TVTRACK_PAPER_PATH", "").split(os.pathsep) if p)]
