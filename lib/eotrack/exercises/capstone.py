"""Exercises of notebook 07 (the capstone); expected values come from the library."""

from __future__ import annotations

from eotrack.exercises import Choice, NumericAnswer, register


def _range_error():
    from eotrack.experiments import capstone as C

    return C.range_error_km(37_000.0, 4_900.0, 1.0)


def _drift():
    from eotrack.experiments import capstone as C

    return C.sidereal_drift_px(C.CapstoneConfig(), dec_deg=30.0)


def _snr_6400():
    from eotrack.experiments import capstone as C

    return C.target_peak_snr(C.with_changes(sky_e=6400.0))


def _p_wrong_in_gate():
    import numpy as np
    from scipy.stats import norm

    from eotrack.experiments import capstone as C

    g = C.epipolar_gate_px()
    se = np.sqrt(2.0) * 0.3
    return float(norm.cdf((g - 0.5) / se) - norm.cdf((-g - 0.5) / se))


def _gate_5():
    from eotrack.experiments import capstone as C

    return C.velocity_gate(C.with_changes(pixel_scale_arcsec=5.0))


CRITIQUE_OPTIONS = (
    "A: the Earth's shadow lasts longer when the sky is brighter",
    "B: in a series that mixes three tracks at the same instants, minimal samples mix tracks "
    "(ill-posed or wildly curved fits) and with few points per track the consensus cannot "
    "single one out, while least squares averages all points",
    "C: two hours of data are too few for the sinusoid-plus-drift model at any noise level",
    "D: the triangulation error propagates into the predicted angles",
)

register("capstone.1", NumericAnswer(
    "Derivation. Two stations a baseline B apart (perpendicular to the line of sight) see an "
    "object at range R with angular errors σ_θ. Show that the range error is σ_R ≈ R² σ_θ / B "
    "to first order, and compute it in km for R = 37,000 km, B = 4,900 km, σ_θ = 1″.",
    expected=_range_error, rtol=2e-2,
    hint="A small rotation σ_θ of one line of sight moves the intersection along the other "
         "line by about R σ_θ / sin(parallax), and the parallax angle is about B / R; convert "
         "arcseconds to radians."))

register("capstone.2", NumericAnswer(
    "Computation. With the default cameras (15″ pixels, 20 s between frames) of a GEO-staring "
    "mount, how many pixels does a star at declination +30° drift between two frames?",
    expected=_drift, rtol=1e-3,
    hint="The sky turns at the Earth's rotation rate (7.292e-5 rad/s); a star at declination "
         "δ moves cos δ times that across the sky."))

register("capstone.3", NumericAnswer(
    "Exploration. In the Explore panel, find the sky level at which the initiation recall "
    "first falls below 0.9. What is the target's peak signal-to-noise ratio there (the "
    "figure's title, or compute it)?",
    expected=_snr_6400, rtol=2e-2,
    hint="Peak pixel = flux / (2π σ²); noise = sqrt(sky + read noise²); the flux comes from "
         "the target magnitude and the zero point."))

register("capstone.4", Choice(
    "Critique. In notebook 07's isolation table (Beyond), one companion's tracklets alone give "
    "an error near the companions' separation, but the mixed series give errors many times "
    "larger, worst for the RANSAC-type predictors. Why? Answer with the option's letter.",
    options=("A", "B", "C", "D"), answer="B",
    hint="Compare the rows: what changes between 'one companion only' and the mixed series, "
         "and what does a minimal sample look like in each?"))

register("capstone.5", NumericAnswer(
    "Derivation. The epipolar gate is g = σ_e √χ²₁(0.99) with σ_e = √2 × 0.3 px (both points' "
    "per-axis centroid errors). A wrong partner's noise-free epipolar distance is d₀ = 0.5 px. "
    "With the gate's own noise model (ε ~ N(0, σ_e²)), what is the probability that it falls "
    "inside the gate, P(|d₀ + ε| < g)?",
    expected=_p_wrong_in_gate, rtol=1e-2,
    hint="Two tails: Φ((g − d₀)/σ_e) − Φ((−g − d₀)/σ_e); the noise of an epipolar distance "
         "comes from both stations' points."))

register("capstone.6", NumericAnswer(
    "Computation. The velocity gate is 1.5 × the fastest expected rate of the night's objects "
    "(table 'expected rates', ″/s) divided by the pixel scale, and at least 2 px over a burst. "
    "What is it (px/s) if the cameras have 5″ pixels instead of 15″ (same objects, same "
    "frames)?",
    expected=_gate_5, rtol=2e-2,
    hint="The rates in ″/s do not change with the camera; divide by the new pixel scale and "
         "keep the margin."))
