"""Nearest-neighbour tracking driver: feeds per-frame detections to a filter."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from eotrack.validation import check_int, check_positive

from .filters import KalmanFilter
from .modes import FilterMode

__all__ = ["TrackResult", "track_nearest"]


@dataclass
class TrackResult:
    """Output of :func:`track_nearest`.

    Attributes
    ----------
    xs
        Filtered states ``(n, d)``.
    Ps
        Filtered covariances ``(n, d, d)``.
    modes
        :class:`FilterMode` per frame ``(n,)``.
    z
        The measurement associated at each frame ``(n, 2)`` (NaN where none).
    confidence
        ``C_k`` per frame (NaN where none or for the standard filter).
    innovations, S
        Innovation ``(n, m)`` and its covariance ``(n, m, m)`` at each frame (NaN without a
        measurement).
    """

    xs: np.ndarray
    Ps: np.ndarray
    modes: np.ndarray
    z: np.ndarray
    confidence: np.ndarray
    innovations: np.ndarray
    S: np.ndarray
    extra: dict[str, Any] = field(default_factory=dict)


def track_nearest(filt: KalmanFilter, detections: Sequence[np.ndarray], *,
                  gate_px: float = 10.0, gate_sigma: float | None = 4.0,
                  gate_max_px: float = 30.0, hold_after: int | None = 5,
                  c_img: Sequence[np.ndarray] | None = None) -> TrackResult:
    """Track one star through per-frame detections with nearest-neighbour association.

    At each frame the filter predicts; the detection nearest to the predicted position within
    the gate is handed to ``filt.update`` with its image confidence. The gate radius is
    ``min(gate_max_px, max(gate_px, gate_sigma · sqrt(λ_max(S))))`` (pixels; ``S`` the
    innovation covariance), so it opens while the star is hidden and the prediction becomes
    uncertain, but never so far that a coasting track grabs any spot in the image; no
    detection in the gate means a prediction-only frame. A sequence in which the star is never
    detected is a valid input: the result is pure prediction from ``x0`` (all modes
    ``PREDICT``, covariances growing).

    Parameters
    ----------
    filt
        A :class:`KalmanFilter` or :class:`ConfidenceKalmanFilter` (state; modified in place).
    detections
        One ``(n_i, 2)`` array of centroids (x, y) per frame.
    gate_px
        Smallest association radius (pixels, > 0).
    gate_sigma
        Gate in standard deviations of the innovation (``None``: fixed radius ``gate_px``).
    gate_max_px
        Largest association radius (pixels, ≥ ``gate_px``).
    hold_after
        Track maintenance (not in the paper): after this many consecutive frames without an
        associated measurement the velocity and acceleration states are set to zero, so the
        estimate holds the last position instead of running away along an extrapolated
        parabola; the star is re-acquired when it reappears inside the (grown) gate.
        ``None`` disables it (pure prediction for ever).
    c_img
        One ``(n_i,)`` array of image confidences per frame (default: all 1).

    Returns
    -------
    TrackResult
    """
    if not isinstance(filt, KalmanFilter):
        raise TypeError(f"filt must be a KalmanFilter, got {type(filt).__name__}")
    gate0 = check_positive(gate_px, "gate_px")
    gs = None if gate_sigma is None else check_positive(gate_sigma, "gate_sigma")
    gmax = check_positive(gate_max_px, "gate_max_px")
    hold = None if hold_after is None else check_int(hold_after, "hold_after", min_value=1)
    missed = 0
    if gmax < gate0:
        raise ValueError(f"gate_max_px must be >= gate_px, got {gate_max_px} < {gate_px}")
    n = len(detections)
    if c_img is not None and len(c_img) != n:
        raise ValueError(f"c_img must have one entry per frame ({n}), got {len(c_img)}")
    d = filt.F.shape[0]
    m = filt.H.shape[0]
    xs = np.empty((n, d))
    Ps = np.empty((n, d, d))
    modes = np.empty(n, dtype=np.int8)
    zs = np.full((n, m), np.nan)
    conf = np.full(n, np.nan)
    innov = np.full((n, m), np.nan)
    Ss = np.full((n, m, m), np.nan)
    H = filt.H
    for k in range(n):
        xp = filt.predict()
        det = detections[k]
        z = None
        ci = 1.0
        if len(det):
            pp = H @ xp
            dist2 = np.sum((det - pp) ** 2, axis=1)
            j = int(np.argmin(dist2))
            S = filt.innovation_covariance()
            g2 = gate0 * gate0
            if gs is not None:
                g2 = min(max(g2, gs * gs * float(np.linalg.eigvalsh(S)[-1])), gmax * gmax)
            if dist2[j] <= g2:
                z = det[j]
                ci = float(c_img[k][j]) if c_img is not None else 1.0
                zs[k] = z
                innov[k] = z - pp
                Ss[k] = S
        modes[k] = filt.update(z, ci)
        missed = missed + 1 if modes[k] == FilterMode.PREDICT else 0
        if hold is not None and missed >= hold:
            x_hold = filt.x.copy()
            x_hold[m:] = 0.0
            filt.x = x_hold
        if filt.adaptive and z is not None:
            conf[k] = filt.last_confidence
        xs[k] = filt.x
        Ps[k] = filt.P
    return TrackResult(xs, Ps, modes, zs, conf, innov, Ss)

