"""The step-wise standard Kalman filter (:class:`KalmanFilter`)."""

from __future__ import annotations

from typing import Any

import numpy as np

from eotrack.validation import as_finite_array

from ._validation import _inv_stack, _model, _square
from .modes import FilterMode

__all__ = ["KalmanFilter"]


def _ro(a: np.ndarray) -> np.ndarray:
    """A read-only view of ``a`` (in-place edits through a property cannot bypass the setter's
    validation)."""
    v = a.view()
    v.setflags(write=False)
    return v


class KalmanFilter:
    """Step-wise standard Kalman filter (the same algebra as :func:`kalman_filter`).

    The model matrices ``F``, ``H``, ``Q`` and ``R`` are public and may be replaced between
    steps, as with FilterPy (``kf.F = ...; kf.predict()``): every assignment is validated
    (shape against the state and measurement dimensions, finiteness, symmetry and
    (semi-)definiteness of the covariances) and is used by the next step — nothing is cached.
    For irregular time steps pass the step's matrices to :meth:`predict` instead
    (``predict(F=F_k, Q=Q_k)``), which leaves the stored ones unchanged.

    The state ``x`` and covariance ``P`` are validated on assignment too: ``x`` of shape
    ``(d,)`` or FilterPy's column ``(d, 1)`` (flattened to ``(d,)``; any other shape raises),
    ``P`` symmetric positive semi-definite ``(d, d)``. Every property (``F, H, Q, R, x, P``,
    ``x_prior``, ``P_prior``) returns a READ-ONLY view, so an in-place edit such as
    ``kf.Q[0, 0] = -5`` raises ``ValueError: assignment destination is read-only`` instead of
    silently bypassing the checks; assign a whole new array (``Q = kf.Q.copy(); Q[0, 0] = 2;
    kf.Q = Q``).

    Parameters
    ----------
    F, H, Q, R, x0, P0
        See :func:`kalman_filter`.
    """

    adaptive = False

    def __init__(self, F: Any, H: Any, Q: Any, R: Any, x0: Any, P0: Any) -> None:
        F_, H_, Q_, R_, x_, P_ = _model(F, H, Q, R, x0, P0)
        self._d, self._m = F_.shape[0], H_.shape[0]
        self._F, self._H, self._Q, self._R = F_.copy(), H_.copy(), Q_.copy(), R_.copy()
        self._x = x_.copy()
        self._P = P_.copy()
        self._I = np.eye(self._d)
        self._x_prior = self._x.copy()
        self._P_prior = self._P.copy()

    # -- state: validated on assignment (FilterPy's column x is flattened) --------------------
    @property
    def x(self) -> np.ndarray:
        """State estimate ``(d,)`` (read-only view; assign a new array to change it)."""
        return _ro(self._x)

    @x.setter
    def x(self, value: Any) -> None:
        self._x = self._check_x(value, "x")

    @property
    def P(self) -> np.ndarray:
        """State covariance ``(d, d)`` (symmetric positive semi-definite; read-only view)."""
        return _ro(self._P)

    @P.setter
    def P(self, value: Any) -> None:
        self._P = _square(value, "P", self._d, psd=True).copy()

    @property
    def x_prior(self) -> np.ndarray:
        """The last predicted state ``x⁻`` (read-only view)."""
        return _ro(self._x_prior)

    @property
    def P_prior(self) -> np.ndarray:
        """The last predicted covariance ``P⁻`` (read-only view)."""
        return _ro(self._P_prior)

    def _check_x(self, value: Any, name: str) -> np.ndarray:
        arr = as_finite_array(value, name)
        if arr.shape == (self._d, 1):          # FilterPy's column state
            arr = arr[:, 0]
        if arr.shape != (self._d,):
            raise ValueError(f"{name} must have shape ({self._d},) or ({self._d}, 1), got "
                             f"{arr.shape}")
        return arr.astype(float, copy=True)

    # -- model matrices: validated on assignment, never cached --------------------------------
    @property
    def F(self) -> np.ndarray:
        """State transition ``(d, d)`` (read-only view)."""
        return _ro(self._F)

    @F.setter
    def F(self, value: Any) -> None:
        self._F = self._check_F(value, "F")

    @property
    def H(self) -> np.ndarray:
        """Measurement matrix ``(m, d)`` (read-only view)."""
        return _ro(self._H)

    @H.setter
    def H(self, value: Any) -> None:
        H = as_finite_array(value, "H", ndim=2)
        if H.shape != (self._m, self._d):
            raise ValueError(f"H must have shape ({self._m}, {self._d}), got {H.shape}")
        self._H = H.copy()

    @property
    def Q(self) -> np.ndarray:
        """Process noise ``(d, d)`` (symmetric positive semi-definite; read-only view)."""
        return _ro(self._Q)

    @Q.setter
    def Q(self, value: Any) -> None:
        self._Q = self._check_Q(value, "Q")

    @property
    def R(self) -> np.ndarray:
        """Measurement noise ``(m, m)`` (symmetric positive definite; read-only view)."""
        return _ro(self._R)

    @R.setter
    def R(self, value: Any) -> None:
        self._R = _square(value, "R", self._m, pd=True).copy()

    def _check_F(self, value: Any, name: str) -> np.ndarray:
        F = as_finite_array(value, name, ndim=2)
        if F.shape != (self._d, self._d):
            raise ValueError(f"{name} must have shape ({self._d}, {self._d}), got {F.shape}")
        return F.copy()

    def _check_Q(self, value: Any, name: str) -> np.ndarray:
        return _square(value, name, self._d, psd=True).copy()

    # -- steps ---------------------------------------------------------------------------------
    def predict(self, F: Any = None, Q: Any = None) -> np.ndarray:
        """Predict one step ahead; returns the predicted state ``x⁻``.

        Parameters
        ----------
        F, Q
            Transition and process noise of THIS step only (irregular time steps, e.g.
            ``constant_velocity_model(dt_k)``); ``None`` uses the stored ``self.F`` / ``self.Q``.
        """
        F_ = self._F if F is None else self._check_F(F, "F")
        Q_ = self._Q if Q is None else self._check_Q(Q, "Q")
        self._x = F_ @ self._x
        self._P = F_ @ self._P @ F_.T + Q_
        self._x_prior = self._x
        self._P_prior = self._P
        return self.x

    def innovation_covariance(self) -> np.ndarray:
        """``S = H P⁻ Hᵀ + R`` at the current prediction."""
        return self._H @ self._P_prior @ self._H.T + self._R

    def _measurement(self, z: Any) -> np.ndarray | None:
        """``z`` as a float ``(m,)`` array, or ``None`` when it is missing (``None`` or any NaN,
        as a NaN row of :func:`kalman_filter`); ±inf or a wrong shape raise."""
        if z is None:
            return None
        try:
            zz = np.asarray(z, dtype=float)
        except (TypeError, ValueError):
            raise TypeError(f"z must be a numeric array of shape ({self._m},) or None, got "
                            f"{type(z).__name__}") from None
        if zz.shape != (self._m,):
            raise ValueError(f"z must have shape ({self._m},), got {zz.shape}")
        if np.any(np.isnan(zz)):
            return None
        if not np.all(np.isfinite(zz)):
            raise ValueError(f"z must be finite (NaN means missing), got {zz.tolist()}")
        return zz

    def update(self, z: np.ndarray | None, c_img: float = 1.0) -> int:
        """Update with measurement ``z``; returns the :class:`FilterMode`.

        ``z`` is ``None`` or contains NaN: no measurement this step (the state stays the
        prediction, mode ``PREDICT``; a NaN component is never folded into the state). An
        infinite component or a wrong shape raises ``ValueError``. ``c_img`` is accepted for
        interface compatibility with :class:`ConfidenceKalmanFilter` and ignored.
        """
        zz = self._measurement(z)
        if zz is None:
            self._P = 0.5 * (self._P + self._P.T)
            return FilterMode.PREDICT
        self._update(zz, self._R)
        return FilterMode.UPDATE

    def _update(self, z: np.ndarray, R: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        P = self._P
        H = self._H
        PHT = P @ H.T
        S = H @ PHT + R
        K = PHT @ _inv_stack(S)
        e = z - H @ self._x
        self._x = self._x + K @ e
        IKH = self._I - K @ H
        P = IKH @ P @ IKH.T + K @ R @ K.T
        self._P = 0.5 * (P + P.T)
        return e, K
