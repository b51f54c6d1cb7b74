"""One package per paper (issue 23): model, algorithms, study drivers, register, plots, recording."""
