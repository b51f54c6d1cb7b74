"""C001-9's horizons and target sets (Fisenko et al. 2008, text before Fig. 1): the constants the register's
``horizon`` and ``targets`` entries name. Nothing is imported here, so the register reads them without an import
circle through :mod:`.spherical`, which measures them (and needs :mod:`.curves` for its prediction-RMS tolerance).
"""

__all__ = ["HORIZONS", "TARGET_SETS"]


#: C001-9's extrapolation horizon: the scenario's 10 s loss (seconds), or the 3rd-order filter's memory, its gain
#: bound k_b3 in frames (the register's 100 frames are 4 s at 25 Hz, 2 s at 50 Hz): the unit each is counted in.
HORIZONS = {"10 s loss": "s", "k_b3 filter memory": "frames"}


#: The target sets of C001-9: ranges m, speeds m/s, headings deg, initial elevations deg.
TARGET_SETS = {
    "2-20 km, 100-300 m/s": ((2e3, 5e3, 10e3, 20e3), (100.0, 300.0), (90.0, 45.0), (0.0, 10.0, 15.0)),
    "20-100 km, 50-250 m/s": ((20e3, 50e3, 100e3), (50.0, 250.0), (90.0, 45.0), (0.0, 10.0, 15.0)),
    "50-100 km, 100-300 m/s": ((50e3, 70e3, 100e3), (100.0, 300.0), (90.0, 45.0), (0.0, 10.0, 15.0)),
}
