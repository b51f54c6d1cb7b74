"""Each register entry's kind, with the line of the paper that decides it (:func:`tvtrack.register.with_kinds` applies
them; the three kinds are explained there)."""

from __future__ import annotations

#: {entry name: (kind, the line of the paper that decides it)}.
KINDS = {
    "epoch": ("reading", "a reading of 'coordinates' (captions) against 'initial position' and 'parameters' (text)"),
    "statistic": ("statistic", "a reading of 'sum of variances'"),
    "accuracy ratio of C002-11": ("statistic", "a reading of 'x4 difference in accuracy'"),
    "gross errors": ("statistic", "a reading of a 1999 Monte Carlo 'sum of variances'"),
    "photon model": (
        "model",
        "a world beyond the paper: the paper observes each frame's relative photon frequencies v*_ikl and its "
        "likelihood (3) gives every frame the same weight, which is its maximum likelihood only when every frame "
        "holds the same number of photons, so 'the number of target photons m_k' (with p_j its relative weight) is "
        "a fixed count in the paper's model; Poisson counts per frame are a world it did not model, in which the "
        "ULA (fed counts, exact there) weighs a bright frame more and the two-stage's unweighted line fit does not: "
        "C002-12's flip under Poisson counts comes from that line fit",
    ),
    "designation error (sigma)": (
        "unreported setting",
        "an unreported setting: the accuracy of the designation that started the paper's algorithms is never printed",
    ),
    "noise (photons/sigma^2/frame)": (
        "unreported setting",
        "an unreported setting: the noise weight p_o of the paper's simulation is never printed",
    ),
    "velocity (sigma/frame)": (
        "unreported setting",
        "an unreported setting: the velocities of the paper's simulated objects are never printed",
    ),
    "tracks": (
        "unreported setting",
        "an unreported setting: the motion of the paper's two 'close' objects is never printed (parallel tracks are the fixed distance its figures' axes read)",
    ),
    "EM stopping": ("reading", "a reading of 'practically stop changing'"),
    "two-stage": ("comparator", "a reading of ref. [4]'s trajectory algorithm, which the paper does not describe"),
    "ULA": ("comparator", "a reading of the ULA against designation-started marks (the paper's ULA is ML)"),
    "velocity knowledge": ("reading", "a reading of 'initial conditions' given by the designation"),
    "Delta of Figs 4, 5, 7 (sigma)": (
        "unreported setting",
        "an unreported setting: Figs 4, 5 and 7 were drawn at a pixel size the paper never printed",
    ),
    "T of Figs 4, 6, 7": (
        "unreported setting",
        "an unreported setting: Figs 4, 6 and 7 were drawn at a number of frames the paper never printed",
    ),
    "EM tolerance of Fig 7": ("reading", "a reading of 'practically stop changing' for Fig 7's iteration counts"),
    "m_k of Fig 5": (
        "unreported setting",
        "an unreported setting: Fig 5 was drawn at a photon count the paper never printed",
    ),
    "m_k of C002-12": ("reading", "a reading of the 'practically coincide' statement, which names no photon count"),
    "T of Figs 1a,b": (
        "unreported setting",
        "an unreported setting: Figs 1a,b were drawn at a number of frames the paper never printed",
    ),
    "m_k of C002-1": ("reading", "a reading of which of Fig 1's 10- and 20-photon curves C002-1 is about"),
    "Delta of C002-1 (sigma)": (
        "reading",
        "a reading of which of Fig 1's panels (3 or 1 sigma pixels) C002-1 is about",
    ),
    "m_k of Fig 1c": ("reading", "a reading of the text's m_k = 10 against the caption's 50"),
    "T of the Fig 3a claims": ("reading", "a reading of the conclusions, which do not say at which T"),
    "coarse Delta of C002-7, C002-8 (sigma)": ("reading", "a reading of 'large pixels', 'poor CCDs'"),
    "Delta of the C002-9 order (sigma)": (
        "unreported setting",
        "an unreported setting: Fig 3a was drawn at a pixel size the paper never printed",
    ),
    "separation of C002-5 (sigma)": ("reading", "a reading of C002-5's statement, which gives no separation"),
    "small separations of C002-6 (sigma)": ("reading", "a reading of 'fewer photons weaken the T dependence'"),
    "m_k pair of C002-6": (
        "operating point",
        "a world beyond the paper: Fig 2 compares 20 and 10 photons, 10 against 5 is one step fainter",
    ),
    "coordinate of C002-6": ("statistic", "a reading of Fig 2's 'of the coordinate' (singular)"),
    "Delta of C002-6 (sigma)": (
        "operating point",
        "a world beyond the paper: Fig 2 is drawn at Delta = sigma, 3 sigma is Fig 1a's",
    ),
    "T pair of C002-6": (
        "operating point",
        "a world beyond the paper: Fig 2 is drawn at T = 10 and 5 (l. 105, 'T=10,5', curves 1 and 2), 5 against 50 "
        "frames is Fig 5's frame span",
    ),
    "T dependence of C002-6": ("statistic", "a reading of Fig 2's lost axis scale"),
    "close separations of C002-10 (sigma)": ("reading", "a reading of 'the gain grows with pixel size and frames'"),
    "distance unit of C002-11": (
        "reading",
        "a reading of 'the reduced distances between the objects 3 and 1', which names no unit",
    ),
    "bound": ("statistic", "a reading of 'practically potential accuracy', which names no bound"),
    "pixel pair of C002-5": ("reading", "a reading of C002-5's citation of Figs 1c and 2a"),
    "very close separation of C002-15 (sigma)": ("reading", "a reading of 'very close objects'"),
}
