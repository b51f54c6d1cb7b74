"""Paper 001: Fisenko, Vilesov, Mozheiko, Fisenko (2008), manoeuvre detection and prediction through occlusion.

Modules: :mod:`.track_modes` (the per-channel TRACK2 / TRACK3 / COAST mode logic), :mod:`.maneuver_detector`
(the two-window manoeuvre detector of eqs. (3)-(14) and its thresholds), :mod:`.study` (the measurement functions
the explorer calls), :mod:`.register` (the notebook's register of unstated choices).
"""
