"""Each register entry of paper 004 in plain words (:data:`PLAIN`), for :mod:`.register`."""

__all__ = ["PLAIN"]

#: Every entry in plain words: {name: (title, {value: phrase})} (what a reader sees in the labels' "where" lists).
PLAIN = {
    "C004-2 statistic": (
        "error behind the paper's '1...2 pixels'",
        {
            "per-axis RMS": "RMS prediction error per image axis",
            "radial RMS": "RMS distance between the predicted and the measured spot centre",
        },
    ),
    "floor form": (
        "what the floor on the correction freezes",
        {
            "whole gain frozen": "the whole gain vector frozen at the floor",
            "first gain bounded": "only the position gain bounded at the floor (a variant set here)",
        },
    ),
    "spectral index": (
        "slope of the wander spectrum between its corners",
        {
            0.0: "wander mostly fast (flat spectrum between the corners)",
            2 / 3: "wander spectrum f^-2/3 between the corners (tilt-like)",
            5 / 3: "wander mostly slow (Kolmogorov-like f^-5/3 spectrum)",
        },
    ),
    "roll-off": (
        "how fast the wander spectrum falls above its corners",
        {
            "f^-4": "smooth wander (spectrum falling as f^-4)",
            "f^-2": "rough wander without a velocity (f^-2)",
            "f^-6": "smoother wander (spectrum falling as f^-6)",
            "G-tilt": "Tyler's turbulence tilt spectrum (G-tilt)",
        },
    ),
    "bandwidth": (
        "speed of the wander (a factor on its corner frequencies)",
        {
            1.0: "slow wander (fastest corner 0.5 Hz; the filter errs 0.33 px, below the paper's 1-2 px)",
            "calibrated": "wander re-calibrated in every world to the paper's 1-2 px (fastest corner 1.5 Hz in the "
            "default world)",
            8.0: "fast wander (fastest corner 4 Hz; the filter errs 3.9 px, above the paper's 1-2 px)",
        },
    ),
    "error in the band": (
        "where in the paper's 1-2 px its filter erred (the wander's speed set to put it there)",
        {
            1.0: "the wander's speed set so that the filter errs 1 px, the low end of the paper's 1-2 px",
            1.5: "the wander's speed set so that the filter errs 1.5 px, the middle of the paper's 1-2 px",
            2.0: "the wander's speed set so that the filter errs 2 px, the top of the paper's 1-2 px",
        },
    ),
    "amplitude": (
        "size of the wander (RMS x this)",
        {
            0.5: "half-size wander (1.5-4 px RMS)",
            1.0: "wander of 3-8 px RMS per axis",
            2.0: "double-size wander (6-16 px RMS)",
        },
    ),
    "jitter": (
        "frame-to-frame jitter of the spot (x the one-frame motion)",
        {
            0.0: "no frame-to-frame jitter",
            1.0: "jitter as large as the one-frame motion",
            4.0: "jitter 4x the one-frame motion",
        },
    ),
    "frame rate": (
        "camera frame rate",
        {25.0: "25 frames/s (as stated)", 200.0: "200 frames/s (the 'every 5 ms' of the text)"},
    ),
    "read noise": (
        "camera read noise",
        {
            2.0: "read noise 2 DN (clean camera)",
            16.0: "read noise 16 DN",
            64.0: "read noise 64 DN (spot barely above the noise)",
        },
    ),
    "saturation": (
        "sensor full scale",
        {"8-bit": "8-bit sensor (bright frames clip)", "none": "no clipping (16-bit converter)"},
    ),
    "scintillation": (
        "whole-spot fading (sigma of ln irradiance)",
        {0.3: "moderate fading (sigma ln I = 0.3)", 0.8: "strong fading (sigma ln I = 0.8)"},
    ),
    "energy centre": (
        "energy-centre algorithm",
        {
            "windowed": "energy centre in a window re-centred on itself",
            "whole gate": "energy centre over the whole 31 px gate",
        },
    ),
    "horizon": (
        "prediction horizon",
        {
            1: "predicting 1 frame (40 ms) ahead",
            3: "predicting 3 frames ahead",
            10: "predicting 10 frames (0.4 s) ahead",
        },
    ),
    "network lags": (
        "past centres fed to the networks",
        {"cross-validated": "network lag count chosen by cross-validation", 10: "networks fed a fixed 10 lags"},
    ),
    "network inputs": (
        "what the networks are fed",
        {
            "increments": "networks fed increments to the newest centre",
            "absolute centres": "networks fed the centres as measured",
        },
    ),
    "tuning": (
        "how the floor and the windows are chosen",
        {
            "cross-validated": "floor and windows chosen by cross-validation over paths",
            "fixed": "fixed floor N_f = 10 and window L = 10",
        },
    ),
    "reference": (
        "what the error is measured against",
        {"measured centre": "error against the next measured centre", "true centre": "error against the true centre"},
    ),
    "C004-1 statistic": (
        "statistic behind 'does not exceed 2 px'",
        {
            "95th percentile": "95th percentile of the per-axis error",
            "99th percentile": "99th percentile of the per-axis error",
            "radial 95th percentile": "95th percentile of the radial (2-D) error",
        },
    ),
    "spline": (
        "which spline extrapolates",
        {
            "interpolating": "cubic spline through the last L centres",
            "least-squares cubic": "least-squares cubic over the last L centres",
            "natural cubic": "natural cubic spline (straight beyond its last knot)",
        },
    ),
    "exposure": (
        "camera exposure",
        {
            "instant": "short exposure",
            "interlaced, frame integration": "interlaced TV camera integrating a whole frame",
        },
    ),
    "spot size": (
        "spot size (Gaussian sigma)",
        {4.0: "spot sigma 4 px", 0.6: "focused, undersampled spot (sigma 0.6 px)"},
    ),
    "C004-3 statistic": (
        "statistic the methods are ranked by",
        {"MSE": "ranked by mean squared error", "95th percentile": "ranked by the 95th percentile of the error"},
    ),
    "vibration": (
        "mount vibration at 8 Hz",
        {0.0: "no mount vibration", 1.0: "1 px mount vibration at 8 Hz"},
    ),
    "C004-8 pipeline": (
        "what is timed for 'real time'",
        {
            "batched plain centroid": "plain centroid timed in a batch",
            "streaming, the study's energy centre": "each frame timed as it arrives (the study's energy centre)",
        },
    ),
    "C004-8 statistic": (
        "statistic of the time per frame",
        {"mean": "mean time per frame", "99th percentile": "99th percentile of the time per frame"},
    ),
    "C004-8 frame": (
        "image area measured per frame",
        {"gate": "measured in the 31 px gate", "whole frame": "measured over the whole 128 x 128 frame"},
    ),
    "C004-8 clock": (
        "clock of the timing",
        {"CPU": "CPU time", "wall": "wall-clock time"},
    ),
    "lost frames": (
        "what the recursion does with a lost frame",
        {
            "held": "a lost frame's centre held at the last one",
            "skipped (coast)": "lost frames skipped (the recursion coasts)",
        },
    ),
    "frame loss": (
        "frames lost to obscuration or deep fades",
        {0.0: "no frame lost", 0.01: "frames lost (1 % of frames start a 1-5 frame obscuration)"},
    ),
    "C004-5 noise": (
        "law of the white measurement noise",
        {"Gaussian": "Gaussian noise", "Student t3": "heavy-tailed noise (Student t, 3 degrees of freedom)"},
    ),
}
