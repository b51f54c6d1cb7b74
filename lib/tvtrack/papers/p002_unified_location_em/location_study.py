"""A cache of paper 002's simulated configurations computed on demand (:class:`LocationStudy`): the interactive
entry to :func:`.simulation.run_config` (the explorer's measurements go through :mod:`.study`'s job cache instead).
"""

from __future__ import annotations

import multiprocessing
from concurrent.futures import ProcessPoolExecutor
from dataclasses import fields
from functools import partial

import numpy as np

from tvtrack.estimate import Estimate
from .sim_config import Config, StudySettings, base, seed_sequence
from .simulation import run_config
from .summaries import bootstrap_groups, variance_ratio_ci

__all__ = ["LocationStudy"]


class LocationStudy:
    """Cache of configuration results, computed in parallel on demand.

    ``study[c]`` returns the result dict of :func:`run_config` for ``c`` whatever algorithms
    ``c`` names (the simulation ran with the union of those asked for its scenes).
    """

    def __init__(self, settings: StudySettings, n_workers: int = 1):
        if n_workers < 1:
            raise ValueError(f"n_workers = {n_workers}; it must be >= 1")
        self.settings = settings
        self.n_workers = n_workers
        self._cache: dict[tuple, dict] = {}

    def config(
        self,
        q,
        d,
        pix,
        m,
        T,
        algs="uecr",
        dsd=None,
        init=None,
        assoc=None,
        n=None,
        tag="main",
        vsd=None,
        variant: dict | None = None,
    ) -> Config:
        """A :class:`Config` with the settings' defaults filled in (``dsd``, ``vsd``, ``n``);
        ``variant`` maps :class:`StudySettings` field names to this configuration's own values."""
        st = self.settings
        unknown = set(variant or {}) - {f.name for f in fields(StudySettings)}
        if unknown:
            raise ValueError(f"variant names {sorted(unknown)}; it may override only StudySettings fields")
        return Config(
            int(q),
            float(d),
            float(pix),
            int(m),
            int(T),
            algs,
            float(st.designation_sd_sigma if dsd is None else dsd),
            init,
            assoc,
            int(n or st.n_trials),
            tag,
            float(st.designation_velocity_sd if vsd is None else vsd),
            tuple(sorted((variant or {}).items())),
        )

    def __getitem__(self, c) -> dict:
        return self._cache[base(c)]

    def __contains__(self, c) -> bool:
        return base(c) in self._cache

    def __len__(self) -> int:
        return len(self._cache)

    def compute(self, configs) -> None:
        """Run every configuration not yet cached, each scene set once with the union of the
        algorithms asked for it (longest first, in ``n_workers`` forked processes)."""
        union: dict[tuple, str] = {}
        for c in configs:
            if c not in self:
                union[base(c)] = "".join(sorted(set(union.get(base(c), "")) | set(c[5])))
        todo = [Config(*k[:5], a, *k[6:]) for k, a in union.items()]
        todo.sort(key=lambda c: -c.T * c.n * (1 + 2 * ("e" in c.algs) + 3 * ("p" in c.algs) + 3 * ("q" in c.algs)))
        run = partial(run_config, self.settings)
        if self.n_workers > 1 and len(todo) > 1:
            with ProcessPoolExecutor(self.n_workers, mp_context=multiprocessing.get_context("fork")) as pool:
                for c, r in zip(todo, pool.map(run, todo)):
                    self._cache[base(c)] = r
        else:
            for c in todo:
                self._cache[base(c)] = run(c)

    def bootstrap_rng(self) -> np.random.Generator:
        """This run's bootstrap generator (the same draws on every call)."""
        return np.random.default_rng(seed_sequence(self.settings.seed, ("bootstrap",)))

    def variance_ratio(self, e_num, e_den, paired=True, mse=False, sqrt=False, spread="variance") -> Estimate:
        """:func:`variance_ratio_ci` with :meth:`bootstrap_rng` and ``settings.n_bootstrap`` resamples."""
        return variance_ratio_ci(
            e_num,
            e_den,
            self.bootstrap_rng(),
            self.settings.n_bootstrap,
            paired=paired,
            mse=mse,
            sqrt=sqrt,
            spread=spread,
        )

    def groups_ci(self, groups, statistic) -> Estimate:
        """:func:`bootstrap_groups` with :meth:`bootstrap_rng` and ``settings.n_bootstrap`` resamples."""
        return bootstrap_groups(groups, statistic, self.bootstrap_rng(), self.settings.n_bootstrap)
