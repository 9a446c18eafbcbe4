"""Association rules (steps 4–5), the summary table (step 6) and the three-view check."""

import numpy as np
import pytest
from eotrack.geometry import (
    PinholeCamera,
    associate,
    greedy_candidates,
    intrinsics_from_fov,
    look_at,
    summary_table,
    three_view_check,
)
from hypothesis import given, settings
from hypothesis import strategies as st


def test_paper_rule_nearest_one_to_one():
    d = np.array([[1.0, 2.0, 50.0], [1.5, 9.0, 50.0], [50.0, 50.0, 50.0]])
    pairs = associate(d, 10.0)
    assert pairs.tolist() == [[0, 0], [1, 1]]  # 0 takes its nearest; 1 left with its second
    assert associate(d, 1.2).tolist() == [[0, 0]]
    # greedy steals: the global assignment does better on total distance
    d2 = np.array([[1.0, 2.0], [1.1, 20.0]])
    assert associate(d2, 10.0).tolist() == [[0, 0]]
    assert associate(d2, 10.0, rule="hungarian").tolist() == [[0, 1], [1, 0]]


@settings(max_examples=40, deadline=None)
@given(st.integers(0, 2**31 - 1), st.integers(0, 8), st.integers(0, 8), st.floats(0, 30),
       st.sampled_from(["paper", "hungarian"]))
def test_one_to_one_and_gated(seed, n1, n2, L, rule):
    d = np.random.default_rng(seed).uniform(0, 20, (n1, n2))
    pairs = associate(d, L, rule=rule)
    assert len(set(pairs[:, 0])) == len(pairs) == len(set(pairs[:, 1]))
    assert np.all(d[pairs[:, 0], pairs[:, 1]] < L)
    if rule == "hungarian":  # the global rule never associates fewer pairs than the greedy one
        assert len(pairs) >= len(associate(d, L))


def test_greedy_prefix_property():
    rng = np.random.default_rng(0)
    d = rng.uniform(0, 20, (8, 9))
    full = greedy_candidates(d, 20.0)
    for L in (3.0, 7.0, 12.0):
        dd = d[full[:, 0], full[:, 1]]
        want = {tuple(p) for p in full[dd < L]}
        assert {tuple(p) for p in associate(d, L)} == want


def test_empty_inputs_give_empty_results():
    assert associate(np.zeros((0, 3)), 5.0).shape == (0, 2)
    assert associate(np.zeros((2, 0)), 5.0, rule="hungarian").shape == (0, 2)
    assert summary_table([0, 0], {}).shape == (0, 2)


def test_summary_table_logic():
    # map0: p0 (target A), p1 (target B); map1: p0 (A); map2: p0 (A), p1 (B), p2 (lone)
    matches = {(0, 1): [[0, 0]], (0, 2): [[0, 0], [1, 1]], (1, 2): [[0, 0]]}
    rows = summary_table([2, 1, 3], matches)
    assert rows.tolist() == [[0, 0, 0], [1, -1, 1], [-1, -1, 2]]
    # an element that does not associate with *all* earlier members starts a new row
    rows = summary_table([1, 1, 1], {(0, 1): [[0, 0]], (0, 2): [[0, 0]]})
    assert rows.tolist() == [[0, 0, -1], [-1, -1, 0]]


def test_three_view_check_rejects_false_pair():
    K = intrinsics_from_fov(2, 2, 512, 512)
    X = np.array([[0.0, 0, 40000], [50.0, 30, 40000]])
    cams = []
    for c in ([0.0, 0, 0], [3000.0, 0, 0], [0.0, 3000, 0]):
        c = np.array(c)
        cams.append(PinholeCamera(K, look_at(np.array([0, 0, 40000.0]) - c, up=[0, 1, 0]), c))
    pts = [cam.project(X) for cam in cams]
    good = three_view_check(pts[0], pts[1], [[0, 0], [1, 1]], cams[0], cams[1],
                            [(cams[2], pts[2])], 5.0)
    assert good.tolist() == [True, True]
    bad = three_view_check(pts[0], pts[1], [[0, 1]], cams[0], cams[1],
                           [(cams[2], pts[2])], 5.0)
    assert bad.tolist() == [False]
    assert three_view_check(pts[0], pts[1], np.zeros((0, 2)), cams[0], cams[1], [], 5).size == 0


def test_bad_input():
    with pytest.raises(ValueError, match="threshold must be finite and >= 0"):
        associate(np.ones((2, 2)), -1.0)
    with pytest.raises(TypeError, match="threshold must be a real number"):
        associate(np.ones((2, 2)), "10")
    with pytest.raises(ValueError, match="rule must be one of"):
        associate(np.ones((2, 2)), 1.0, rule="jpda")
    with pytest.raises(ValueError, match="dist must be a 2-D"):
        associate(np.ones(3), 1.0)
    with pytest.raises(ValueError, match="dist must hold non-negative"):
        greedy_candidates(-np.ones((2, 2)), 1.0)
    with pytest.raises(ValueError, match="matches keys"):
        summary_table([1, 1], {(1, 0): [[0, 0]]})
    with pytest.raises(ValueError, match="outside the maps"):
        summary_table([1, 1], {(0, 1): [[0, 3]]})
    with pytest.raises(ValueError, match="n_points must be non-negative"):
        summary_table([-1, 1], {})
    K = intrinsics_from_fov(2, 2, 512, 512)
    cam = PinholeCamera(K, np.eye(3), np.zeros(3))
    with pytest.raises(ValueError, match="gate_px"):
        three_view_check([[1, 1]], [[1, 1]], [[0, 0]], cam, cam, [], 0.0)


# ----------------------------------------------------------------- the default χ² gate
def test_chi2_gate_values_and_default():
    from eotrack.geometry import DEFAULT_GATE_PROBABILITY, chi2_gate
    from scipy.stats import norm

    assert DEFAULT_GATE_PROBABILITY == 0.99
    # one degree of freedom: the two-sided normal quantile
    assert chi2_gate(2.0) == pytest.approx(2.0 * norm.ppf(0.995), rel=1e-12)
    assert chi2_gate(1.0, 0.95) == pytest.approx(norm.ppf(0.975), rel=1e-12)
    # two degrees of freedom: the Rayleigh quantile sqrt(-2 ln(1 - p))
    assert chi2_gate(1.0, 0.9, dof=2) == pytest.approx(np.sqrt(-2 * np.log(0.1)), rel=1e-12)
    d = np.random.default_rng(3).uniform(0, 12, (9, 7))
    np.testing.assert_array_equal(associate(d, sigma_px=2.0), associate(d, chi2_gate(2.0)))
    np.testing.assert_array_equal(associate(d, sigma_px=2.0, p=0.9, rule="hungarian"),
                                  associate(d, chi2_gate(2.0, 0.9), rule="hungarian"))
    # backward compatible: positional threshold, rule keyword
    np.testing.assert_array_equal(associate(d, 5.0, rule="paper"), associate(d, 5.0))


def test_chi2_gate_bad_input():
    from eotrack.geometry import chi2_gate

    with pytest.raises(ValueError, match="sigma_px"):
        chi2_gate(-1.0)
    with pytest.raises(ValueError, match="p must be a probability"):
        chi2_gate(1.0, 1.0)
    with pytest.raises(ValueError, match="dof"):
        chi2_gate(1.0, 0.9, dof=0)
    with pytest.raises(TypeError, match=r"threshold \(px\) or sigma_px"):
        associate(np.ones((2, 2)))
    with pytest.raises(TypeError, match="not both"):
        associate(np.ones((2, 2)), 3.0, sigma_px=1.0)


def test_chi2_gate_coverage_on_simulated_true_pairs():
    """Held out: true pairs of random two-camera scenes with centroid noise σ per axis fall
    inside the default gate at its nominal rate (the σ of the distance is computed here by
    propagating both points' noise through the line, not taken from the library)."""
    from eotrack.geometry import chi2_gate, epipolar_distances, fundamental_from_poses

    rng = np.random.default_rng(11)
    Kc = intrinsics_from_fov(8.0, 6.0, 1024, 768, 500.0, 390.0)  # not the paper's sensor
    inside, total = 0, 0
    for _ in range(40):
        target = rng.normal(size=3) * 1e4
        c1, c2 = target + rng.normal(size=(2, 3)) * 3e4
        R1 = look_at(target - c1, up=rng.normal(size=3))
        R2 = look_at(target - c2, up=rng.normal(size=3))
        X = target + rng.normal(size=(30, 3)) * 300
        p1 = PinholeCamera(Kc, R1, c1).project(X)
        p2 = PinholeCamera(Kc, R2, c2).project(X)
        F = fundamental_from_poses(Kc, R1, c1, Kc, R2, c2)
        sig = 0.4
        # σ of the signed distance: unit normal of line 2 (p2 noise) plus the line's motion
        # with p1 (finite differences), both per axis
        l2 = np.column_stack([p1, np.ones(len(p1))]) @ F.T
        nrm = np.hypot(l2[:, 0], l2[:, 1])
        g1 = []
        for ax in (0, 1):
            q = p1.copy()
            q[:, ax] += 1e-3
            lq = np.column_stack([q, np.ones(len(q))]) @ F.T
            dq = (np.sum(lq[:, :2] * p2, 1) + lq[:, 2]) / np.hypot(lq[:, 0], lq[:, 1])
            g1.append(dq / 1e-3)
        sd = sig * np.sqrt(1.0 + g1[0] ** 2 + g1[1] ** 2)
        n1 = p1 + rng.normal(size=p1.shape) * sig
        n2 = p2 + rng.normal(size=p2.shape) * sig
        d = np.diag(epipolar_distances(F, n1, n2))
        inside += int(np.sum(d < np.array([chi2_gate(s) for s in sd])))
        total += len(d)
        assert np.all(nrm > 0)
    rate = inside / total
    assert 0.98 < rate <= 1.0  # nominal 0.99; 1,200 pairs: ±0.006 (2σ)


@settings(max_examples=25, deadline=None)
@given(st.integers(0, 2**31 - 1), st.integers(3, 6))
def test_held_out_multiview_scene_recovers_truth(seed, n_cams):
    """Held out: random multi-camera scenes with a sensor unlike the paper's, random
    visibility: noise-free, every true pair whose row and column hold no foreign candidate
    within the gate is associated (both rules), the global rule associates at least as many
    pairs as there are true pairs, and a summary of the true pairs rebuilds each object's
    row."""
    from eotrack.geometry import chi2_gate, epipolar_distances, fundamental_from_poses

    rng = np.random.default_rng(seed)
    Kc = intrinsics_from_fov(10.0, 10.0, 2048, 2048)
    target = rng.normal(size=3) * 1e3
    X = target + rng.normal(size=(12, 3)) * 60.0
    cams = []
    for _ in range(n_cams):
        c = target + rng.normal(size=3) * 2e3
        cams.append(PinholeCamera(Kc, look_at(target - c, up=rng.normal(size=3)), c,
                                  (2048, 2048)))
    vis = np.stack([cam.sees(X) for cam in cams]) & (rng.uniform(size=(n_cams, 12)) < 0.7)
    idx = [np.flatnonzero(v) for v in vis]
    pts = [cam.project(X[i]) for cam, i in zip(cams, idx)]
    gate = chi2_gate(0.5)
    matches = {}
    for a in range(n_cams):
        for b in range(a + 1, n_cams):
            if not (len(pts[a]) and len(pts[b])):
                matches[(a, b)] = np.zeros((0, 2), int)
                continue
            ca, cb = cams[a], cams[b]
            D = epipolar_distances(fundamental_from_poses(ca.K, ca.R, ca.c, cb.K, cb.R, cb.c),
                                   pts[a], pts[b])
            true = idx[a][:, None] == idx[b][None, :]
            assert np.all(D[true] < 1e-5)
            for rule in ("paper", "hungarian"):
                got = {tuple(x) for x in associate(D, sigma_px=0.5, rule=rule).tolist()}
                for i, j in zip(*np.nonzero(true)):
                    clean = (np.sum(D[i] < gate) == 1) and (np.sum(D[:, j] < gate) == 1)
                    if clean:
                        assert (i, j) in got
                if rule == "hungarian":
                    assert len(got) >= int(true.sum())
            matches[(a, b)] = np.argwhere(true)
    rows = summary_table([len(p) for p in pts], matches)
    rows = rows[(rows >= 0).sum(1) >= 2]
    want = sorted((j, tuple(np.flatnonzero(vis[:, j]))) for j in range(12)
                  if vis[:, j].sum() >= 2)
    got = []
    for r in rows:
        maps = np.flatnonzero(r >= 0)
        objs = {int(idx[k][r[k]]) for k in maps}
        assert len(objs) == 1  # one object per row
        got.append((objs.pop(), tuple(maps)))
    assert sorted(got) == want


def _three_view_scene(seed):
    rng = np.random.default_rng(seed)
    Kc = intrinsics_from_fov(5.0, 5.0, 1024, 1024)  # not the paper's sensor
    target = rng.normal(size=3) * 100
    X = target + rng.normal(size=(10, 3)) * 12
    cams = []
    for _ in range(4):
        v = rng.normal(size=3)
        c = target + 2000 * v / np.linalg.norm(v)
        cams.append(PinholeCamera(Kc, look_at(target - c, up=rng.normal(size=3)), c,
                                  (1024, 1024)))
    pts = [cam.project(X) + rng.normal(size=(10, 2)) * 0.3 for cam in cams]
    return cams, pts


def test_held_out_three_view_check_on_random_scenes():
    """Held out: 120 random four-camera scenes of another sensor (5°, 1024 px), 0.3 px
    centroid noise. With the uncertainty-aware gate (sigma_px) the check keeps true pairs at
    its nominal rate and rejects most false pairs; a fixed 5 px radius rejects true pairs
    where the pair's lines of sight are nearly parallel (the transferred point is then
    uncertain by tens of px) — the failure this gate exists for."""
    ii, jj = np.nonzero(~np.eye(10, dtype=bool))
    false = np.column_stack([ii, jj])
    true = np.column_stack([np.arange(10), np.arange(10)])
    kept_true, kept_true_fixed, kept_false, n_false_seen = 0, 0, 0, 0
    for seed in range(120):
        cams, pts = _three_view_scene(seed)
        others = [(cams[k], pts[k]) for k in (2, 3)]
        kept_true += int(three_view_check(pts[0], pts[1], true, cams[0], cams[1], others,
                                          sigma_px=0.3, p=0.999).sum())
        kept_true_fixed += int(three_view_check(pts[0], pts[1], true, cams[0], cams[1],
                                                others, 5.0).sum())
        k = three_view_check(pts[0], pts[1], false, cams[0], cams[1], others, sigma_px=0.3,
                             p=0.999)
        kept_false += int(k.sum())
        n_false_seen += len(k)
    n_true = 120 * 10
    assert kept_true / n_true >= 0.99  # nominal 0.999² per pair
    assert kept_true_fixed < kept_true  # the fixed radius loses true pairs
    assert kept_false / n_false_seen < 0.2


def test_three_view_check_gate_arguments():
    cams, pts = _three_view_scene(0)
    with pytest.raises(TypeError, match="exactly one of gate_px"):
        three_view_check(pts[0], pts[1], [[0, 0]], cams[0], cams[1], [], 5.0, sigma_px=0.3)
    with pytest.raises(TypeError, match="exactly one of gate_px"):
        three_view_check(pts[0], pts[1], [[0, 0]], cams[0], cams[1], [])
    with pytest.raises(ValueError, match="sigma_px"):
        three_view_check(pts[0], pts[1], [[0, 0]], cams[0], cams[1], [], sigma_px=-1.0)
    with pytest.raises(ValueError, match="p must be"):
        three_view_check(pts[0], pts[1], [[0, 0]], cams[0], cams[1], [], sigma_px=1.0, p=2)


def test_p_with_an_explicit_threshold_is_refused():
    from eotrack.geometry import associate

    d = np.array([[1.0, 5.0], [4.0, 0.5]])
    with pytest.raises(TypeError, match="p "):
        associate(d, 10.0, p=1.0)
    with pytest.raises(TypeError, match="p "):
        associate(d, 10.0, p=0.99)
    with pytest.raises(ValueError):
        associate(d, sigma_px=1.0, p=1.0)  # p outside (0, 1)
    assert associate(d, sigma_px=1.0).tolist() == associate(d, sigma_px=1.0, p=0.99).tolist()


def test_held_out_three_view_check_rejects_pairs_meeting_behind_the_cameras():
    """Held out (not the paper's scene): two cameras 100 m apart looking at a point 10 km away.
    A false pair that satisfies the epipolar constraint but whose lines of sight diverge meets
    behind the cameras; with no third view the check must still reject it (cheirality), and
    keep the true pair."""
    from eotrack.geometry import PinholeCamera, epipolar_distances, fundamental_from_poses
    from eotrack.geometry.rotations import look_at

    K = np.array([[1000.0, 0, 320], [0, 1000.0, 240], [0, 0, 1]])
    X = np.array([0.0, 0.0, 10.0])
    ca, cb = np.array([-0.05, 0, 0]), np.array([0.05, 0, 0])
    cam_a = PinholeCamera(K, look_at(X - ca, up=(0, 1, 0)), ca, (640, 480), None)
    cam_b = PinholeCamera(K, look_at(X - cb, up=(0, 1, 0)), cb, (640, 480), None)
    pa = np.stack([cam_a.project(X[None])[0], [300.0, 250.0]])
    # the image-b point of a spot 20 km *behind* camera a on pa[1]'s line of sight: the pair
    # satisfies eq. (8), but its lines of sight meet behind both cameras
    Xf = ca - 20.0 * cam_a.rays(pa[1:])[0]
    uvb = K @ (cam_b.R @ (Xf - cb))
    pb = np.stack([cam_b.project(X[None])[0], uvb[:2] / uvb[2]])
    assert (cam_b.R @ (Xf - cb))[2] < 0
    F = fundamental_from_poses(K, cam_a.R, ca, K, cam_b.R, cb)
    d = epipolar_distances(F, pa, pb)
    assert d[0, 0] < 1e-6 and d[1, 1] < 1e-6  # both pairs satisfy eq. (8)
    keep = three_view_check(pa, pb, [[0, 0], [1, 1]], cam_a, cam_b, [], gate_px=3.0)
    assert keep.tolist() == [True, False]


def test_summary_table_refuses_non_integer_and_non_one_to_one_pairs():
    with pytest.raises(ValueError, match="one-to-one"):
        summary_table([2, 1], {(0, 1): [[0, 0], [1, 0]]})
    with pytest.raises(ValueError, match="integer"):
        summary_table([2, 1], {(0, 1): [[0.7, 0]]})
    with pytest.raises(ValueError, match="integer"):
        summary_table([2, 1], {(0, 1): [["a", "b"]]})
    # whole-valued floats (e.g. from a float array) are accepted
    assert summary_table([1, 1], {(0, 1): np.array([[0.0, 0.0]])}).tolist() == [[0, 0]]
