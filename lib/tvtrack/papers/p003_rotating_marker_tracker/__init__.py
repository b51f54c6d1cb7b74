"""Paper 003 (Yukhno 2025): tracking a marker whose emitter rotates about the object, through interference.

Modules: :mod:`.scene` (the rotating-marker scene, interferers, decoy and the scenario runner), :mod:`.discriminators`
(quadrant and edge discriminators, S-curves), :mod:`.loops` (the rotating-gate tracking loops, their coupled
frequency response, the EKF trackers (five states, and with velocity), the 1-D two-emitter tracker), :mod:`.crb`
(the posterior CRB and the trackers against it), :mod:`.lock` (loss-of-lock criterion, loss
criteria and mechanisms, the omega lock detector, logistic loss-curve fits), :mod:`.study` (the measurement functions
the explorer calls, on direct counts), :mod:`.register` (what the paper left unstated), :mod:`.params` (parameter
rules), :mod:`.plots`, :mod:`.prose` (generated sentences) and :mod:`.recording` (Rerun layout).
"""
