"""Association of points across views by the epipolar constraint (Huang et al., §1.2 steps 4–6).

**The gate a user gets by default.** Give :func:`associate` the predicted spread of a true
pair's point-to-line distance, ``sigma_px`` (one signed, roughly Gaussian coordinate), instead
of a threshold: the gate is then the χ² bound ``L = σ · sqrt(χ²₁(p))`` with ``p = 0.99``
(:func:`chi2_gate`) — a true pair falls outside it with probability 1 − p. The paper guesses
L (8–12 px); ``eotrack.experiments.epipolar.error_budget_gate`` derives σ from an attitude /
position / centroid error budget. An explicit ``threshold`` still overrides.

* :func:`associate` — step 4 (candidates: distance below the threshold L) and step 5 (a point
  with several candidates keeps the nearest; every point is used at most once). The paper's
  rule is implemented as a greedy pass over all candidate pairs in increasing distance, which
  is "nearest wins, one-to-one" without depending on the order of the points. The global
  alternative solves the one-to-one assignment that maximises the number of pairs and then
  minimises their total distance (``scipy.optimize.linear_sum_assignment``).
* :func:`summary_table` — step 6 (Table 3): maps in order, a new point joins a row if it is
  associated with every earlier element of that row, otherwise it starts a new row.
* :func:`three_view_check` — beyond the paper: a pair is kept only if the triangulated point,
  projected into every other view whose image it falls in, finds a detection there.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import numpy as np
from scipy.optimize import linear_sum_assignment
from scipy.stats import chi2

from eotrack.validation import as_finite_array, as_points, check_choice, check_positive

from .camera import PinholeCamera
from .triangulation import triangulate_two_rays

__all__ = [
    "ASSOCIATION_RULES",
    "DEFAULT_GATE_PROBABILITY",
    "associate",
    "chi2_gate",
    "greedy_candidates",
    "summary_table",
    "three_view_check",
]

ASSOCIATION_RULES = ("paper", "hungarian")
#: Probability that a true pair lies inside the default χ² gate.
DEFAULT_GATE_PROBABILITY = 0.99


def chi2_gate(sigma_px, p: float = DEFAULT_GATE_PROBABILITY, *, dof: int = 1) -> float:
    """The χ² gate ``L = σ · sqrt(χ²_dof(p))`` (px).

    Parameters
    ----------
    sigma_px
        Standard deviation (px, > 0) of a true pair's signed distance to the epipolar line.
    p
        Probability in (0, 1) that a true pair falls inside the gate (default 0.99).
    dof
        Degrees of freedom: 1 for a point-to-line distance (the default), 2 for a point-to-
        point distance in an image.

    Returns
    -------
    float
        The gate (px).

    Examples
    --------
    >>> round(chi2_gate(2.0), 3)  # 99 %: 2.576 σ
    5.152
    """
    s = check_positive(sigma_px, "sigma_px")
    if isinstance(p, bool) or not isinstance(p, int | float | np.floating) or not 0 < p < 1:
        raise ValueError(f"p must be a probability in (0, 1), got {p!r}")
    if isinstance(dof, bool) or not isinstance(dof, int | np.integer) or dof < 1:
        raise ValueError(f"dof must be an integer >= 1, got {dof!r}")
    return float(s * np.sqrt(chi2.ppf(float(p), int(dof))))


def _check_dist(dist) -> np.ndarray:
    d = as_finite_array(dist, "dist", allow_nan=False)
    if d.ndim != 2:
        raise ValueError(f"dist must be a 2-D (n1, n2) distance matrix, got shape {d.shape}")
    if d.size and d.min() < 0:
        raise ValueError("dist must hold non-negative distances")
    return d


def _check_threshold(threshold) -> float:
    if isinstance(threshold, bool) or not isinstance(threshold, int | float | np.number):
        raise TypeError(f"threshold must be a real number (pixels), got "
                        f"{type(threshold).__name__}")
    t = float(threshold)
    if not np.isfinite(t) or t < 0:
        raise ValueError(f"threshold must be finite and >= 0 (pixels), got {threshold!r}")
    return t


def greedy_candidates(dist, threshold) -> np.ndarray:
    """The paper's rule: pairs ``(i, j)`` with ``dist < threshold``, nearest first, one-to-one.

    Because candidates are taken in increasing distance, the pairs accepted for a smaller
    threshold are exactly the accepted pairs whose distance is below it — one pass at the
    largest threshold serves a whole threshold sweep.

    Returns
    -------
    numpy.ndarray
        ``(k, 2)`` integer pairs in acceptance order (increasing distance).
    """
    d = _check_dist(dist)
    t = _check_threshold(threshold)
    ii, jj = np.nonzero(d < t)
    if len(ii) == 0:
        return np.zeros((0, 2), int)
    order = np.argsort(d[ii, jj], kind="stable")
    used_i = np.zeros(d.shape[0], bool)
    used_j = np.zeros(d.shape[1], bool)
    out = []
    for i, j in zip(ii[order], jj[order]):
        if not used_i[i] and not used_j[j]:
            used_i[i] = used_j[j] = True
            out.append((i, j))
    return np.array(out, int).reshape(-1, 2)


def associate(dist, threshold=None, *, rule: str = "paper", sigma_px=None,
              p: float | None = None) -> np.ndarray:
    """One-to-one association from a distance matrix.

    Parameters
    ----------
    dist
        ``(n1, n2)`` non-negative distances (e.g. :func:`epipolar_distances`).
    threshold
        Gate L (px, ≥ 0): only pairs with ``dist < L`` can be associated. If omitted, the
        default χ² gate :func:`chi2_gate` ``(sigma_px, p)`` is used.
    rule
        ``"paper"`` (greedy nearest-first) or ``"hungarian"`` (global assignment).
    sigma_px
        Predicted spread (px) of a true pair's distance; required when ``threshold`` is
        omitted, not allowed with it.
    p
        Probability of the default gate (``None``: 0.99); only with ``sigma_px`` (an explicit
        ``threshold`` has no probability, and ``p`` is then refused rather than ignored).

    Returns
    -------
    numpy.ndarray
        ``(k, 2)`` integer index pairs ``(i, j)``, sorted by ``i``.

    Raises
    ------
    TypeError
        If neither or both of ``threshold`` and ``sigma_px`` are given, or ``p`` is given
        with ``threshold``.
    """
    d = _check_dist(dist)
    if threshold is None:
        if sigma_px is None:
            raise TypeError("associate needs threshold (px) or sigma_px (the spread of a true "
                            "pair's distance, for the default χ² gate)")
        t = chi2_gate(sigma_px, DEFAULT_GATE_PROBABILITY if p is None else p)
    else:
        if sigma_px is not None:
            raise TypeError("give threshold or sigma_px, not both")
        if p is not None:
            raise TypeError("p sets the probability of the default χ² gate (with sigma_px); "
                            "it has no meaning with an explicit threshold")
        t = _check_threshold(threshold)
    check_choice(rule, "rule", ASSOCIATION_RULES)
    if d.size == 0:
        return np.zeros((0, 2), int)
    if rule == "paper":
        pairs = greedy_candidates(d, t)
    else:
        ok = d < t
        if not ok.any():
            return np.zeros((0, 2), int)
        big = (d[ok].sum() + 1.0) * 2.0
        cost = np.where(ok, d, big)
        ri, ci = linear_sum_assignment(cost)
        keep = ok[ri, ci]
        pairs = np.stack([ri[keep], ci[keep]], 1)
    return pairs[np.argsort(pairs[:, 0], kind="stable")] if len(pairs) else pairs


def summary_table(n_points: Sequence[int], matches: Mapping[tuple[int, int], np.ndarray]
                  ) -> np.ndarray:
    """Step 6: merge pairwise associations into rows of one target each (Table 3).

    Parameters
    ----------
    n_points
        Number of points in each map, in map order.
    matches
        ``{(a, b): pairs}`` with ``a < b`` map indices and ``pairs`` ``(k, 2)`` index pairs
        (point of map a, point of map b). Missing map pairs mean "no associations".

    Returns
    -------
    numpy.ndarray
        ``(rows, n_maps)`` point indices, −1 where a map has no element in the row. Every point
        appears in exactly one row; rows with a single element are points associated with
        nothing (the paper's table lists only rows with two or more).

    Raises
    ------
    ValueError
        Negative counts, keys not ``(a, b)`` with ``a < b``, non-integer or out-of-range
        indices, or pairs that are not one-to-one (a point in two pairs of one map pair).
    """
    counts = [int(n) for n in n_points]
    if any(n < 0 for n in counts):
        raise ValueError("n_points must be non-negative")
    n_maps = len(counts)
    linked: dict[tuple[int, int], set[tuple[int, int]]] = {}
    for key, pairs in matches.items():
        a, b = key
        if not (0 <= a < b < n_maps):
            raise ValueError(f"matches keys must be (a, b) with 0 <= a < b < {n_maps}, got {key}")
        raw = np.asarray(pairs)
        if raw.size and (raw.dtype.kind not in "iuf" or (raw.dtype.kind == "f" and (
                not np.all(np.isfinite(raw)) or np.any(raw != np.round(raw))))):
            raise ValueError(f"matches[{key}] must hold integer point indices")
        p = raw.astype(int).reshape(-1, 2)
        if len(p) and (p[:, 0].max() >= counts[a] or p[:, 1].max() >= counts[b] or p.min() < 0):
            raise ValueError(f"matches[{key}] holds an index outside the maps' point counts")
        if len(np.unique(p[:, 0])) < len(p) or len(np.unique(p[:, 1])) < len(p):
            raise ValueError(f"matches[{key}] is not one-to-one: a point appears in two pairs")
        linked[(a, b)] = {(int(i), int(j)) for i, j in p}
    rows: list[list[int]] = []
    for m in range(n_maps):
        for p in range(counts[m]):
            target = None
            for row in rows:
                if row[m] != -1:
                    continue
                members = [(a, row[a]) for a in range(m) if row[a] != -1]
                if members and all((i, p) in linked.get((a, m), ()) for a, i in members):
                    target = row
                    break
            if target is None:
                target = [-1] * n_maps
                rows.append(target)
            target[m] = p
    return np.array(rows, int).reshape(-1, n_maps)


def three_view_check(pts_a, pts_b, pairs, cam_a: PinholeCamera, cam_b: PinholeCamera,
                     others: Sequence[tuple[PinholeCamera, np.ndarray]], gate_px=None, *,
                     sigma_px=None, p: float = DEFAULT_GATE_PROBABILITY) -> np.ndarray:
    """Keep a pair only if the views that should see its target do see something there.

    For each pair the two lines of sight are triangulated and the point projected into every
    other camera; if it falls inside that image and no detection lies within the gate, the
    pair is inconsistent (a false association such as the paper's Fig. 4(e)). A pair whose
    lines of sight meet behind either of its own cameras (they diverge: the epipolar
    constraint holds for such points too) is inconsistent as well, even with no other view.

    Two gates:

    * ``gate_px`` — a fixed radius (px) around the transferred point.
    * ``sigma_px`` — the centroid noise (px rms per axis) of every map: the transferred point
      then carries the triangulation's uncertainty too, which grows without bound as the two
      lines of sight become parallel (a short baseline seen from the third view's side). Its
      2×2 covariance ``σ² (J Jᵀ + I)`` (``J``: the transferred pixel's sensitivity to the four
      pair coordinates, by central differences) gates a detection at the χ²₂(p) Mahalanobis
      bound. A fixed ``gate_px`` rejects true pairs of such geometries; use ``sigma_px`` on
      scenes you have not tuned a radius for.

    Parameters
    ----------
    pts_a, pts_b
        Pixel coordinates of the two maps.
    pairs
        ``(k, 2)`` index pairs into ``pts_a`` and ``pts_b``.
    cam_a, cam_b
        The two cameras (poses as known to the associator).
    others
        ``(camera, points)`` of the other maps.
    gate_px
        Fixed transfer gate (px, > 0); give this or ``sigma_px``.
    sigma_px
        Centroid noise (px rms per axis, > 0) for the uncertainty-aware gate.
    p
        Probability of the uncertainty-aware gate (default 0.99).

    Returns
    -------
    numpy.ndarray of bool
        ``(k,)`` — True where the pair is consistent.

    Raises
    ------
    TypeError
        If neither or both of ``gate_px`` and ``sigma_px`` are given.
    """
    pa = as_points(pts_a, "pts_a")
    pb = as_points(pts_b, "pts_b")
    pr = np.asarray(pairs, int).reshape(-1, 2)
    if (gate_px is None) == (sigma_px is None):
        raise TypeError("three_view_check needs exactly one of gate_px (px) and sigma_px "
                        "(centroid noise, px)")
    if gate_px is not None:
        gate = check_positive(gate_px, "gate_px")
    else:
        sig = check_positive(sigma_px, "sigma_px")
        if isinstance(p, bool) or not isinstance(p, int | float | np.floating) or not 0 < p < 1:
            raise ValueError(f"p must be a probability in (0, 1), got {p!r}")
        bound = float(chi2.ppf(float(p), 2))
    if len(pr) == 0:
        return np.zeros(0, bool)
    ua, ub = pa[pr[:, 0]], pb[pr[:, 1]]

    def tri(qa: np.ndarray, qb: np.ndarray) -> np.ndarray:
        return triangulate_two_rays(cam_a.c, cam_a.rays(qa), cam_b.c, cam_b.rays(qb))

    X = tri(ua, ub)
    if sigma_px is not None:
        h = 1e-2 * sig  # central differences, well inside the linear regime
        shifted = []
        for which in (0, 1):
            for ax in (0, 1):
                step = np.zeros(2)
                step[ax] = h
                qa, qb = (ua + step, ub) if which == 0 else (ua, ub + step)
                qa2, qb2 = (ua - step, ub) if which == 0 else (ua, ub - step)
                shifted.append((tri(qa, qb), tri(qa2, qb2)))
    keep = np.ones(len(pr), bool)
    for cam in (cam_a, cam_b):  # cheirality: the point must lie in front of both cameras
        keep &= cam.project(X, return_depth=True)[1] > 0
    for cam, pts in others:
        q = as_points(pts, "others points")
        inside = cam.sees(X)
        uv = cam.project(X)
        if not len(q):
            near = np.zeros(len(pr), bool)
        elif sigma_px is None:
            near = np.min(np.linalg.norm(uv[:, None, :] - q[None], axis=2), axis=1) <= gate
        else:
            J = np.stack([(cam.project(xp) - cam.project(xm)) / (2 * h)
                          for xp, xm in shifted], axis=2)  # (k, 2, 4)
            cov = sig**2 * (J @ J.transpose(0, 2, 1) + np.eye(2))
            r = q[None, :, :] - uv[:, None, :]  # (k, n, 2)
            m2 = np.einsum("kni,kij,knj->kn", r, np.linalg.inv(cov), r)
            near = m2.min(axis=1) <= bound
        keep &= ~inside | near
    return keep
