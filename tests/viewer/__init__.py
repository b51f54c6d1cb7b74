"""The Rerun viewer check (a package, so its conftest does not shadow ``tests/conftest.py``)."""
