"""Each register entry of paper 002 in plain words (:data:`PLAIN`), for :mod:`.register`."""

from __future__ import annotations

__all__ = ["PLAIN"]

_FIG1 = {3.0: "pixels 3 sigma wide (Fig 1a)", 1.0: "pixels 1 sigma wide (Fig 1b)"}
_PIX = {v: f"pixels {v:g} sigma wide" for v in (0.5, 1.0, 3.0, 5.0)}
#: Each entry in plain words: ``{name: (title, {value: phrase})}`` (sigma: the PSF's standard deviation; Delta: the
#: pixel size; m_k: target photons per object per frame; T: frames; d: the distance between the objects).
PLAIN = {
    "epoch": (
        "time at which the position error is scored",
        {
            "first": "error of the initial position, at the first frame (the paper's 'initial position')",
            "mid": "error of the position at the middle frame",
            "last": "error of the position at the last frame",
            "velocity": "error of the velocity instead of the position (the text's 'parameters')",
        },
    ),
    "statistic": (
        "how the spread of the errors is summarised",
        {
            "variance": "sum of the variances of the coordinates (the captions' 'sum of variances')",
            "MSE": "sum of the mean squared errors (bias included)",
        },
    ),
    "accuracy ratio of C002-11": (
        "what C002-11's 'x4 difference in accuracy' compares",
        {
            "variance": "a ratio of variance sums (the captions' 'sum of variances')",
            "SD": "a ratio of standard deviations ('x4 difference in accuracy' as RMS)",
        },
    ),
    "gross errors": (
        "whether lost-object errors count",
        {
            "kept": "every trial's error counts",
            "trimmed 10 %": "the 10 % largest errors of every spread dropped (anomalous errors discarded)",
        },
    ),
    "photon model": (
        "number of target photons per frame",
        {
            "fixed": "exactly m_k target photons per object per frame",
            "poisson": "a Poisson number of target photons with mean m_k",
        },
    ),
    "designation error (sigma)": (
        "error of the target designation that starts both algorithms, sigma per coordinate",
        {0.3: "designation within 0.3 sigma of the truth", 1.0: "designation as coarse as the PSF (1 sigma)"},
    ),
    "noise (photons/sigma^2/frame)": (
        "uniform noise photons per sigma^2 per frame",
        {0.01: "faint noise: 0.01 photons per sigma^2 per frame", 0.05: "five times the noise: 0.05 per sigma^2"},
    ),
    "velocity (sigma/frame)": (
        "common velocity of the objects, sigma per frame",
        {
            "0, 0": "motionless objects",
            "0.2, 0.1": "objects moving 0.22 sigma per frame",
            "0.5, 0.25": "objects moving 0.56 sigma per frame",
        },
    ),
    "tracks": (
        "geometry of the two tracks",
        {
            "parallel": "parallel tracks a constant distance d apart",
            "crossing": "tracks that cross at mid-sequence (d apart at both ends)",
            "diverging": "tracks that separate from d to 3 d (satellites after release)",
        },
    ),
    "EM stopping": (
        "when the EM of both algorithms stops",
        {
            "SQUAREM to 1e-6 sigma": "EM run to convergence (accelerated, parameters stable to 1e-6 sigma)",
            "plain EM, cap 100": "plain EM stopped after at most 100 iterations",
            "plain EM to a log-likelihood gap of 0.1": "plain EM stopped within 0.1 nats of each algorithm's own "
            "maximum (a practical stop: the same gap for the ULA and each frame's mark, not the same added error)",
        },
    ),
    "two-stage": (
        "how the two-stage comparator starts and associates its marks",
        {
            "designation start, labels by start": "marks started at the designation, labelled by their start",
            "previous start + assignment": "marks started from the previous frame, assigned to the designation",
            "designation start + line association": "marks started at the designation, associated by straight lines",
            "no designation: moment start + line association": "marks found without any designation, associated "
            "by straight lines",
        },
    ),
    "ULA": (
        "the single-stage estimator",
        {
            "ML": "the ULA as published (maximum likelihood)",
            "MAP (designation prior)": "the ULA with the designation as a prior (maximum a posteriori)",
        },
    ),
    "velocity knowledge": (
        "what both algorithms know of the velocity",
        {
            "free": "velocity estimated from the frames by both algorithms",
            "designated": "the designated velocity given to both algorithms",
        },
    ),
    "Delta of Figs 4, 5, 7 (sigma)": ("pixel size of Figs 4, 5 and 7", _PIX),
    "T of Figs 4, 6, 7": ("frames of Figs 4, 6 and 7", {10: "10 frames in Figs 4, 6, 7", 20: "20 frames"}),
    "EM tolerance of Fig 7": (
        "when the iterations counted in Fig 7 stop",
        {
            "1e-6 sigma": "iterations counted to convergence (1e-6 sigma)",
            "log-likelihood gap 0.01": "iterations counted to within 0.01 nats of each EM's maximum",
            "log-likelihood gap 0.1": "iterations counted to within 0.1 nats of each EM's maximum",
        },
    ),
    "m_k of Fig 5": (
        "target photons of Fig 5",
        {20: "20 photons per object per frame in Fig 5", 50: "50 photons in Fig 5", 10: "10 photons in Fig 5"},
    ),
    "m_k of C002-12": (
        "target photons where the algorithms should coincide",
        {20: "20 photons per object per frame", 10: "10 photons (the faintest of Figs 1c, 2)"},
    ),
    "T of Figs 1a,b": ("frames of Fig 1a,b", {5: "5 frames (as Fig 1c)", 10: "10 frames (as Fig 2)"}),
    "m_k of C002-1": ("target photons of C002-1", {20: "the 20-photon curve of Fig 1", 10: "the 10-photon curve"}),
    "Delta of C002-1 (sigma)": ("pixel size of C002-1", _FIG1),
    "m_k of Fig 1c": ("target photons of Fig 1c", {10: "10 photons (the text)", 50: "50 photons (the caption)"}),
    "T of the Fig 3a claims": (
        "frames at which the one-object claims are read",
        {5: "one object over 5 frames", 10: "one object over 10 frames", 50: "one object over 50 frames"},
    ),
    "coarse Delta of C002-7, C002-8 (sigma)": (
        "what 'large pixels' means",
        {3.0: "large pixels = 3 sigma", 5.0: "large pixels = 5 sigma"},
    ),
    "Delta of the C002-9 order (sigma)": ("pixel size of the Fig 3a ordering", _PIX),
    "separation of C002-5 (sigma)": (
        "distance between the objects in C002-5",
        {1.0: "objects 1 sigma apart", 2.0: "objects 2 sigma apart", 3.0: "objects 3 sigma apart"},
    ),
    "small separations of C002-6 (sigma)": (
        "distances over which C002-6 is read",
        {1.0: "objects at most 1 sigma apart", 2.0: "objects at most 2 sigma apart", 8.0: "the whole distance axis"},
    ),
    "m_k pair of C002-6": (
        "photon counts C002-6 compares",
        {"20 vs 10": "20 against 10 photons (Fig 2)", "10 vs 5": "10 against 5 photons (one step fainter)"},
    ),
    "coordinate of C002-6": (
        "coordinates whose variance C002-6 reads",
        {
            "both": "both coordinates of both objects",
            "along the separation": "only the coordinate along the separation",
            "across the separation": "only the coordinate across the separation",
        },
    ),
    "Delta of C002-6 (sigma)": ("pixel size of C002-6", {1.0: "pixels 1 sigma wide (Fig 2)", 3.0: _FIG1[3.0]}),
    "T pair of C002-6": (
        "frame counts C002-6 compares",
        {"5 vs 10": "5 against 10 frames (Fig 2)", "5 vs 50": "5 against 50 frames"},
    ),
    "T dependence of C002-6": (
        "how the dependence on the number of frames is measured",
        {
            "relative (log ratio)": "as a ratio of variances (a log axis)",
            "absolute (variance gap)": "as a difference of variances in sigma^2 (a linear axis)",
        },
    ),
    "close separations of C002-10 (sigma)": (
        "distances where the ULA's gain is read",
        {1.0: "objects 1 sigma apart", 2.0: "objects up to 2 sigma apart", 3.0: "objects up to 3 sigma apart"},
    ),
    "pixel pair of C002-5": (
        "pixel sizes whose influence C002-5 reads",
        {
            "3 vs 1": "pixels 3 sigma wide against 1 sigma wide (Figs 1c and 2a together)",
            "5 vs 3": "pixels 5 sigma wide against 3 sigma wide (the two pixel sizes of Fig 1c)",
        },
    ),
    "very close separation of C002-15 (sigma)": (
        "distance between the objects at which 'very close' is read",
        {
            1.0: "very close = 1 sigma apart (the smallest distance the text names)",
            0.5: "very close = 0.5 sigma apart (the closest objects of the distance axis)",
        },
    ),
    "distance unit of C002-11": (
        "unit of C002-11's 'reduced distances 3 and 1'",
        {
            "sigma": "distances of 3 and 1 PSF sigmas (this project's default)",
            "pixel": "distances of 3 and 1 pixels of Fig 5 (3 and 1 Delta)",
        },
    ),
    "bound": (
        "the 'potential accuracy'",
        {
            "CRB": "the Cramer-Rao bound (unbiased estimators)",
            "van Trees (designation prior)": "the van Trees bound with the designation as prior (any estimator)",
        },
    ),
}
