"""Paper 000: Martyshevsky (1995), coordinate accuracy of an image-dissector tracker under signal-dependent noise.

Modules: :mod:`.model` (the scan, the message, the data generators), :mod:`.ekf` (the paper's two EKFs),
:mod:`.reference` (grid filter, PCRLB), :mod:`.baseline` (centroid + fixed-gain tracker), :mod:`.settling`
(steady state, settling and acquisition), :mod:`.study` (measurement functions), :mod:`.register` (unstated choices).
"""
