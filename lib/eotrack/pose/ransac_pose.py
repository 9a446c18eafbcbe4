"""Robust pose: the paper's 6-point DLT RANSAC (§2.2), OpenCV's RANSAC, and pose refinement.

The paper's RANSAC feature selection, step by step (§2.2):

1. draw 6 feature points at random and estimate the pose from them (linear DLT);
2. test every point against that pose: a point whose reprojection error is below a threshold is
   an *inlier*, otherwise an *outlier*;
3. if enough points are inliers, accept the model: its inliers are the selected features
   (and, as in the general description of §2.2, the pose is re-estimated from all of them);
4. otherwise draw again;
5. if a preset number of draws all fail, RANSAC fails: the image is unsuitable and discarded.

:func:`ransac_pose_dlt` follows these steps literally but evaluates the draws in vectorised
batches; the accepted draw is the first one (in draw order) that passes step 3, so the result is
the same as a one-at-a-time loop. Failure is a reported outcome (``RansacResult.success``), not an
exception. :func:`ransac_pose_opencv` wraps ``cv2.solvePnPRansac`` (SQPnP) and
``cv2.solvePnPRefineLM``. :func:`refine_pose` is a (weighted) Gauss–Newton/Levenberg–Marquardt
refinement with the analytic Jacobian of :mod:`eotrack.pose.fisher` — with ``σ_i`` it is the
maximum-likelihood pose.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import cv2
import numpy as np
from scipy.spatial.transform import Rotation

from eotrack.validation import (
    as_points,
    check_generator,
    check_int,
    check_positive,
    check_probability,
    check_same_length,
)

from .dlt import dlt_pose, dlt_pose_batch, plane_frame
from .fisher import _du_dxc, _sigma
from .projection import _check_K, check_rotation, check_translation, skew

__all__ = [
    "RansacConfig",
    "RansacResult",
    "best_initial_pose",
    "ippe_poses",
    "ransac_pose_dlt",
    "ransac_pose_opencv",
    "refine_pose",
    "refine_pose_opencv",
    "reprojection_errors",
]


def _check_pair(points: Any, pixels: Any, min_points: int = 6) -> tuple[np.ndarray, np.ndarray]:
    X = as_points(points, "points", dim=3)
    u = as_points(pixels, "pixels", dim=2)
    check_same_length("points", X, "pixels", u)
    if X.shape[0] < min_points:
        raise ValueError(f"points needs at least {min_points} correspondences, got {X.shape[0]}")
    Xc = X - X.mean(axis=0)
    s = np.linalg.svd(Xc, compute_uv=False)
    if s[1] <= 1e-9 * max(s[0], 1e-300):
        raise ValueError("points are collinear (degenerate): the pose is not determined")
    return X, u


def reprojection_errors(points: Any, pixels: Any, R: Any, t: Any, K: Any) -> np.ndarray:
    """Euclidean reprojection error of each point (image units); ``inf`` behind the camera."""
    X = as_points(points, "points", dim=3)
    u = as_points(pixels, "pixels", dim=2)
    check_same_length("points", X, "pixels", u)
    R = check_rotation(R, atol=1e-5)
    t = check_translation(t)
    K = _check_K(K)
    p = (X @ R.T + t) @ K.T
    z = p[:, 2]
    with np.errstate(divide="ignore", invalid="ignore"):
        e = np.linalg.norm(p[:, :2] / z[:, None] - u, axis=1)
    return np.where(z > 0, e, np.inf)


def _batch_errors(X: np.ndarray, u: np.ndarray, R: np.ndarray, t: np.ndarray,
                  K: np.ndarray) -> np.ndarray:
    """(B, n) reprojection errors of all points under B poses."""
    p = (np.einsum("bij,nj->bni", R, X) + t[:, None, :]) @ K.T
    z = p[..., 2]
    with np.errstate(divide="ignore", invalid="ignore"):
        e = np.linalg.norm(p[..., :2] / z[..., None] - u[None], axis=-1)
    return np.where(z > 0, e, np.inf)


def refine_pose(points: Any, pixels: Any, K: Any, R0: Any, t0: Any, *,
                sigma_px: Any = None, max_iter: int = 30,
                tol: float = 1e-9) -> tuple[np.ndarray, np.ndarray]:
    """Levenberg–Marquardt pose refinement minimising ``Σ |u_i − π(R X_i + t)|² / σ_i²``.

    Parameters
    ----------
    points, pixels
        (n, 3) target points and (n, 2) image points, n ≥ 3.
    K
        Intrinsic matrix.
    R0, t0
        Initial pose.
    sigma_px
        Per-point noise standard deviation (scalar or (n,)); ``None`` = unweighted
        (ordinary least squares). With the true ``σ_i`` this is the maximum-likelihood pose.
    max_iter, tol
        Iteration limit and relative step tolerance.

    Returns
    -------
    R, t
        Refined pose.
    """
    X = as_points(points, "points", dim=3)
    u = as_points(pixels, "pixels", dim=2)
    check_same_length("points", X, "pixels", u)
    if X.shape[0] < 3:
        raise ValueError(f"points needs at least 3 correspondences, got {X.shape[0]}")
    K = _check_K(K)
    R = check_rotation(R0, "R0", atol=1e-5)
    t = check_translation(t0, "t0").copy()
    max_iter = check_int(max_iter, "max_iter", min_value=1)
    w = np.ones(len(X)) if sigma_px is None else 1.0 / _sigma(sigma_px, len(X)) ** 2

    def residual(R: np.ndarray, t: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        RX = X @ R.T
        xc = RX + t
        p = xc @ K.T
        r = u - p[:, :2] / p[:, 2:3]
        return r, RX, xc

    r, RX, xc = residual(R, t)
    cost = float(np.sum(w * np.sum(r * r, axis=1)))
    lam = 1e-3
    for _ in range(max_iter):
        D = _du_dxc(xc, K)
        G = np.concatenate([D, -D @ skew(RX)], axis=2)
        Gw = G * w[:, None, None]
        H = np.einsum("nki,nkj->ij", Gw, G)
        g = np.einsum("nki,nk->i", Gw, r)
        improved = False
        for _ in range(10):
            step = np.linalg.solve(H + lam * np.diag(np.diag(H)), g)
            R_new = Rotation.from_rotvec(step[3:]).as_matrix() @ R
            t_new = t + step[:3]
            r_new, RX_new, xc_new = residual(R_new, t_new)
            if np.all(xc_new[:, 2] > 0):
                c_new = float(np.sum(w * np.sum(r_new * r_new, axis=1)))
                if c_new <= cost:
                    improved = True
                    break
            lam *= 10.0
        if not improved:
            break
        R, t, r, RX, xc = R_new, t_new, r_new, RX_new, xc_new
        rel = abs(cost - c_new) / max(cost, 1e-300)
        cost = c_new
        lam = max(lam / 10.0, 1e-9)
        if rel < tol or np.linalg.norm(step) < tol:
            break
    return R, t


def refine_pose_opencv(points: Any, pixels: Any, K: Any, R0: Any,
                       t0: Any) -> tuple[np.ndarray, np.ndarray]:
    """Unweighted refinement with ``cv2.solvePnPRefineLM`` (same model, OpenCV's solver)."""
    X = as_points(points, "points", dim=3)
    u = as_points(pixels, "pixels", dim=2)
    check_same_length("points", X, "pixels", u)
    K = _check_K(K)
    rvec = cv2.Rodrigues(check_rotation(R0, "R0", atol=1e-5))[0]
    tvec = check_translation(t0, "t0").reshape(3, 1).copy()
    rvec, tvec = cv2.solvePnPRefineLM(X, u, K, None, rvec, tvec)
    return cv2.Rodrigues(rvec)[0], tvec.ravel()


def ippe_poses(points: Any, pixels: Any, K: Any) -> list[tuple[np.ndarray, np.ndarray]]:
    """Both IPPE solutions of a coplanar target, computed in the plane's own frame.

    ``cv2.solvePnPGeneric(..., SOLVEPNP_IPPE)`` given coplanar points that do not lie in the
    object's ``Z = 0`` plane (here ``Z_t = −1`` m) returns two wrong poses (both ≈ 24° off) in
    about half of the paper's scenes even with tiny noise (benchmark notes). Expressing the
    points in the plane frame ``X = c + B p`` (:func:`eotrack.pose.plane_frame`, ``p_z = 0``)
    and mapping back, ``R = R_p Bᵀ``, ``t = t_p − R c``, removes the failure.

    Returns
    -------
    list of (R, t)
        The two solutions, lowest reprojection error first.
    """
    X, u = _check_pair(points, pixels, 4)
    K = _check_K(K)
    c, B = plane_frame(X)
    P = (X - c) @ B
    if np.max(np.abs(P[:, 2])) > 1e-6 * np.max(np.abs(P[:, :2])):
        raise ValueError("points must be coplanar for IPPE")
    P[:, 2] = 0.0
    _, rv, tv, _ = cv2.solvePnPGeneric(np.ascontiguousarray(P), np.ascontiguousarray(u), K,
                                       None, flags=cv2.SOLVEPNP_IPPE)
    out = []
    for r, tt in zip(rv, tv):
        Rp = cv2.Rodrigues(r)[0]
        R = Rp @ B.T
        out.append((R, tt.ravel().astype(float) - R @ c))
    return out


def best_initial_pose(points: Any, pixels: Any, K: Any, *,
                      extra: Any = ()) -> tuple[np.ndarray, np.ndarray]:
    """Linear start resolved against the planar two-fold ambiguity.

    Candidates: the DLT pose, any ``extra`` (R, t) pairs and, for a coplanar target, both IPPE
    solutions (:func:`ippe_poses`); each is refined by unweighted LM and the one with the
    lowest reprojection cost is returned. With noisy images of a small, distant plane the DLT
    start often falls into the mirrored ("flipped") local minimum; this picks the better one.
    """
    X, u = _check_pair(points, pixels, 6)
    K = _check_K(K)
    cands = [dlt_pose(X, u, K), *[(np.asarray(R, float), np.asarray(t, float).ravel())
                                  for R, t in extra]]
    s = np.linalg.svd(X - X.mean(0), compute_uv=False)
    if s[2] <= 1e-6 * s[0]:
        cands += ippe_poses(X, u, K)
    best, best_cost = None, np.inf
    for R0, t0 in cands:
        if np.any((X @ R0.T + t0)[:, 2] <= 0):
            continue
        R1, t1 = refine_pose(X, u, K, R0, t0)
        c = float(np.sum(reprojection_errors(X, u, R1, t1, K) ** 2))
        if c < best_cost:
            best, best_cost = (R1, t1), c
    if best is None:
        raise ValueError("points: no candidate pose puts the points in front of the camera")
    return best


@dataclass(frozen=True)
class RansacConfig:
    """Settings of the paper's RANSAC (§2.2); the paper gives none of the numbers.

    Attributes
    ----------
    sample_size
        Points per random draw (6 in the paper: the linear DLT minimum).
    inlier_threshold_px
        Reprojection-error threshold of the inlier test (image units).
    min_inlier_ratio
        Step 3: a model is accepted when at least this fraction of all points are inliers.
    max_draws
        Step 5: the preset number of draws after which RANSAC reports failure.
    refit
        Re-estimate the pose from all inliers of the accepted model (§2.2's general description:
        :func:`best_initial_pose`, i.e. DLT or IPPE + unweighted LM) and re-run the inlier test
        once with it.
    batch
        Draws evaluated per vectorised batch (does not change the result).
    """

    sample_size: int = 6
    inlier_threshold_px: float = 1.0
    min_inlier_ratio: float = 0.7
    max_draws: int = 500
    refit: bool = True
    batch: int = 64

    def __post_init__(self) -> None:
        check_int(self.sample_size, "sample_size", min_value=6)
        check_positive(self.inlier_threshold_px, "inlier_threshold_px")
        check_probability(self.min_inlier_ratio, "min_inlier_ratio", open_low=True)
        check_int(self.max_draws, "max_draws", min_value=1)
        check_int(self.batch, "batch", min_value=1)


@dataclass(frozen=True)
class RansacResult:
    """Outcome of a robust pose estimate.

    ``success`` is False when every draw failed (step 5): the image is to be discarded; then
    ``R``/``t`` are ``None`` and ``inliers`` is all False.
    """

    success: bool
    R: np.ndarray | None
    t: np.ndarray | None
    inliers: np.ndarray
    n_draws: int
    message: str = ""
    errors: np.ndarray | None = field(default=None, repr=False)

    @property
    def n_inliers(self) -> int:
        """Number of selected (inlier) points."""
        return int(np.count_nonzero(self.inliers))


def ransac_pose_dlt(points: Any, pixels: Any, K: Any, rng: np.random.Generator,
                    config: RansacConfig | None = None) -> RansacResult:
    """The paper's RANSAC feature selection with a 6-point DLT pose (§2.2, steps 1–5).

    Parameters
    ----------
    points, pixels
        (n, 3) target points and (n, 2) matched image points, n ≥ ``sample_size``.
    K
        Intrinsic matrix.
    rng
        Random generator for the draws.
    config
        :class:`RansacConfig`; paper-style defaults.

    Returns
    -------
    RansacResult
        ``success=False`` (not an exception) when ``max_draws`` draws all fail.
    """
    cfg = config if config is not None else RansacConfig()
    if not isinstance(cfg, RansacConfig):
        raise TypeError(f"config must be a RansacConfig, got {type(cfg).__name__}")
    rng = check_generator(rng)
    X, u = _check_pair(points, pixels, cfg.sample_size)
    K = _check_K(K)
    n = len(X)
    need = int(np.ceil(cfg.min_inlier_ratio * n))
    planar = np.linalg.svd(X - X.mean(0), compute_uv=False)
    planar = bool(planar[2] <= 1e-6 * planar[0])
    drawn = 0
    while drawn < cfg.max_draws:
        b = min(cfg.batch, cfg.max_draws - drawn)
        # step 1: b independent draws of sample_size distinct points
        idx = np.argsort(rng.random((b, n)), axis=1)[:, :cfg.sample_size]
        R, t, ok = dlt_pose_batch(X[idx], u[idx], K, planar=planar)
        # step 2: inlier test of every point against each draw's pose
        err = _batch_errors(X, u, R, t, K)
        inl = (err < cfg.inlier_threshold_px) & ok[:, None]
        # step 3: the first draw (in draw order) with enough inliers is accepted
        good = np.flatnonzero(inl.sum(axis=1) >= need)
        if good.size:
            k = int(good[0])
            drawn += k + 1
            inliers = inl[k]
            Rk, tk = R[k], t[k]
            if cfg.refit:
                Rk, tk = best_initial_pose(X[inliers], u[inliers], K)
                e = reprojection_errors(X, u, Rk, tk, K)
                inliers = e < cfg.inlier_threshold_px
                if inliers.sum() >= 6:
                    Rk, tk = refine_pose(X[inliers], u[inliers], K, Rk, tk)
            e = reprojection_errors(X, u, Rk, tk, K)
            return RansacResult(True, Rk, tk, inliers, drawn, "accepted", e)
        drawn += b  # step 4: all draws of this batch failed, draw again
    # step 5: failure after the preset number of draws
    return RansacResult(False, None, None, np.zeros(n, bool), drawn,
                        f"no draw out of {drawn} had >= {need} inliers: image discarded")


def ransac_pose_opencv(points: Any, pixels: Any, K: Any, *, threshold_px: float = 1.0,
                       confidence: float = 0.99, max_iters: int = 500,
                       method: str = "sqpnp", refine: bool = True,
                       disambiguate: bool = True) -> RansacResult:
    """Robust pose with ``cv2.solvePnPRansac`` (+ ``cv2.solvePnPRefineLM`` on the inliers).

    Parameters
    ----------
    points, pixels
        (n, 3) / (n, 2) correspondences, n ≥ 6.
    K
        Intrinsic matrix.
    threshold_px
        Inlier reprojection threshold.
    confidence, max_iters
        OpenCV's RANSAC confidence and iteration cap.
    method
        ``"sqpnp"``, ``"epnp"``, ``"iterative"`` or ``"ippe"`` (OpenCV's solver inside RANSAC).
    refine
        Refine on the inliers with ``solvePnPRefineLM``.
    disambiguate
        Also refine the DLT and both IPPE poses of the inliers (:func:`best_initial_pose`) and
        keep the lowest reprojection cost. SQPnP/EPnP minimise an algebraic (object-space)
        error; for a small, distant plane under large noise the two planar minima differ in
        reprojection cost by ~3 % and those solvers return the mirrored one in most scenes
        (see ``benchmarks/bench_ransac_crlb_pose.py``); this option fixes that.
    """
    from eotrack.validation import check_choice

    X, u = _check_pair(points, pixels, 6)
    K = _check_K(K)
    check_positive(threshold_px, "threshold_px")
    check_probability(confidence, "confidence", open_low=True, open_high=True)
    check_int(max_iters, "max_iters", min_value=1)
    flags = {"sqpnp": cv2.SOLVEPNP_SQPNP, "epnp": cv2.SOLVEPNP_EPNP,
             "iterative": cv2.SOLVEPNP_ITERATIVE,
             "ippe": cv2.SOLVEPNP_IPPE}[check_choice(method, "method",
                                                     ["sqpnp", "epnp", "iterative", "ippe"])]
    ok, rvec, tvec, idx = cv2.solvePnPRansac(X, u, K, None, iterationsCount=int(max_iters),
                                             reprojectionError=float(threshold_px),
                                             confidence=float(confidence), flags=flags)
    n = len(X)
    if not ok or idx is None or len(idx) < 6:
        return RansacResult(False, None, None, np.zeros(n, bool), int(max_iters),
                            "cv2.solvePnPRansac found no consensus: image discarded")
    inliers = np.zeros(n, bool)
    inliers[idx.ravel()] = True
    if refine:
        rvec, tvec = cv2.solvePnPRefineLM(X[inliers], u[inliers], K, None, rvec, tvec)
    R = cv2.Rodrigues(rvec)[0]
    t = tvec.ravel().astype(float)
    if disambiguate:
        # like the paper's refit: best of the candidate poses (OpenCV's, the DLT's and both
        # planar IPPE solutions), each refined by OpenCV's LM on the inliers; then the inlier
        # test is repeated against that pose and the pose refined once more
        Xi, ui = X[inliers], u[inliers]
        cands = [(R, t), dlt_pose(Xi, ui, K)]
        sv = np.linalg.svd(Xi - Xi.mean(0), compute_uv=False)
        if sv[2] <= 1e-6 * sv[0]:
            cands += ippe_poses(Xi, ui, K)
        best, best_cost = (R, t), np.inf
        for Rc, tc in cands:
            if np.any((Xi @ Rc.T + tc)[:, 2] <= 0):
                continue
            rv, tv = cv2.solvePnPRefineLM(Xi, ui, K, None, cv2.Rodrigues(Rc)[0],
                                          np.asarray(tc, float).reshape(3, 1).copy())
            Rr, tr = cv2.Rodrigues(rv)[0], tv.ravel().astype(float)
            c = float(np.sum(_batch_errors(Xi, ui, Rr[None], tr[None], K)[0] ** 2))
            if c < best_cost:
                best, best_cost = (Rr, tr), c
        R, t = best
        again = _batch_errors(X, u, R[None], t[None], K)[0] < threshold_px
        if again.sum() >= 6:
            inliers = again
            rv, tv = cv2.solvePnPRefineLM(X[inliers], u[inliers], K, None, cv2.Rodrigues(R)[0],
                                          t.reshape(3, 1).copy())
            R, t = cv2.Rodrigues(rv)[0], tv.ravel().astype(float)
    e = _batch_errors(X, u, R[None], t[None], K)[0]
    return RansacResult(True, R, t, inliers, -1, "cv2.solvePnPRansac", e)
