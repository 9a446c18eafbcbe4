"""M-estimators by iteratively reweighted least squares (IRLS) for linear models.

``irls_linear`` minimises ``Σ ρ(e_i / s)`` for a linear-in-parameters model with a known scale
``s`` by IRLS, started from given parameters (e.g. a RANSAC fit, so that the redescending Cauchy
loss starts in the right basin). Weight functions (Huber 1981; Holland & Welsch 1977):

- ``"huber"``: ``w(u) = min(1, k/|u|)``, ``k = 1.345`` (95 % Gaussian efficiency);
- ``"cauchy"``: ``w(u) = 1 / (1 + (u/c)²)``, ``c = 2.385`` (95 % Gaussian efficiency);
- ``"tukey"``: ``w(u) = (1 − (u/c)²)²`` for ``|u| < c``, else 0, ``c = 4.685``.
"""

from __future__ import annotations

import numpy as np

from eotrack.validation import as_finite_array, check_choice, check_int, check_positive

from .models import LinearModel, _check_model, _wls

__all__ = ["M_ESTIMATORS", "irls_linear", "m_weights"]

#: Weight-function name → default tuning constant (95 % efficiency under Gaussian noise).
M_ESTIMATORS: dict[str, float] = {"huber": 1.345, "cauchy": 2.385, "tukey": 4.685}


def m_weights(u: np.ndarray, kind: str = "huber", c: float | None = None) -> np.ndarray:
    """IRLS weights ``w(u)`` of standardised residuals ``u = e/s``.

    Parameters
    ----------
    u
        Standardised residuals.
    kind
        ``"huber"``, ``"cauchy"`` or ``"tukey"``.
    c
        Tuning constant (default: :data:`M_ESTIMATORS`).
    """
    check_choice(kind, "kind", tuple(M_ESTIMATORS))
    a = np.abs(as_finite_array(u, "u"))
    k = M_ESTIMATORS[kind] if c is None else check_positive(c, "c")
    if kind == "huber":
        return np.minimum(1.0, k / np.maximum(a, 1e-300))
    if kind == "cauchy":
        return 1.0 / (1.0 + (a / k) ** 2)
    return np.where(a < k, (1.0 - (a / k) ** 2) ** 2, 0.0)


def irls_linear(model: LinearModel, x: np.ndarray, y: np.ndarray, theta0: np.ndarray, *,
                scale: float, kind: str = "huber", c: float | None = None,
                max_iter: int = 50, tol: float = 1e-9) -> np.ndarray:
    """M-estimate of a linear model by IRLS from ``theta0`` with known residual scale.

    Parameters
    ----------
    model
        A linear model (``design``, ``n_params``).
    x, y
        Data ``(n,)``.
    theta0
        Start parameters (``(n_params,)``), e.g. RANSAC's.
    scale
        Residual scale ``s`` (> 0), e.g. the noise σ.
    kind, c
        Weight function and tuning constant (see :func:`m_weights`).
    max_iter, tol
        Iteration cap and relative parameter tolerance.

    Returns
    -------
    numpy.ndarray
        Parameters ``(n_params,)``.
    """
    _check_model(model)
    xx = as_finite_array(x, "x", ndim=1)
    yy = as_finite_array(y, "y", ndim=1)
    th = as_finite_array(theta0, "theta0", ndim=1)
    if th.shape != (model.n_params,):
        raise ValueError(f"theta0 must have shape ({model.n_params},), got {th.shape}")
    s = check_positive(scale, "scale")
    n_it = check_int(max_iter, "max_iter", min_value=1)
    a = model.design(xx)
    for _ in range(n_it):
        w = m_weights((yy - a @ th) / s, kind, c)
        if np.count_nonzero(w) < model.n_params:
            break
        new = _wls(a, yy, w)
        step = np.max(np.abs(new - th))
        th = new
        if step <= tol * (1.0 + np.max(np.abs(th))):
            break
    return th
