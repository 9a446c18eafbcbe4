"""Gating helpers shared by the logic and Hough initiators.

* :func:`check_velocity_gate` — validate a speed gate ``v_min <= v <= v_max`` (pixels per second).
* :func:`velocity_gated_pairs` — every pair (detection of an earlier frame, detection of a later
  frame) whose apparent speed lies in the gate; frames need not be consecutive nor evenly spaced,
  the speed is ``|Δxy| / Δt`` with the real time difference.
* :func:`angle_at_middle_deg` — the angle at the middle point of three points (the
  angle-constrained logic rejects "V-shaped" triples whose angle is ≤ 90°).
* :func:`fit_constant_velocity` — least-squares straight-line constant-velocity fit ``xy(t)``.
* :class:`TrackHandOff` — what happens to a track once it is confirmed: it is handed to tracking,
  which claims its detections in later frames (nearest neighbour inside a gate around the
  constant-velocity prediction) so that they no longer feed initiation. All initiators of this
  package use it, so none of them confirms the same object twice.
* :func:`canonical_order` — a permutation that sorts a frame's detections by (x, y); initiators
  work in that order so their result does not depend on the order of detections in a frame.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from eotrack.validation import as_finite_array, check_positive

from .base import Frame, Track
from .pairs import PointGrid, cv_fit_batch, greedy_disjoint

__all__ = [
    "TrackHandOff",
    "angle_at_middle_deg",
    "canonical_order",
    "check_velocity_gate",
    "fit_constant_velocity",
    "velocity_gated_pairs",
]


def check_velocity_gate(v_min: float, v_max: float) -> tuple[float, float]:
    """Check a speed gate ``0 <= v_min < v_max`` (pixels per second) and return it as floats.

    Raises
    ------
    ValueError
        If either bound is negative or not finite, or the gate is inverted or empty.
    """
    lo = check_positive(v_min, "v_min", allow_zero=True)
    hi = check_positive(v_max, "v_max")
    if not lo < hi:
        raise ValueError(f"velocity gate must satisfy v_min < v_max, got v_min={lo}, v_max={hi}")
    return lo, hi


def velocity_gated_pairs(xy_a: np.ndarray, t_a: float, xy_b: np.ndarray, t_b: float,
                         v_min: float, v_max: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """All pairs ``(a, b)`` whose apparent speed ``|xy_b − xy_a| / (t_b − t_a)`` is in the gate.

    Parameters
    ----------
    xy_a, xy_b
        Detections ``(n_a, 2)`` at time ``t_a`` and ``(n_b, 2)`` at time ``t_b`` (pixels).
    t_a, t_b
        Times (s), ``t_b > t_a``.
    v_min, v_max
        Speed gate (pixels per second), inclusive.

    Returns
    -------
    ia, ib : numpy.ndarray
        Indices of the gated pairs into ``xy_a`` and ``xy_b`` (row-major order over ``(a, b)``).
    velocity : numpy.ndarray
        ``(n_pairs, 2)`` pair velocities (pixels per second).
    """
    a = as_finite_array(xy_a, "xy_a", ndim=2)
    b = as_finite_array(xy_b, "xy_b", ndim=2)
    if a.shape[1:] != (2,) or b.shape[1:] != (2,):
        raise ValueError(f"xy_a and xy_b must have shape (n, 2), got {a.shape} and {b.shape}")
    dt = float(t_b) - float(t_a)
    if not np.isfinite(dt) or dt <= 0:
        raise ValueError(f"t_b must be later than t_a, got t_a={t_a}, t_b={t_b}")
    lo, hi = check_velocity_gate(v_min, v_max)
    d = (b[None, :, :] - a[:, None, :]) / dt
    v2 = np.einsum("abk,abk->ab", d, d)
    ia, ib = np.nonzero((v2 >= lo * lo) & (v2 <= hi * hi))
    return ia, ib, d[ia, ib]


def angle_at_middle_deg(p0: np.ndarray, p1: np.ndarray, p2: np.ndarray) -> np.ndarray:
    """Angle (degrees, in [0, 180]) at ``p1`` of the triangle ``p0 – p1 – p2``; rows broadcast.

    A straight uniform motion gives 180°; a "V" (the third point doubling back) gives < 90°.
    Coincident points give 0° (treated as the worst case).
    """
    a = as_finite_array(p0, "p0") - as_finite_array(p1, "p1")
    b = as_finite_array(p2, "p2") - as_finite_array(p1, "p1")
    if a.shape[-1] != 2 or b.shape[-1] != 2:
        raise ValueError("p0, p1, p2 must have a last axis of length 2 (x, y)")
    na = np.hypot(a[..., 0], a[..., 1])
    nb = np.hypot(b[..., 0], b[..., 1])
    dot = a[..., 0] * b[..., 0] + a[..., 1] * b[..., 1]
    with np.errstate(invalid="ignore", divide="ignore"):
        c = np.where((na > 0) & (nb > 0), dot / (na * nb), 1.0)
    return np.degrees(np.arccos(np.clip(c, -1.0, 1.0)))


def fit_constant_velocity(t_s: np.ndarray, xy: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Least-squares constant-velocity fit ``xy(t) = p + v (t − t̄)``.

    Parameters
    ----------
    t_s
        Times ``(k,)`` (s), at least two distinct values.
    xy
        Positions ``(k, 2)``.

    Returns
    -------
    p_mean, v : numpy.ndarray
        Position at the mean time ``t̄`` and velocity (pixels per second); ``p_mean`` is returned
        together with ``t̄`` implicitly — predict with :math:`p + v (t − \\bar t)`.
    """
    t = as_finite_array(t_s, "t_s", ndim=1)
    p = as_finite_array(xy, "xy", shape=(None, 2))
    if len(t) != len(p):
        raise ValueError(f"t_s and xy must have the same length, got {len(t)} and {len(p)}")
    tc = t - t.mean()
    den = float(tc @ tc)
    if den <= 0:
        raise ValueError("t_s needs at least two distinct times for a velocity fit")
    pm = p.mean(axis=0)
    v = tc @ (p - pm) / den
    return pm, v


def canonical_order(xy: np.ndarray) -> np.ndarray:
    """Permutation sorting detections by x, then y (ties keep input order)."""
    xy = np.asarray(xy, float)
    if len(xy) == 0:
        return np.zeros(0, dtype=int)
    return np.lexsort((xy[:, 1], xy[:, 0]))


class TrackHandOff:
    """Confirmed tracks handed to tracking; they claim their detections in later frames.

    Each frame, every confirmed track predicts its position with a least-squares
    constant-velocity fit of its (last four) hits; detections within ``gate_px`` of a
    prediction are assigned greedily by increasing distance (ties broken by detection position),
    each detection to at most one track. Claimed detections are appended to the track and are
    no longer candidates for initiation. All tracks are predicted and gated at once (arrays, a
    spatial grid and :func:`~eotrack.tracking.initiation.pairs.greedy_disjoint`).

    Parameters
    ----------
    gate_px
        Radius of the maintenance gate (pixels, > 0).
    """

    _KEEP = 4  # hits used for the prediction

    def __init__(self, gate_px: float) -> None:
        self.gate_px = check_positive(gate_px, "gate_px")
        self._hits: list[list[tuple[int, int]]] = []
        self._confirmed: list[int] = []
        self._info: list[dict] = []
        k = self._KEEP
        self._t = np.zeros((0, k))
        self._x = np.zeros((0, k))
        self._y = np.zeros((0, k))
        self._n = np.zeros(0, dtype=np.int64)
        self._pending: list[tuple[np.ndarray, np.ndarray, np.ndarray, int]] = []

    def __len__(self) -> int:
        return len(self._hits)

    def confirm(self, hits: Sequence[tuple[int, int]], confirmed_at: int,
                frames: Sequence[Frame], info: dict | None = None) -> None:
        """Register a newly confirmed track (``hits`` in any order; stored in frame order)."""
        hits = sorted((int(f), int(d)) for f, d in hits)
        self._hits.append(hits)
        self._confirmed.append(int(confirmed_at))
        self._info.append(dict(info or {}))
        last = hits[-self._KEEP:]
        t = np.array([frames[f].time_s for f, _ in last], float)
        xy = np.array([frames[f].xy[d] for f, d in last], float).reshape(-1, 2)
        self._pending.append((t, xy[:, 0], xy[:, 1], len(last)))

    def confirm_batch(self, frame_idx: np.ndarray, det_idx: np.ndarray, confirmed_at: int,
                      frames: Sequence[Frame], info: dict | Sequence[dict] | None = None) -> None:
        """Register several newly confirmed tracks at once.

        Parameters
        ----------
        frame_idx, det_idx
            ``(n_tracks, k)`` frame and detection indices of the hits, one row per track,
            sorted by frame within a row; ``det_idx < 0`` marks an empty slot (empty slots
            after the row's hits are not allowed to interleave with them).
        confirmed_at
            Frame index of the confirmation.
        frames
            The frames the indices refer to.
        info
            One dict for all tracks or one per track.
        """
        fi = np.asarray(frame_idx, dtype=np.int64)
        di = np.asarray(det_idx, dtype=np.int64)
        if fi.shape != di.shape or fi.ndim != 2:
            raise ValueError(f"frame_idx and det_idx must be 2-D of one shape, got {fi.shape} "
                             f"and {di.shape}")
        n = len(fi)
        if n == 0:
            return
        self._flush()
        ok = di >= 0
        infos = [dict(info or {}) for _ in range(n)] if info is None or isinstance(info, dict) \
            else [dict(x) for x in info]
        for f_row, d_row, o_row in zip(fi.tolist(), di.tolist(), ok.tolist()):
            self._hits.append([(f, d) for f, d, o in zip(f_row, d_row, o_row) if o])
        self._confirmed += [int(confirmed_at)] * n
        self._info += infos
        # the last (up to) four hits, right-aligned, for the prediction arrays
        k = self._KEEP
        times = np.array([f.time_s for f in frames])
        order = np.argsort(~ok, axis=1, kind="stable")  # hits first, in frame order
        fs = np.take_along_axis(fi, order, 1)
        ds = np.take_along_axis(di, order, 1)
        nh = ok.sum(axis=1)
        t = np.zeros((n, k))
        x = np.zeros((n, k))
        y = np.zeros((n, k))
        for j in range(k):
            src = nh - k + j  # column of the hit that lands in slot j
            have = src >= 0
            r = np.flatnonzero(have)
            if len(r) == 0:
                continue
            f = fs[r, src[r]]
            d = ds[r, src[r]]
            t[r, j] = times[f]
            xy = np.array([frames[ff].xy[dd] for ff, dd in zip(f.tolist(), d.tolist())])
            x[r, j] = xy[:, 0]
            y[r, j] = xy[:, 1]
        self._t = np.concatenate([self._t, t])
        self._x = np.concatenate([self._x, x])
        self._y = np.concatenate([self._y, y])
        self._n = np.concatenate([self._n, np.minimum(nh, k)])

    def _flush(self) -> None:
        if not self._pending:
            return
        k = self._KEEP
        m = len(self._pending)
        t = np.zeros((m, k))
        x = np.zeros((m, k))
        y = np.zeros((m, k))
        n = np.zeros(m, dtype=np.int64)
        for i, (ti, xi, yi, ni) in enumerate(self._pending):
            t[i, k - ni:] = ti
            x[i, k - ni:] = xi
            y[i, k - ni:] = yi
            n[i] = ni
        self._t = np.concatenate([self._t, t])
        self._x = np.concatenate([self._x, x])
        self._y = np.concatenate([self._y, y])
        self._n = np.concatenate([self._n, n])
        self._pending = []

    def predict(self, time_s: float) -> np.ndarray:
        """Predicted positions ``(n_tracks, 2)`` of all confirmed tracks at ``time_s``."""
        self._flush()
        if len(self._n) == 0:
            return np.zeros((0, 2))
        mask = np.arange(self._KEEP)[None, :] >= (self._KEEP - self._n)[:, None]
        tm, pm, v, _ = cv_fit_batch(self._t, self._x, self._y, mask)
        return pm + v * (float(time_s) - tm)[:, None]

    def claim(self, frame_index: int, time_s: float, xy: np.ndarray,
              available: np.ndarray) -> np.ndarray:
        """Assign detections of one frame to the confirmed tracks.

        Parameters
        ----------
        frame_index, time_s
            The frame.
        xy
            Its detections ``(n, 2)``.
        available
            Boolean mask ``(n,)`` of detections still free; updated in place.

        Returns
        -------
        numpy.ndarray
            Boolean mask of the detections claimed in this call.
        """
        claimed = np.zeros(len(xy), dtype=bool)
        if not self._hits or len(xy) == 0:
            return claimed
        pred = self.predict(time_s)
        free = np.flatnonzero(available)
        if len(free) == 0:
            return claimed
        grid = PointGrid(xy[free], self.gate_px)
        ti, j, d2 = grid.query(pred)
        if len(ti) == 0:
            return claimed
        di = free[j]
        d = np.sqrt(d2)
        order = np.lexsort((xy[di, 1], xy[di, 0], d))
        rank = np.empty(len(order), dtype=np.int64)
        rank[order] = np.arange(len(order))
        n_t = len(pred)
        win = greedy_disjoint(np.stack([ti, n_t + di], 1), rank, n_t + len(xy))
        a, b = ti[win], di[win]
        claimed[b] = True
        for ta, db in zip(a.tolist(), b.tolist()):
            self._hits[ta].append((int(frame_index), db))
        # shift the new hit into the prediction window of the claiming tracks
        for arr, val in ((self._t, np.full(len(a), float(time_s))), (self._x, xy[b, 0]),
                         (self._y, xy[b, 1])):
            arr[a, :-1] = arr[a, 1:]
            arr[a, -1] = val
        self._n[a] = np.minimum(self._n[a] + 1, self._KEEP)
        available &= ~claimed
        return claimed

    def tracks(self, perms: Sequence[np.ndarray] | None = None) -> list[Track]:
        """The confirmed tracks; ``perms[f]`` maps working indices back to input indices."""
        out = []
        for hits, conf, info in zip(self._hits, self._confirmed, self._info):
            h = [(f, int(perms[f][d]) if perms is not None else d) for f, d in hits]
            out.append(Track(hits=h, confirmed_at=conf, info=dict(info)))
        return out
