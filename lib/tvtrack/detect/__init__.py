"""Detectors and decision statistics (maneuver detection, loss of lock)."""
