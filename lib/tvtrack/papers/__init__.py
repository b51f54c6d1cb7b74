"""One package per paper: its model, algorithms, study (measurement) functions, register, plots,
recording layout and parameter rules. Packages here import the core (``tvtrack.*``) and never each
other; the core and the pipeline never import them (``tests/test_layout.py``)."""
