"""One package per paper: model, algorithms, study drivers, register, plots and recording layout."""
