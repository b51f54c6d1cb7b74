"""Sensor models other than the staring pixel array of :mod:`tvtrack.render` (e.g. image dissector)."""
