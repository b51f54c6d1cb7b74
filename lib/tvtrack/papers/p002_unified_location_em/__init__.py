"""Paper 002: Savanevich (1999), a unified location algorithm (ULA) for the linear motion of closely spaced objects.

Modules: ``model`` (the linear-motion scene: geometry, truth, designation, photon counts), ``em`` (the ULA: EM over
all frames, eqs. (10)-(11), with SQUAREM and the MAP variant), ``two_stage`` (per-frame marks and line fits, the
paper's comparator), ``study`` (the Monte Carlo study and the measurement functions the explorer calls),
``register`` (the unstated choices), ``plots`` and ``recording``.
"""
