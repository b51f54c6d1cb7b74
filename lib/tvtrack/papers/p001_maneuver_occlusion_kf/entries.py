"""The entries of notebook 001's register (:mod:`.register`): what Fisenko et al. (2008) left unstated, each with
its default, every defensible value and why, and the words a reader sees for each value.

Entries with ``origin="adversarial"`` were added while trying to flip the labels: the measurement-error models of
a real TV measurer, the arming reading that lets every window and bound test before the onset, the switch time
of Fig. 4 within the detection spread, an RMS span that includes reacquisition, the frame rate for the curves;
and, from the independent reviewer's pass, a manoeuvre that ends, a weaker second channel, long-range targets and
the filter-memory horizon of C001-9.
"""

from __future__ import annotations

from ...register import Entry
from .scenario import (
    ACCEL_UNITS,
    ARMING_RULES,
    CHANNEL_Y,
    COMPENSATION_COMPARATORS,
    MANOEUVRES,
    NOISE_MODELS,
    RMS_SPANS,
    TEST_CADENCES,
    THRESHOLD_READINGS,
    UMP_COMPARATORS,
)
from .spherical_sets import HORIZONS, TARGET_SETS
from .tradeoff import RMS_STATISTICS

__all__ = ["ENTRIES"]

ENTRIES = (
    Entry(
        "threshold",
        "reading",
        "exact",
        THRESHOLD_READINGS,
        "c(alpha) from sigma_S: the paper assumes independent samples with sigma 'the RMS velocity error at the "
        "filter output' (independent) or of the raw increments its independence argument is about; the "
        "correlated values (stationary Lyapunov; exact for the time-varying gains and coasts) are what (14) needs",
        title="how the detector's threshold c(alpha) is computed",
        phrases={
            "exact": "threshold from the exact spread of S for the actual, time-varying gains (correlation included)",
            "stationary": "threshold from the spread of S of the filter at its frozen gains (correlation included)",
            "independent": "threshold as the paper derives it: independent samples with the filter-output velocity "
            "error",
            "raw increments": "threshold as the paper derives it with the error of the raw coordinate increments",
        },
    ),
    Entry(
        "alpha",
        "reading",
        1e-3,
        (1e-4, 1e-3, 1e-2),
        "'c(alpha) computed from the given alpha', alpha not given; 1e-3 (this project's choice) is meant to keep "
        "false alarms in the 5 s before the manoeuvre rare; a decade either side. C001-1, -2 and -3 are each judged at this "
        "alpha (their rates in multiples of it)",
        title="false-alarm probability per test alpha the detector is designed for (and C001-1 to -3 judged at)",
        phrases={
            1e-4: "detector designed for one false alarm in 10,000 tests",
            1e-3: "detector designed for one false alarm in 1,000 tests",
            1e-2: "detector designed for one false alarm in 100 tests",
        },
    ),
    Entry(
        "arming",
        "reading",
        "gains at bound",
        ARMING_RULES,
        "not stated; sigma 'known and the same for all samples' needs both windows at the frozen gains "
        "(k_b2 + 2n); the earliest valid test has two windows of least-squares velocities (2n + 1) with the "
        "exact threshold; a rule that would first test after the onset arms when its windows are full (the "
        "paper's detector runs before the manoeuvre, Fig. 2)",
        title="when the manoeuvre detector starts testing",
        phrases={
            "gains at bound": "the detector starts once both windows hold velocities of the filter at its frozen gains",
            "windows full": "the detector starts as soon as both windows hold fitted velocities",
        },
    ),
    Entry(
        "test_cadence",
        "unreported setting",
        TEST_CADENCES[0],
        TEST_CADENCES,
        "the paper observes the output velocities 'on an interval 2T ... following at the frame rate' and splits it "
        "into T1 and T2; how often decision (14) is taken is never printed: every frame (sliding windows), every n "
        "frames, or once per interval 2T (disjoint intervals, the literal reading of 'on an interval 2T')",
        "adversarial",
        title="how often the armed manoeuvre detector takes its decision",
        phrases={
            "every frame": "the detector decides at every frame (sliding windows)",
            "every n frames": "the detector decides every n frames (windows overlapping by half)",
            "every 2n frames": "the detector decides once per interval 2T (disjoint intervals)",
        },
    ),
    Entry(
        "window_n",
        "reading",
        25,
        (10, 25, 50),
        "half-window n = T f not stated; 25 frames (1 s, chosen here) matches the 0.5 s delay; 0.4 s and 2 s",
        title="detector half-window n (frames per window)",
        phrases={
            10: "detector windows of 10 frames (0.4 s at 25 Hz)",
            25: "detector windows of 25 frames (1 s at 25 Hz)",
            50: "detector windows of 50 frames (2 s at 25 Hz)",
        },
    ),
    Entry(
        "k_bound2",
        "reading",
        50,
        (30, 50, 100),
        "2nd-order gain bound not stated ('narrow band'); 50 frames (chosen here) matches the 0.5 s delay",
        title="frame at which the 2nd-order filter's gains stop decreasing (k_b2)",
        phrases={
            30: "2nd-order gains frozen at frame 30 (wider band)",
            50: "2nd-order gains frozen at frame 50",
            100: "2nd-order gains frozen at frame 100 (narrower band)",
        },
    ),
    Entry(
        "frame_rate_hz",
        "unreported setting",
        25.0,
        (25.0, 50.0),
        "the paper states its motion per frame (10 el/frame, an acceleration of 0.2 el/frame²) and its times in "
        "seconds (onset 5 s, detection 5.5 s, loss 12-22 s), and Fig. 4's bound in frames; the frame rate that "
        "turns the seconds into frames is never printed: TV frame (25 Hz) or field (50 Hz) rate, the per-frame "
        "motion the same at both",
        "adversarial",
        title="camera frame rate (Hz), the paper's per-frame motion kept and its times in seconds",
        phrases={
            25.0: "25 frames per second (TV frame rate)",
            50.0: "50 frames per second (TV field rate; the same motion per frame, every time twice the frames)",
        },
    ),
    Entry(
        "noise",
        "model",
        "white Gaussian",
        NOISE_MODELS,
        "the paper: Gaussian, zero mean, 1 element RMS; a TV coordinate measurer quantises to whole elements, "
        "its errors correlate between frames and it has outliers (same RMS)",
        "adversarial",
        title="measurement error of the coordinate measurer (always 1 element RMS)",
        phrases={
            "white Gaussian": "independent Gaussian measurement errors (the paper's)",
            "quantised": "measurements rounded to whole raster elements",
            "AR(1), rho = 0.5": "measurement errors correlated between frames (lag-one correlation 0.5)",
            "Student t, 3 dof": "measurement errors with outliers (Student t, 3 degrees of freedom)",
        },
    ),
    Entry(
        "alternative",
        "reading",
        "ramp",
        ("ramp", "step"),
        "hypotheses (5) compare the window means: (14) is UMP for a common offset (a velocity step); the "
        "paper's manoeuvre is a constant acceleration (a ramp)",
        title="manoeuvre against which the detector's optimality is judged",
        phrases={
            "ramp": "optimality judged against the paper's manoeuvre, a constant acceleration",
            "step": "optimality judged against a sudden velocity step, the case (14) is derived for",
        },
    ),
    Entry(
        "paper_sigma",
        "reading",
        "filter-output velocity",
        ("filter-output velocity", "raw increments"),
        "the sigma of (4) is 'the RMS velocity error at the filter output', while the independence argument "
        "before it is about the raw increments at the filter input",
        title="which velocity error the paper's independence threshold uses",
        phrases={
            "filter-output velocity": "the paper's threshold built from the filter-output velocity error",
            "raw increments": "the paper's threshold built from the error of the raw coordinate increments",
        },
    ),
    Entry(
        "restart",
        "reading",
        "A",
        ("A", "B", "C"),
        "'the coefficients are increased' at the switch, no rule given: A restarts the 3rd-order law at k = 3 "
        "with a = 0; B fits a quadratic to the window; C is a covariance-consistent Kalman reset",
        title="how the gains are raised when a manoeuvre is detected",
        phrases={
            "A": "on detection the 3rd-order gain law restarts at its third frame, acceleration set to zero",
            "B": "on detection a quadratic is fitted to the detector's window and the gain law restarts from it",
            "C": "on detection a Kalman reset with a broad prior on the acceleration",
        },
    ),
    Entry(
        "restart_accel_var",
        "reading",
        1e4,
        (1e2, 1e4, 1e6),
        "restart C's prior variance of the acceleration (elements²/frame⁴): not in the paper (restart C is "
        "ours); 1e4 is diffuse against the 0.2 el/frame² manoeuvre; two decades either side",
        title="restart C: prior variance of the acceleration at the reset (elements²/frame⁴)",
        phrases={
            1e2: "restart C with a prior acceleration spread of 10 el/frame²",
            1e4: "restart C with a prior acceleration spread of 100 el/frame²",
            1e6: "restart C with a prior acceleration spread of 1000 el/frame²",
        },
    ),
    Entry(
        "k_bound3",
        "reading",
        100,
        (50, 100, 200),
        "3rd-order gain bound not stated; Fig. 4's axis spans 20-200 frames",
        title="frame at which the 3rd-order filter's gains stop decreasing (k_b3)",
        phrases={
            50: "3rd-order gains frozen 50 frames after the restart",
            100: "3rd-order gains frozen 100 frames after the restart",
            200: "3rd-order gains frozen 200 frames after the restart",
        },
    ),
    Entry(
        "rms_statistic",
        "statistic",
        RMS_STATISTICS[0],
        RMS_STATISTICS,
        "C001-4: 'sped up the transient of the dynamic error and minimised the RMS (СКО)' keeps the two errors "
        "apart (Fig. 4's curves 1 and 2 too), so the RMS is the random error (SD over runs); the total mean "
        "square (bias and random together) and '|bias| + RMS at 12 s' (the acceptance first set here) are the "
        "other readings",
        title="what 'the gain law minimises the RMS error' measures (C001-4)",
        phrases={
            "random error (SD)": "RMS read as the random error (spread over runs), the dynamic error judged apart",
            "total mean square": "RMS read as the total mean-square error (dynamic and random together)",
            "|bias| + RMS at 12 s": "RMS read as |mean error| + random error at 12 s, when the object is lost "
            "(the acceptance first set here)",
        },
    ),
    Entry(
        "rms_span",
        "statistic",
        "4 s to loss",
        RMS_SPANS,
        "the span the RMS of C001-4 is taken over. Default 4 s to the loss: the tracking interval of Fig. 3 once "
        "the 2nd-order gains (bound at 2 s) and the detector (armed at 4 s) have settled, to the loss at 12 s; it "
        "contains the switch's transient because the claim is about the whole gain law, transient included. Also "
        "the manoeuvre only, every visible frame including reacquisition, or the prediction at the end of the loss "
        "(Fig. 4's quantity)",
        "adversarial",
        title="span of frames the RMS error of C001-4 is taken over",
        phrases={
            "4 s to loss": "RMS over the tracking from 4 s to the loss at 12 s",
            "onset to loss": "RMS over the manoeuvre only, 5 s to the loss at 12 s",
            "visible after 4 s": "RMS over every visible frame after 4 s, reacquisition included",
            "end of the loss": "RMS of the prediction at the end of the loss (Fig. 4's quantity)",
        },
    ),
    Entry(
        "compensation_end_s",
        "statistic",
        8.0,
        (6.0, 8.0, 12.0),
        "'speeds up compensation of the dynamic error': the dynamic error from the onset to a time; 12 s is the loss",
        title="end of the interval over which the dynamic error's compensation is scored (s)",
        phrases={
            6.0: "dynamic error scored from the onset to 6 s",
            8.0: "dynamic error scored from the onset to 8 s",
            12.0: "dynamic error scored from the onset to the loss at 12 s",
        },
    ),
    Entry(
        "occlusion",
        "reading",
        "scenario 12-22 s",
        ("scenario 12-22 s", "from 10 s"),
        "Fig. 4: 'disappearance at the 10th second' against the scenario's loss at 12 s and return at 22 s",
        title="the loss Fig. 4's prediction error is computed for",
        phrases={
            "scenario 12-22 s": "Fig. 4 for the scenario's loss from 12 to 22 s",
            "from 10 s": "Fig. 4 for a 10 s loss starting at 10 s",
        },
    ),
    Entry(
        "switch_s",
        "operating point",
        5.5,
        (5.3, 5.5, 6.0),
        "Fig. 4 and C001-7 force the switch at the paper's detection time 5.5 s; 5.3 s and 6.0 s are an early and a "
        "late detection around it",
        "adversarial",
        title="time of the forced order switch for Fig. 4 and the loss-time sweep (s)",
        phrases={
            5.3: "order switch forced at 5.3 s (an early detection)",
            5.5: "order switch forced at 5.5 s (the paper's detection time)",
            6.0: "order switch forced at 6.0 s (a late detection)",
        },
    ),
    Entry(
        "curve_tolerance",
        "statistic",
        0.01,
        (0.001, 0.01, 0.1),
        "C001-8 judges deterministic curves (noise-free runs, covariance recursion): a step smaller than this many "
        "elements counts as flat (C001-7's steps are judged against the random prediction error instead). 0.01 el is 1 % of the measurement RMS, below what Fig. 4's axis (tens "
        "of elements) can show; the curves are flat by construction where the gains never reach the bound before "
        "the loss, and float rounding (1e-6) must not read as a trend",
        title="smallest step of a deterministic error curve that counts as a change (elements)",
        phrases={
            0.001: "curve steps under 0.001 element count as flat",
            0.01: "curve steps under 0.01 element (1 % of the measurement error) count as flat",
            0.1: "curve steps under 0.1 element count as flat",
        },
    ),
    Entry(
        "extrapolation",
        "reading",
        "quadratic",
        ("quadratic", "linear"),
        "C001-9: the paper coasts with the 3rd-order filter (quadratic); 'linear' is its own word",
        title="how the angle is extrapolated through the loss (C001-9)",
        phrases={
            "quadratic": "angle extrapolated with its rate and acceleration, as the 3rd-order filter coasts",
            "linear": "angle extrapolated with its rate only (the paper's word 'linear')",
        },
    ),
    Entry(
        "targets",
        "regime",
        "2-20 km, 100-300 m/s",
        tuple(TARGET_SETS),
        "C001-9: the paper names no target; aircraft-like crossings at 2-20 km, or distant slow ones (20-100 km), "
        "where the angular motion curves least, or aircraft at 50-100 km, the range of a 0.15 mrad/element "
        "long-range TV tracker (the last added by the adversarial pass)",
        "adversarial",
        title="grid of target geometries C001-9 is also checked on",
        phrases={
            "2-20 km, 100-300 m/s": "aircraft crossing at 2-20 km, 100-300 m/s",
            "20-100 km, 50-250 m/s": "distant, slower targets at 20-100 km, 50-250 m/s",
            "50-100 km, 100-300 m/s": "aircraft at 50-100 km, 100-300 m/s",
        },
    ),
    Entry(
        "manoeuvre",
        "regime",
        "constant acceleration",
        tuple(MANOEUVRES),
        "the paper gives the onset (5 s) and the acceleration (0.2 el/frame²), not how long it lasts; held to 22 s "
        "it takes the velocity from 10 to 95 el/frame, while a 2 s manoeuvre doubles it and then ends",
        "adversarial",
        title="how long the manoeuvre's acceleration lasts",
        phrases={
            "constant acceleration": "the acceleration lasts to the end of the run",
            "2 s acceleration": "the acceleration lasts 2 s, then the object moves uniformly again",
        },
    ),
    Entry(
        "compensation_comparator",
        "comparator",
        COMPENSATION_COMPARATORS[0],
        COMPENSATION_COMPARATORS,
        "C001-4 credits the switch to 3rd order: against the filter that never switches, or against the same "
        "detection raising the 2nd-order gains without changing the order (its bound tuned for the measure)",
        "adversarial",
        title="filter the faster compensation of C001-4 is compared with",
        phrases={
            COMPENSATION_COMPARATORS[0]: "compared with the 2nd-order filter that never switches",
            COMPENSATION_COMPARATORS[1]: "compared with the 2nd-order filter whose gains are raised at the same "
            "detection (no change of order)",
        },
    ),
    Entry(
        "C001-4 switch",
        "reading",
        "detected",
        ("detected", "forced at the detection time"),
        "C001-4 credits the gain law with the smaller RMS; Fig. 4 is computed here with the switch at the paper's "
        "detection time 5.5 s (the filter then linear), while in the scheme the switch comes when the detector "
        "fires, so the spread of the detection time enters the random error; the text does not say which error the "
        "sentence means",
        "adversarial",
        title="when the scheme switches to 3rd order in C001-4's errors",
        phrases={
            "detected": "the scheme switching when its detector fires (the detection time's spread included)",
            "forced at the detection time": "the scheme switching at the paper's detection time, as Fig. 4 is "
            "computed (the gain law alone)",
        },
    ),
    Entry(
        "ump_comparator",
        "comparator",
        UMP_COMPARATORS[0],
        UMP_COMPARATORS,
        "C001-2's 'most powerful among invariant rules': any function of z is invariant; against Q, or against the "
        "GLS-weighted sum w·z (w = C_z⁻¹ 1), the most powerful invariant test for a common offset with the filter "
        "outputs' correlation",
        "adversarial",
        title="other invariant test the detector's power is compared with (C001-2)",
        phrases={
            UMP_COMPARATORS[0]: "power compared with the sum of squared window differences",
            UMP_COMPARATORS[1]: "power compared with the correlation-weighted window difference",
        },
    ),
    Entry(
        "roc_delay_s",
        "reading",
        0.5,
        (0.25, 0.5, 1.0),
        "C001-2's power comparison counts a detection within this delay of the onset; 0.5 s is the paper's own "
        "detection delay (5 s -> 5.5 s); half and twice it",
        title="delay after the onset within which a detection counts (C001-2's power, s)",
        phrases={
            0.25: "a detection counts within 0.25 s of the onset",
            0.5: "a detection counts within 0.5 s of the onset (the paper's delay)",
            1.0: "a detection counts within 1 s of the onset",
        },
    ),
    Entry(
        "step_dv",
        "operating point",
        1.0,
        (0.5, 1.0, 2.0),
        "the velocity step of C001-2's step alternative (elements/frame): not in the paper; 1 el/frame is the "
        "velocity the paper's manoeuvre adds in 5 frames (0.2 s at 25 Hz); half and twice it",
        title="size of the velocity step in C001-2's step alternative (elements/frame)",
        phrases={
            0.5: "velocity step of 0.5 element/frame",
            1.0: "velocity step of 1 element/frame",
            2.0: "velocity step of 2 elements/frame",
        },
    ),
    Entry(
        "accel_unit",
        "reading",
        "el/frame²",
        tuple(ACCEL_UNITS),
        "'acceleration 0.2 raster elements per frame': per frame² (this project's default), or 0.2 el/frame of "
        "velocity gained per second, the paper giving every time in seconds (0.2/f el/frame² at f frames per "
        "second: 0.008 at 25 Hz)",
        "adversarial",
        title="unit of the paper's 'acceleration 0.2 raster elements per frame'",
        phrases={
            "el/frame²": "acceleration of 0.2 element per frame² (this project's default reading)",
            "el/frame per s": "acceleration of 0.2 element/frame gained per second (25 times smaller at 25 Hz)",
        },
    ),
    Entry(
        "channel_y",
        "regime",
        "v -6, a -0.2",
        tuple(CHANNEL_Y),
        "the paper simulated one channel; the second channel's motion is this project's choice; a turn mostly in x "
        "gives y a quarter of x's acceleration (C001-1 pools both channels)",
        "adversarial",
        title="motion of the second (elevation) channel",
        phrases={
            "v -6, a -0.2": "second channel: -6 el/frame, acceleration -0.2 el/frame² (as strong as the first)",
            "v -6, a -0.05": "second channel: -6 el/frame, acceleration -0.05 el/frame² (a quarter of the first)",
        },
    ),
    Entry(
        "horizon",
        "reading",
        "10 s loss",
        tuple(HORIZONS),
        "C001-9: 'accuracy acceptable for prediction' over the 10 s loss, or over the span the 3rd-order filter "
        "fits a polynomial to (its memory, k_b3 frames: 100 frames are 4 s at 25 Hz)",
        "adversarial",
        title="time over which the angle must stay predictable (C001-9)",
        phrases={
            "10 s loss": "predictable over the 10 s loss",
            "k_b3 filter memory": "predictable over the k_b3 frames the 3rd-order filter remembers",
        },
    ),
    Entry(
        "tolerance",
        "reading",
        "1 element",
        ("1 element", "prediction RMS at k_b3"),
        "'accuracy acceptable for prediction': the measurement error (1 element) or the random prediction "
        "error at reappearance",
        title="deviation from a straight line that is 'acceptable for prediction' (C001-9)",
        phrases={
            "1 element": "acceptable if within 1 raster element (the measurement error)",
            "prediction RMS at k_b3": "acceptable if within the random prediction error at reappearance",
        },
    ),
    Entry(
        "loss_length_s",
        "regime",
        10.0,
        (10.0, 5.0, 2.0),
        "the paper's loss lasts 10 s (12-22 s; Fig. 4's 'at the 10th second'); a cloud or an obstruction can hide "
        "the object for less. C001-7's sweep and Fig. 4 with a loss of 5 s or 2 s (added by an adversarial review)",
        "adversarial",
        title="how long the object stays lost in Fig. 4 and the loss-time sweep (s)",
        phrases={
            10.0: "the object lost for 10 s (the paper's)",
            5.0: "the object lost for 5 s",
            2.0: "the object lost for 2 s",
        },
    ),
)
