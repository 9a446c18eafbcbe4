"""Kalman filters for star-spot tracking: standard, Singer, Sage–Husa adaptive, confidence-gated.

The state of a star spot on the image is ``X = [x, y, v_x, v_y, a_x, a_y]`` (pixels, pixels per
second, pixels per second squared; Sheng 2026, eq. 30) and the measurement is its centroid
``Z = [x, y]`` (eq. 36). Everything here is plain linear algebra on numpy arrays:

* :func:`kalman_filter` — the standard filter over a measurement sequence (a NaN row means "no
  measurement": predict only);
* :func:`kalman_filter_batch` — the same filter run on many independent sequences at once
  (vectorised over the batch axis, for Monte Carlo work);
* :func:`singer_process_noise` — eqs. (33)–(35), the Singer acceleration variance
  ``q_a = σ_w²/(2α)(1 − e^{−2αΔT})`` put on the acceleration states;
* :func:`sage_husa_weight` and :func:`sage_husa_update` — eq. (41) with ``d_k = (1−b)/(1−b^{k+1})``
  and a safeguard that keeps ``R`` and ``Q`` positive definite;
* :class:`ConfidenceKalmanFilter` — eqs. (42)–(46): a confidence ``C_k`` from image quality and
  motion consistency selects one of three modes (update / update with inflated ``R`` / predict
  only with a growing ``Q``);
* :func:`track_nearest` — a nearest-neighbour driver that feeds per-frame detections to a filter;
* :func:`nees` and :func:`nis` — consistency statistics.

Conventions: every filter step is *predict, then update* (as FilterPy's ``batch_filter``), so
``x0, P0`` describe the state one frame period before the first measurement. Updates use the
Joseph form ``P = (I−KH)P(I−KH)ᵀ + KRKᵀ`` and covariances are re-symmetrised after each step.

The package is split by concern: :mod:`.models` (motion models, Singer noise), :mod:`.batch`
(whole-sequence filters), :mod:`.filters` (step-wise :class:`KalmanFilter`), :mod:`.adaptive`
(Sage–Husa, :class:`ConfidenceKalmanFilter`), :mod:`.association` (:func:`track_nearest`) and
:mod:`.consistency` (NEES/NIS); everything is re-exported here.
"""

from __future__ import annotations

from ._validation import is_positive_definite
from .adaptive import ConfidenceConfig, ConfidenceKalmanFilter, sage_husa_update, sage_husa_weight
from .association import TrackResult, track_nearest
from .batch import kalman_filter, kalman_filter_batch
from .consistency import nees, nis
from .filters import KalmanFilter
from .models import (
    constant_acceleration_model,
    constant_velocity_model,
    singer_acceleration_variance,
    singer_process_noise,
    white_acceleration_noise,
)
from .modes import FilterMode

__all__ = [
    "ConfidenceConfig",
    "ConfidenceKalmanFilter",
    "FilterMode",
    "KalmanFilter",
    "TrackResult",
    "constant_acceleration_model",
    "constant_velocity_model",
    "is_positive_definite",
    "kalman_filter",
    "kalman_filter_batch",
    "nees",
    "nis",
    "sage_husa_update",
    "sage_husa_weight",
    "singer_acceleration_variance",
    "singer_process_noise",
    "track_nearest",
    "white_acceleration_noise",
]
