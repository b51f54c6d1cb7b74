"""One package per paper: its model, algorithms, study (measurement functions), register, plots and recording."""
