"""Each register entry's kind, with the line of the paper that decides it (:func:`tvtrack.register.with_kinds` applies
them; the three kinds are explained there)."""

from __future__ import annotations

#: {entry name: (kind, the line of the paper that decides it)}.
KINDS = {
    "threshold": (
        "reading",
        "a reading of (14)'s sigma_S: 'the RMS velocity error at the filter output' under independence",
    ),
    "alpha": (
        "unreported setting",
        "an unreported setting: 'c(alpha) computed from the given alpha', a value the paper never printed",
    ),
    "arming": ("unreported setting", "an unreported setting: when the paper's detector first tests is never printed"),
    "test_cadence": (
        "unreported setting",
        "an unreported setting: the velocities are observed 'on an interval 2T' at the frame rate (before (3)); how "
        "often (14) decides is never printed",
    ),
    "window_n": ("unreported setting", "an unreported setting: the half-window n = T f of (14) is never printed"),
    "k_bound2": (
        "unreported setting",
        "an unreported setting: the 2nd-order gain bound ('narrow band') is never printed",
    ),
    "frame_rate_hz": (
        "unreported setting",
        "an unreported setting: the paper's TV system's frame rate is never printed; its motion is stated per "
        "frame ('10 raster elements per frame', 'acceleration 0.2 raster elements per frame') and kept so at every "
        "frame rate, only its times in seconds become frames",
    ),
    "noise": ("model", "a world beyond the paper: it simulated Gaussian noise of 1 element RMS"),
    "alternative": ("reading", "a reading of hypotheses (5), UMP for a step, against the paper's ramp"),
    "paper_sigma": ("reading", "a reading of (4)'s sigma against the independence argument before it"),
    "restart": ("reading", "a reading of 'the coefficients are increased' at the switch"),
    "restart_accel_var": ("reading", "a reading of the same sentence as restart (the constant of its restart C)"),
    "k_bound3": (
        "unreported setting",
        "an unreported setting: the 3rd-order gain bound is never printed (Fig. 4's axis spans 20-200)",
    ),
    "rms_statistic": ("statistic", "a reading of 'minimised the RMS (SKO)' beside the dynamic error"),
    "rms_span": ("statistic", "a reading of the span 'the RMS' of C001-4 is taken over"),
    "compensation_end_s": ("statistic", "a reading of 'speeds up compensation of the dynamic error'"),
    "occlusion": ("reading", "a reading of Fig. 4's 'disappearance at the 10th second' against the 12-22 s loss"),
    "switch_s": (
        "operating point",
        "a world beyond the paper: it states the detection at 5.5 s; 5.3 s and 6.0 s are an early and a late detection",
    ),
    "curve_tolerance": ("statistic", "a reading of a 'flat' deterministic curve on Fig. 4's axis"),
    "extrapolation": ("reading", "a reading of C001-9's coasting: the 3rd-order filter, or its own word 'linear'"),
    "targets": ("regime", "a world beyond the paper: it names no target for C001-9"),
    "manoeuvre": (
        "unreported setting",
        "an unreported setting: the paper gives the onset and the acceleration; how long its manoeuvre lasted is never printed",
    ),
    "compensation_comparator": ("comparator", "a reading of what C001-4 credits the switch against"),
    "C001-4 switch": (
        "reading",
        "a reading of 'minimised the RMS': the gain law's error with the switch at Fig. 4's 5.5 s, or the scheme's",
    ),
    "ump_comparator": ("comparator", "a reading of 'most powerful among invariant rules' (C001-2)"),
    "roc_delay_s": ("reading", "a reading of C001-2's power: a detection within the paper's own 0.5 s delay"),
    "step_dv": ("operating point", "a world beyond the paper: the step alternative is not in it"),
    "accel_unit": ("reading", "a reading of 'acceleration 0.2 raster elements per frame'"),
    "channel_y": ("regime", "a world beyond the paper: it simulated one channel"),
    "horizon": ("reading", "a reading of 'accuracy acceptable for prediction' (C001-9): over what span"),
    "tolerance": ("reading", "a reading of 'accuracy acceptable for prediction' (C001-9): against what error"),
    "loss_length_s": ("regime", "a world beyond the paper: its loss lasts 10 s (12-22 s)"),
}
