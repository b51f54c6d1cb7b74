"""The learned predictors of paper 004 (Kokryatska & Hrynchyshyn 2005 compare their filter with back-propagation and
RBF networks, 2-3 px and 2-4 px): lag features, the networks fitted with scikit-learn, their forecasts, and the
path folds of their cross-validated tuning. Re-exported by :mod:`.predictors`."""

from __future__ import annotations

import numpy as np
from numpy.lib.stride_tricks import sliding_window_view

from ._checks import check_steps, check_z

__all__ = [
    "LEARNED_INPUTS",
    "lag_features",
    "fit_learned_predictor",
    "learned_forecast",
    "path_folds",
    "cross_validated_pick",
]


def lag_features(z, n_lags: int, steps: int = 1, inputs: str = "increments"):
    """Inputs and targets for learned predictors.

    ``inputs="increments"`` (translation-invariant): inputs at frame ``n`` are ``z[n-j] - z[n]`` for
    ``j = 1..n_lags`` (increments to the newest sample, px), the target ``z[n+steps] - z[n]``.
    ``inputs="absolute centres"``: the last ``n_lags`` centres as measured, ``z[n-j]`` for ``j = 0..n_lags-1``
    (newest first, px), the target ``z[n+steps]`` (the network must learn the identity map over the field).

    Returns
    -------
    X : ndarray, shape (..., T, n_lags)
        NaN rows where fewer than ``n_lags+1`` samples exist.
    y : ndarray, shape (..., T)
        NaN where ``n + steps >= T``.
    """
    steps = check_steps(steps)
    z = check_z(z)
    if not (isinstance(n_lags, (int, np.integer)) and 1 <= n_lags < z.shape[-1]):
        raise ValueError(f"parameter 'n_lags' = {n_lags!r}; it must be an integer in [1, T-1]")
    if inputs not in LEARNED_INPUTS:
        raise ValueError(f"parameter 'inputs' = {inputs!r}; it must be one of {LEARNED_INPUTS}")
    T = z.shape[-1]
    X = np.full(z.shape + (n_lags,), np.nan)
    y = np.full(z.shape, np.nan)
    if inputs == "absolute centres":
        win = sliding_window_view(z, n_lags, axis=-1)  # (..., T-n_lags+1, n_lags), newest last
        X[..., n_lags - 1 :, :] = win[..., ::-1]
        y[..., : T - steps] = z[..., steps:]
        return X, y
    win = sliding_window_view(z, n_lags + 1, axis=-1)  # (..., T-n_lags, n_lags+1), newest last
    X[..., n_lags:, :] = win[..., -2::-1] - win[..., -1:]
    y[..., : T - steps] = z[..., steps:] - z[..., : T - steps]
    return X, y


LEARNED_INPUTS = ("increments", "absolute centres")


def _sklearn_unchecked():
    """scikit-learn without its per-call parameter validation and finiteness checks (the inputs here are built
    finite and the parameters fixed): the same numbers, about a fifth less CPU time per network."""
    import sklearn

    return sklearn.config_context(skip_parameter_validation=True, assume_finite=True)


def _r2(y_true, y_pred) -> float:
    """scikit-learn's ``r2_score`` of one output without weights, by the same NumPy operations on the same shapes
    (so the same bits), without its per-call input checks: a network's early stopping scores its validation
    set once per epoch, and those checks were about a third of the training time."""
    yt = np.asarray(y_true, dtype=np.float64).reshape(-1, 1)
    yp = np.asarray(y_pred, dtype=np.float64).reshape(-1, 1)
    if yt.shape[0] < 2:
        return float("nan")
    # np.sum and np.average as the reductions they call (the same numbers): a sum over the axis, divided by the count
    numerator = np.add.reduce(1.0 * (yt - yp) ** 2, axis=0)
    denominator = np.add.reduce(1.0 * (yt - np.add.reduce(yt, axis=0) / yt.shape[0]) ** 2, axis=0)
    scores = np.ones([1], dtype=numerator.dtype)
    valid = (denominator != 0) & (numerator != 0)
    scores[valid] = 1 - (numerator[valid] / denominator[valid])
    scores[(numerator != 0) & (denominator == 0)] = 0.0
    return float(scores[0])  # the average of one score


def _tanh_backprop(net, X, y) -> tuple:
    """scikit-learn's ``MLPRegressor._backprop`` for one tanh hidden layer, an identity output and the squared loss
    without sample weights (what :func:`fit_learned_predictor` trains): the same NumPy operations in the same
    order on the same arrays (so the same bits), without the per-call dispatch of ``safe_sparse_dot`` and the
    layer loops.

    Returns
    -------
    (loss, [coefficient gradients], [intercept gradients])
    """
    (w0, w1), (b0, b1) = net.coefs_, net.intercepts_
    n = X.shape[0]
    hidden = X @ w0
    hidden += b0
    np.tanh(hidden, out=hidden)
    out = hidden @ w1
    out += b1
    per_output = np.add.reduce((y - out) ** 2, axis=0) / n  # np.average's numbers, without its checks
    loss = 0.5 * (per_output[0] if per_output.shape == (1,) else per_output.mean())  # the mean of one: itself
    values = 0
    for w in (w0, w1):
        w = w.ravel()
        values += np.dot(w, w)
    loss += (0.5 * net.alpha) * values / n
    delta1 = out - y
    g1 = hidden.T @ delta1
    g1 += net.alpha * w1
    g1 /= n
    delta0 = delta1 @ w1.T
    slope = np.square(hidden)
    delta0 *= np.subtract(1, slope, out=slope)  # tanh's derivative 1 - h^2, in place as scikit-learn's
    g0 = X.T @ delta0
    g0 += net.alpha * w0
    g0 /= n
    return loss, [g0, g1], [np.add.reduce(delta0, axis=0) / n, np.add.reduce(delta1, axis=0) / n]  # np.sum's numbers


class _FlatAdam:
    """scikit-learn's ``AdamOptimizer.update_params`` on one flat buffer of every weight and bias: the network's
    ``coefs_`` and ``intercepts_`` become views into it, and each step runs the optimiser's element-wise operations
    once over the buffer instead of once per array (an element-wise operation gives each element the same number
    whatever array it sits in, so the same bits), in the same order, with the same scalars."""

    def __init__(self, net):
        self.opt = net._optimizer
        params = net.coefs_ + net.intercepts_
        self.p = np.concatenate([q.ravel() for q in params])
        self.m, self.v, self.g = np.zeros_like(self.p), np.zeros_like(self.p), np.empty_like(self.p)
        self.u, self.d = np.empty_like(self.p), np.empty_like(self.p)
        ends = np.cumsum([0] + [q.size for q in params])

        def views(buf):
            return [buf[a:b].reshape(q.shape) for a, b, q in zip(ends[:-1], ends[1:], params)]

        k = len(net.coefs_)
        views_p = views(self.p)
        net.coefs_, net.intercepts_ = views_p[:k], views_p[k:]
        self.grads = views(self.g)
        self.opt.ms, self.opt.vs = views(self.m), views(self.v)  # the optimiser's state, as it would hold it

    def step(self, grads) -> None:
        """One update: ``m = b1 m + (1 - b1) g``, ``v = b2 v + (1 - b2) g^2``, ``p += -lr m / (sqrt(v) + eps)``."""
        o = self.opt
        for view, g in zip(self.grads, grads):
            view[...] = g
        o.t += 1
        np.multiply(self.m, o.beta_1, out=self.m)
        self.m += np.multiply(self.g, 1 - o.beta_1, out=self.u)
        np.multiply(self.v, o.beta_2, out=self.v)
        np.square(self.g, out=self.u)
        self.v += np.multiply(self.u, 1 - o.beta_2, out=self.u)
        o.learning_rate = o.learning_rate_init * np.sqrt(1 - o.beta_2**o.t) / (1 - o.beta_1**o.t)
        np.multiply(self.m, -o.learning_rate, out=self.u)
        np.sqrt(self.v, out=self.d)
        self.d += o.epsilon
        self.u /= self.d
        self.p += self.u


def _adam_epochs(net, X, y) -> None:
    """scikit-learn's ``MLPRegressor._fit_stochastic`` for what :func:`fit_learned_predictor` trains (Adam, early
    stopping, shuffled mini-batches, no sample weights, a fresh fit), step for step and draw for draw, with the
    NumPy arrays indexed directly: scikit-learn's ``_safe_indexing`` (called for the shuffle of every epoch and
    for every mini-batch) first asks whether the array is a data frame, which took about a third of a network's
    training time. The same networks bit for bit (tested against ``MLPRegressor``)."""
    import warnings

    from sklearn.exceptions import ConvergenceWarning
    from sklearn.model_selection import train_test_split
    from sklearn.neural_network._stochastic_optimizers import AdamOptimizer
    from sklearn.utils import gen_batches

    net._optimizer = AdamOptimizer(
        net.coefs_ + net.intercepts_, net.learning_rate_init, net.beta_1, net.beta_2, net.epsilon
    )
    adam = _FlatAdam(net)
    rs = net._random_state
    X_train, X_val, y_train, y_val = train_test_split(X, y, random_state=rs, test_size=net.validation_fraction)
    if X_val.shape[0] < 2:
        raise ValueError("The validation set is too small. Increase 'validation_fraction' or the size of your dataset.")
    n_samples = X_train.shape[0]
    sample_idx = np.arange(n_samples, dtype=int)
    batch_size = min(200, n_samples)
    activations, deltas = [None] * (len(net.coefs_) + 1), [None] * len(net.coefs_)
    coef_grads = [np.empty_like(c) for c in net.coefs_]
    intercept_grads = [np.empty_like(b) for b in net.intercepts_]
    net.n_iter_ = 0
    lean = (net.n_layers_, net.activation, net.out_activation_, net.loss) == (3, "tanh", "identity", "squared_error")
    for _ in range(net.max_iter):
        order = np.arange(n_samples)  # sklearn.utils.shuffle: the same permutation of the same generator
        rs.shuffle(order)
        sample_idx = sample_idx[order]
        accumulated_loss = 0.0
        for batch_slice in gen_batches(n_samples, batch_size):
            batch_idx = sample_idx[batch_slice]
            X_batch = X_train[batch_idx]
            if lean:
                batch_loss, coef_grads, intercept_grads = _tanh_backprop(net, X_batch, y_train[batch_idx])
            else:
                activations[0] = X_batch
                batch_loss, coef_grads, intercept_grads = net._backprop(
                    X_batch, y_train[batch_idx], None, activations, deltas, coef_grads, intercept_grads
                )
            accumulated_loss += batch_loss * (batch_slice.stop - batch_slice.start)
            adam.step(coef_grads + intercept_grads)
        net.n_iter_ += 1
        net.loss_ = accumulated_loss / X_train.shape[0]
        net.t_ += n_samples
        net.loss_curve_.append(net.loss_)
        net._update_no_improvement_count(True, X_val, y_val, None)
        net._optimizer.iteration_ends(net.t_)
        if net._no_improvement_count > net.n_iter_no_change:
            if net._optimizer.trigger_stopping("no improvement", net.verbose):
                break
            net._no_improvement_count = 0
        if net.n_iter_ == net.max_iter:
            warnings.warn(
                "Stochastic Optimizer: Maximum iterations (%d) reached and the optimization hasn't converged yet."
                % net.max_iter,
                ConvergenceWarning,
                stacklevel=2,
            )
    net.coefs_ = net._best_coefs  # restore the best weights (early stopping)
    net.intercepts_ = net._best_intercepts


_MLP = None


def _mlp_regressor():
    """``sklearn.neural_network.MLPRegressor`` whose early-stopping score is :func:`_r2` (one output, no sample
    weights: what :func:`fit_learned_predictor` trains) and whose training loop is :func:`_adam_epochs`; the same
    networks bit for bit (tested)."""
    global _MLP
    if _MLP is None:
        from sklearn.neural_network import MLPRegressor

        class _EarlyStoppedMLP(MLPRegressor):
            def _score(self, X, y, sample_weight=None):
                if sample_weight is not None or np.shape(y)[1:] not in ((), (1,)):
                    return super()._score(X, y, sample_weight=sample_weight)
                y_pred = self._predict(X, check_input=False)
                return np.nan if not np.isfinite(y_pred).all() else _r2(y, y_pred)

            def _fit_stochastic(self, X, y, sample_weight, activations, deltas, cg, ig, layer_units, incremental):
                plain = (self.solver, self.batch_size, self.early_stopping, self.shuffle) == (
                    "adam",
                    "auto",
                    True,
                    True,
                )
                if not plain or incremental or sample_weight is not None or not isinstance(X, np.ndarray):
                    return super()._fit_stochastic(
                        X, y, sample_weight, activations, deltas, cg, ig, layer_units, incremental
                    )
                _adam_epochs(self, X, y)

        _EarlyStoppedMLP.__module__ = __name__  # pickled by name: see __getattr__
        _EarlyStoppedMLP.__qualname__ = "_EarlyStoppedMLP"
        _MLP = _EarlyStoppedMLP
    return _MLP


def __getattr__(name: str):
    """The network class by its module-level name (what a pickled model refers to), created on first use."""
    if name == "_EarlyStoppedMLP":
        return _mlp_regressor()
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def fit_learned_predictor(
    kind: str,
    z_train,
    n_lags: int,
    steps: int = 1,
    *,
    hidden_units: int = 16,
    rbf_centres: int = 100,
    max_samples: int | None = 4000,
    seed: int = 0,
    inputs: str = "increments",
):
    """Train a learned ``steps``-ahead predictor on the series in ``z_train`` (``inputs``: what the network is
    fed, see :func:`lag_features`; with absolute centres the target is standardised as well).

    Parameters
    ----------
    kind : {"mlp", "rbf"}
        ``"mlp"``: ``StandardScaler -> MLPRegressor`` (one tanh hidden layer of ``hidden_units``,
        back-propagation with Adam, early stopping). ``"rbf"``: ``StandardScaler ->
        Nystroem(rbf, rbf_centres units centred on training points, gamma = 1/n_lags) -> RidgeCV``.
    z_train : ndarray, shape (..., T)
        Training series (whole paths; keep test paths out).
    max_samples : int, optional
        Train on at most this many (input, target) pairs, drawn at random without replacement
        (``None`` = all).
    seed : int
        For the sample draw, the network's initial weights and the choice of RBF centres.

    Returns
    -------
    sklearn Pipeline, with attribute ``n_lags_`` and ``steps_`` set.
    """
    from sklearn.kernel_approximation import Nystroem
    from sklearn.linear_model import RidgeCV
    from sklearn.pipeline import make_pipeline
    from sklearn.preprocessing import StandardScaler

    if kind not in ("mlp", "rbf"):
        raise ValueError(f"parameter 'kind' = {kind!r}; it must be 'mlp' or 'rbf'")
    X, y = lag_features(z_train, n_lags, steps, inputs)
    X = X.reshape(-1, n_lags)
    y = y.reshape(-1)
    ok = np.all(np.isfinite(X), axis=1) & np.isfinite(y)
    if ok.sum() < 10 * n_lags:
        raise ValueError(f"only {ok.sum()} training samples for {n_lags} lags; give longer or more series")
    idx = np.flatnonzero(ok)
    if max_samples is not None and idx.size > max_samples:
        idx = np.sort(np.random.default_rng(seed).choice(idx, max_samples, replace=False))
    if kind == "mlp":
        model = make_pipeline(
            StandardScaler(),
            _mlp_regressor()(
                hidden_layer_sizes=(hidden_units,),
                activation="tanh",
                solver="adam",
                alpha=1e-4,
                learning_rate_init=1e-3,
                max_iter=2000,
                early_stopping=True,
                n_iter_no_change=10,
                random_state=seed,
            ),
        )
    else:
        model = make_pipeline(
            StandardScaler(),
            Nystroem(kernel="rbf", gamma=1.0 / n_lags, n_components=rbf_centres, random_state=seed),
            RidgeCV(alphas=np.logspace(-6, 2, 9)),
        )
    if inputs == "absolute centres":  # the target standardised too: a next centre, not a small increment
        from sklearn.compose import TransformedTargetRegressor

        model = TransformedTargetRegressor(regressor=model, transformer=StandardScaler())
    with _sklearn_unchecked():
        model.fit(X[idx], y[idx])
    model.n_lags_ = n_lags
    model.steps_ = steps
    model.inputs_ = inputs
    return model


def learned_forecast(model, z) -> np.ndarray:
    """Apply a model from :func:`fit_learned_predictor`: ``forecast = z + model(lags)``."""
    z = check_z(z)
    inputs = getattr(model, "inputs_", "increments")
    X, _ = lag_features(z, model.n_lags_, model.steps_, inputs)
    flat = X.reshape(-1, model.n_lags_)
    ok = np.all(np.isfinite(flat), axis=1)
    out = np.full(flat.shape[0], np.nan)
    with _sklearn_unchecked():
        out[ok] = model.predict(flat[ok])
    return out.reshape(z.shape) if inputs == "absolute centres" else z + out.reshape(z.shape)


def path_folds(n_paths: int, n_folds: int) -> list[tuple[np.ndarray, np.ndarray]]:
    """Split path indices ``0..n_paths-1`` into ``n_folds`` contiguous (train, test) folds."""
    if not (2 <= n_folds <= n_paths):
        raise ValueError(f"parameter 'n_folds' = {n_folds!r}; it must be in [2, n_paths={n_paths}]")
    idx = np.arange(n_paths)
    return [(np.setdiff1d(idx, test), test) for test in np.array_split(idx, n_folds)]


def cross_validated_pick(per_path_loss, folds) -> np.ndarray:
    """Tuning by cross-validation over paths: for each fold, the candidate with the smallest mean
    loss over the fold's *training* paths is used on its test paths.

    Parameters
    ----------
    per_path_loss : ndarray, shape (C, P)
        Loss (e.g. mean squared prediction error) of each of ``C`` candidate settings on each path.
    folds : list of (train, test) index arrays
        :func:`path_folds`.

    Returns
    -------
    ndarray of int, shape (P,)
        Index of the candidate applied to each path (chosen without that path).
    """
    loss = np.asarray(per_path_loss, dtype=float)
    if loss.ndim != 2:
        raise ValueError(f"parameter 'per_path_loss' has shape {loss.shape}; it must be (candidates, paths)")
    pick = np.full(loss.shape[1], -1)
    for train, test in folds:
        pick[test] = int(np.argmin(loss[:, train].mean(axis=1)))
    if np.any(pick < 0):
        raise ValueError("the folds do not cover every path")
    return pick
