"""Each register entry's kind, with the line of the paper that decides it (:func:`tvtrack.register.with_kinds` applies
them; the three kinds are explained there)."""

from __future__ import annotations

#: {entry name: (kind, the line of the paper that decides it)}.
KINDS = {
    "sample model": (
        "unreported setting",
        "an unreported setting: how the paper's own Monte Carlo sampled the dissector current is never printed; "
        "(E5)-(E6)'s N0/dt fits the integrating sampler and the point sample alike",
    ),
    "scoring time": ("reading", "a reading of (E9)'s 'X1(k) - X1_hat(k|k)' for an integrated sample"),
    "photon model": ("model", "a world beyond the paper: eq. (1) makes the shot noise white Gaussian"),
    "manoeuvre": ("regime", "a world beyond the paper: its message is Gauss-Markov (eq. (8))"),
    "background": ("regime", "a world beyond the paper: eq. (2) holds N0 constant"),
    "sigma_sh": ("reading", "a reading of 'psi_A = A / sigma_sh', which names no bandwidth"),
    "G22": ("reading", "a reading of (E8)'s printed 2 beta_0 dt against eq. (8)"),
    "signal-noise scale": ("reading", "a reading of eq. (6)'s printed sqrt(A S) against eq. (2)'s N0 P/(1-P) S"),
    "v2 noise at": ("reading", "a reading of eq. (9)'s 'at the estimate'"),
    "initial estimate": ("reading", "a reading of which of Fig. 1's curves (solid or dashed) the claim is about"),
    "initial position": (
        "regime",
        "a world beyond the paper: eq. (3) makes the message stationary, so the object starts from its own law "
        "N(0, sigma_1^2); 'the image is within the micro-raster' motivates the filters' D11(0) = 0.2, not the truth's "
        "start",
    ),
    "convergence criterion": ("reading", "a reading of 'converge fairly quickly' (Conclusions)"),
    "lock threshold": ("reading", "a reading of what 'converged' requires of one run"),
    "C000-6 filter": ("reading", "a reading of the sentence whose opening is lost at a page break"),
    "potentially achievable": ("comparator", "a reading of 'potentially achievable', which the paper does not define"),
    "C000-3 accuracy": ("reading", "a reading of 'give approximately the same estimate of potential accuracy'"),
    "micro-raster size": ("reading", "a reading of '2 % of the micro-raster size'"),
    "psi_A": (
        "unreported setting",
        "an unreported setting: Figs. 1 and 3 were drawn at an SNR the paper never printed",
    ),
    "sigma_1": (
        "operating point",
        "a world beyond the paper: it calls sigma_1 / T = 0.1 'typical', 0.2 T is another image spread",
    ),
    "contrast": (
        "unreported setting",
        "an unreported setting: Figs. 1 and 2 were drawn at a contrast P the paper never printed",
    ),
    "contrast convention": (
        "unreported setting",
        "an unreported setting: what Fig. 3 held fixed as P varied is never printed",
    ),
    "steady window": ("statistic", "a reading of Fig. 2's 'steady' sigma_x^2, whose window is not given"),
    "C000-4 cost measure": ("reading", "a reading of 'needs more computation'"),
    "C000-4 batch": ("statistic", "a reading of C000-4's CPU ratio for a tracker that filters one object"),
    "substantially determines": ("reading", "a reading of 'for P > 0.5 it substantially determines the accuracy'"),
    "C000-2 contrasts": ("reading", "a reading of the Conclusions' '2 % at psi_A = 20', which names no contrast"),
    "C000-5 comparison": (
        "reading",
        "a reading of the Conclusions' 'accounting for the non-stationary noise component'",
    ),
    "statistic": (
        "scale",
        "a world beyond the paper: (E9) prints sigma_x^2 as the ensemble mean (its overline); the median run's "
        "variance is a yardstick the paper does not use, and a flip under it says a claim does not extend to it",
    ),
}
