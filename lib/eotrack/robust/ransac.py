"""A vectorised RANSAC engine with pluggable model, loss and refit.

A batch of ``U`` minimal samples is drawn at once, every hypothesis is fitted and scored on all
data with array operations (no Python loop per hypothesis), the best is chosen by cost
``J = Σ L(e)`` (eq. 3 of Yan et al. 2019; ties broken by more inliers, then smaller inlier
residual variance), and the final model is refitted on the best hypothesis's inliers — by
ordinary least squares (classic RANSAC) or by weighted least squares with weights from the loss
(WRANSAC).

Where the WRANSAC weights come from is not printed in the paper; three readings are offered
(``weighting``):

- ``"weighted"`` — from the residuals of the best minimal-sample *hypothesis* (the residuals
  that chose the inlier set);
- ``"weighted_refit"`` — one step: ordinary least squares on the inliers, then weights from
  *that* fit's residuals and one weighted refit;
- ``"weighted_iterated"`` — the same step iterated to a fixed point (an IRLS with the loss's
  weight function on the fixed inlier set).

Common random numbers: pass the same ``samples`` (from :func:`draw_samples`) to several calls
and every method scores exactly the same hypotheses.

The engine is generic: a model is given as two batched callables,
``fit_batch(x_samples (U, m, …), y_samples (U, m)) -> (params (U, p), valid (U,))`` and
``residuals_batch(params (U, p), x, y) -> (U, n)``, plus a ``refit(x, y, weights) -> params``.
:func:`ransac_linear` wires these up for any :class:`~eotrack.robust.models.LinearModel`.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from eotrack.validation import (
    as_finite_array,
    check_choice,
    check_generator,
    check_int,
    check_positive,
    check_same_length,
)

from .losses import LOSSES, get_loss
from .models import LinearModel, _check_model, _wls, fit_linear

__all__ = ["REFITS", "WEIGHTED_REFITS", "RansacResult", "draw_samples", "ransac", "ransac_linear",
           "wransac_linear"]

REFITS = ("lsq", "weighted", "weighted_refit", "weighted_iterated", "none")
#: Readings of "weights from the purified inlier set" (``weighting`` values of the WRANSAC refit).
WEIGHTED_REFITS = ("weighted", "weighted_refit", "weighted_iterated")


@dataclass(frozen=True)
class RansacResult:
    """Outcome of a RANSAC run.

    Attributes
    ----------
    params
        Final model parameters (after the refit).
    inliers
        Boolean mask of the best hypothesis's inliers (``|e| ≤ t``).
    weights
        Refit weights (1 on inliers for ``"lsq"``, ``1 − L(e)`` for ``"weighted"``, 0 elsewhere).
    cost
        Cost ``Σ L(e)`` of the best hypothesis.
    residuals
        Residuals of the best hypothesis (before the refit).
    losses
        Loss values of the best hypothesis.
    sample
        Indices of the best minimal sample.
    n_hypotheses, n_valid
        Hypotheses drawn and those that gave a well-posed fit.
    refitted
        Whether the refit ran (it needs at least ``m`` inliers with non-zero weight).
    hypothesis_params
        Parameters of the best minimal-sample hypothesis (before the refit).
    refit_iterations
        Weighted refits performed (0 for ``"lsq"``/``"none"``, 1 for ``"weighted"``, ≥ 1 for
        the refit readings).
    """

    params: np.ndarray
    inliers: np.ndarray
    weights: np.ndarray
    cost: float
    residuals: np.ndarray
    losses: np.ndarray
    sample: np.ndarray
    n_hypotheses: int
    n_valid: int
    refitted: bool
    hypothesis_params: np.ndarray | None = None
    refit_iterations: int = 0

    @property
    def n_inliers(self) -> int:
        """Number of inliers of the best hypothesis."""
        return int(self.inliers.sum())


def draw_samples(rng: np.random.Generator, n: int, sample_size: int, n_samples: int) -> np.ndarray:
    """``n_samples`` minimal samples of ``sample_size`` distinct indices out of ``n``.

    Returns
    -------
    numpy.ndarray
        Integer array ``(n_samples, sample_size)``.
    """
    check_generator(rng)
    n = check_int(n, "n", min_value=1)
    m = check_int(sample_size, "sample_size", min_value=1, max_value=n)
    u = check_int(n_samples, "n_samples", min_value=1)
    keys = rng.random((u, n))
    if m == n:
        return np.argsort(keys, axis=1)
    return np.argpartition(keys, m, axis=1)[:, :m]


def ransac(x: np.ndarray, y: np.ndarray, *, sample_size: int,
           fit_batch: Callable[[np.ndarray, np.ndarray], tuple[np.ndarray, np.ndarray]],
           residuals_batch: Callable[[np.ndarray, np.ndarray, np.ndarray], np.ndarray],
           refit: Callable[[np.ndarray, np.ndarray, np.ndarray], np.ndarray] | None,
           threshold: float, n_hypotheses: int, rng: np.random.Generator,
           loss: str = "zero_one", weighting: str = "lsq", samples: np.ndarray | None = None,
           max_refit_iterations: int = 100, refit_tol: float = 1e-9) -> RansacResult:
    """Generic vectorised RANSAC.

    Parameters
    ----------
    x, y
        Data: ``x`` ``(n, …)``, ``y`` ``(n,)``.
    sample_size
        Minimal sample size ``m``.
    fit_batch
        Fits all minimal samples at once (see module docstring).
    residuals_batch
        Residuals of every hypothesis on every datum, ``(U, n)``.
    refit
        ``refit(x, y, weights) -> params`` (weighted least squares); ``None`` keeps the best
        minimal-sample model.
    threshold
        Inlier threshold ``t`` (> 0).
    n_hypotheses
        Number of minimal samples ``U`` (eq. 2 gives the minimum).
    rng
        Random generator.
    loss
        Scoring loss, a key of :data:`eotrack.robust.LOSSES`.
    weighting
        ``"lsq"`` (inliers weight 1), ``"weighted"`` (``w = 1 − L(e)`` from the hypothesis's
        residuals), ``"weighted_refit"`` (``w`` from the residuals of the least-squares refit on
        the inliers, one weighted step), ``"weighted_iterated"`` (that step repeated until the
        parameters change by less than ``refit_tol`` relative), or ``"none"`` (no refit).
    samples
        Minimal samples to use, integer ``(U, m)`` (common random numbers across methods);
        ``None`` draws them with ``rng``. When given, ``n_hypotheses`` must equal ``U``.
    max_refit_iterations, refit_tol
        Iteration cap and relative tolerance of ``"weighted_iterated"``.

    Returns
    -------
    RansacResult
    """
    check_generator(rng)
    xx = as_finite_array(x, "x", ndim=(1, 2))
    yy = as_finite_array(y, "y", ndim=1)
    check_same_length("x", xx, "y", yy)
    m = check_int(sample_size, "sample_size", min_value=1)
    if len(yy) < m:
        raise ValueError(f"need at least sample_size={m} data points, got {len(yy)}")
    t = check_positive(threshold, "threshold")
    u = check_int(n_hypotheses, "n_hypotheses", min_value=1)
    loss_fn = get_loss(loss)
    check_choice(weighting, "weighting", REFITS)
    n_iter_max = check_int(max_refit_iterations, "max_refit_iterations", min_value=1)
    tol = check_positive(refit_tol, "refit_tol")

    if samples is None:
        idx = draw_samples(rng, len(yy), m, u)
    else:
        idx = np.asarray(samples)
        if idx.ndim != 2 or idx.shape[1] != m or not np.issubdtype(idx.dtype, np.integer):
            raise ValueError(f"samples must be an integer array of shape (U, {m}), got "
                             f"{idx.dtype} {idx.shape}")
        if idx.shape[0] != u:
            raise ValueError(f"samples has {idx.shape[0]} rows but n_hypotheses={u}")
        if idx.min() < 0 or idx.max() >= len(yy):
            raise ValueError(f"samples must index 0..{len(yy) - 1}")
    params, valid = fit_batch(xx[idx], yy[idx])
    res = residuals_batch(params, xx, yy)
    res = np.where(valid[:, None], res, np.inf)
    finite = np.isfinite(res)
    lossv = np.where(finite, loss_fn(np.where(finite, res, 0.0), t), 1.0)
    cost = np.where(valid, lossv.sum(axis=1), np.inf)
    inl = np.abs(res) <= t
    n_inl = inl.sum(axis=1)
    # mean squared inlier residual: the "variance" tie-break of the paper's step 3
    var = np.where(n_inl > 0, np.where(inl, res, 0.0) ** 2 @ np.ones(len(yy))
                   / np.maximum(n_inl, 1), np.inf)
    best = int(np.lexsort((var, -n_inl, cost))[0])
    best_res, best_loss, best_inl = res[best], lossv[best], inl[best]
    if not valid[best]:
        raise ValueError("no minimal sample gave a well-posed fit (degenerate data, e.g. repeated "
                         "x values); add data or hypotheses")
    if weighting == "weighted":
        w = np.where(best_inl, 1.0 - best_loss, 0.0)
    else:
        w = best_inl.astype(float)
    theta = params[best]
    refitted = False
    n_iter = 0
    if weighting != "none" and refit is not None and np.count_nonzero(w) >= m:
        theta = refit(xx, yy, w)
        refitted = True
        n_iter = int(weighting == "weighted")
        if weighting in ("weighted_refit", "weighted_iterated"):
            n_max = 1 if weighting == "weighted_refit" else n_iter_max
            for _ in range(n_max):
                e = residuals_batch(np.asarray(theta)[None, :], xx, yy)[0]
                w_new = np.where(best_inl, 1.0 - loss_fn(e, t), 0.0)
                if np.count_nonzero(w_new) < m:
                    break
                w = w_new
                new = refit(xx, yy, w)
                n_iter += 1
                step = np.max(np.abs(np.asarray(new) - theta))
                theta = new
                if step <= tol * (1.0 + np.max(np.abs(theta))):
                    break
    return RansacResult(params=np.asarray(theta), inliers=best_inl, weights=w,
                        cost=float(cost[best]), residuals=best_res, losses=best_loss,
                        sample=idx[best], n_hypotheses=u, n_valid=int(valid.sum()),
                        refitted=refitted, hypothesis_params=np.asarray(params[best]),
                        refit_iterations=n_iter)


def _linear_callables(model: LinearModel):
    def fit_batch(xs: np.ndarray, ys: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        a = model.design(xs)  # (U, m, p), m = p: one exact solve per sample, batched LU
        # scale-free conditioning test: |det A| relative to Hadamard's bound Π‖a_j‖
        det = np.abs(np.linalg.det(a))
        bound = np.prod(np.linalg.norm(a, axis=1), axis=1)
        ok = det > 1e-13 * bound
        a = np.where(ok[:, None, None], a, np.eye(a.shape[-1]))
        theta = np.linalg.solve(a, ys[..., None])[..., 0]
        return theta, ok

    def residuals_batch(theta: np.ndarray, x: np.ndarray, y: np.ndarray) -> np.ndarray:
        return y[None, :] - theta @ model.design(x).T

    cache: dict[str, np.ndarray] = {}

    def refit(x: np.ndarray, y: np.ndarray, w: np.ndarray) -> np.ndarray:
        # the refits of one call share x: build its design matrix once
        if "x" not in cache or cache["x"] is not x:
            cache["x"], cache["a"] = x, model.design(x)
        if np.count_nonzero(w) < model.n_params:
            return fit_linear(model, x, y, weights=w)  # raises the documented error
        return _wls(cache["a"], y, w)

    return fit_batch, residuals_batch, refit


def ransac_linear(model: LinearModel, x: np.ndarray, y: np.ndarray, *, threshold: float,
                  n_hypotheses: int, rng: np.random.Generator, loss: str = "zero_one",
                  weighting: str = "lsq", samples: np.ndarray | None = None,
                  max_refit_iterations: int = 100) -> RansacResult:
    """RANSAC for a linear-in-parameters model (minimal samples solved exactly, batched).

    Classic RANSAC is ``loss="zero_one", weighting="lsq"``; see :func:`wransac_linear` for the
    paper's WRANSAC. Other parameters as in :func:`ransac`.
    """
    _check_model(model)
    if loss not in LOSSES:
        check_choice(loss, "loss", tuple(LOSSES))
    fit_batch, residuals_batch, refit = _linear_callables(model)
    return ransac(x, y, sample_size=model.n_params, fit_batch=fit_batch,
                  residuals_batch=residuals_batch, refit=refit, threshold=threshold,
                  n_hypotheses=n_hypotheses, rng=rng, loss=loss, weighting=weighting,
                  samples=samples, max_refit_iterations=max_refit_iterations)


def wransac_linear(model: LinearModel, x: np.ndarray, y: np.ndarray, *, threshold: float,
                   n_hypotheses: int, rng: np.random.Generator, weighting: str = "weighted",
                   samples: np.ndarray | None = None) -> RansacResult:
    """WRANSAC (Yan et al. 2019): sinusoidal-loss scoring and a refit weighted by ``1 − L_s(e)``.

    ``weighting`` picks the reading of where the weights come from (one of
    :data:`WEIGHTED_REFITS`; default: the best hypothesis's residuals).
    """
    check_choice(weighting, "weighting", WEIGHTED_REFITS)
    return ransac_linear(model, x, y, threshold=threshold, n_hypotheses=n_hypotheses, rng=rng,
                         loss="sinusoidal", weighting=weighting, samples=samples)
