"""Paper 002: Savanevich (1999), a unified location algorithm (ULA) for the linear motion of closely spaced objects.

Modules: ``model`` (the linear-motion scene: geometry, truth, designation, photon counts), ``em`` (the ULA: EM over
all frames, eqs. (10)-(11), with SQUAREM and the MAP variant), ``two_stage`` (per-frame marks and line fits, the
paper's comparator), ``simulation`` (one configuration's Monte Carlo: every algorithm on the same scenes, errors,
bounds, interval helpers), ``study`` (the measurement functions the explorer calls, the figure data and the
sentences' statistics), ``register`` (the unstated choices and which claim reads which), ``params`` (the notebook's
parameter rules), ``plots`` (one function per figure) and ``recording`` (the Rerun layout of one trial).
"""
