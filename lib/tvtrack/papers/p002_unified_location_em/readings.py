"""How a register configuration of paper 002 picks the simulation points and statistics its claims read.

Each function takes a configuration ``{register entry name: value}`` (:mod:`.register`) and returns the point a
claim compares (pixel sizes Delta / sigma, photon counts m_k, frame counts T, separations d / sigma); the
constants are the values of the adversarial register rows. Shared by :mod:`.study` (which points to simulate) and
:mod:`.claim_values` (what each claim computes from them).
"""

from __future__ import annotations

__all__ = [
    "D_GRID",
    "CLOSE",
    "TRIMMED",
    "PHOTONS6",
    "COORDINATE6",
    "FRAMES6",
    "T_DEPENDENCE6",
    "FIG7_TOLERANCE",
    "FIG1_PANEL",
    "PIXELS5",
    "photons6",
    "c6_point",
    "c1_point",
    "c5_pair",
    "c10_close",
    "c15_close",
    "c11_separations",
    "fig7_variant",
]

#: Separations d / sigma of the distance axes (this project's choice; the text names 1, 3 and > 8).
D_GRID = (0.5, 1.0, 1.5, 2.0, 3.0, 4.0, 6.0, 8.0)
#: Separations (sigma) over which C002-10's "coarser pixels" and "more frames" gains are averaged (up to the
#: register's "close separations" value): the text names d = 1 and 3 sigma.
CLOSE = (1.0, 2.0, 3.0)
#: The "gross errors" reading that trims the 10 % largest per-trial squared errors (an adversarial register row).
TRIMMED = "trimmed 10 %"


#: The photon counts C002-6 compares (an adversarial register row): ``"20 vs 10"`` (Fig 2) or ``"10 vs 5"`` ("at
#: least from some critical level": a level below Fig 2's).
PHOTONS6 = {"20 vs 10": (20, 10), "10 vs 5": (10, 5)}
#: Columns of the per-trial errors ``(x1, y1, x2, y2)`` that C002-6's "sum of variances of the coordinate" reads
#: (an adversarial register row): the objects are separated along ``y``.
COORDINATE6 = {
    "both": slice(None),
    "along the separation": slice(1, None, 2),
    "across the separation": slice(0, None, 2),
}


def photons6(config: dict) -> tuple[int, int]:
    """The (more, fewer) target photons per frame whose T dependences C002-6 compares."""
    return PHOTONS6[config.get("m_k pair of C002-6", "20 vs 10")]


#: The frame counts whose variance ratio r_T C002-6 reads (an adversarial register row): Fig 2's ``"5 vs 10"``, or
#: ``"5 vs 50"``, the range of Figs 3a and 5 ("the number of analysed frames" over the study's whole T axis).
FRAMES6 = {"5 vs 10": (5, 10), "5 vs 50": (5, 50)}


#: How C002-6 reads "the dependence on T" (an adversarial register row): relative, |ln r_T| (the gap between the T
#: curves on a log axis), or absolute, |Sigma^2(T_lo) - Sigma^2(T_hi)| in sigma^2 (the gap on a linear axis).
T_DEPENDENCE6 = ("relative (log ratio)", "absolute (variance gap)")


def c6_point(config: dict) -> tuple[float, tuple[int, int]]:
    """C002-6's pixel size Delta / sigma (Fig 2: 1; an adversarial register row) and its frame pair."""
    return float(config.get("Delta of C002-6 (sigma)", 1.0)), FRAMES6[config.get("T pair of C002-6", "5 vs 10")]


#: The "EM tolerance of Fig 7" reading (an adversarial register row): the practical stop of the iteration counts of
#: Fig 7, the log-likelihood gap (nats) each EM (ULA and per-frame marks alike) may leave, the same gap as in "EM
#: stopping"; ``None`` keeps the study's own 1e-6 sigma.
FIG7_TOLERANCE = {"1e-6 sigma": None, "log-likelihood gap 0.01": 0.01, "log-likelihood gap 0.1": 0.1}


#: Fig 1's panels by pixel size Delta / sigma.
FIG1_PANEL = {3.0: "1a", 1.0: "1b"}


def c1_point(config: dict) -> tuple[int, float]:
    """C002-1's point of Fig 1: ``(m_k, Delta / sigma)`` from the register (default 20 photons, Fig 1a)."""
    return int(config.get("m_k of C002-1", 20)), float(config.get("Delta of C002-1 (sigma)", 3.0))


#: The pixel sizes Delta / sigma (coarser, finer) whose variance ratio C002-5 reads (an adversarial register row): the
#: default 3 against 1 sigma (Figs 1c and 2a together), or Fig 1c's own pair, 5 against 3 sigma.
PIXELS5 = {"3 vs 1": (3.0, 1.0), "5 vs 3": (5.0, 3.0)}


def c5_pair(config: dict) -> tuple[float, float]:
    """The (coarser, finer) pixel sizes Delta / sigma of C002-5."""
    return PIXELS5[config.get("pixel pair of C002-5", "3 vs 1")]


def c10_close(config: dict) -> list:
    """C002-10's close separations d / sigma: those of :data:`CLOSE` up to the register's "close separations"."""
    return [d for d in CLOSE if d <= float(config["close separations of C002-10 (sigma)"])]


def c15_close(config: dict) -> float:
    """The separation d / sigma at which C002-15 reads "very close objects" (an adversarial register row: 1 sigma,
    the smallest separation the text names, or 0.5 sigma, the closest of the study's distance axis)."""
    return float(config.get("very close separation of C002-15 (sigma)", 1.0))


def c11_separations(config: dict) -> tuple[float, float]:
    """The separations d / sigma of C002-11's two parts, (x4.5 at 1, x4 at 3): 1 and 3 sigma, or under the pixel
    reading 1 and 3 pixels of Figs 4, 5, 7 (Delta and 3 Delta)."""
    if config.get("distance unit of C002-11", "sigma") == "pixel":
        pix = float(config["Delta of Figs 4, 5, 7 (sigma)"])
        return pix, 3.0 * pix
    return 1.0, 3.0


def fig7_variant(config: dict) -> tuple:
    """The :class:`Config` ``variant`` of the Fig 7 points (C002-13, C002-14): the register's stopping tolerance
    of the iteration counts, or ``()`` at the default (the default's cache keys and draws are unchanged; a variant
    sees the same scenes, common random numbers)."""
    tol = FIG7_TOLERANCE[config.get("EM tolerance of Fig 7", "1e-6 sigma")]
    return () if tol is None else (("tol_loglik", float(tol)),)
