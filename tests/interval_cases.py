"""Simulated experiments for the coverage of the interval helpers (``tests/test_intervals.py``).

Each case draws ``(R, n)`` per-trial values of known mean (or ratio of means) at the sample sizes the
notebooks use the helpers at: 10 and 30 trials (003: 10 runs per seed, 3 seeds), 15 paths (004), 16-48
trials or clusters per grid point (003), 100 trials (002 headline sweeps). The experiments are vectorised:
one call resamples all ``R`` experiments at once through the helpers' own batched interval code.
"""

import hashlib

import numpy as np
from scipy import stats

from tvtrack import montecarlo as mc
from tvtrack import resampling

SIZES = (5, 10, 15, 30, 48, 100)
N_EXPERIMENTS = 2000


def _scaled(rng, s, sigma, noise, ratio=1.3):
    """Per-path mean squares of two methods on the same paths: a path's scale (log-normal ``sigma``,
    paths of different wander amplitude) times each method's own noise of mean 1."""
    scale = rng.lognormal(0.0, sigma, s)
    return ratio * scale * noise(rng, s), scale * noise(rng, s)


def _gamma4(rng, s):
    return rng.gamma(4.0, 0.25, s)


def _sq_t3(rng, s):
    return (rng.standard_t(3, s + (20,)) ** 2).mean(axis=-1) / 3.0


#: Positive per-trial values (mean squares): name -> (draw(rng, shape), true mean, heavy tail?)
MEAN_SQUARE_CASES = {
    "mean of 20 squared normals": (lambda rng, s: rng.chisquare(20, s) / 20, 1.0, False),
    "exponential": (lambda rng, s: rng.exponential(1.0, s), 1.0, False),
    "log-normal sigma 0.5": (lambda rng, s: rng.lognormal(0.0, 0.5, s), np.exp(0.125), False),
    "log-normal sigma 1": (lambda rng, s: rng.lognormal(0.0, 1.0, s), np.exp(0.5), True),
    "mean of 20 squared t3": (lambda rng, s: (rng.standard_t(3, s + (20,)) ** 2).mean(axis=-1), 3.0, True),
}

#: Paired positive per-trial values: name -> (draw(rng, shape) -> (a, b), true mean(a) / mean(b), heavy?)
RATIO_CASES = {
    "common exponential, a = 1.5 c + exp(0.5)": (
        lambda rng, s: (lambda c: (1.5 * c + rng.exponential(0.5, s), c))(rng.exponential(1.0, s)),
        2.0,
        False,
    ),
    "path scale log-normal 0.5 x gamma(4)": (lambda rng, s: _scaled(rng, s, 0.5, _gamma4), 1.3, False),
    "path scale log-normal 1 x gamma(4)": (lambda rng, s: _scaled(rng, s, 1.0, _gamma4), 1.3, True),
    "path scale log-normal 1 x squared t3": (lambda rng, s: _scaled(rng, s, 1.0, _sq_t3), 1.3, True),
}

#: Real-valued samples for the Student-t mean: name -> (draw, true mean, heavy?)
MEAN_CASES = {
    "normal": (lambda rng, s: rng.normal(1.0, 1.0, s), 1.0, False),
    "exponential": (lambda rng, s: rng.exponential(1.0, s), 1.0, False),
    "log-normal sigma 0.5": (lambda rng, s: rng.lognormal(0.0, 0.5, s), np.exp(0.125), False),
    "Student t3": (lambda rng, s: rng.standard_t(3, s), 0.0, True),
    "log-normal sigma 1": (lambda rng, s: rng.lognormal(0.0, 1.0, s), np.exp(0.5), True),
}

CASES = {"mean_square": MEAN_SQUARE_CASES, "ratio": RATIO_CASES, "mean": MEAN_CASES}


def draw(helper: str, case: str, n: int, r: int = N_EXPERIMENTS):
    f, truth, _ = CASES[helper][case]
    rng = np.random.default_rng([20261125, list(CASES[helper]).index(case), n])
    return f(rng, (r, n)), truth


def intervals(helper: str, data, method: str = "new"):
    """Lower and upper 95 % bounds (R,) of every experiment, by the helper's interval (``"new"``) or by
    the interval it used before (``"BCa"`` bootstrap via scipy, batched; for ``"mean"`` Student t)."""
    rng = np.random.default_rng(mc.BOOTSTRAP_SEED)
    if method == "new" and helper == "mean_square":
        lo, hi = _studentized(data)
        return np.maximum(lo, 0.0), hi
    if method == "new" and helper == "ratio":
        lo, hi, _ = resampling.expanded_percentile_ratio(data[0], data[1], 0.95, True, mc.N_BOOTSTRAP, rng)
        return lo, hi
    if helper == "mean":
        x = data
        if method == "new":
            return _studentized(x)
        half = stats.t.ppf(0.975, x.shape[1] - 1) * x.std(axis=1, ddof=1) / np.sqrt(x.shape[1])
        return x.mean(axis=1) - half, x.mean(axis=1) + half
    # the BCa interval the helpers used before: scipy.stats.bootstrap's paired BCa, batched (bca_interval)
    samples = (data,) if helper == "mean_square" else tuple(data)
    lo, hi = [], []
    for r0 in range(0, samples[0].shape[0], 200):
        chunk_lo, chunk_hi = bca_interval(tuple(x[r0 : r0 + 200] for x in samples), mc.N_BOOTSTRAP, rng)
        lo.append(chunk_lo)
        hi.append(chunk_hi)
    return np.concatenate(lo), np.concatenate(hi)


#: the bootstrap-t bounds of each set of experiments already resampled, by a digest of its values
_STUDENTIZED: dict[str, tuple[np.ndarray, np.ndarray]] = {}


def _studentized(x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The bootstrap-t bounds of every row of ``x`` (R, n), from the generator seeded as each helper's, computed once
    per set of values: the mean and mean-square tables resample the same exponential draws (the same seed and
    position of the case), which gave the same bounds twice. The bounds depend on the values and the seed alone,
    so a set seen before gets the very arrays it gave then."""
    key = hashlib.sha256(np.ascontiguousarray(x).tobytes() + repr((x.shape, x.dtype.str)).encode()).hexdigest()
    if key not in _STUDENTIZED:
        lo, hi, _ = resampling.studentized_mean_interval(
            x, 0.95, mc.N_BOOTSTRAP, np.random.default_rng(mc.BOOTSTRAP_SEED)
        )
        _STUDENTIZED[key] = (lo, hi)
    return _STUDENTIZED[key]


def _ratio_of_means(samples, n: int | None = None):
    """The statistic: the mean of one sample, or the ratio of the means of two paired samples (over the last
    axis; given ``n``, ``samples`` hold sums of ``n`` values instead)."""
    means = [x.mean(axis=-1) if n is None else x / n for x in samples]
    return means[0] if len(means) == 1 else means[0] / means[1]


def bca_interval(samples, n_resamples: int, rng: np.random.Generator, confidence: float = 0.95):
    """The 95 % BCa interval of :func:`_ratio_of_means` for each row of the paired ``samples`` (each (R, n)):
    the computation of ``scipy.stats.bootstrap(samples, statistic, paired=True, vectorized=True, axis=-1,
    n_resamples=n_resamples, method="BCa", rng=rng)`` step by step, with its one draw from ``rng`` (the
    resample indices (B, n)), its jackknife acceleration and its percentile of score, but the resample means
    taken as ``x @ W.T / n`` with ``W`` the resample counts instead of scipy's (R, B, n) gather, which took most
    of the test's time: the same intervals to rounding (``test_the_bca_reference_is_scipys_bootstrap``)."""
    from scipy.special import ndtr, ndtri

    n = samples[0].shape[-1]
    idx = rng.integers(0, n, (n_resamples, n))  # scipy's rng_integers(rng, 0, n, (n_resamples, n))
    counts = resampling._resample_weights(idx, n)  # (B, n)
    if (counts == 1).all(axis=1).any():
        # a resample that permutes the sample (4 % of them at 5 trials, none drawn at 15) has the sample's statistic,
        # and rounding alone, which depends on the shape numpy reduces, puts it below, at or above the estimate in
        # the percentile of score: such a draw is taken through scipy's own gather, so the interval is scipy's
        theta_b = _ratio_of_means([x[..., idx] for x in samples])
    else:
        theta_b = _ratio_of_means([x @ counts.T for x in samples], n)  # (R, B) the same to rounding
    theta = _ratio_of_means([x[..., np.arange(n)] for x in samples])[:, None]  # scipy's statistic(arange(n))
    z0 = ndtri(
        (np.count_nonzero(theta_b < theta, axis=-1) + np.count_nonzero(theta_b <= theta, axis=-1)) / (2 * n_resamples)
    )
    keep = ~np.eye(n, dtype=bool)
    jack = np.broadcast_to(np.arange(n), (n, n))[keep].reshape(n, n - 1)  # row i leaves out trial i
    theta_i = _ratio_of_means([x[..., jack] for x in samples])  # (R, n)
    u = (n - 1) * (theta_i.mean(axis=-1, keepdims=True) - theta_i)
    a_hat = 1 / 6 * (np.sum(u**3, axis=-1) / n**3) / (np.sum(u**2, axis=-1) / n**2) ** (3 / 2)
    z = float(ndtri((1 - confidence) / 2))
    alphas = [ndtr(z0 + (z0 + zz) / (1 - a_hat * (z0 + zz))) for zz in (z, -z)]
    levels = np.stack(alphas, axis=-1)  # (R, 2)
    ci = stats.quantile(theta_b, levels, axis=-1)
    return ci[:, 0], ci[:, 1]


def coverage(helper: str, case: str, n: int, method: str = "new") -> float:
    data, truth = draw(helper, case, n)
    lo, hi = intervals(helper, data, method)
    return float(np.mean((lo <= truth) & (truth <= hi)))


if __name__ == "__main__":  # prints the coverage table (helper, n, case, before, after)
    import sys

    helpers = sys.argv[1:] or list(CASES)
    for h in helpers:
        for case, (_, _, heavy) in CASES[h].items():
            for n in SIZES:
                before = coverage(h, case, n, "BCa" if h != "mean" else "t")
                after = coverage(h, case, n)
                print(f"| {h} | {n} | {case}{' (heavy)' if heavy else ''} | {before:.3f} | {after:.3f} |", flush=True)
