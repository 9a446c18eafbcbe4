"""Logic (n/m) track initiation, with the optional angle constraint of Yuan et al. (2010).

The sliding-window logic method (e.g. He You et al., *Radar Data Processing*, §4): every
detection not yet in a confirmed track opens a *head*. In a later frame of the head's window the
head is paired with every detection inside the **velocity gate** ``v_min ≤ |Δxy|/Δt ≤ v_max``
(Δt the real time difference, so frames need not be consecutive nor evenly spaced); each pair
becomes a tentative track, and the head itself stays open for the later frames of its window (so
a target missed in the frame after its head is still found).
A tentative track with two or more points predicts its position with a **constant-velocity**
model from its last two points and takes the **nearest neighbour** inside a circular gate of
radius ``gate_px`` (the segment must also satisfy the velocity gate). A track is confirmed as
soon as it holds ``n`` detections within ``m`` consecutive frames of the sequence starting at
its head (2/3: fast confirmation in quiet scenes; 3/4: the standard rule), and dropped when it
can no longer reach ``n``.

Angle constraint (Yuan G., Sheng F., Ship Electronic Engineering 30(5), 2010): a distant target
moves nearly uniformly on a straight line, so the angle at the middle of three successive points
of a track is > 90°; a candidate third point making an angle ≤ ``min_angle_deg`` (90°) with the
track's last two points ("V shape") is rejected.

Conflicts: tentative tracks reaching ``n`` in the same frame are confirmed in order of more
points, then smaller total gate distance, then detection position; a tentative track sharing a
detection with a confirmed one is deleted. Confirmed tracks are handed to tracking
(:class:`~eotrack.tracking.initiation.gating.TrackHandOff`), which claims their later
detections.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from eotrack.validation import check_int, check_positive

from .base import Frame, Track, validate_frames
from .gating import TrackHandOff, canonical_order, check_velocity_gate
from .pairs import PointGrid, greedy_disjoint, occupancy_image

__all__ = ["AngleConstrainedLogicInitiator", "LogicInitiator", "logic_false_track_rate"]


@dataclass(frozen=True)
class LogicInitiator:
    """Sliding-window n/m logic initiator (defaults: 3/4, the paper's velocity gate).

    Parameters
    ----------
    n, m
        Confirm with ``n`` detections in ``m`` consecutive frames (``2 ≤ n ≤ m``).
    v_min, v_max
        Velocity gate for the second point and every later segment (pixels per second).
    gate_px
        Radius of the constant-velocity prediction gate for the third and later points (pixels).
    min_angle_deg
        If set, reject a new point whose angle at the middle of the last three points is
        ``≤ min_angle_deg`` (the angle-constrained logic uses 90°).
    handoff_gate_px
        Gate of the tracking hand-off after confirmation (pixels).
    """

    n: int = 3
    m: int = 4
    v_min: float = 10.0
    v_max: float = 240.0
    gate_px: float = 10.0
    min_angle_deg: float | None = None
    handoff_gate_px: float = 5.0

    def __post_init__(self) -> None:
        check_int(self.m, "m", min_value=2)
        check_int(self.n, "n", min_value=2, max_value=self.m)
        check_velocity_gate(self.v_min, self.v_max)
        check_positive(self.gate_px, "gate_px")
        if self.min_angle_deg is not None:
            a = check_positive(self.min_angle_deg, "min_angle_deg", allow_zero=True)
            if a >= 180:
                raise ValueError(f"min_angle_deg must lie in [0, 180), got {a}")
        check_positive(self.handoff_gate_px, "handoff_gate_px")

    @property
    def label(self) -> str:
        """Short name, e.g. ``"logic 3/4"`` or ``"angle logic 3/4"``."""
        pre = "angle logic" if self.min_angle_deg is not None else "logic"
        return f"{pre} {self.n}/{self.m}"

    def initiate(self, frames: Sequence) -> list[Track]:
        """Confirmed tracks from ``frames`` (a sequence of ``(time_s, xy)``)."""
        fr = validate_frames(frames)
        perms = [canonical_order(f.xy) for f in fr]
        xys = [f.xy[p] for f, p in zip(fr, perms)]
        times = np.array([f.time_s for f in fr])
        if self.n == 3:
            return _TripletLogicRun(self, xys, times).run(perms)
        return _LogicRun(self, xys, times).run(perms)


def AngleConstrainedLogicInitiator(n: int = 3, m: int = 4, *, min_angle_deg: float = 90.0,
                                   **kw) -> LogicInitiator:
    """The angle-constrained logic initiator: :class:`LogicInitiator` with ``min_angle_deg=90``."""
    return LogicInitiator(n=n, m=m, min_angle_deg=min_angle_deg, **kw)


class _LogicRun:
    """One pass of the logic method over the frames (internal).

    Tentative tracks are rows of arrays: ``start`` (frame of the head), ``hits`` (global
    detection id per window slot, −1 = none), ``count``, ``last``/``prev`` (slots of the last two
    hits) and ``cost`` (summed gate distances), all updated in place, so each frame costs a few
    passes over the rows.
    """

    def __init__(self, cfg: LogicInitiator, xys: list[np.ndarray], times: np.ndarray):
        self.cfg = cfg
        self.xys = xys
        self.times = times
        sizes = [len(x) for x in xys]
        self.off = np.concatenate([[0], np.cumsum(sizes)]).astype(np.int64)
        self.avail = np.ones(int(self.off[-1]), dtype=bool)
        self.xy_flat = np.concatenate(xys) if self.off[-1] else np.zeros((0, 2))
        self.handoff = TrackHandOff(cfg.handoff_gate_px)
        m = cfg.m
        self.start = np.zeros(0, dtype=np.int32)
        self.hits = np.zeros((0, m), dtype=np.int32)
        self.count = np.zeros(0, dtype=np.int32)
        self.last = np.zeros(0, dtype=np.int32)
        self.prev = np.zeros(0, dtype=np.int32)
        self.cost = np.zeros(0)
        self.frames = [Frame(float(t), x) for t, x in zip(times, xys)]

    _FIELDS = ("start", "hits", "count", "last", "prev", "cost")

    def _avail_view(self, f: int) -> np.ndarray:
        return self.avail[self.off[f]:self.off[f + 1]]

    def run(self, perms: list[np.ndarray]) -> list[Track]:
        for k in range(len(self.xys)):
            self._frame(k)
        return self.handoff.tracks(perms)

    def _frame(self, k: int) -> None:
        cfg = self.cfg
        m = cfg.m
        xy_k = self.xys[k]
        # (the hand-off claims detections of frame k only, which no tentative track holds yet;
        # tracks sharing a detection with a confirmed one were deleted when it was confirmed)
        self.handoff.claim(k, self.times[k], xy_k, self._avail_view(k))
        self._select(self.start > k - m)
        slot_k = k - self.start
        ids_k = self.off[k] + np.flatnonzero(self._avail_view(k))
        pk = self.xy_flat[ids_k]
        tk = self.times[k]
        new = []
        if len(ids_k) and len(self.start):
            # --- extension of tracks with >= 2 points: CV prediction + nearest neighbour
            ext = np.flatnonzero(self.count >= 2)
            if len(ext):
                last, prev = self.last[ext], self.prev[ext]
                g_last = self.hits[ext, last]
                g_prev = self.hits[ext, prev]
                t_last = self.times[self.start[ext] + last]
                t_prev = self.times[self.start[ext] + prev]
                p_last = self.xy_flat[g_last]
                p_prev = self.xy_flat[g_prev]
                vel = (p_last - p_prev) / (t_last - t_prev)[:, None]
                dt = tk - t_last
                pred = p_last + vel * dt[:, None]
                # every detection inside a prediction gate (spatial grid, no tracks × detections
                # matrix), then the segment's velocity gate and the angle test on those pairs
                ti, dj, d2 = PointGrid(pk, cfg.gate_px).query(pred)
                seg = np.hypot(pk[dj, 0] - p_last[ti, 0], pk[dj, 1] - p_last[ti, 1]) / dt[ti]
                ok = (seg >= cfg.v_min) & (seg <= cfg.v_max)
                if cfg.min_angle_deg is not None:
                    a = p_prev[ti] - p_last[ti]
                    b = pk[dj] - p_last[ti]
                    na = np.hypot(a[:, 0], a[:, 1])
                    nb = np.hypot(b[:, 0], b[:, 1])
                    cosang = (a[:, 0] * b[:, 0] + a[:, 1] * b[:, 1]) / np.maximum(na * nb, 1e-300)
                    ok &= cosang < np.cos(np.radians(cfg.min_angle_deg))
                ti, dj, d2 = ti[ok], dj[ok], d2[ok]
                # nearest per track (ties: lowest canonical index, i.e. x then y); the
                # matches come ordered by track, so per-track minima are segment reductions
                if len(ti):
                    start = np.flatnonzero(np.r_[True, ti[1:] != ti[:-1]])
                    cnt = np.diff(np.r_[start, len(ti)])
                    best = d2 == np.repeat(np.minimum.reduceat(d2, start), cnt)
                    big = np.iinfo(np.int32).max
                    pick = np.minimum.reduceat(np.where(best, dj, big), start)
                    ti, dj = ti[start], pick
                    d = np.sqrt(np.minimum.reduceat(d2, start))
                else:
                    d = np.zeros(0)
                rows = ext[ti]
                self.hits[rows, slot_k[rows]] = ids_k[dj]
                self.cost[rows] += d
                self.prev[rows] = self.last[rows]
                self.last[rows] = slot_k[rows]
                self.count[rows] += 1
            # --- heads: pair with every detection in the velocity gate
            # (a head whose window ends too soon to reach n with this pair is skipped)
            heads = np.flatnonzero((self.count == 1)
                                   & (self.start + m - 1 - k + 2 >= cfg.n))
            if len(heads):
                s0 = self.last[heads]
                p0 = self.xy_flat[self.hits[heads, s0]]
                dt = tk - self.times[self.start[heads] + s0]
                hi, di = self._gated(p0, pk, dt)
                if len(hi):
                    rows = heads[hi]
                    nh = self.hits[rows]
                    sk = slot_k[rows]
                    nh[np.arange(len(hi)), sk] = ids_k[di]
                    new.append((self.start[rows], nh, np.full(len(hi), 2), sk, s0[hi],
                                np.zeros(len(hi))))
        # --- new heads
        if len(ids_k):
            nh = np.full((len(ids_k), m), -1, dtype=np.int32)
            nh[:, 0] = ids_k
            z = np.zeros(len(ids_k), dtype=np.int32)
            new.append((np.full(len(ids_k), k, dtype=np.int32), nh, z + 1, z, z,
                        np.zeros(len(ids_k))))
        if new:
            for i, name in enumerate(self._FIELDS):
                setattr(self, name, np.concatenate([getattr(self, name)] + [n[i] for n in new]))
        self._confirm(k)
        # drop tracks that can no longer reach n within their window
        self._select(self.count + (self.start + m - 1 - k) >= cfg.n)

    def _gated(self, p0: np.ndarray, pk: np.ndarray, dt: np.ndarray):
        """Pairs (head, detection) inside the velocity gate, head-major (one broadcast)."""
        cfg = self.cfg
        dx = pk[None, :, 0] - p0[:, None, 0]
        dy = pk[None, :, 1] - p0[:, None, 1]
        d2 = dx * dx
        d2 += dy * dy
        dt2 = (dt * dt)[:, None]
        return np.nonzero((d2 >= cfg.v_min**2 * dt2) & (d2 <= cfg.v_max**2 * dt2))

    def _select(self, keep: np.ndarray) -> None:
        if np.all(keep):
            return
        for name in self._FIELDS:
            setattr(self, name, getattr(self, name)[keep])

    def _confirm(self, k: int) -> None:
        ready = np.flatnonzero(self.count >= self.cfg.n)
        if len(ready) == 0:
            return
        first = np.max(self.hits[ready], axis=1)
        order = ready[np.lexsort((self.xy_flat[first, 1], self.xy_flat[first, 0],
                                  self.cost[ready], -self.count[ready]))]
        # best first, each detection in one track (vectorised greedy); rows holding a
        # detection already claimed cannot be confirmed
        h = self.hits[order]
        free = np.all((h < 0) | self.avail[np.maximum(h, 0)], axis=1)
        order, h = order[free], h[free]
        win = greedy_disjoint(h, np.arange(len(order)), len(self.avail))
        if len(win) == 0:
            return
        rows = order[win]
        g = self.hits[rows]
        ok = g >= 0
        self.avail[g[ok]] = False
        fr = np.searchsorted(self.off, np.maximum(g, 0), side="right") - 1
        det = np.where(ok, g - self.off[fr], -1)
        self.handoff.confirm_batch(fr, det, k, self.frames, info={"method": self.cfg.label})
        done = np.zeros(len(self.start), dtype=bool)
        done[rows] = True
        h = self.hits
        clash = np.any((h >= 0) & ~self.avail[np.maximum(h, 0)], axis=1)
        self._select(~(done | clash))


class _TripletLogicRun(_LogicRun):
    """The n = 3 logic without storing tentative tracks (internal; same result as
    :class:`_LogicRun`).

    With n = 3 a tentative track is a gated pair (head in frame f₁, second point in f₂) until it
    takes a third point, when it is confirmed or deleted. So at frame k the tracks that can
    become ready are the pairs of every (f₁, f₂) with ``k − m + 1 ≤ f₁ < f₂ < k`` that have not
    taken a point in a frame between f₂ and k. Their constant-velocity predictions at k are an
    outer sum over the two frames' detections, looked up in a dilated occupancy image of frame k
    (one gather per pair); only pairs that land near a detection are gated and searched
    exactly. A boolean matrix per (f₁, f₂) remembers the pairs that already took a point.
    """

    def __init__(self, cfg: LogicInitiator, xys: list[np.ndarray], times: np.ndarray):
        super().__init__(cfg, xys, times)
        self.resolved: dict[tuple[int, int], np.ndarray] = {}
        self._occ_cache: tuple = (-1, None)

    def _frame(self, k: int) -> None:
        cfg = self.cfg
        m = cfg.m
        self.handoff.claim(k, self.times[k], self.xys[k], self._avail_view(k))
        lo = max(0, k - m + 1)
        for key in [key for key in self.resolved if key[0] < lo]:
            del self.resolved[key]
        ids_k = np.flatnonzero(self._avail_view(k))
        ready = []
        for f1 in range(lo, k - 1):
            for f2 in range(f1 + 1, k):
                key = (f1, f2)
                if key not in self.resolved:
                    self.resolved[key] = np.zeros((len(self.xys[f1]), len(self.xys[f2])), bool)
                if len(ids_k):
                    got = self._extend_pairs(f1, f2, k, ids_k)
                    if got is not None:
                        ready.append(got)
        if ready:
            self._confirm_ready(k, *(np.concatenate(c) for c in zip(*ready)))

    def _occ(self, k: int, pk: np.ndarray, r: float):
        if self._occ_cache[0] != k:
            self._occ_cache = (k, occupancy_image(pk, r))
        return self._occ_cache[1]

    def _extend_pairs(self, f1: int, f2: int, k: int, ids_k: np.ndarray):
        """Nearest gated third point at k of every unresolved pair (f1 → f2)."""
        cfg = self.cfg
        a_id = np.flatnonzero(self._avail_view(f1))
        b_id = np.flatnonzero(self._avail_view(f2))
        if len(a_id) == 0 or len(b_id) == 0:
            return None
        a, b = self.xys[f1][a_id], self.xys[f2][b_id]
        pk = self.xys[k][ids_k]
        t1, t2, tk = self.times[f1], self.times[f2], self.times[k]
        tau = (tk - t2) / (t2 - t1)
        r = cfg.gate_px
        span = np.ptp(pk, axis=0) + 2 * r
        if len(pk) * np.pi * r**2 >= 0.3 * span[0] * span[1]:
            # the gates cover most of the frame: the occupancy look-up would reject little
            sa, sb = (g.ravel() for g in np.meshgrid(np.arange(len(a)), np.arange(len(b)),
                                                       indexing="ij"))
            sa, sb = sa[~self.resolved[(f1, f2)][a_id[sa], b_id[sb]]], \
                sb[~self.resolved[(f1, f2)][a_id[sa], b_id[sb]]]
            return self._finish_pairs(f1, f2, k, ids_k, a_id, b_id, a, b, pk, sa, sb, tau)
        occ, x0, y0, w, h = self._occ(k, pk, r)
        f32 = np.float32
        qx = ((1 + tau) * b[:, 0] - x0).astype(f32)[None, :] + (-tau * a[:, 0]).astype(f32)[:, None]
        qy = ((1 + tau) * b[:, 1] - y0).astype(f32)[None, :] + (-tau * a[:, 1]).astype(f32)[:, None]
        np.clip(qx, 0, w - 1, out=qx)
        np.clip(qy, 0, h - 1, out=qy)
        key = qy.astype(np.int32)
        key *= w
        key += qx.astype(np.int32)
        near = occ[key]
        near &= ~self.resolved[(f1, f2)][np.ix_(a_id, b_id)]
        sa, sb = np.nonzero(near)
        return self._finish_pairs(f1, f2, k, ids_k, a_id, b_id, a, b, pk, sa, sb, tau)

    def _finish_pairs(self, f1, f2, k, ids_k, a_id, b_id, a, b, pk, sa, sb, tau):
        """Gate the candidate pairs ``(sa, sb)`` and take each one's nearest third point."""
        cfg = self.cfg
        r = cfg.gate_px
        t1, t2, tk = self.times[f1], self.times[f2], self.times[k]
        if len(sa) == 0:
            return None
        d = b[sb] - a[sa]
        v2 = (d[:, 0] ** 2 + d[:, 1] ** 2) / (t2 - t1) ** 2
        ok = (v2 >= cfg.v_min**2) & (v2 <= cfg.v_max**2)
        sa, sb = sa[ok], sb[ok]
        pa, pb = a[sa], b[sb]
        pred = pb + (pb - pa) * tau
        ti, dj, d2 = PointGrid(pk, r).query(pred)
        dt = tk - t2
        seg2 = ((pk[dj, 0] - pb[ti, 0]) ** 2 + (pk[dj, 1] - pb[ti, 1]) ** 2) / dt**2
        ok = (seg2 >= cfg.v_min**2) & (seg2 <= cfg.v_max**2)
        if cfg.min_angle_deg is not None:
            u = pa[ti] - pb[ti]
            v = pk[dj] - pb[ti]
            nu = np.hypot(u[:, 0], u[:, 1])
            nv = np.hypot(v[:, 0], v[:, 1])
            cosang = (u[:, 0] * v[:, 0] + u[:, 1] * v[:, 1]) / np.maximum(nu * nv, 1e-300)
            ok &= cosang < np.cos(np.radians(cfg.min_angle_deg))
        ti, dj, d2 = ti[ok], dj[ok], d2[ok]
        if len(ti) == 0:
            return None
        # nearest per pair (ties: lowest canonical index); matches come ordered by pair
        start = np.flatnonzero(np.r_[True, ti[1:] != ti[:-1]])
        cnt = np.diff(np.r_[start, len(ti)])
        best = d2 == np.repeat(np.minimum.reduceat(d2, start), cnt)
        pick = np.minimum.reduceat(np.where(best, dj, np.iinfo(np.int64).max), start)
        pair = ti[start]
        ga = a_id[sa[pair]]
        gb = b_id[sb[pair]]
        self.resolved[(f1, f2)][ga, gb] = True
        hits = np.stack([self.off[f1] + ga, self.off[f2] + gb, self.off[k] + ids_k[pick]], 1)
        return hits, np.sqrt(np.minimum.reduceat(d2, start))

    def _confirm_ready(self, k: int, hits: np.ndarray, cost: np.ndarray) -> None:
        last = hits[:, 2]
        order = np.lexsort((self.xy_flat[last, 1], self.xy_flat[last, 0], cost))
        h = hits[order]
        win = greedy_disjoint(h, np.arange(len(h)), len(self.avail))
        if len(win) == 0:
            return
        g = h[win]
        self.avail[g.ravel()] = False
        fr = np.searchsorted(self.off, g, side="right") - 1
        self.handoff.confirm_batch(fr, g - self.off[fr], k, self.frames,
                                   info={"method": self.cfg.label})


def logic_false_track_rate(n: int, m: int, clutter_per_frame: float, pair_prob: Sequence[float],
                           gate_prob: float,
                           inside_prob: Sequence[Sequence[float]] | None = None) -> float:
    """Expected false tracks confirmed per frame by the n/m logic in uniform Poisson clutter.

    A clutter head opens tentative tracks with the clutter points of each later frame of its
    window that fall in its velocity gate (expected number ``N_c · pair_prob[Δ−1]`` at a frame
    gap ``Δ``; the head stays open). Each tentative track then needs ``n − 2`` further points
    within the ``m``-frame window; in the ``j``-th frame after its second point it finds one with
    probability ``inside_prob[Δ−1][j−1] · (1 − exp(−N_c · gate_prob))`` — the prediction must
    fall inside the field (``inside_prob``, default 1) and the gate must hold a clutter point.
    The expected number of confirmed branches per head, times ``N_c`` heads per frame, is the
    steady-state rate. Every branch is counted (no conflict resolution: a detection confirmed in
    one track cannot serve another), so it is an upper bound, tight only when confirmations are
    rare (3/4 at low density; not 2/3, which confirms almost every pair).

    Parameters
    ----------
    n, m
        The logic rule.
    clutter_per_frame
        Mean number of uniform clutter points per frame ``N_c``.
    pair_prob
        ``pair_prob[Δ−1]``: probability that a random clutter point lies in the velocity gate of
        a random head ``Δ`` frames earlier (``Δ = 1 … m−1``).
    gate_prob
        Probability that a random clutter point lies in the prediction gate (gate area over field
        area).
    inside_prob
        Optional ``(m−1) × (m−2)`` table described above.

    Returns
    -------
    float
        Expected number of false tracks confirmed per frame.
    """
    from math import exp

    m = check_int(m, "m", min_value=2)
    n = check_int(n, "n", min_value=2, max_value=m)
    lam = check_positive(clutter_per_frame, "clutter_per_frame", allow_zero=True)
    pp = [float(p) for p in pair_prob]
    if len(pp) < m - 1:
        raise ValueError(f"pair_prob needs m − 1 = {m - 1} entries, got {len(pp)}")
    g = check_positive(gate_prob, "gate_prob", allow_zero=True)
    pg = 1.0 - exp(-lam * g)
    total = 0.0
    for gap in range(1, m):
        rest = m - 1 - gap  # frames left in the window after the second point
        probs = [pg * (float(inside_prob[gap - 1][j]) if inside_prob is not None else 1.0)
                 for j in range(rest)]
        # Poisson-binomial distribution of further hits
        dist = np.zeros(rest + 1)
        dist[0] = 1.0
        for p in probs:
            dist[1:] = dist[1:] * (1 - p) + dist[:-1] * p
            dist[0] *= 1 - p
        need = n - 2
        p_ok = float(dist[need:].sum()) if need <= rest else 0.0
        total += lam * pp[gap - 1] * p_ok
    return lam * total
