"""Robust pose on a scene family (notebook 06 and its benchmark share this call)."""

from __future__ import annotations

import numpy as np
import pytest
from eotrack.experiments import ransac_crlb_pose as E
from eotrack.pose import random_pnp_scene


@pytest.fixture(scope="module")
def family():
    rng = np.random.default_rng(606)
    return [random_pnp_scene(rng) for _ in range(3)]


def test_family_comparison_finds_the_pose(family):
    res = E.pose_family_comparison(family, methods=(E.OURS, E.OPENCV))
    assert list(res) == [E.OURS, E.OPENCV]
    for errs, ms in res.values():
        assert errs.shape == (3, 2) and ms > 0
        assert np.all(errs[:, 0] < 5.0)  # degrees: every scene found
    t = E.family_table(res)
    assert t.loc[E.OURS, "found (< 5°)"] == 3 and t.loc[E.OURS, "of"] == 3
    assert t.loc[E.OPENCV, "rotation × OpenCV"] == pytest.approx(1.0)
    assert t.loc[E.OURS, "rotation × OpenCV"] == pytest.approx(
        t.loc[E.OURS, "median rotation error (deg)"]
        / t.loc[E.OPENCV, "median rotation error (deg)"])
    assert "CPU ms per image" not in E.family_table(res, timing=False)


def test_family_comparison_rejects_bad_input(family):
    with pytest.raises(ValueError, match="scenes"):
        E.pose_family_comparison([])
    with pytest.raises(ValueError, match="cv_threshold"):
        E.pose_family_comparison(family, cv_threshold=0.0)
    with pytest.raises(ValueError, match="methods"):
        E.pose_family_comparison(family, methods=("lsq",))
    with pytest.raises(ValueError, match="reference"):
        E.family_table(E.pose_family_comparison(family[:1], methods=(E.OURS,)))
