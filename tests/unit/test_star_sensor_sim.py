"""Tests of eotrack.imaging.star_sensor_sim."""

from __future__ import annotations

import numpy as np
import pytest
from eotrack.geometry.shipboard import sea_state_motion
from eotrack.imaging.star_sensor_sim import (
    SCENARIOS,
    Scenario,
    SensorConfig,
    scenario,
    simulate_sequence,
    sway_acceleration_variance,
)


@pytest.fixture(scope="module")
def nominal():
    return simulate_sequence(np.random.default_rng(0), "nominal", n_frames=40)


def test_sequence_shapes_and_star(nominal):
    seq = nominal
    assert seq.images.shape == (40, 128, 128) and seq.images.dtype == np.uint8
    assert seq.truth.shape == (40, 2) and np.all(np.isfinite(seq.truth))
    assert 1.5 <= seq.info["target_mag"] <= 2.6
    k = 10
    x, y = np.rint(seq.truth[k]).astype(int)
    patch = seq.images[k, y - 1:y + 2, x - 1:x + 2].astype(float)
    assert patch.max() > np.median(seq.images[k]) + 50


def test_same_seed_same_images():
    a = simulate_sequence(np.random.default_rng(5), "cloud", n_frames=30)
    b = simulate_sequence(np.random.default_rng(5), "cloud", n_frames=30)
    assert np.array_equal(a.images, b.images)


def test_cloud_hides_star():
    seq = simulate_sequence(np.random.default_rng(1), "cloud", n_frames=200)
    hidden = seq.visible < 0.5
    assert 5 <= hidden.sum() <= 120


@pytest.mark.parametrize("name", SCENARIOS)
def test_presets(name):
    sc = scenario(name)
    assert isinstance(sc, Scenario) and sc.name == name


def test_sway_variance_grows_with_sea_state():
    s = SensorConfig()
    assert sway_acceleration_variance(sea_state_motion(5), s) > \
        sway_acceleration_variance(sea_state_motion(3), s) > 0


def test_bad_inputs():
    with pytest.raises(ValueError, match="name"):
        scenario("fog")
    with pytest.raises(ValueError, match="n_frames"):
        simulate_sequence(np.random.default_rng(0), "nominal", n_frames=1)
    with pytest.raises(TypeError, match="rng"):
        simulate_sequence(0, "nominal")
    with pytest.raises(ValueError, match="fov_deg"):
        SensorConfig(fov_deg=120)
    with pytest.raises(ValueError, match="cloud_opacity"):
        Scenario(cloud_opacity=(0.8, 0.2))
    with pytest.raises(ValueError, match="exposure_s"):
        SensorConfig(exposure_s=1.0)
