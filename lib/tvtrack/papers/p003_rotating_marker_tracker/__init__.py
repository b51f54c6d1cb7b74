"""Paper 003 (Yukhno 2025): tracking a marker whose emitter rotates about the object, through interference.

Modules: :mod:`.scene` (the rotating-marker scene, interferers, decoy and the scenario runner), :mod:`.discriminators`
(quadrant and edge discriminators), :mod:`.loops` (the rotating-gate tracking loops and the EKF tracker),
:mod:`.lock` (loss-of-lock criterion, loss mechanisms, loss-curve fits), :mod:`.loss_study` (loss-curve studies over
SIR grids and seeds), :mod:`.study` (measurement functions the explorer calls), :mod:`.register` (unstated choices).
"""
