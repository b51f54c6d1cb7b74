"""The register of what paper 000 (Martyshevsky 1995) leaves unstated, and which claims read which entries.

Every entry names its default, its defensible values and why; :func:`tvtrack.explore.explore` measures every
claim over it (:func:`.study.measure` reads the configuration). Rows with ``origin="adversarial"`` were added
while trying to flip a label.
"""

from __future__ import annotations

from ...register import Entry, Register
from .rules import CONVERGENCE_READINGS
from .study import JOINT_READING_C6

__all__ = ["REGISTER", "DEPENDS"]

REGISTER = Register(
    [
        # ---- the data model: decided once, the filters, the grid likelihood and the PCRLB model the same sample
        Entry(
            "sample model",
            "model",
            "integrated",
            ("integrated", "point"),
            "a sampled tracker integrates the current over each dt (integrate and dump: the noise variance N/dt of the "
            "paper's (E5), (E6)); the point sample is the textbook idealisation the filters, grid filter and PCRLB model "
            "exactly",
        ),
        Entry(
            "scoring time",
            "reading",
            "interval end",
            ("interval end", "interval centre"),
            "the paper's error (E9) is the filtering error X1(k) - X1_hat(k|k): the estimate against the message at "
            "the time of its newest datum, the end of the sample's integration interval; the filters model an "
            "integrated sample by the pulse at its interval centre, so scoring there (half an interval of later data "
            "in the estimate, a short smoother) is the other reading (a point sample is scored at its instant)",
        ),
        Entry(
            "photon model",
            "model",
            "Gaussian",
            ("Gaussian", "Poisson counts"),
            origin="adversarial",
            why="eq. (1) models the shot noise as white Gaussian; it is the count statistics of photo-electrons, skewed "
            "at few counts per sample (about 5 background electrons per sample at psi_A = 20, P = 0.9)",
        ),
        Entry(
            "manoeuvre",
            "regime",
            "none",
            ("none", "weave 0.1 T / 2 T"),
            origin="adversarial",
            why="the filters assume a Gauss-Markov message; a real object also manoeuvres: a weave of amplitude sigma_1 "
            "(0.1 T) over 2 scans (still sampled by the once-per-scan pulse), random phase per run (a 5-scan weave "
            "moved C000-2 and C000-3 less: left out to spare the paper profile)",
        ),
        Entry(
            "background",
            "regime",
            "stationary",
            ("stationary", "drifting +-50 %"),
            origin="adversarial",
            why="eq. (2) holds the background intensity N0 constant; a real background (sky, scattered light) drifts: "
            "N0 (1 + 0.5 sin(2 pi t / 10 T + phase)), unknown to the filters, a random phase per run",
        ),
        # ---- readings of the paper's ambiguous or inconsistent sentences
        Entry(
            "sigma_sh",
            "reading",
            "per sample",
            ("per sample", "unit bandwidth"),
            "psi_A = A / sigma_sh: the RMS of the background noise in one sample sqrt(N0/dt), or in a 1/T bandwidth "
            "sqrt(N0) (4.5 times more noise per sample at the same psi_A)",
        ),
        Entry(
            "G22",
            "reading",
            "paper",
            ("paper", "euler", "matched"),
            "(E8) prints 2 beta_0 dt (a unit-variance X2); Euler on eq. (8) gives beta_0^2 dt; the matched value makes "
            "sqrt(c_s S) X2 carry the truth's per-sample signal-noise variance",
        ),
        Entry(
            "v2 noise at",
            "reading",
            "predicted estimate",
            ("predicted estimate", "updated estimate"),
            "eq. (9) evaluates the noise intensity at 'the estimate': the prediction is the only one before the update; "
            "one re-evaluation at the updated estimate is the other reading",
        ),
        Entry(
            "initial estimate",
            "reading",
            "process means",
            ("process means", "random N(0, D11(0))"),
            "the paper's solid curves start at the process means; its dashed curves from normally distributed initial "
            "estimates of unstated variance (read as D(0))",
        ),
        Entry(
            "initial position",
            "reading",
            "stationary N(0, sigma_1^2)",
            ("stationary N(0, sigma_1^2)", "uniform in the micro-raster"),
            origin="adversarial",
            why="'the image is within the micro-raster' (the paper's motivation of D11(0) = 0.2): the message's own law, "
            "or anywhere in the raster with equal probability",
        ),
        Entry(
            "convergence criterion",
            "reading",
            CONVERGENCE_READINGS[0],
            CONVERGENCE_READINGS,
            "'converge fairly quickly' (Conclusions) gives no measure: the time by which 90 % of runs are in lock for "
            "good, or the card's ensemble-mean sigma_x^2 within 10 % of its steady value",
        ),
        Entry(
            "lock threshold",
            "reading",
            "lock_factor",
            ("lock_factor", "2 x steady RMS"),
            origin="adversarial",
            why="'in lock' is not the paper's word: a scan's RMS error above the notebook's lock_factor (5) x the steady "
            "RMS error, or a strict 2 x (a scan's error at twice its steady value counts as not yet acquired)",
        ),
        Entry(
            "C000-6 filter",
            "reading",
            "variant 2",
            ("variant 2", "variant 1", "ignoring the signal noise"),
            "the sentence's opening is lost at a page break: 'accounting for' (a matched variant) or 'ignoring' (the "
            "filter that assumes P = 0) the non-stationary component",
        ),
        Entry(
            "potentially achievable",
            "comparator",
            "sigma_x^2*",
            ("sigma_x^2*", "PCRLB", "grid filter"),
            "'potentially achievable' is undefined: the stationary-noise accuracy of Fig. 3 (the paper's own "
            "reference), the posterior Cramer-Rao bound, or the near-optimal grid (point-mass) filter",
        ),
        Entry(
            "C000-6 joint reading",
            "reading",
            "the entries above",
            ("the entries above", JOINT_READING_C6),
            origin="adversarial",
            why="a flip the joint samples can miss: 'ignoring' the component, with the background current held fixed "
            "(psi_A = 180 at P = 0.9); its ensemble mean is carried by the 3-4 % of runs that lose lock",
        ),
        Entry(
            "C000-3 accuracy",
            "reading",
            "Monte Carlo error",
            ("Monte Carlo error", "filters' own D11"),
            origin="adversarial",
            why="'the two algorithms give approximately the same estimate of potential accuracy': the accuracy they "
            "achieve (the Monte Carlo error), or the accuracy each computes for itself (its steady covariance D11)",
        ),
        Entry(
            "micro-raster size",
            "reading",
            "T",
            ("T", "T_u"),
            origin="adversarial",
            why="'2 % of the micro-raster size': the coordinate is a time shift within the scan interval T; the pulse "
            "duration T_u = T/2 is the other length a reader could take",
        ),
        # ---- operating points of the figures the claims come from
        Entry(
            "psi_A",
            "operating point",
            20.0,
            (2.0, 5.0, 10.0, 20.0, 50.0, 100.0),
            "Figs. 1 and 3 do not state psi_A; 20 is the only SNR the paper quotes; Fig. 2 spans 2-100 (2 added by the "
            "adversarial pass: there C000-5 and C000-7 turn partly)",
        ),
        Entry(
            "sigma_1",
            "operating point",
            "0.1 T",
            ("0.1 T", "0.2 T"),
            origin="adversarial",
            why="the paper calls sigma_1 / T = 0.1 'typical'; 0.2 T is an image spread over the micro-raster (within "
            "+-T/2 of its centre 98 % of the time; D11(0) = 0.2 is the paper's own prior spread), alpha_0 T = 0.15 kept",
        ),
        Entry(
            "contrast",
            "operating point",
            0.5,
            (0.0, 0.5, 0.9),
            "Figs. 1 and 2 do not state P; 0.5 is the paper's boundary, 0.9 its high-contrast example",
        ),
        Entry(
            "contrast convention",
            "operating point",
            "fixed N0",
            ("fixed N0", "fixed total current", "fixed background"),
            "what is held fixed as P varies in Fig. 3 is unstated: N0 (only P/(1-P) changes), the total current or the "
            "background current (psi_A then moves with P, anchored at psi_A at P = 0.5)",
        ),
        # ---- statistics
        Entry(
            "steady window",
            "scale",
            "window_T",
            ("window_T", "after 5 T"),
            origin="adversarial",
            why="Fig. 2's steady sigma_x^2 is read over an unstated window: the notebook's final window_T, or every "
            "sample after the 5 T transient (more samples, closer to the transient)",
        ),
        Entry(
            "C000-4 cost measure",
            "reading",
            "operation count",
            ("operation count", "CPU time"),
            "'needs more computation': the arithmetic of one filter step (multiplications, additions and divisions "
            "of each variant's equations, counted; deterministic), or the CPU time of the vectorised filters (least "
            "of 5 repeats; it moves between machines and runs, so it never enters the README's results)",
        ),
        Entry(
            "C000-4 batch",
            "scale",
            "all trials",
            ("all trials", "one trial"),
            "the paper's tracker filters one object; a Monte Carlo batch amortises the Python overhead per step, so "
            "the CPU ratio of C000-4 is read both ways (a register row so that joint samples combine it with "
            "'v2 noise at')",
            origin="adversarial",
        ),
        Entry(
            "statistic",
            "statistic",
            "mean",
            ("mean", "median"),
            "the paper's sigma_x^2 is an ensemble mean (E9); the median of per-run variances is not carried by the few "
            "runs that lose lock",
        ),
    ]
)

_DATA = ["sample model", "scoring time", "sigma_sh", "photon model"]
#: The entries each claim reads (the explorer counts a condition for a claim only if it changes one of them).
DEPENDS = {
    "C000-4": ["C000-4 cost measure", "v2 noise at", "C000-4 batch"],
    "C000-1": _DATA
    + ["G22", "v2 noise at", "initial estimate", "initial position", "convergence criterion", "psi_A", "contrast"]
    + ["sigma_1", "lock threshold"],
    "C000-2": _DATA + ["G22", "v2 noise at", "micro-raster size", "sigma_1", "manoeuvre", "steady window"],
    "C000-3": _DATA
    + ["G22", "v2 noise at", "psi_A", "contrast", "contrast convention", "statistic", "sigma_1"]
    + ["C000-3 accuracy", "manoeuvre", "steady window"],
    "C000-5": _DATA
    + ["v2 noise at", "psi_A", "contrast convention", "statistic", "sigma_1", "background", "steady window"]
    + ["manoeuvre"],
    "C000-6": _DATA
    + [
        "G22",
        "v2 noise at",
        "C000-6 filter",
        "C000-6 joint reading",
        "potentially achievable",
        "psi_A",
        "contrast convention",
        "statistic",
    ],
    "C000-7": _DATA
    + ["v2 noise at", "psi_A", "contrast convention", "statistic", "sigma_1", "background", "steady window"]
    + ["manoeuvre"],
    "C000-8": ["sigma_sh", "G22", "v2 noise at", "contrast convention"],
    "C000-9": _DATA + ["G22", "v2 noise at", "contrast", "statistic", "sigma_1", "steady window"],
}
