"""Performance bounds: (posterior) Cramer-Rao bounds for the measurement models."""
