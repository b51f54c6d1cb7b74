"""Estimators that work on whole image sequences (e.g. multi-frame EM location)."""
