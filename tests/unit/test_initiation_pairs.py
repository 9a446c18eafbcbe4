"""The vectorised pair / triplet engine (eotrack.tracking.initiation.pairs)."""

import numpy as np
import pytest
from eotrack.tracking.initiation import PointGrid, cv_fit_batch, gated_pairs, greedy_disjoint
from hypothesis import example, given, settings
from hypothesis import strategies as st


@given(st.integers(0, 2**32 - 1), st.integers(0, 40), st.integers(0, 40),
       st.floats(0.5, 3.0), st.floats(0.0, 60.0), st.floats(0.0, 200.0))
@settings(max_examples=40, deadline=None)
def test_gated_pairs_equal_brute_force(seed, na, nb, dt, v_lo, dv):
    rng = np.random.default_rng(seed)
    a, b = rng.uniform(0, 300, (na, 2)), rng.uniform(0, 300, (nb, 2))
    ia, ib, dx, dy = gated_pairs(a, b, dt, v_lo, v_lo + dv)
    brute = {(i, j) for i in range(na) for j in range(nb)
             if v_lo <= np.hypot(*(b[j] - a[i])) / dt <= v_lo + dv}
    assert set(zip(ia.tolist(), ib.tolist())) == brute
    np.testing.assert_allclose(dx, b[ib, 0] - a[ia, 0])
    np.testing.assert_allclose(dy, b[ib, 1] - a[ia, 1])


@given(st.integers(0, 2**32 - 1), st.integers(0, 60), st.integers(0, 60), st.floats(0.2, 20.0))
@settings(max_examples=50, deadline=None)
def test_point_grid_finds_exactly_the_close_pairs(seed, n_pts, n_q, radius):
    rng = np.random.default_rng(seed)
    pts = rng.uniform(-50, 150, (n_pts, 2))
    q = np.concatenate([rng.uniform(-100, 200, (n_q, 2)),
                        pts[:5] + rng.normal(0, radius / 2, (min(5, n_pts), 2))])
    r = rng.uniform(0.1, 1.0, len(q)) * radius
    qi, pi, d2 = PointGrid(pts, radius).query(q, r)
    brute = {(i, j) for i in range(len(q)) for j in range(n_pts)
             if np.sum((q[i] - pts[j]) ** 2) <= r[i] ** 2}
    assert set(zip(qi.tolist(), pi.tolist())) == brute
    np.testing.assert_allclose(d2, np.sum((q[qi] - pts[pi]) ** 2, axis=1))
    assert np.all(np.diff(qi) >= 0)


def test_point_grid_bad_input():
    with pytest.raises(ValueError, match="radius"):
        PointGrid(np.zeros((3, 2)), 0.0)
    with pytest.raises(ValueError, match="xy"):
        PointGrid(np.zeros((3, 3)), 1.0)


def test_gated_pairs_bad_input():
    with pytest.raises(ValueError, match="dt"):
        gated_pairs(np.zeros((2, 2)), np.ones((2, 2)), 0.0, 1, 2)
    with pytest.raises(ValueError, match="v_max"):
        gated_pairs(np.zeros((2, 2)), np.ones((2, 2)), 1.0, 3, 2)
    with pytest.raises(ValueError, match="xy_a"):
        gated_pairs(np.zeros((2, 3)), np.ones((2, 2)), 1.0, 1, 2)


@given(st.integers(0, 2**32 - 1))
@settings(max_examples=30, deadline=None)
def test_cv_fit_batch_matches_polyfit(seed):
    rng = np.random.default_rng(seed)
    n, m = 7, 5
    t = np.sort(rng.uniform(0, 10, (n, m)), axis=1)
    x, y = rng.normal(0, 50, (n, m)), rng.normal(0, 50, (n, m))
    mask = rng.random((n, m)) < 0.7
    mask[:, :2] = True
    tm, pm, v, rss = cv_fit_batch(t, x, y, mask)
    for i in range(n):
        w = mask[i]
        px, py = np.polyfit(t[i, w], x[i, w], 1), np.polyfit(t[i, w], y[i, w], 1)
        assert v[i, 0] == pytest.approx(px[0]) and v[i, 1] == pytest.approx(py[0])
        assert pm[i, 0] == pytest.approx(np.polyval(px, tm[i]))
        res = (np.sum((np.polyval(px, t[i, w]) - x[i, w]) ** 2)
               + np.sum((np.polyval(py, t[i, w]) - y[i, w]) ** 2))
        assert rss[i] == pytest.approx(res, rel=1e-7, abs=1e-8)


def test_cv_fit_batch_bad_input():
    t = np.array([[0.0, 1.0, 2.0]])
    with pytest.raises(ValueError, match="two hits"):
        cv_fit_batch(t, t, t, np.array([[True, False, False]]))
    with pytest.raises(ValueError, match="distinct times"):
        cv_fit_batch(np.ones((1, 3)), t, t, np.ones((1, 3), bool))


def _sequential_greedy(members, rank):
    used, out = set(), []
    for c in np.lexsort((np.arange(len(rank)), rank)):
        items = {int(i) for i in members[c] if i >= 0}
        if items & used:
            continue
        used |= items
        out.append(int(c))
    return out


@given(st.integers(0, 2**32 - 1), st.integers(0, 80), st.integers(1, 30))
@settings(max_examples=60, deadline=None)
def test_greedy_disjoint_equals_sequential_greedy(seed, n_cand, n_items):
    rng = np.random.default_rng(seed)
    mem = rng.integers(-1, n_items, (n_cand, 3))
    mem[:, 0] = rng.integers(0, n_items, n_cand)
    rank = rng.permutation(n_cand).astype(float)
    got = greedy_disjoint(mem, rank, n_items).tolist()
    assert got == _sequential_greedy(mem, rank)


def test_greedy_disjoint_bad_input():
    with pytest.raises(ValueError, match="members"):
        greedy_disjoint(np.zeros(3), np.zeros(3))
    with pytest.raises(ValueError, match="rank"):
        greedy_disjoint(np.zeros((3, 2)), np.zeros(2))
    assert greedy_disjoint(np.zeros((0, 3)), np.zeros(0)).size == 0


@given(st.integers(0, 2**32 - 1), st.floats(0.5, 12.0))
@settings(max_examples=30, deadline=None)
def test_occupancy_image_covers_every_close_position(seed, radius):
    from eotrack.tracking.initiation import occupancy_image

    rng = np.random.default_rng(seed)
    pts = rng.uniform(0, 200, (rng.integers(1, 30), 2))
    occ, x0, y0, w, h = occupancy_image(pts, radius)
    # positions within radius of some point must land on marked pixels
    ang = rng.uniform(0, 2 * np.pi, (len(pts), 50))
    rr = radius * np.sqrt(rng.uniform(0, 1, (len(pts), 50)))
    q = pts[:, None, :] + np.stack([rr * np.cos(ang), rr * np.sin(ang)], -1)
    q = q.reshape(-1, 2)
    ix = np.floor(q[:, 0] - x0).astype(int)
    iy = np.floor(q[:, 1] - y0).astype(int)
    assert np.all(occ[iy * w + ix] > 0)
    # the border is empty
    img = occ.reshape(h, w)
    assert not img[0].any() and not img[-1].any() and not img[:, 0].any() and not img[:, -1].any()
    with pytest.raises(ValueError, match="radius"):
        occupancy_image(pts, 0.0)
    with pytest.raises(ValueError, match="at least one"):
        occupancy_image(np.zeros((0, 2)), 1.0)


@given(st.integers(0, 2**32 - 1), st.floats(0.5, 400.0), st.floats(1.0, 80.0))
@settings(max_examples=30, deadline=None)
@example(211, 9.0, 1.1)  # found on a fresh clone: the origin rounded into the border
def test_occupancy_image_in_coarse_cells_covers_every_close_position(seed, radius, cell):
    from eotrack.tracking.initiation import occupancy_image

    rng = np.random.default_rng(seed)
    pts = rng.uniform(0, 500, (rng.integers(1, 30), 2))
    occ, x0, y0, w, h = occupancy_image(pts, radius, cell_px=cell)
    ang = rng.uniform(0, 2 * np.pi, (len(pts), 50))
    rr = radius * np.sqrt(rng.uniform(0, 1, (len(pts), 50)))
    q = (pts[:, None, :] + np.stack([rr * np.cos(ang), rr * np.sin(ang)], -1)).reshape(-1, 2)
    ix = np.floor((q[:, 0] - x0) / cell).astype(int)
    iy = np.floor((q[:, 1] - y0) / cell).astype(int)
    assert np.all(occ[iy * w + ix] > 0)
    img = occ.reshape(h, w)
    assert not img[0].any() and not img[-1].any() and not img[:, 0].any() and not img[:, -1].any()
    with pytest.raises(ValueError, match="cell_px"):
        occupancy_image(pts, radius, cell_px=0.0)
