"""One package per paper: each holds its model, algorithms, study drivers, register, plots and recording layout."""
