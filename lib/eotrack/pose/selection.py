"""CRLB-based feature selection (§2.4) and budgeted (optimal-design) selection.

The paper's procedure (§2.4, Fig. 3), applied to the RANSAC inliers:

1. score a point set by the weighted sum of the 7 CRLB values of ``(t1, t2, t3, q0, q1, q2, q3)``;
2. draw 6 random inliers and compare their score with the score of *all* inliers; if the 6 score
   worse, draw again; if every draw up to a preset count scores worse, use all inliers;
3. otherwise add the remaining inliers one at a time, keeping a point only when it lowers the
   score; the final set is used for the pose.

Fisher information is additive, ``J(S ∪ {i}) = J(S) + J_i`` with ``J_i ⪰ 0``, so with the exact
CRLB (``rule="exact"``) adding a point never raises the score: step 3 keeps every point and step 2
never succeeds. The rule as printed therefore selects nothing. The readings implemented here:

``"exact"``
    CRLB with the (known) per-point noise ``σ_i``: monotone, the rule as printed.
``"pooled"``
    The paper's eq. (5) model — one common ``σ²`` for all points — with ``σ²`` estimated from the
    set's own reprojection residuals, ``σ̂²(S) = Σ_S |r_i|² / (2|S|)``; score
    ``σ̂²(S) · tr(W (Σ_S G_iᵀG_i)⁻¹)``. Not monotone: a point with a large residual raises ``σ̂²``.
``"sandwich"``
    Covariance of the *unweighted* least-squares pose on the set with the true ``σ_i`` (oracle):
    ``H⁻¹ (Σ σ_i² G_iᵀG_i) H⁻¹``, ``H = Σ G_iᵀG_i``. Not monotone: a noisy point can hurt an
    unweighted solver.
``"tolerance"``
    Exact CRLB, but a point is kept only when it lowers the score by more than a fraction
    ``tol`` (a stopping rule).

The start test (step 2) compares raw scores (``start="paper"``) or scores per point,
``|S| · score(S)`` (``start="per_point"``), which lets 6 good points beat the average quality of
all inliers.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from eotrack.validation import (
    as_finite_array,
    as_points,
    check_choice,
    check_generator,
    check_int,
    check_positive,
    check_same_length,
)

from .fisher import _sigma, minimal_to_quaternion_jacobian, projection_jacobian
from .projection import quaternion_from_matrix

__all__ = [
    "RULES",
    "STARTS",
    "CRLBSelection",
    "crlb_weight_matrix",
    "greedy_design",
    "information_monotonicity",
    "scaled_crlb_weights",
    "score_shares",
    "select_features_crlb",
    "set_score",
]

RULES = ("exact", "pooled", "sandwich", "tolerance")
STARTS = ("paper", "per_point")


def crlb_weight_matrix(R: Any, weights: Any = None) -> np.ndarray:
    """6×6 matrix ``W₆ = Eᵀ diag(w) E`` so that ``tr(W₆ C₆)`` = weighted sum of the 7 CRLBs.

    ``C₆`` is the CRLB of (δt, δθ) and ``E`` (7×6) maps it to the paper's (t, q) (see
    :func:`eotrack.pose.minimal_to_quaternion_jacobian`). ``weights`` (7,) default to ones (the
    paper does not give its weights).
    """
    w = np.ones(7) if weights is None else as_finite_array(weights, "weights", shape=(7,))
    if np.any(w < 0):
        raise ValueError("weights must be >= 0")
    E = minimal_to_quaternion_jacobian(quaternion_from_matrix(R))
    return E.T @ (w[:, None] * E)


def scaled_crlb_weights(length_m: float) -> np.ndarray:
    """Weights that make the paper's score dimensionless: ``(1/L², 1/L², 1/L², 1, 1, 1, 1)``.

    With unit weights the score adds the translation variances (m²) to the quaternion
    variances (dimensionless) — its value and the selection depend on the unit of length.
    Dividing the translation terms by a stated length ``L`` squared (e.g. the range ``|t|``:
    the score then adds relative position variances to quaternion variances, which are about
    a quarter of the attitude variances in rad²) removes the unit.

    Parameters
    ----------
    length_m
        The length scale ``L`` (m), > 0.

    Returns
    -------
    numpy.ndarray
        (7,) weights for :func:`set_score` / :func:`select_features_crlb` (``weights=``).
    """
    L = check_positive(length_m, "length_m")
    return np.r_[np.full(3, 1.0 / L**2), np.ones(4)]


def score_shares(points: Any, R: Any, t: Any, K: Any, sigma_px: Any,
                 weights: Any = None) -> dict[str, float]:
    """Share of the exact weighted CRLB score from the translation and the quaternion terms.

    Returns
    -------
    dict
        ``{"translation": s_t, "quaternion": s_q}`` with ``s_t + s_q = 1``.
    """
    from .fisher import quaternion_crlb

    w = np.ones(7) if weights is None else as_finite_array(weights, "weights", shape=(7,))
    d = w * np.diag(quaternion_crlb(points, R, t, K, sigma_px))
    total = float(d.sum())
    return {"translation": float(d[:3].sum()) / total, "quaternion": float(d[3:].sum()) / total}


def _point_info(G: np.ndarray) -> np.ndarray:
    return np.einsum("nki,nkj->nij", G, G)


def _score(H: np.ndarray, W: np.ndarray, *, rule: str, s2sum: float = 0.0, m: int = 1,
           Sw: np.ndarray | None = None) -> float:
    """Score of a set from its accumulated quantities (inf if singular)."""
    try:
        Hi = np.linalg.inv(H)
    except np.linalg.LinAlgError:
        return np.inf
    if rule == "pooled":
        C = (s2sum / (2.0 * m)) * Hi
    elif rule == "sandwich":
        C = Hi @ Sw @ Hi
    else:
        C = Hi
    val = float(np.sum(W * C))
    return val if np.isfinite(val) and val > 0 else np.inf


@dataclass(frozen=True)
class CRLBSelection:
    """Result of :func:`select_features_crlb`.

    Attributes
    ----------
    selected
        Boolean mask over the input points (the chosen features).
    fallback
        True when no start draw beat the all-point score: all points are used (paper's rule).
    n_draws
        Start draws made.
    score_all, score_selected
        Set scores (same rule) of all points and of the selection.
    """

    selected: np.ndarray
    fallback: bool
    n_draws: int
    score_all: float
    score_selected: float

    @property
    def n_selected(self) -> int:
        """Number of chosen points."""
        return int(np.count_nonzero(self.selected))


def _prepare(points, R, t, K, sigma_px, residuals, rule):
    X = as_points(points, "points", dim=3)
    if X.shape[0] < 6:
        raise ValueError(f"points needs at least 6 points for CRLB selection, got {X.shape[0]}")
    G = projection_jacobian(X, R, t, K)
    n = len(X)
    sig = None
    if rule in ("exact", "tolerance", "sandwich"):
        if sigma_px is None:
            raise ValueError(f"sigma_px is required for rule={rule!r}")
        sig = _sigma(sigma_px, n)
    r2 = None
    if rule == "pooled":
        if residuals is None:
            raise ValueError("residuals (n, 2) are required for rule='pooled'")
        res = as_points(residuals, "residuals", dim=2)
        check_same_length("points", X, "residuals", res)
        r2 = np.sum(res * res, axis=1)
    return X, G, sig, r2


def set_score(points: Any, R: Any, t: Any, K: Any, *, rule: str = "exact",
              sigma_px: Any = None, residuals: Any = None, weights: Any = None) -> float:
    """Weighted sum of the 7 CRLB values of a point set under a selection ``rule``.

    Parameters
    ----------
    points
        (n, 3) target points of the set.
    R, t, K
        Reference pose (the RANSAC estimate) and intrinsics.
    rule
        One of :data:`RULES`.
    sigma_px
        Per-point noise (``"exact"``, ``"tolerance"``, ``"sandwich"``).
    residuals
        (n, 2) reprojection residuals at the reference pose (``"pooled"``).
    weights
        (7,) weights of the 7 CRLB values (default ones).
    """
    check_choice(rule, "rule", RULES)
    X, G, sig, r2 = _prepare(points, R, t, K, sigma_px, residuals, rule)
    W = crlb_weight_matrix(R, weights)
    A = _point_info(G)
    if rule in ("exact", "tolerance"):
        return _score(np.sum(A / sig[:, None, None] ** 2, axis=0), W, rule=rule)
    if rule == "pooled":
        return _score(A.sum(0), W, rule=rule, s2sum=float(r2.sum()), m=len(X))
    return _score(A.sum(0), W, rule=rule, Sw=np.sum(A * sig[:, None, None] ** 2, axis=0))


def select_features_crlb(points: Any, R: Any, t: Any, K: Any, rng: np.random.Generator, *,
                         rule: str = "pooled", start: str = "per_point", sigma_px: Any = None,
                         residuals: Any = None, weights: Any = None, max_draws: int = 50,
                         tol: float = 0.01, sample_size: int = 6,
                         order: str = "random") -> CRLBSelection:
    """The paper's CRLB feature selection (§2.4) over the RANSAC inliers.

    Parameters
    ----------
    points
        (n, 3) target points of the RANSAC inliers.
    R, t, K
        Reference pose (RANSAC estimate on the inliers) and intrinsics; the Jacobians are
        evaluated there.
    rng
        Generator for the start draws and the order in which the rest are tried.
    rule
        Score reading, one of :data:`RULES` (module docstring).
    start
        Start test, ``"paper"`` (raw score of 6 vs all) or ``"per_point"``.
    sigma_px, residuals, weights
        See :func:`set_score`.
    max_draws
        Preset number of start draws before falling back to all points.
    tol
        Relative decrease required to keep a point under ``rule="tolerance"``.
    sample_size
        Start-set size (6 in the paper).
    order
        Order in which the remaining points are tried (the paper does not say):
        ``"random"`` or ``"residual"`` (ascending reprojection residual; needs ``residuals``).

    Returns
    -------
    CRLBSelection
    """
    rng = check_generator(rng)
    check_choice(rule, "rule", RULES)
    check_choice(start, "start", STARTS)
    max_draws = check_int(max_draws, "max_draws", min_value=1)
    m0 = check_int(sample_size, "sample_size", min_value=6)
    tol = check_positive(tol, "tol", allow_zero=True)
    check_choice(order, "order", ["random", "residual"])
    if order == "residual" and residuals is None:
        raise ValueError("residuals (n, 2) are required for order='residual'")
    X, G, sig, r2 = _prepare(points, R, t, K, sigma_px, residuals, rule)
    if r2 is None and residuals is not None:
        res = as_points(residuals, "residuals", dim=2)
        check_same_length("points", X, "residuals", res)
        rr = np.sum(res * res, axis=1)
    else:
        rr = r2
    n = len(X)
    if n < m0:
        raise ValueError(f"points needs at least sample_size={m0} points, got {n}")
    W = crlb_weight_matrix(R, weights)
    A = _point_info(G)
    if rule in ("exact", "tolerance"):
        Ai = A / sig[:, None, None] ** 2
    else:
        Ai = A
    Si = A * sig[:, None, None] ** 2 if rule == "sandwich" else np.zeros_like(A)
    r2v = r2 if r2 is not None else np.zeros(n)

    def score_of(idx: np.ndarray) -> float:
        return _score(Ai[idx].sum(0), W, rule=rule, s2sum=float(r2v[idx].sum()), m=len(idx),
                      Sw=Si[idx].sum(0))

    all_idx = np.arange(n)
    s_all = score_of(all_idx)
    ref_all = s_all * (n if start == "per_point" else 1)
    # step 2: start draws, scored in one batch; the first (in draw order) that beats all wins
    draws_idx = np.argsort(rng.random((max_draws, n)), axis=1)[:, :m0]
    Hd = Ai[draws_idx].sum(1)
    with np.errstate(all="ignore"):
        ok_d = np.linalg.cond(Hd) < 1e12
        Hinv = np.linalg.inv(np.where(ok_d[:, None, None], Hd, np.eye(6)))
        if rule == "pooled":
            Cd = (r2v[draws_idx].sum(1) / (2.0 * m0))[:, None, None] * Hinv
        elif rule == "sandwich":
            Cd = Hinv @ Si[draws_idx].sum(1) @ Hinv
        else:
            Cd = Hinv
        sd = np.where(ok_d, np.einsum("ij,bij->b", W, Cd), np.inf)
    sd = np.where(np.isfinite(sd) & (sd > 0), sd, np.inf)
    win = np.flatnonzero(sd * (m0 if start == "per_point" else 1) < ref_all)
    if win.size == 0:
        return CRLBSelection(np.ones(n, bool), True, max_draws, s_all, s_all)
    draws = int(win[0]) + 1
    chosen = draws_idx[win[0]]
    sel = np.zeros(n, bool)
    sel[chosen] = True
    H = Ai[chosen].sum(0)
    Sw = Si[chosen].sum(0)
    s2 = float(r2v[chosen].sum())
    m = m0
    cur = score_of(chosen)
    rest = np.flatnonzero(~sel)
    rest = rng.permutation(rest) if order == "random" else rest[np.argsort(rr[rest], kind="stable")]
    inv = np.linalg.inv
    for i in rest:
        H_new = H + Ai[i]
        Hi = inv(H_new)
        if rule == "pooled":
            s_new = (s2 + r2v[i]) / (2.0 * (m + 1)) * float(np.sum(W * Hi))
        elif rule == "sandwich":
            s_new = float(np.sum(W * (Hi @ (Sw + Si[i]) @ Hi)))
        else:
            s_new = float(np.sum(W * Hi))
        keep = s_new < cur * (1.0 - tol) if rule == "tolerance" else s_new < cur
        if keep:
            sel[i] = True
            H = H_new
            Sw = Sw + Si[i]
            s2 += r2v[i]
            m += 1
            cur = s_new
    return CRLBSelection(sel, False, draws, s_all, cur)


def information_monotonicity(points: Any, R: Any, t: Any, K: Any, sigma_px: Any,
                             order: Any = None, *, weights: Any = None) -> np.ndarray:
    """Exact-CRLB score of the nested sets ``S_6 ⊂ S_7 ⊂ … ⊂ S_n`` (points added in ``order``).

    Returns
    -------
    numpy.ndarray
        (n − 5,) scores; non-increasing because ``J(S ∪ {i}) = J(S) + J_i``, ``J_i ⪰ 0``.
    """
    X = as_points(points, "points", dim=3)
    n = len(X)
    if n < 6:
        raise ValueError(f"points needs at least 6 points, got {n}")
    order = np.arange(n) if order is None else np.asarray(order)
    if sorted(order.tolist()) != list(range(n)):
        raise ValueError(f"order must be a permutation of range({n})")
    G = projection_jacobian(X, R, t, K)
    sig = _sigma(sigma_px, n)
    A = _point_info(G)[order] / sig[order, None, None] ** 2
    cum = np.cumsum(A, axis=0)[5:]
    W = crlb_weight_matrix(R, weights)
    C = np.linalg.inv(cum)
    return np.einsum("ij,nij->n", W, C)


def greedy_design(points: Any, R: Any, t: Any, K: Any, k: int, sigma_px: Any, *,
                  criterion: str = "D", weights: Any = None) -> np.ndarray:
    """Best ``k`` points by greedy optimal design on the Fisher information.

    ``criterion="D"`` maximises ``log det J(S)`` (volume of the confidence ellipsoid),
    ``"A"`` minimises ``tr(W J(S)⁻¹)`` (the paper's weighted CRLB sum). Each step adds the point
    with the best rank-2 update for all candidates at once (determinant lemma / Woodbury).

    Returns
    -------
    numpy.ndarray
        The ``k`` chosen indices, in the order they were added.
    """
    check_choice(criterion, "criterion", ["D", "A"])
    X = as_points(points, "points", dim=3)
    n = len(X)
    k = check_int(k, "k", min_value=6, max_value=n)
    G = projection_jacobian(X, R, t, K) / _sigma(sigma_px, n)[:, None, None]
    W = crlb_weight_matrix(R, weights)
    A = _point_info(G)
    eps = 1e-9 * np.trace(A.sum(0)) / 6.0
    H = eps * np.eye(6)
    free = np.ones(n, bool)
    chosen: list[int] = []
    I2 = np.eye(2)
    for _ in range(k):
        Hi = np.linalg.inv(H)
        cand = np.flatnonzero(free)
        Gc = G[cand]
        GH = Gc @ Hi                                   # (c, 2, 6)
        S = I2 + GH @ np.swapaxes(Gc, 1, 2)            # (c, 2, 2)
        if criterion == "D":
            val = -np.linalg.slogdet(S)[1]             # minimise −log det
        else:
            # tr(W (H + GᵀG)⁻¹) = tr(W H⁻¹) − tr(W H⁻¹Gᵀ S⁻¹ G H⁻¹)
            M = np.swapaxes(GH, 1, 2) @ np.linalg.solve(S, GH)   # (c, 6, 6)
            val = -np.einsum("ij,cij->c", W, M)
        best = int(cand[np.argmin(val)])
        chosen.append(best)
        free[best] = False
        H = H + A[best]
    return np.array(chosen)
