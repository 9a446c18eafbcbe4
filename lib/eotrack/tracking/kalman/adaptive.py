"""Adaptive filtering: the Sage–Husa noise estimator (eq. 41) and the confidence-gated
adaptive Kalman filter (eqs. 42–46)."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from eotrack.validation import check_int, check_positive, check_probability

from ._validation import _inv_stack
from .filters import KalmanFilter
from .modes import FilterMode

__all__ = ["ConfidenceConfig", "ConfidenceKalmanFilter", "sage_husa_update", "sage_husa_weight"]


def sage_husa_weight(k: int, b: float) -> float:
    """Eq. (41) weight ``d_k = (1 − b) / (1 − b^{k+1})`` (``k = 0, 1, …``; ``d_0 = 1``).

    Parameters
    ----------
    k
        Index of the adaptive step (≥ 0).
    b
        Forgetting factor in (0, 1) (the paper uses 0.95–0.99).
    """
    kk = check_int(k, "k", min_value=0)
    bb = check_probability(b, "b", open_low=True, open_high=True)
    return (1.0 - bb) / (1.0 - bb ** (kk + 1))


def _clip_eig(a: np.ndarray, lo: float, hi: float) -> np.ndarray:
    a = 0.5 * (a + a.T)
    if a.shape == (2, 2):  # closed-form eigenvalues: most steps need no change
        tr, det = a[0, 0] + a[1, 1], a[0, 0] * a[1, 1] - a[0, 1] * a[1, 0]
        disc = np.sqrt(max(0.25 * tr * tr - det, 0.0))
        if lo <= 0.5 * tr - disc and 0.5 * tr + disc <= hi:
            return a
    w, v = np.linalg.eigh(a)
    w = np.clip(w, lo, hi)
    return (v * w) @ v.T


def sage_husa_update(R: np.ndarray, Q: np.ndarray, *, e: np.ndarray, K: np.ndarray,
                     H: np.ndarray, F: np.ndarray, P_prior: np.ndarray, P_post: np.ndarray,
                     P_prev: np.ndarray, d: float, safeguard: bool = True,
                     r_bounds: tuple[float, float] = (1e-3, 1e6),
                     q_structure: np.ndarray | None = None,
                     q_bounds: tuple[float, float] = (0.0, np.inf)
                     ) -> tuple[np.ndarray, np.ndarray]:
    """One Sage–Husa step (eq. 41) for ``R`` and ``Q``.

    ``R_k = (1−d) R + d (e eᵀ − H P⁻ Hᵀ)``;
    ``Q_k = (1−d) Q + d (K e eᵀ Kᵀ + P_k − F P_{k−1} Fᵀ)``.

    Parameters
    ----------
    R, Q
        Current estimates.
    e, K, H, F
        Innovation, gain, measurement and transition matrices of this step.
    P_prior, P_post, P_prev
        ``P_{k|k−1}``, ``P_k`` and ``P_{k−1}``.
    d
        Weight ``d_k`` (:func:`sage_husa_weight`).
    safeguard
        Keep the estimates positive definite: ``R`` is symmetrised and its eigenvalues clipped
        to ``r_bounds``; ``Q`` is projected onto ``q_structure`` (a 0/1 diagonal mask, e.g. the
        acceleration states of eq. 35: the mean of the masked diagonal becomes the new ``q_a``,
        clipped to ``q_bounds``) or, without a structure, its eigenvalues are clipped to
        ``q_bounds``. Without the safeguard the raw estimates are returned — they can become
        indefinite (the known weakness of Sage–Husa).
    r_bounds, q_structure, q_bounds
        See ``safeguard``.

    Returns
    -------
    R_new, Q_new : numpy.ndarray
    """
    dd = float(d)
    if not 0.0 < dd <= 1.0:
        raise ValueError(f"d must lie in (0, 1], got {d!r}")
    ee = np.outer(e, e)
    R_new = (1 - dd) * R + dd * (ee - H @ P_prior @ H.T)
    Ke = K @ e
    Q_new = (1 - dd) * Q + dd * (np.outer(Ke, Ke) + P_post - F @ P_prev @ F.T)
    if not safeguard:
        return R_new, Q_new
    R_new = _clip_eig(R_new, *r_bounds)
    if q_structure is not None:
        mask = np.asarray(q_structure, dtype=bool)
        qa = float(np.clip(np.mean(np.diag(Q_new)[mask]), *q_bounds))
        Q_new = np.diag(np.where(mask, qa, 0.0))
    else:
        Q_new = _clip_eig(Q_new, *q_bounds)
    return R_new, Q_new



@dataclass(frozen=True)
class ConfidenceConfig:
    """Parameters of the confidence-gated adaptive Kalman filter (eqs. 41–46).

    The paper gives the smoothing constant 0.9, the threshold ratios 0.85 and 0.35 and the
    forgetting-factor range 0.95–0.99; it gives no values for ω, η, γ, λ or the Q growth — ours
    are stated here and varied in the notebook's Explore section.

    Attributes
    ----------
    omega
        ω, weight of the image confidence ``C_img`` in ``C_k`` (eq. 42).
    eta
        η, decay rate of ``C_motion = exp(−η max(0, D_M − γ))`` (eq. 43).
    gamma
        γ, Mahalanobis distance tolerated without penalty.
    lam
        λ ≥ 1, the R inflation of the middle mode.
    smoothing
        ``Ĉ_k = s Ĉ_{k−1} + (1 − s) C_k`` (eq. 44, s = 0.9).
    tau_high, tau_low
        ``τ_h = 0.85 Ĉ_k``, ``τ_l = 0.35 Ĉ_k`` (eqs. 45–46).
    forgetting
        b of the Sage–Husa weight ``d_k`` (eq. 41).
    adaptive_noise
        Run the Sage–Husa estimators of R and Q (eq. 41) on trusted updates.
    safeguard
        Keep the Sage–Husa estimates positive definite (see :func:`sage_husa_update`).
    r_bounds
        Eigenvalue bounds of the adapted R (pixels²).
    q_bounds_ratio
        Bounds of the adapted q_a relative to the initial q_a.
    q_growth
        During prediction-only frames Q is multiplied by ``1 + q_growth · n_missed`` …
    q_growth_max
        … up to this factor.
    """

    omega: float = 0.5
    eta: float = 1.0
    gamma: float = 5.0
    lam: float = 10.0
    smoothing: float = 0.9
    tau_high: float = 0.85
    tau_low: float = 0.35
    forgetting: float = 0.97
    adaptive_noise: bool = True
    safeguard: bool = True
    r_bounds: tuple[float, float] = (0.01, 1.0)
    q_bounds_ratio: tuple[float, float] = (1.0, 16.0)
    q_growth: float = 0.5
    q_growth_max: float = 20.0

    def __post_init__(self) -> None:
        check_probability(self.omega, "omega")
        check_positive(self.eta, "eta", allow_zero=True)
        check_positive(self.gamma, "gamma", allow_zero=True)
        if check_positive(self.lam, "lam") < 1.0:
            raise ValueError(f"lam must be >= 1 (an inflation of R), got {self.lam!r}")
        check_probability(self.smoothing, "smoothing", open_high=True)
        check_probability(self.tau_high, "tau_high")
        check_probability(self.tau_low, "tau_low")
        if self.tau_low > self.tau_high:
            raise ValueError(f"tau_low must be <= tau_high, got {self.tau_low} > {self.tau_high}")
        check_probability(self.forgetting, "forgetting", open_low=True, open_high=True)
        lo, hi = self.r_bounds
        if not 0 < lo <= hi:
            raise ValueError(f"r_bounds must satisfy 0 < lo <= hi, got {self.r_bounds}")
        lo, hi = self.q_bounds_ratio
        if not 0 < lo <= 1 <= hi:
            raise ValueError(f"q_bounds_ratio must satisfy 0 < lo <= 1 <= hi, got "
                             f"{self.q_bounds_ratio}")
        check_positive(self.q_growth, "q_growth", allow_zero=True)
        if check_positive(self.q_growth_max, "q_growth_max") < 1:
            raise ValueError(f"q_growth_max must be >= 1, got {self.q_growth_max}")


class ConfidenceKalmanFilter(KalmanFilter):
    """Confidence-gated adaptive Kalman filter (Sheng 2026, eqs. 41–46).

    At each frame with a candidate measurement ``z``:

    * innovation ``e = z − H x⁻``, ``S = H P⁻ Hᵀ + R``, ``D_M = sqrt(eᵀ S⁻¹ e)``;
    * ``C_motion = exp(−η max(0, D_M − γ))``, ``C_k = ω C_img + (1 − ω) C_motion``;
    * ``Ĉ_k = 0.9 Ĉ_{k−1} + 0.1 C_k`` (``Ĉ_0 = 1``), ``τ_h = 0.85 Ĉ_k``, ``τ_l = 0.35 Ĉ_k``;
    * ``C_k ≥ τ_h``: standard update, then a Sage–Husa step for R and q_a (eq. 41);
      ``τ_l ≤ C_k < τ_h``: update with ``λ R``; ``C_k < τ_l``: prediction only.

    Without a measurement (or with ``C_k < τ_l``) the step is prediction only and the process
    noise of the *next* prediction is multiplied by ``1 + q_growth · n_missed`` (capped), so the
    covariance opens up while the star is hidden. Frames without a measurement leave ``Ĉ``
    unchanged (the paper does not say; updating it with ``C = 0`` would drive the thresholds to
    zero during a long occlusion and accept anything afterwards).

    ``C_img`` is not defined by the paper; the caller supplies it per measurement (our
    definition is in :func:`eotrack.imaging.image_confidence`).

    Parameters
    ----------
    F, H, Q, R, x0, P0
        As for :class:`KalmanFilter`; ``Q`` is the initial (Singer) process noise. ``self.Q``
        (alias ``Q_base``) and ``self.R`` are the CURRENT estimates, which Sage–Husa adapts;
        assigning them (validated) replaces the current estimate, while the structure of ``Q``
        (which states carry q_a) and the q_a bounds stay those of the constructor's ``Q``.
        ``predict(F=..., Q=...)`` takes one step's matrices (irregular time steps); the
        step's ``Q`` is grown during occlusions like the stored one.
    config
        :class:`ConfidenceConfig`.
    """

    adaptive = True

    @property
    def Q_base(self) -> np.ndarray:
        """The current (adapted) process noise; the same values as ``self.Q`` (read-only)."""
        return self.Q

    @Q_base.setter
    def Q_base(self, value: Any) -> None:
        self.Q = value

    def __init__(self, F: Any, H: Any, Q: Any, R: Any, x0: Any, P0: Any,
                 config: ConfidenceConfig | None = None) -> None:
        super().__init__(F, H, Q, R, x0, P0)
        if config is None:
            config = ConfidenceConfig()
        if not isinstance(config, ConfidenceConfig):
            raise TypeError(f"config must be a ConfidenceConfig, got {type(config).__name__}")
        self.config = config
        if config.adaptive_noise and config.safeguard:
            ev = np.linalg.eigvalsh(0.5 * (self._R + self._R.T))
            lo_r, hi_r = config.r_bounds
            if ev.min() < lo_r or ev.max() > hi_r:
                raise ValueError(
                    f"R's eigenvalues [{ev.min():.3g}, {ev.max():.3g}] lie outside "
                    f"config.r_bounds {config.r_bounds}: the Sage–Husa safeguard would clip the "
                    "noise to those bounds at the first trusted update. Set r_bounds to the "
                    "scale of your measurement noise (e.g. ConfidenceConfig(r_bounds="
                    f"({ev.min() / 25:.3g}, {ev.max() * 25:.3g}))) or adaptive_noise=False")
        diag = np.diag(self.Q)
        self._q_mask = diag > 0 if np.allclose(self.Q, np.diag(diag)) and np.any(diag > 0) \
            else None
        qa0 = float(np.mean(diag[self._q_mask])) if self._q_mask is not None else 1.0
        lo, hi = config.q_bounds_ratio
        self._q_bounds = (lo * qa0, hi * qa0)
        self.c_smooth = 1.0
        self.n_missed = 0
        self.k_adapt = 0
        self.last_confidence = np.nan
        self.last_mahalanobis = np.nan
        self._P_prev = self._P.copy()
        self._F_step = self._F

    def predict(self, F: Any = None, Q: Any = None) -> np.ndarray:
        """Predict, with the process noise grown by the number of frames already missed.

        Parameters
        ----------
        F, Q
            This step's transition and process noise (irregular time steps); ``None``: the
            stored ``self.F`` and the current adapted ``self.Q``.
        """
        cfg = self.config
        F_ = self._F if F is None else self._check_F(F, "F")
        Q_ = self._Q if Q is None else self._check_Q(Q, "Q")
        grow = min(1.0 + cfg.q_growth * self.n_missed, cfg.q_growth_max)
        self._P_prev = self._P
        self._F_step = F_
        self._x = F_ @ self._x
        self._P = F_ @ self._P @ F_.T + grow * Q_
        self._x_prior = self._x
        self._P_prior = self._P
        return self.x

    def confidence(self, z: np.ndarray, c_img: float = 1.0) -> tuple[float, float]:
        """``(C_k, D_M)`` of a candidate measurement at the current prediction (eqs. 42–43)."""
        cfg = self.config
        if isinstance(c_img, bool) or not isinstance(c_img, (int, float, np.floating,
                                                              np.integer)):
            raise TypeError(f"c_img must be a number in [0, 1], got {type(c_img).__name__}")
        if not 0.0 <= float(c_img) <= 1.0:       # NaN fails too
            raise ValueError(f"c_img must be an image confidence in [0, 1], got {c_img!r}")
        e = np.asarray(z, dtype=float) - self.H @ self.x_prior
        S = self.innovation_covariance()
        d2 = float(e @ _inv_stack(S) @ e)
        dm = float(np.sqrt(max(d2, 0.0))) if np.isfinite(d2) else np.inf
        c_motion = float(np.exp(-cfg.eta * max(0.0, dm - cfg.gamma)))
        return cfg.omega * float(c_img) + (1 - cfg.omega) * c_motion, dm

    def update(self, z: np.ndarray | None, c_img: float = 1.0) -> int:
        """Gate and update with ``z`` (``None``: no star this frame); returns the mode."""
        cfg = self.config
        z = self._measurement(z)
        if z is None:
            self.n_missed += 1
            self.last_confidence = np.nan
            self._P = 0.5 * (self._P + self._P.T)
            return FilterMode.PREDICT
        c, dm = self.confidence(z, c_img)
        self.last_confidence, self.last_mahalanobis = c, dm
        self.c_smooth = cfg.smoothing * self.c_smooth + (1 - cfg.smoothing) * c
        tau_h = cfg.tau_high * self.c_smooth
        tau_l = cfg.tau_low * self.c_smooth
        if c >= tau_h:
            P_prior = self._P
            e, K = self._update(z, self._R)
            if cfg.adaptive_noise:
                d = sage_husa_weight(self.k_adapt, cfg.forgetting)
                # internal arrays directly: the safeguard keeps them valid, and re-validating
                # every step would cost a Cholesky per frame
                self._R, self._Q = sage_husa_update(
                    self._R, self._Q, e=e, K=K, H=self._H, F=self._F_step, P_prior=P_prior,
                    P_post=self._P, P_prev=self._P_prev, d=d, safeguard=cfg.safeguard,
                    r_bounds=cfg.r_bounds, q_structure=self._q_mask, q_bounds=self._q_bounds)
                self.k_adapt += 1
            self.n_missed = 0
            return FilterMode.UPDATE
        if c >= tau_l:
            self._update(z, cfg.lam * self._R)
            self.n_missed = 0
            return FilterMode.INFLATED
        self.n_missed += 1
        self._P = 0.5 * (self._P + self._P.T)
        return FilterMode.PREDICT

