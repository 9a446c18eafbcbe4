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
