"""Scene generators: object motion and what the sensor sees, built on :mod:`tvtrack.render`."""
