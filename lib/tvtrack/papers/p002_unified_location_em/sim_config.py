"""What one simulation of paper 002 is: its settings (:class:`StudySettings`), its point (:class:`Config`) and the
seeds its draws come from (:func:`seed_sequence`).

A :class:`Config` is ``(Q, d/sigma, Delta/sigma, m_k, T)`` plus the algorithm letters to run (:data:`ALGORITHMS`),
the designation errors, the mark initialisation/association, the number of trials and a variant of the settings;
:func:`base` is the part that fixes the scenes (configurations differing only in their letters share them).

Units: sigma (the PSF standard deviation) for lengths, frames for time.
"""

from __future__ import annotations

import zlib
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np

__all__ = [
    "ALGORITHMS",
    "N_SEED_BLOCKS",
    "StudySettings",
    "CANONICAL_SETTINGS",
    "Config",
    "seed_sequence",
    "base",
    "scene_key",
]

#: Algorithm letters of :attr:`Config.algs`.
ALGORITHMS = {
    "u": "ULA (accelerated as set)",
    "p": "ULA with plain EM (iteration counts)",
    "m": "MAP-ULA: the ULA with the designation as a Gaussian prior (its own error model)",
    "e": "two-stage, iterative (per-frame EM) marks",
    "k": "ULA (ML) with the designated velocity kept (its error as the velocity prior), no position prior",
    "1": "ULA with Q' = 1: one track fitted to all objects (errors against their mean)",
    "w": "ULA with the weights p_j and the PSF width sigma estimated too (plain EM; an extension the paper calls "
    "feasible)",
    "s": "multi-start ULA: the log-likelihood the designation start leaves below the best of 4 starts",
    "q": "two-stage, iterative marks by plain EM (iteration counts)",
    "c": "two-stage, centre-of-region marks",
    "b": "BIC fits with Q' = 1, 2, 3",
    "r": "the bounds: the CRB and the van Trees bound of the designation prior (no estimator)",
}
#: Every configuration's trials are drawn from one seed (``settings.seed``): independent replicates are whole
#: runs with other seeds (the explorer's), never thirds of one run.
N_SEED_BLOCKS = 1


@dataclass(frozen=True)
class StudySettings:
    """Everything a configuration's simulation needs besides the :class:`Config` itself.

    Attributes
    ----------
    seed : int
        Run seed; every configuration's generator derives from it.
    velocity_sigma : (float, float)
        Common velocity ``(Vx, Vy)`` of the objects, sigma per frame.
    noise_density : float
        Uniform noise photons per sigma^2 per frame.
    photon_model : {"fixed", "poisson"}
        Target photons per object per frame: fixed count or Poisson with that mean.
    margin_sigma : float
        Empty window border around all trajectories, sigma.
    designation_sd_sigma, designation_velocity_sd : float
        Default designation errors (position sigma; velocity sigma per frame).
    tol_sigma : float
        EM stopping tolerance on position-equivalent change, sigma.
    max_iter : int
        EM iteration cap (ULA and per-frame marks).
    merge_sigma : float
        Two ULA estimates closer than this count as merged, sigma.
    accelerate : {"squarem", "none"}
        EM variant of the "u" algorithm.
    mark_init, mark_association : str
        Defaults of :func:`~tvtrack.papers.p002_unified_location_em.two_stage.em_marks` ``init`` and ``association``.
    gate_half_sigma : float
        Centre-of-region gate half-size, sigma (at least 1.5 px).
    bic_max_iter : int
        Iteration cap of the BIC fits.
    crb_phases : int
        Sub-pixel phases averaged in each CRB value.
    n_trials : int
        Default trials per configuration.
    velocity_knowledge : {"free", "designated"}
        What the MAP-ULA and its two-stage twin know of the velocity: nothing ("free": the MAP prior
        covers the initial positions only, the line fit is ordinary least squares), or the designated
        velocity with its error ``designation_velocity_sd`` ("designated": the MAP prior's velocity sd is
        that error, the line fit keeps the designated velocity and fits the intercept).
    tracks : {"parallel", "crossing", "diverging"}
        Two-object scenes: the common velocity, or object 2 with its y velocity lowered (raised) by
        ``2 d / (T - 1)``: the tracks cross at mid-sequence (diverge from ``d`` to ``3 d``); see
        :func:`track_velocities`.
    n_bootstrap : int
        Bootstrap resamples of a claim's intervals (at least 2000: intervals at
        the 2.5 % and 97.5 % tails need thousands).
    tol_loglik : float or None
        The practical stop (nats): every EM of the ULA and of the per-frame marks stops when the
        log-likelihood it can still gain is below this (each on its own likelihood: all frames for the ULA, one
        frame for a mark; ``tol_sigma`` is then not used). ``None``: the parameter-change rule ``tol_sigma``.
    """

    seed: int
    velocity_sigma: tuple[float, float]
    noise_density: float
    photon_model: str
    margin_sigma: float
    designation_sd_sigma: float
    designation_velocity_sd: float
    tol_sigma: float
    max_iter: int
    merge_sigma: float
    accelerate: str
    mark_init: str
    mark_association: str
    gate_half_sigma: float
    bic_max_iter: int
    crb_phases: int
    n_trials: int
    n_bootstrap: int
    velocity_knowledge: str = "free"
    tracks: str = "parallel"
    tol_loglik: float | None = None


CANONICAL_SETTINGS = StudySettings(
    seed=0,
    velocity_sigma=(0.2, 0.1),
    noise_density=0.01,
    photon_model="fixed",
    margin_sigma=6.0,
    designation_sd_sigma=0.0,
    designation_velocity_sd=0.0,
    tol_sigma=1e-6,
    max_iter=5000,
    merge_sigma=0.1,
    accelerate="squarem",
    mark_init="designation",
    mark_association="designation",
    gate_half_sigma=3.0,
    bic_max_iter=300,
    crb_phases=64,
    n_trials=0,
    n_bootstrap=2000,
    velocity_knowledge="free",
)
"""The study's canonical settings (the paper-profile world); ``dataclasses.replace(CANONICAL_SETTINGS, ...)``
gives any other (tests, smaller runs)."""


class Config(NamedTuple):
    """One configuration (a point of a curve).

    ``algs`` is a string of letters from :data:`ALGORITHMS`; ``init``/``assoc`` of ``None`` mean
    the settings' defaults; ``tag`` separates otherwise equal configurations drawn for different
    studies (different seeds). ``variant`` overrides :class:`StudySettings` fields for this
    configuration alone, as sorted ``(name, value)`` pairs (e.g. ``(("max_iter", 30),)``); it does not
    enter the scene seed, so a variant sees the same draws as its default (common random numbers).
    """

    q: int
    d: float
    pix: float
    m: int
    T: int
    algs: str
    dsd: float
    init: str | None
    assoc: str | None
    n: int
    tag: str
    vsd: float
    variant: tuple = ()


def seed_sequence(seed: int, values) -> np.random.SeedSequence:
    """Seed sequence from the run seed and a tuple of values (numbers to 1e-3, ``None`` as 0,
    strings hashed with CRC-32, which, unlike ``hash()``, does not change between processes)."""

    def word(v):
        if v is None:
            return 0
        if isinstance(v, str):
            return zlib.crc32(v.encode())
        return int(round(1000 * v)) & 0xFFFFFFFF

    return np.random.SeedSequence([seed, *[word(v) for v in values]])


def base(c) -> tuple:
    """A configuration without its algorithm letters (the scene draws do not depend on them)."""
    return tuple(c[:5]) + ("",) + tuple(c[6:])


def scene_key(c: Config) -> tuple:
    """What a configuration's scene seed derives from (:func:`seed_sequence`).

    Parameters
    ----------
    c : Config
        A simulation configuration.

    Returns
    -------
    tuple
        :func:`base` of ``c`` without the settings variant, the algorithm letters already left out: a variant
        redraws exactly its default's scenes.
    """
    return base(c)[:-1]
