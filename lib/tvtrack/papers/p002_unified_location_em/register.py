"""The register of what Savanevich (1999) left unstated, and which claims read which entry.

Each entry's ``why`` says why its values are defensible; ``origin="adversarial"`` marks rows added while trying to
flip a label (the designation-free and velocity-knowledge readings of the comparison, motionless objects, a
stopped-early EM, the Bayesian bound; in a second pass the photon pair and the coordinate of C002-6 and the
practical stopping tolerance of Fig 7's iteration counts; in a fourth the pixel size, the frame pair and the
T-dependence statistic of C002-6; in an adversarial review the separation that is "very close" in C002-15 and the pixel
pair of C002-5; in a fifth the unit of C002-11's distances). :data:`DEPENDS` names the entries each claim's
measurement reads: an entry left out cannot change that claim's number (it changes only simulation points the claim
does not use).
"""

from __future__ import annotations

from dataclasses import replace

from tvtrack.register import Entry, Register

from ...register import with_kinds
from .kinds import KINDS
from .plain import PLAIN

__all__ = ["REGISTER", "DEPENDS", "PLAIN"]


def _plain(entry: Entry) -> Entry:
    title, phrases = PLAIN[entry.name]
    return replace(entry, title=title, phrases={v: t for v, t in phrases.items() if v in entry.values})


REGISTER = Register(
    [
        Entry(
            "epoch",
            "reading",
            "first",
            ("first", "mid", "last", "velocity"),
            "captions say 'coordinates' and the text 'initial position'; the frame the accuracy is read at is not given; "
            "the text of Figs 4-6 says 'parameters', which includes the velocities",
        ),
        Entry(
            "statistic",
            "statistic",
            "variance",
            ("variance", "MSE"),
            "'sum of variances' may include bias (MSE); every spread, gain and log gain reads it",
        ),
        Entry(
            "accuracy ratio of C002-11",
            "statistic",
            "variance",
            ("variance", "SD"),
            "'x4 difference in accuracy' may be a ratio of SDs (the paper does not say which); only C002-11 quotes a "
            "ratio of the paper's own, so only C002-11 reads it: a band the study set on a variance ratio (C002-2's "
            "1.6-2.4, C002-7's 1.2, C002-12's 0.9-1.1, C002-15's 0.8-1.5) would follow the statistic to its square "
            "root, and an ordering against 1 is the same under a square root, so under an SD ratio no other claim's "
            "verdict could change",
        ),
        Entry(
            "gross errors",
            "statistic",
            "kept",
            ("kept", "trimmed 10 %"),
            "a Monte Carlo 'sum of variances' of 1999 may have dropped anomalous (lost-object) errors; the 10 % largest "
            "per-trial squared errors trimmed in every spread and gain (never in the bound's efficiency)",
            origin="adversarial",
        ),
        Entry(
            "photon model",
            "model",
            "fixed",
            ("fixed", "poisson"),
            "'m_k target photons' may be a fixed count or a Poisson mean (the paper does not say which); the CRB is "
            "Poisson's",
        ),
        Entry(
            "designation error (sigma)",
            "regime",
            0.3,
            (0.3, 1.0),
            "the target designation that starts both algorithms has no stated accuracy (0.3 sigma is this project's "
            "default); a designation as coarse as the PSF is where a designation-started two-stage would lose its help",
        ),
        Entry(
            "noise (photons/sigma^2/frame)",
            "regime",
            0.01,
            (0.01, 0.05),
            "the noise weight p_o is never given; this project's default level and five times it",
        ),
        Entry(
            "velocity (sigma/frame)",
            "regime",
            "0.2, 0.1",
            ("0, 0", "0.2, 0.1", "0.5, 0.25"),
            "velocities are not stated; motionless objects have no sub-pixel phase diversity",
            origin="adversarial",
        ),
        Entry(
            "tracks",
            "regime",
            "parallel",
            ("parallel", "crossing", "diverging"),
            "the paper's objects are 'close' but their motion is not given; objects released together may cross (a "
            "case tried here) or separate, like the satellites released by one launcher the paper names "
            "(C002-16); claims read along 'the distance between objects' presume a fixed distance, so only the claims "
            "on labour and on very close objects read it",
            origin="adversarial",
        ),
        Entry(
            "EM stopping",
            "reading",
            "SQUAREM to 1e-6 sigma",
            ("SQUAREM to 1e-6 sigma", "plain EM, cap 100", "plain EM to a log-likelihood gap of 0.1"),
            "the paper stops when the parameters 'practically stop changing'; a practical cap may stop plain EM early, "
            "and so may a practical stop: each EM stops when the log-likelihood it can still gain (Aitken's estimate) "
            "is below 0.1 nats, whether its likelihood pools T frames (ULA) or one (a mark). The same gap is not the "
            "same added error: a mark's likelihood holds one frame's photons, the ULA's all T frames', so the same "
            "gap leaves a mark further from its own maximum in sigma, every mark short towards the designation it "
            "started at, and the line through the marks averages those shortfalls without cancelling them; the "
            "added error of each algorithm varies with the frames and the distance (the adversarial pass that "
            "added this reading found no gap rule giving both the same added error at every frame count and "
            "distance). So the default runs both to convergence (the "
            "comparison the claims are judged on) and the practical stop is kept as what it is, a reading of the "
            "paper's stopping rule under which the two-stage gains a shrinkage towards its start",
            origin="adversarial",
        ),
        Entry(
            "two-stage",
            "comparator",
            "designation start, labels by start",
            (
                "designation start, labels by start",
                "previous start + assignment",
                "designation start + line association",
                "no designation: moment start + line association",
            ),
            "ref. [4]'s trajectory algorithm is not described: the paper does not say how its marks start and are "
            "associated",
            origin="adversarial",
        ),
        Entry(
            "ULA",
            "comparator",
            "ML",
            ("ML", "MAP (designation prior)"),
            "the paper's ULA is ML; the two-stage's marks start at the designation, so a ULA with the designation as "
            "its prior (the designation's own error model) is the matched comparison",
        ),
        Entry(
            "velocity knowledge",
            "reading",
            "free",
            ("free", "designated"),
            "the designation gives 'initial conditions'; whether they include the velocity is not said; the ULA (ML or "
            "MAP) and its two-stage twin always get the same knowledge",
            origin="adversarial",
        ),
        Entry(
            "Delta of Figs 4, 5, 7 (sigma)",
            "operating point",
            3.0,
            (1.0, 3.0, 5.0),
            "Figs 4, 5 and 7 give no pixel size; the text names 1, 3 and 5 sigma elsewhere",
        ),
        Entry("T of Figs 4, 6, 7", "operating point", 10, (10, 20), "not stated; Fig 5 uses 5 and 50"),
        Entry(
            "EM tolerance of Fig 7",
            "reading",
            "1e-6 sigma",
            ("1e-6 sigma", "log-likelihood gap 0.01", "log-likelihood gap 0.1"),
            "the iterations stop when the parameters 'practically stop changing'; the study counts them to 1e-6 sigma, "
            "a practical stop leaves a small log-likelihood gap, the same gap for the ULA and each frame's mark as "
            "in 'EM stopping' (each EM within 0.01 or 0.1 nats of its own maximum; C002-14)",
            origin="adversarial",
        ),
        Entry(
            "m_k of Fig 5",
            "operating point",
            20,
            (20, 50, 10),
            "not stated; Fig 4 uses 20 and 50; 10 (Figs 1c, 2) is where a single frame's marks are weakest and pooling "
            "T = 50 frames should help the ULA most (value 10 added by the adversarial pass)",
        ),
        Entry(
            "m_k of C002-12",
            "operating point",
            20,
            (20, 10),
            "the 'practically coincide' statement names no photon count; Figs 1c and 2 go down to m_k = 10, where a "
            "single frame's mark is weakest",
            origin="adversarial",
        ),
        Entry("T of Figs 1a,b", "operating point", 5, (5, 10), "not stated; Fig 1c states 5, Fig 2 uses 5 and 10"),
        Entry(
            "m_k of C002-1",
            "operating point",
            20,
            (20, 10),
            "C002-1 cites 'Fig 1', whose panels a and b draw both the 10- and the 20-photon curves; the claim names "
            "neither (third adversarial pass; a joint sample that sets it to 10 is pinned, see the pinned conditions)",
            origin="adversarial",
        ),
        Entry(
            "Delta of C002-1 (sigma)",
            "operating point",
            3.0,
            (3.0, 1.0),
            "C002-1 cites 'Fig 1': panel a has pixels of 3 sigma, panel b of 1 sigma (third adversarial pass)",
            origin="adversarial",
        ),
        Entry("m_k of Fig 1c", "reading", 10, (10, 50), "the text says m_k = 10, the caption 50"),
        Entry(
            "T of the Fig 3a claims",
            "operating point",
            10,
            (5, 10, 50),
            "Fig 3a spans the number of frames; the conclusions do not say at which T",
        ),
        Entry(
            "coarse Delta of C002-7, C002-8 (sigma)",
            "operating point",
            5.0,
            (3.0, 5.0),
            "'large pixels', 'poor CCDs' are not quantified; Figs 1 and 3 name 3 and 5 sigma",
            origin="adversarial",
        ),
        Entry(
            "Delta of the C002-9 order (sigma)",
            "operating point",
            3.0,
            (1.0, 3.0, 5.0),
            "Fig 3a gives no pixel size; the ordering is implied for the figure as a whole",
        ),
        Entry(
            "separation of C002-5 (sigma)",
            "operating point",
            2.0,
            (1.0, 2.0, 3.0),
            "the statement gives no separation; Figs 1c and 2a span the distance axis",
        ),
        Entry(
            "small separations of C002-6 (sigma)",
            "reading",
            2.0,
            (1.0, 2.0, 8.0),
            "'fewer photons weaken the T dependence' is read at small d (d <= 2 sigma, this project's choice); the "
            "paper's sentence compares Figs 2a and 2b as a whole, so 8 (the whole distance axis) is a reading too "
            "(value 8 added by the adversarial pass)",
        ),
        Entry(
            "m_k pair of C002-6",
            "operating point",
            "20 vs 10",
            ("20 vs 10", "10 vs 5"),
            "Fig 2 compares 20 and 10 photons, but the text says the T dependence weakens 'at least from some critical "
            "level' of photons: in a world whose noise and pixels differ from the paper's, that level may lie below "
            "10, so 10 against 5 is the same comparison one step fainter",
            origin="adversarial",
        ),
        Entry(
            "coordinate of C002-6",
            "statistic",
            "both",
            ("both", "along the separation", "across the separation"),
            "Fig 2's caption reads the variance of the estimates 'of the coordinate' (singular), and the paper does not "
            "say along which axis its objects are separated: x and y of both objects, or only the coordinate along "
            "(or across) the separation, where the merging of the two images does (or does not) act",
            origin="adversarial",
        ),
        Entry(
            "Delta of C002-6 (sigma)",
            "operating point",
            1.0,
            (1.0, 3.0),
            "Fig 2 is drawn at Delta = sigma, but the paper credits the weakening to the grouped (binned) sample, and "
            "a pixel groups more of an object's photons the coarser it is: at Fig 1a's 3 sigma the same comparison "
            "is made where the grouping acts more (fourth adversarial pass)",
            origin="adversarial",
        ),
        Entry(
            "T pair of C002-6",
            "operating point",
            "5 vs 10",
            ("5 vs 10", "5 vs 50"),
            "Fig 2 compares T = 5 and 10; the sentence speaks of 'the number of analysed frames' without a range, and "
            "the study's frame axis (Figs 3a, 5) runs to 50: a dependence that weakens should show more over 5 to "
            "50 frames (fourth adversarial pass)",
            origin="adversarial",
        ),
        Entry(
            "T dependence of C002-6",
            "statistic",
            "relative (log ratio)",
            ("relative (log ratio)", "absolute (variance gap)"),
            "Fig 2 is lost and its axis scale with it: the T dependence is the gap between the T = 5 and T = 10 "
            "curves, relative (|ln r_T|, a log axis) or absolute (|Sigma^2(5) - Sigma^2(10)| in sigma^2, a linear "
            "axis); the paper calls the weakening inexplicable for ungrouped samples, which holds for both (fourth "
            "adversarial pass)",
            origin="adversarial",
        ),
        Entry(
            "close separations of C002-10 (sigma)",
            "reading",
            3.0,
            (1.0, 2.0, 3.0),
            "'the gain grows with pixel size and frames' is read where the gain is visible; the text names d = 1 and 3",
        ),
        Entry(
            "bound",
            "statistic",
            "CRB",
            ("CRB", "van Trees (designation prior)"),
            "'practically potential accuracy' names no bound; the CRB holds for unbiased estimators only, the van Trees "
            "bound with the designation as prior for any estimator started there",
            origin="adversarial",
        ),
        Entry(
            "pixel pair of C002-5",
            "reading",
            "3 vs 1",
            ("3 vs 1", "5 vs 3"),
            "C002-5 cites Figs 1c and 2a for 'with more frames the influence of pixel size weakens'; Fig 1c compares "
            "pixels of 3 and 5 sigma, Fig 2a has pixels of 1 sigma only, so the default 3 against 1 sigma joins two "
            "figures and Fig 1c's own 5 against 3 sigma is the pair the cited figure draws (adversarial review)",
            origin="adversarial",
        ),
        Entry(
            "very close separation of C002-15 (sigma)",
            "reading",
            1.0,
            (1.0, 0.5),
            "'very close objects' is not quantified; the text names d = 1 sigma as its smallest distance, and the "
            "study's distance axis (this project's choice) starts at 0.5 sigma, where the images overlap most and "
            "the ULA leans on its designated start: a biased estimator, which the CRB (unbiased estimators only) "
            "need not bound, so the 'bound' entry's van Trees reading matters most there (adversarial review)",
            origin="adversarial",
        ),
        Entry(
            "distance unit of C002-11",
            "reading",
            "sigma",
            ("sigma", "pixel"),
            "the x4 and x4.5 are stated 'for the reduced distances between the objects 3 and 1' without the unit they "
            "are reduced by, and the figures' axes are lost; this project reduces them by the PSF's sigma, but the "
            "paper's other scale is the pixel (its pixel sizes are Delta / sigma), so 3 and 1 pixels of Fig 5 (9 "
            "and 3 sigma at its default 3-sigma pixels) is one a reviewer could hold (fifth adversarial pass)",
            origin="adversarial",
        ),
    ],
    pinned=[
        # the joint sample that made C002-1 not reproduced in the paper-profile run of 2026-11-25
        {
            "gross errors": "trimmed 10 %",
            "noise (photons/sigma^2/frame)": 0.05,
            "velocity (sigma/frame)": "0.5, 0.25",
            "EM stopping": "plain EM, cap 100",
        },
        # the joint sample that made C002-1 not reproduced (with 'm_k of C002-1' = 10) in the paper-profile run of
        # 2026-11-28; it also moved C002-5, C002-9, C002-10, C002-11 and C002-12. Pinned whole: a register that grows
        # draws other joint samples, and this flip must not be lost with them
        {
            "epoch": "velocity",
            "statistic": "MSE",
            "gross errors": "trimmed 10 %",
            "designation error (sigma)": 1.0,
            "m_k of C002-1": 10,
            "separation of C002-5 (sigma)": 3.0,
            "small separations of C002-6 (sigma)": 8.0,
            "m_k pair of C002-6": "10 vs 5",
            "coordinate of C002-6": "along the separation",
            "two-stage": "previous start + assignment",
            "T of the Fig 3a claims": 5,
            "Delta of the C002-9 order (sigma)": 1.0,
            "Delta of Figs 4, 5, 7 (sigma)": 1.0,
            "T of Figs 4, 6, 7": 20,
            "close separations of C002-10 (sigma)": 1.0,
            "ULA": "MAP (designation prior)",
            "velocity knowledge": "designated",
            "m_k of C002-12": 10,
            "tracks": "crossing",
            "EM tolerance of Fig 7": "log-likelihood gap 0.01",
            "bound": "van Trees (designation prior)",
        },
    ],
)

REGISTER = Register(
    [_plain(e) for e in with_kinds(REGISTER.entries, KINDS)], REGISTER.pinned
)  # every entry in plain words

_WORLD = ["photon model", "designation error (sigma)", "noise (photons/sigma^2/frame)", "velocity (sigma/frame)"]
_ULA_ONLY = ["epoch", "statistic", "gross errors", *_WORLD, "EM stopping"]
_RHO = [*_ULA_ONLY, "two-stage"]
_TWO = ["tracks"]  # two objects whose distance changes: labour and very close objects only
#: Register entries each claim's measurement reads.
DEPENDS = {
    "C002-1": [*_ULA_ONLY, "T of Figs 1a,b", "m_k of C002-1", "Delta of C002-1 (sigma)"],
    "C002-2": [*_ULA_ONLY, "T of Figs 1a,b"],
    "C002-3": [*_ULA_ONLY, "T of Figs 1a,b"],
    "C002-4": [*_ULA_ONLY, "m_k of Fig 1c"],
    "C002-5": [*_ULA_ONLY, "separation of C002-5 (sigma)", "pixel pair of C002-5"],
    "C002-6": [
        *_ULA_ONLY,
        "small separations of C002-6 (sigma)",
        "m_k pair of C002-6",
        "coordinate of C002-6",
        "Delta of C002-6 (sigma)",
        "T pair of C002-6",
        "T dependence of C002-6",
    ],
    "C002-7": [*_RHO, "T of the Fig 3a claims", "coarse Delta of C002-7, C002-8 (sigma)"],
    "C002-8": [*_RHO, "T of the Fig 3a claims", "coarse Delta of C002-7, C002-8 (sigma)"],
    "C002-9": [*_RHO, "T of the Fig 3a claims", "Delta of the C002-9 order (sigma)"],
    "C002-10": [
        *_RHO,
        "Delta of Figs 4, 5, 7 (sigma)",
        "T of Figs 4, 6, 7",
        "m_k of Fig 5",
        "close separations of C002-10 (sigma)",
    ],
    "C002-11": [
        *_RHO,
        "accuracy ratio of C002-11",
        "distance unit of C002-11",
        "ULA",
        "velocity knowledge",
        "Delta of Figs 4, 5, 7 (sigma)",
        "m_k of Fig 5",
    ],
    "C002-12": [*_RHO, "T of Figs 4, 6, 7", "m_k of C002-12"],
    "C002-13": [*_TWO, *_WORLD, "Delta of Figs 4, 5, 7 (sigma)", "T of Figs 4, 6, 7", "EM tolerance of Fig 7"],
    "C002-14": [
        *_TWO,
        *_WORLD,
        "two-stage",
        "Delta of Figs 4, 5, 7 (sigma)",
        "T of Figs 4, 6, 7",
        "EM tolerance of Fig 7",
    ],
    # the bounds are those of the initial positions and the velocities: the epoch reading cannot apply
    "C002-15": [
        *_TWO,
        *[k for k in _ULA_ONLY if k not in ("epoch", "gross errors")],
        "Delta of Figs 4, 5, 7 (sigma)",
        "T of Figs 4, 6, 7",
        "bound",
        "very close separation of C002-15 (sigma)",
    ],
}
