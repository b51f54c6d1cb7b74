"""The machinery that runs notebooks: papermill runs, sweeps, the report, the command line and the
headless Rerun viewer check. The science modules of :mod:`tvtrack` never import from here."""
