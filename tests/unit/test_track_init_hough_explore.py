"""The Explore figure of notebook 04: built once, updated in place, values drawn as computed."""

from __future__ import annotations

import numpy as np
from eotrack.experiments import track_init_hough as TH


def test_plot_explore_updates_one_figure_with_the_results():
    fig = TH.plot_explore(clutter=5.0, neighbourhood=6)
    again = TH.plot_explore(clutter=5.0, neighbourhood=26)
    assert again is fig  # the same figure, updated in place
    res = TH.explore_results(5.0, 26, False, False)
    left = fig.axes[0]
    np.testing.assert_allclose([b.get_height() for b in left.patches], res["false"])
    np.testing.assert_allclose(left.lines[0].get_ydata(), res["chance"])
    recall = res["correct"].sum() / max(res["eligible"].sum(), 1)
    title = " ".join(left.get_title(loc=k) for k in ("left", "center", "right"))
    assert f"recall {recall:.2f}" in title
    # any title location (the house style, set earlier in the process, puts titles on the left)
    assert "26-nbhd" in " ".join(left.get_title(loc=k) for k in ("left", "center", "right"))
    good = fig.axes[1].lines[2]
    n_good = sum(1 for _, ok in res["tracks"] if ok)
    assert np.isnan(good.get_xdata()).sum() == n_good  # one NaN after each correct track
