"""Capstone chain: configuration, helpers, stage errors, backend equality."""

from __future__ import annotations

import numpy as np
import pytest
from eotrack.experiments import capstone as C
from eotrack.montecarlo import TrialRunner, trial_generators
from hypothesis import given, settings
from hypothesis import strategies as st

#: A short night around XM-3's eclipse (umbra entry ≈ 05:25 UTC): cheap but complete.
SHORT = C.with_changes(night_start_utc="2006-03-25T03:00:00", night_hours=3.5,
                       visit_interval_s=1800.0)


def test_config_bad_input():
    with pytest.raises(ValueError, match="burst_frames"):
        C.CapstoneConfig(burst_frames=3)
    with pytest.raises(ValueError, match="stations"):
        C.CapstoneConfig(stations=(C.CapstoneConfig().stations[0],))
    with pytest.raises(ValueError, match="exposure_s"):
        C.CapstoneConfig(exposure_s=30.0)
    with pytest.raises(ValueError, match="burst"):
        C.CapstoneConfig(visit_interval_s=60.0)
    assert C.CapstoneConfig().fov_deg == pytest.approx(256 * 15 / 3600)


def test_burst_index():
    gens = trial_generators(7, 5)
    assert [C.burst_index(g) for g in gens] == [0, 1, 2, 3, 4]
    with pytest.raises(ValueError, match="spawn"):
        C.burst_index(np.random.default_rng(1))


def test_separate_targets_by_motion_and_catalogue():
    gx, gy = np.meshgrid(np.arange(40.0, 200, 15), np.arange(40.0, 200, 15))
    stars = np.c_[gx.ravel(), gy.ravel()][:30]
    drift = np.array([[-10.0, 0.0]] * 3)
    target = np.array([120.3, 80.7])
    det, sxy = [], []
    for k in range(4):
        s = stars + k * np.array([-10.0, 0.0])
        det.append(np.vstack([s, target + np.array([0.05 * k, 0.0])]))
        sxy.append(s[:10])  # only 10 stars are catalogued
    is_cat, is_cand = C.separate_targets(det, sxy, drift, 256)
    for k in range(4):
        assert is_cat[k][:10].all() and not is_cat[k][10:].any()
        assert np.flatnonzero(is_cand[k]).tolist() == [30]
    with pytest.raises(ValueError, match="drift"):
        C.separate_targets(det, sxy, drift[:2], 256)


@settings(max_examples=40, deadline=None)
@given(st.integers(0, 40), st.integers(0, 40), st.floats(-30, 30), st.integers(0, 2**31))
def test_separate_targets_masks_are_disjoint(n_stars, n_other, dx, seed):
    rng = np.random.default_rng(seed)
    stars = rng.uniform(0, 128, (n_stars, 2))
    det = [np.vstack([stars + k * np.array([dx, 0.0]), rng.uniform(0, 128, (n_other, 2))])
           for k in range(3)]
    sxy = [d[: n_stars // 2] for d in det]
    is_cat, is_cand = C.separate_targets(det, sxy, np.array([[dx, 0.0]] * 2), 128)
    for k in range(3):
        assert is_cat[k].shape == is_cand[k].shape == (len(det[k]),)
        assert not np.any(is_cat[k] & is_cand[k])


def test_bad_config_types():
    with pytest.raises(TypeError, match="config"):
        C.make_plan("tonight")
    with pytest.raises(TypeError, match="config"):
        C.target_peak_snr(3)
    with pytest.raises(ValueError, match="levels"):
        C.noise_sweep(levels=(400.0, -1.0))


def test_simple_formulas():
    assert C.sidereal_drift_px() == pytest.approx(7.292115e-5 * 20 * 206264.806 / 15, rel=1e-6)
    assert C.sidereal_drift_px(dec_deg=60) == pytest.approx(C.sidereal_drift_px() / 2)
    assert C.range_error_km(37000, 4900, 1.0) == pytest.approx(37000 ** 2 / 206264.806 / 4900)
    with pytest.raises(ValueError, match="baseline_km"):
        C.range_error_km(37000, 0.0, 1.0)
    with pytest.raises(ValueError, match="dec_deg"):
        C.sidereal_drift_px(dec_deg=100)
    assert C.target_peak_snr(C.with_changes(sky_e=1600)) < C.target_peak_snr()


def test_stage_sky_object_never_rises():
    # 24208 (ITALSAT 2, near 20°W) is below the horizon of Haleakala and Socorro
    with pytest.raises(ValueError, match=r"stage 'sky'.*24208 never rises"):
        C.make_plan(C.with_changes(norad_ids=(25954, 24208)))


def test_stage_prediction_night_without_eclipse():
    # midsummer: GEO objects never enter the umbra
    cfg = C.with_changes(night_start_utc="2006-06-21T00:30:00", norad_ids=(25954,))
    with pytest.raises(ValueError, match=r"stage 'prediction'.*no eclipse"):
        C.run_night(cfg)


def test_stage_extraction_no_targets():
    cfg = C.with_changes(SHORT, target_mag=30.0, norad_ids=(28626,))
    with pytest.raises(ValueError, match=r"stage 'extraction': no target detected"):
        C.run_night(cfg)
    res = C.run_night(cfg, strict=False)
    assert np.isnan(res.budget["value"].iloc[-1])


def test_run_night_bad_runner():
    with pytest.raises(TypeError, match="runner"):
        C.run_night(SHORT, runner="serial")
    with pytest.raises(TypeError, match="config"):
        C.run_night({"sky_e": 1})


def test_short_night_serial_equals_local_cluster():
    distributed = pytest.importorskip("distributed")
    cfg = C.with_changes(SHORT, norad_ids=(28626, 25954))
    serial = C.run_night(cfg, strict=False)  # 30-min visits: too few points to predict
    assert serial.budget.set_index("metric")["value"]["correct pairs"] == 1.0
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=None) as cl, distributed.Client(cl) as cli:
        dask = C.run_night(cfg, runner=TrialRunner(scheduler=cli, progress=False),
                           strict=False)
    a = serial.budget["value"].to_numpy(float)
    b = dask.budget["value"].to_numpy(float)
    assert np.array_equal(a, b, equal_nan=True)


def _fake_sweep():
    import pandas as pd
    from eotrack.experiments.capstone import figures as F

    rows = [k for k, _ in F._FRACTIONS] + ["triangulation · RMS position error"] + [
        f"prediction · {m}: RMS error through the eclipse" for m in C.PREDICTORS] + [
        "target peak S/N"]
    values = np.random.default_rng(0).uniform(0.1, 1.0, (len(rows), 3))
    return pd.DataFrame(values, index=rows, columns=[400.0, 1600.0, 6400.0])


def test_sweep_explorer_updates_one_figure():
    import io

    draw = C.sweep_explorer(_fake_sweep())
    fig = draw(400.0)
    pos = [tuple(a.get_position().bounds) for a in fig.axes]
    fig.savefig(io.BytesIO(), format="png")
    assert draw(6400) is fig  # the same figure, updated in place
    assert [tuple(a.get_position().bounds) for a in fig.axes] == pos  # no re-layout
    marks = [ln for a in fig.axes for ln in a.lines if ln.get_linestyle() == "--"
             and list(ln.get_xdata()) == [6400.0, 6400.0]]
    assert len(marks) == len(fig.axes)  # one level marker per panel
    assert fig._suptitle.get_text().startswith("sky 6400 e⁻/px")


def test_sweep_explorer_bad_input():
    import pandas as pd

    with pytest.raises(ValueError, match="sweep"):
        C.sweep_explorer(pd.DataFrame())
    draw = C.sweep_explorer(_fake_sweep())
    with pytest.raises(ValueError, match="sky must be one of"):
        draw(1000.0)
