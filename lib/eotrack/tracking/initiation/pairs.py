"""The vectorised pair / triplet engine shared by the initiators.

Track initiation over a few frames is, at heart, three array operations:

* :func:`gated_pairs` — every pair (detection of an earlier frame, detection of a later frame)
  whose apparent speed lies in a velocity gate, formed in one broadcast step;
* :class:`PointGrid` — a uniform-grid spatial hash of one frame's detections answering
  fixed-radius neighbour queries for many predicted positions at once (one gather per query to
  reject the empty neighbourhoods, then an exact distance check on the few survivors);
* :func:`cv_fit_batch` — least-squares constant-velocity fits of many short tracks at once
  (rows of up to ``m`` hits), with their residual sums of squares for a χ² test;

plus :func:`greedy_disjoint`, the conflict resolution "best first, each detection used once"
computed without a loop over candidates (parallel rounds of local minima, which gives exactly the
sequential greedy result).
"""

from __future__ import annotations

import math

import numpy as np

from eotrack.validation import as_finite_array, check_positive

__all__ = ["PointGrid", "cv_fit_batch", "gated_pairs", "greedy_disjoint", "occupancy_image"]

_CHUNK = 4_000_000  # broadcast at most this many pairs at once (memory)


def gated_pairs(xy_a: np.ndarray, xy_b: np.ndarray, dt: float, v_min: float,
                v_max: float) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Pairs ``(a, b)`` with ``v_min ≤ |xy_b − xy_a| / dt ≤ v_max``, in one broadcast step.

    Parameters
    ----------
    xy_a, xy_b
        Detections ``(n_a, 2)`` and ``(n_b, 2)`` (pixels); ``b`` is the later frame.
    dt
        Time from ``a`` to ``b`` (s, > 0).
    v_min, v_max
        Speed gate (pixels per second), inclusive; ``0 ≤ v_min ≤ v_max``.

    Returns
    -------
    ia, ib : numpy.ndarray
        ``int64`` indices into ``xy_a`` and ``xy_b``, row-major over ``(a, b)``.
    dx, dy : numpy.ndarray
        Displacements ``xy_b − xy_a`` of the pairs (pixels).
    """
    a = as_finite_array(xy_a, "xy_a", shape=(None, 2))
    b = as_finite_array(xy_b, "xy_b", shape=(None, 2))
    dt = check_positive(dt, "dt")
    lo = check_positive(v_min, "v_min", allow_zero=True)
    hi = check_positive(v_max, "v_max", allow_zero=True)
    if hi < lo:
        raise ValueError(f"v_max must be >= v_min, got v_min={lo}, v_max={hi}")
    return _gated_pairs(a, b, dt, lo, hi)


def _gated_pairs(a: np.ndarray, b: np.ndarray, dt: float, lo: float, hi: float):
    """:func:`gated_pairs` without input checks (internal hot path)."""
    na, nb = len(a), len(b)
    if na == 0 or nb == 0:
        z = np.zeros(0, dtype=np.int64)
        return z, z, np.zeros(0), np.zeros(0)
    lo2, hi2 = (lo * dt) ** 2, (hi * dt) ** 2
    step = max(1, _CHUNK // nb)
    out_a, out_b, out_x, out_y = [], [], [], []
    bx, by = b[:, 0], b[:, 1]
    for s in range(0, na, step):
        ax = a[s:s + step, 0:1]
        ay = a[s:s + step, 1:2]
        dx = bx - ax
        dy = by - ay
        d2 = dx * dx
        d2 += dy * dy
        flat = np.flatnonzero((d2 >= lo2) & (d2 <= hi2))
        ia, ib = np.divmod(flat, nb)
        out_a.append(ia + s)
        out_b.append(ib)
        out_x.append(dx.ravel()[flat])
        out_y.append(dy.ravel()[flat])
    if len(out_a) == 1:
        return out_a[0], out_b[0], out_x[0], out_y[0]
    return (np.concatenate(out_a), np.concatenate(out_b), np.concatenate(out_x),
            np.concatenate(out_y))


class PointGrid:
    """Uniform-grid spatial hash of points for vectorised fixed-radius queries.

    The cell side is ``2 · radius``, so the disc of any query lies in the 2 × 2 block of cells
    whose lower-left cell contains ``query − radius``. A per-block point count answers "is
    anything near?" with one gather per query; only the queries with a non-empty block are
    expanded to candidate points and checked exactly.

    Parameters
    ----------
    xy
        Points ``(n, 2)``.
    radius
        Largest query radius the grid serves (pixels, > 0).
    """

    def __init__(self, xy: np.ndarray, radius: float) -> None:
        p = as_finite_array(xy, "xy", shape=(None, 2))
        self.radius = check_positive(radius, "radius")
        self.xy = p
        self.cell = 2.0 * self.radius
        if len(p):
            self.lo = p.min(axis=0) - self.cell
            span = p.max(axis=0) - self.lo + self.cell
        else:
            self.lo = np.zeros(2)
            span = np.full(2, 2 * self.cell)
        self.nx = math.ceil(span[0] / self.cell) + 1
        self.ny = math.ceil(span[1] / self.cell) + 1
        ix = ((p[:, 0] - self.lo[0]) / self.cell).astype(np.int64)
        iy = ((p[:, 1] - self.lo[1]) / self.cell).astype(np.int64)
        cid = iy * self.nx + ix
        self.order = np.argsort(cid, kind="stable")
        counts = np.bincount(cid, minlength=self.nx * self.ny)
        self.counts = counts
        self.starts = np.concatenate([[0], np.cumsum(counts)[:-1]])
        c2 = counts.reshape(self.ny, self.nx)
        block = c2[:-1, :-1] + c2[1:, :-1] + c2[:-1, 1:] + c2[1:, 1:]
        self.block = block.ravel()

    def __len__(self) -> int:
        return len(self.xy)

    def query(self, q: np.ndarray, radius: float | np.ndarray | None = None, *,
              sort: bool = True) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Every (query, point) pair closer than ``radius``.

        Parameters
        ----------
        q
            Query positions ``(k, 2)`` (or the tuple of their x and y arrays).
        radius
            Scalar or per-query radius, at most the grid's ``radius`` (default: the grid's).

        sort
            Order the result by query index (default); ``False`` skips that sort.

        Returns
        -------
        qi, pi : numpy.ndarray
            Query index and point index of each close pair (ordered by query if ``sort``).
        d2 : numpy.ndarray
            Squared distances.
        """
        qx, qy = (q[0], q[1]) if isinstance(q, tuple) else (q[:, 0], q[:, 1])
        empty = (np.zeros(0, np.int64), np.zeros(0, np.int64), np.zeros(0))
        if len(self.xy) == 0 or len(qx) == 0:
            return empty
        r = self.radius if radius is None else radius
        inv = 1.0 / self.cell
        fx = (qx - (self.lo[0] + self.radius)) * inv
        fy = (qy - (self.lo[1] + self.radius)) * inv
        np.clip(fx, 0, self.nx - 2, out=fx)
        np.clip(fy, 0, self.ny - 2, out=fy)
        ix = fx.astype(np.int64)
        iy = fy.astype(np.int64)
        bkey = iy * (self.nx - 1) + ix
        hit = np.flatnonzero(self.block[bkey])
        if len(hit) == 0:
            return empty
        ix, iy = ix[hit], iy[hit]
        base = iy * self.nx + ix
        qs, ps = [], []
        for off in (0, 1, self.nx, self.nx + 1):
            c = base + off
            cnt = self.counts[c]
            sel = np.flatnonzero(cnt)
            if len(sel) == 0:
                continue
            n = cnt[sel]
            rep = np.repeat(sel, n)
            first = np.repeat(self.starts[c[sel]] - np.cumsum(n) + n, n)
            qs.append(hit[rep])
            ps.append(self.order[first + np.arange(len(rep))])
        qi = np.concatenate(qs)
        pi = np.concatenate(ps)
        ddx = self.xy[pi, 0] - qx[qi]
        ddy = self.xy[pi, 1] - qy[qi]
        d2 = ddx * ddx + ddy * ddy
        rr = r if np.ndim(r) == 0 else np.asarray(r)[qi]
        ok = d2 <= rr * rr
        qi, pi, d2 = qi[ok], pi[ok], d2[ok]
        if not sort:
            return qi, pi, d2
        o = np.argsort(qi, kind="stable")
        return qi[o], pi[o], d2[o]


def occupancy_image(xy: np.ndarray, radius: float, *, cell_px: float = 1.0,
                    ) -> tuple[np.ndarray, float, float, int, int]:
    """An image of cells of side ``cell_px`` marking where a query may lie within ``radius`` of
    a point.

    Cell ``(ix, iy)`` covers ``[x0 + ix·c, x0 + (ix + 1)·c) × [y0 + iy·c, y0 + (iy + 1)·c)``
    (``c = cell_px``); a query ``q`` looks up cell ``floor((q − (x0, y0)) / c)``. A cell is
    marked when some cell within ``radius / c + √2`` (cell-index distance) holds a point, so
    every position within ``radius`` of a point falls on a marked cell (a superset: marked cells
    are then checked exactly; for kernels above 8 cells the disc is widened to a square, which
    OpenCV dilates in time independent of its size). A border of empty cells surrounds the
    points, so look-ups clipped to the image land on empty cells. Built as one dilation
    (``cv2.dilate``) of the points' cells.

    With ``cell_px = 1`` (the default) the image has ``(span + 2·radius)²`` pixels, which grows
    with the radius; choosing ``cell_px`` proportional to the radius (e.g. ``max(1, radius/6)``)
    bounds the image at about ``(span/c + 20)²`` cells whatever the radius.

    Parameters
    ----------
    xy
        Points ``(n, 2)``, ``n ≥ 1``.
    radius
        Query radius (pixels, > 0).
    cell_px
        Cell side (pixels, > 0).

    Returns
    -------
    occ : numpy.ndarray
        Flattened ``uint8`` image (row-major, ``h × w`` cells).
    x0, y0 : float
        Origin of the image (pixels; integers when ``cell_px = 1``).
    w, h : int
        Size of the image (cells).
    """
    import cv2

    p = as_finite_array(xy, "xy", shape=(None, 2))
    if len(p) == 0:
        raise ValueError("xy must hold at least one point")
    r = check_positive(radius, "radius")
    c = check_positive(cell_px, "cell_px")
    n = math.ceil(r / c + math.sqrt(2.0))
    if c == 1.0:
        x0 = math.floor(float(p[:, 0].min())) - n - 1
        y0 = math.floor(float(p[:, 1].min())) - n - 1
        ix = np.floor(p[:, 0] - x0).astype(np.int64)
        iy = np.floor(p[:, 1] - y0).astype(np.int64)
    else:
        x0 = float(p[:, 0].min()) - (n + 1) * c
        y0 = float(p[:, 1].min()) - (n + 1) * c
        ix = np.floor((p[:, 0] - x0) / c).astype(np.int64)
        iy = np.floor((p[:, 1] - y0) / c).astype(np.int64)
        # (min − x0)/c = n + 1 exactly on paper, but it can round to n + 0.999…: shift the
        # origin by whole cells so that the border of empty cells is always there
        sx, sy = max(0, n + 1 - int(ix.min())), max(0, n + 1 - int(iy.min()))
        x0, y0 = x0 - sx * c, y0 - sy * c
        ix, iy = ix + sx, iy + sy
    w = int(ix.max()) + n + 2
    h = int(iy.max()) + n + 2
    img = np.zeros((h, w), dtype=np.uint8)
    img[iy, ix] = 1
    if n <= 8:
        o = np.arange(-n, n + 1)
        kernel = ((o[:, None] ** 2 + o[None, :] ** 2) <= (r / c + math.sqrt(2.0)) ** 2)
        kernel = kernel.astype(np.uint8)
    else:  # a square (a superset of the disc): OpenCV dilates with it in O(pixels)
        kernel = cv2.getStructuringElement(cv2.MORPH_RECT, (2 * n + 1, 2 * n + 1))
    return cv2.dilate(img, kernel).ravel(), x0, y0, w, h


def cv_fit_batch(t: np.ndarray, x: np.ndarray, y: np.ndarray, mask: np.ndarray,
                 ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Least-squares constant-velocity fits of many short tracks at once.

    Row ``i`` holds up to ``m`` hits: times ``t[i]``, positions ``(x[i], y[i])``, used where
    ``mask[i]`` (at least two distinct times per row).

    Returns
    -------
    t_mean : numpy.ndarray
        Mean time of each row's hits.
    p_mean : numpy.ndarray
        ``(n, 2)`` mean position (the fitted position at ``t_mean``).
    v : numpy.ndarray
        ``(n, 2)`` fitted velocity.
    rss : numpy.ndarray
        Residual sum of squares ``Σ |xy − p(t)|²`` (pixels²); ``rss / σ²`` is χ² with
        ``2 (k − 2)`` degrees of freedom for ``k`` hits with isotropic noise σ.
    """
    w = np.asarray(mask, dtype=float)
    nw = w.sum(axis=1)
    if np.any(nw < 2):
        raise ValueError("every row of mask needs at least two hits")
    tm = (w * t).sum(axis=1) / nw
    tc = (t - tm[:, None]) * w
    den = (tc * tc).sum(axis=1)
    if np.any(den <= 0):
        raise ValueError("every row needs at least two distinct times")
    xm = (w * x).sum(axis=1) / nw
    ym = (w * y).sum(axis=1) / nw
    vx = (tc * x).sum(axis=1) / den
    vy = (tc * y).sum(axis=1) / den
    rx = (x - xm[:, None] - vx[:, None] * tc) * w
    ry = (y - ym[:, None] - vy[:, None] * tc) * w
    rss = (rx * rx + ry * ry).sum(axis=1)
    return tm, np.stack([xm, ym], 1), np.stack([vx, vy], 1), rss


def greedy_disjoint(members: np.ndarray, rank: np.ndarray, n_items: int | None = None,
                    ) -> np.ndarray:
    """Best-first selection of candidates that share no item (detection).

    Equivalent to: sort candidates by ``rank`` (lower is better) and accept each one whose items
    are all still unused. Computed in parallel rounds: a candidate that ranks best among all
    live candidates touching any of its items is accepted (the sequential greedy accepts it
    too), then the candidates it conflicts with are removed.

    Parameters
    ----------
    members
        ``(n_cand, k)`` item ids per candidate, ``−1`` for empty slots.
    rank
        ``(n_cand,)`` priorities (distinct values give a unique result; ties are broken by
        candidate index).
    n_items
        Number of items (default: ``members.max() + 1``).

    Returns
    -------
    numpy.ndarray
        Indices of the accepted candidates, best first.
    """
    mem = np.asarray(members, dtype=np.int64)
    if mem.ndim != 2:
        raise ValueError(f"members must be a 2-D array, got shape {mem.shape}")
    n = len(mem)
    if np.shape(rank) != (n,):
        raise ValueError(f"rank must have shape ({n},), got {np.shape(rank)}")
    if n == 0:
        return np.zeros(0, dtype=np.int64)
    order = np.lexsort((np.arange(n), np.asarray(rank)))
    prio = np.empty(n, dtype=np.int64)
    prio[order] = np.arange(n)  # 0 = best
    n_items = int(mem.max()) + 1 if n_items is None else int(n_items)
    ci, slot = np.nonzero(mem >= 0)
    item = mem[ci, slot]
    live = np.ones(n, dtype=bool)
    accepted = []
    big = np.iinfo(np.int64).max
    while True:
        sel = live[ci]
        if not np.any(sel):
            break
        c, it = ci[sel], item[sel]
        best = np.full(n_items, big, dtype=np.int64)
        np.minimum.at(best, it, prio[c])
        # a candidate wins if it is the best on every one of its items
        lose = np.zeros(n, dtype=bool)
        lose[c[best[it] != prio[c]]] = True
        win = live & ~lose
        win_idx = np.flatnonzero(win)
        accepted.append(win_idx)
        used = np.zeros(n_items, dtype=bool)
        used[item[win[ci]]] = True
        dead = np.zeros(n, dtype=bool)
        dead[ci[used[item]]] = True
        live &= ~dead
    acc = np.concatenate(accepted) if accepted else np.zeros(0, dtype=np.int64)
    return acc[np.argsort(prio[acc])]
