"""Shipboard star-sensor geometry: ship motion, the rotation chain, star angles, image motion.

Frames (Sheng 2026, §1.2, Figs. 2–4):

* **level** (the paper's "Earth"/theodolite frame N): X east, Y north (the azimuth zero line),
  Z up — east-north-up (ENU) at the ship;
* **deck** B: the level frame turned by the heading ψ (plus yaw), then pitch θ about X (the
  starboard axis), then roll φ about the new Y′ (the bow axis) — the sequence the text
  describes; ``R_{N→B} = R_y(φ) R_x(θ) R_z(−ψ)``;
* **camera** C: X′ right, Y′ the optical axis, Z′ up; the optical axis points at azimuth β
  (from the bow, clockwise) and elevation α on the deck: ``R_{B→C} = R_x(α) R_z(−β)``.

Elementary rotations are the paper's passive (frame) rotations
``R_x(a) = [[1,0,0],[0,c,s],[0,−s,c]]``, ``R_y(a) = [[c,0,−s],[0,1,0],[s,0,c]]``,
``R_z(a) = [[c,s,0],[−s,c,0],[0,0,1]]``. A star at image offsets (S_x, S_z) from the centre has
camera-frame direction ∝ ``(S_x, f, S_z)``; pixel coordinates are ``x = c_x + S_x``,
``y = c_y − S_z`` (rows grow downwards).

Errata handled here (see the notebook): eq. (2) prints ``R_x(φ) R_y(θ)`` with the angle symbols
swapped and the factors in the reverse order of the text's sequence; eq. (5) rotates the azimuth
about Y (the optical axis) and its small-angle matrix is the transpose of the product printed;
eq. (10) uses Z as the optical axis although Fig. 3 makes it Y′; the Earth-rotation terms of
eq. (12) omit the observer's latitude (:func:`diurnal_rates` is the correct form,
:func:`diurnal_rates_paper` the printed one).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from eotrack.validation import as_finite_array, check_generator, check_positive

__all__ = [
    "OMEGA_EARTH",
    "ShipMotion",
    "camera_from_deck",
    "camera_from_level",
    "deck_from_level",
    "diurnal_rates",
    "diurnal_rates_paper",
    "enu_from_azalt",
    "image_rate_projective",
    "project_to_image",
    "sea_state_motion",
    "ship_attitude",
    "star_angles_from_image",
]

#: Earth's sidereal rotation rate (rad/s).
OMEGA_EARTH = 7.2921150e-5


def _rot(axis: int, a: np.ndarray) -> np.ndarray:
    """Passive elementary rotations (the paper's form), broadcast over ``a``: ``(..., 3, 3)``."""
    a = np.asarray(a, dtype=float)
    c, s = np.cos(a), np.sin(a)
    one, zero = np.ones_like(a), np.zeros_like(a)
    if axis == 0:
        rows = [[one, zero, zero], [zero, c, s], [zero, -s, c]]
    elif axis == 1:
        rows = [[c, zero, -s], [zero, one, zero], [s, zero, c]]
    else:
        rows = [[c, s, zero], [-s, c, zero], [zero, zero, one]]
    return np.moveaxis(np.array(rows), (0, 1), (-2, -1))


def deck_from_level(heading: np.ndarray, pitch: np.ndarray, roll: np.ndarray) -> np.ndarray:
    """``R_{N→B} = R_y(φ) R_x(θ) R_z(−ψ)`` (eq. 2 in the order of the text's description).

    Parameters
    ----------
    heading, pitch, roll
        ψ (from north, clockwise), θ (bow up positive) and φ (radians), broadcastable.

    Returns
    -------
    numpy.ndarray
        Rotation matrices ``(..., 3, 3)`` taking level (ENU) vectors to deck vectors.
    """
    h = as_finite_array(heading, "heading")
    p = as_finite_array(pitch, "pitch")
    r = as_finite_array(roll, "roll")
    return _rot(1, r) @ _rot(0, p) @ _rot(2, -h)


def camera_from_deck(azimuth: float, elevation: float, *, small_angle: bool = False
                     ) -> np.ndarray:
    """``R_{B→C} = R_x(α) R_z(−β)`` (eqs. 4–5 with the azimuth about the vertical axis).

    Parameters
    ----------
    azimuth
        β, optical-axis azimuth from the bow, clockwise (radians).
    elevation
        α, optical-axis elevation above the deck (radians).
    small_angle
        Return the first-order form ``I + [[0, −β, 0], [β, 0, α], [0, −α, 0]]``.
    """
    b = float(as_finite_array(azimuth, "azimuth", ndim=0))
    a = float(as_finite_array(elevation, "elevation", ndim=0))
    if small_angle:
        return np.eye(3) + np.array([[0.0, -b, 0.0], [b, 0.0, a], [0.0, -a, 0.0]])
    return _rot(0, a) @ _rot(2, -b)


def camera_from_level(heading: np.ndarray, pitch: np.ndarray, roll: np.ndarray,
                      cam_azimuth: float, cam_elevation: float) -> np.ndarray:
    """The full chain of eq. (1): ``R_{B→C} R_{N→B}`` (``(..., 3, 3)``)."""
    return camera_from_deck(cam_azimuth, cam_elevation) @ deck_from_level(heading, pitch, roll)


def enu_from_azalt(azimuth: np.ndarray, altitude: np.ndarray) -> np.ndarray:
    """Unit vectors (E, N, U) ``(..., 3)`` of azimuth A (from north through east) and altitude h
    (radians)."""
    A = as_finite_array(azimuth, "azimuth")
    h = as_finite_array(altitude, "altitude")
    return np.stack(np.broadcast_arrays(np.cos(h) * np.sin(A), np.cos(h) * np.cos(A),
                                        np.sin(h)), axis=-1)


def project_to_image(v_cam: np.ndarray, focal_px: float, centre: tuple[float, float]
                     ) -> np.ndarray:
    """Pinhole projection with Y′ as the optical axis: ``x = c_x + f X/Y``, ``y = c_y − f Z/Y``.

    Parameters
    ----------
    v_cam
        Camera-frame directions ``(..., 3)``; those behind the camera (Y ≤ 0) give NaN.
    focal_px
        Focal length in pixels.
    centre
        Image centre ``(c_x, c_y)`` in pixels.
    """
    v = as_finite_array(v_cam, "v_cam")
    if v.shape[-1:] != (3,):
        raise ValueError(f"v_cam must have shape (..., 3), got {v.shape}")
    f = check_positive(focal_px, "focal_px")
    y = np.where(v[..., 1] > 0, v[..., 1], np.nan)
    return np.stack([centre[0] + f * v[..., 0] / y, centre[1] - f * v[..., 2] / y], axis=-1)


def star_angles_from_image(s_x: np.ndarray, s_z: np.ndarray, focal: float
                           ) -> tuple[np.ndarray, np.ndarray]:
    """Eqs. (6)–(9): camera-frame azimuth ``φ_x = atan(S_x/f)`` and elevation
    ``atan(tan φ_z cos φ_x)`` of a star imaged at offsets (S_x, S_z) (same unit as ``focal``).
    """
    sx = as_finite_array(s_x, "s_x")
    sz = as_finite_array(s_z, "s_z")
    f = check_positive(focal, "focal")
    phi_x = np.arctan(sx / f)
    phi_z = np.arctan(sz / f)
    return phi_x, np.arctan(np.tan(phi_z) * np.cos(phi_x))


def image_rate_projective(r: np.ndarray, r_dot: np.ndarray, focal: float
                          ) -> tuple[np.ndarray, np.ndarray]:
    """Eq. (10): ``u̇ = f (Ẋ Z − X Ż)/Z²``, ``v̇ = f (Ẏ Z − Y Ż)/Z²`` for ``u = f X/Z``,
    ``v = f Y/Z`` (the equation's own convention: Z the optical axis)."""
    p = as_finite_array(r, "r")
    pd = as_finite_array(r_dot, "r_dot")
    if p.shape[-1:] != (3,) or pd.shape != p.shape:
        raise ValueError(f"r and r_dot must have the same shape (..., 3), got {p.shape} and "
                         f"{pd.shape}")
    f = check_positive(focal, "focal")
    X, Y, Z = p[..., 0], p[..., 1], p[..., 2]
    Xd, Yd, Zd = pd[..., 0], pd[..., 1], pd[..., 2]
    return f * (Xd * Z - X * Zd) / Z**2, f * (Yd * Z - Y * Zd) / Z**2


def diurnal_rates(azimuth: np.ndarray, altitude: np.ndarray, lat: float
                  ) -> tuple[np.ndarray, np.ndarray]:
    """Correct diurnal motion of a star: ``(cos h · Ȧ, ḣ)`` in rad/s.

    ``ḣ = ω_e cos(lat) sin A`` and ``cos h · Ȧ = ω_e (sin(lat) cos h − cos(lat) sin h cos A)``
    (A from north through east, h altitude, lat geodetic latitude; all radians). The total
    angular speed is ``ω_e cos δ``.
    """
    A = as_finite_array(azimuth, "azimuth")
    h = as_finite_array(altitude, "altitude")
    la = float(as_finite_array(lat, "lat", ndim=0))
    if abs(la) > np.pi / 2:
        raise ValueError(f"lat must lie in [-pi/2, pi/2] radians, got {lat}")
    w = OMEGA_EARTH
    return (w * (np.sin(la) * np.cos(h) - np.cos(la) * np.sin(h) * np.cos(A)),
            w * np.cos(la) * np.sin(A))


def diurnal_rates_paper(azimuth: np.ndarray, altitude: np.ndarray
                        ) -> tuple[np.ndarray, np.ndarray]:
    """The Earth-rotation terms of eq. (12) as printed, divided by f: ``(−ω_e sin A cos h,
    −ω_e cos A cos h)`` (rad/s) — no latitude dependence (the erratum)."""
    A = as_finite_array(azimuth, "azimuth")
    h = as_finite_array(altitude, "altitude")
    w = OMEGA_EARTH
    return -w * np.sin(A) * np.cos(h), -w * np.cos(A) * np.cos(h)


@dataclass(frozen=True)
class ShipMotion:
    """Ship attitude as sums of sinusoids (degrees, seconds).

    ``angle(t) = Σ_i a_i sin(2π t / T_i + φ_i)`` for roll, pitch and yaw, the phases drawn at
    random per realisation; the heading is constant.

    Attributes
    ----------
    heading_deg
        Mean heading ψ (from north, clockwise).
    roll_amp_deg, roll_period_s, pitch_amp_deg, pitch_period_s, yaw_amp_deg, yaw_period_s
        Amplitudes and periods of the components (equal-length tuples per axis).
    """

    heading_deg: float = 45.0
    roll_amp_deg: tuple[float, ...] = (0.8, 0.3)
    roll_period_s: tuple[float, ...] = (9.0, 6.5)
    pitch_amp_deg: tuple[float, ...] = (0.4, 0.15)
    pitch_period_s: tuple[float, ...] = (6.0, 4.5)
    yaw_amp_deg: tuple[float, ...] = (0.2,)
    yaw_period_s: tuple[float, ...] = (12.0,)

    def __post_init__(self) -> None:
        for ax in ("roll", "pitch", "yaw"):
            amp = np.asarray(getattr(self, f"{ax}_amp_deg"), dtype=float)
            per = np.asarray(getattr(self, f"{ax}_period_s"), dtype=float)
            if amp.shape != per.shape or amp.ndim != 1:
                raise ValueError(f"{ax}_amp_deg and {ax}_period_s must be equal-length tuples")
            if np.any(~np.isfinite(amp)) or np.any(amp < 0):
                raise ValueError(f"{ax}_amp_deg must be finite and >= 0")
            if np.any(~np.isfinite(per)) or np.any(per <= 0):
                raise ValueError(f"{ax}_period_s must be finite and > 0")

    def scaled(self, factor: float) -> ShipMotion:
        """The same motion with all amplitudes multiplied by ``factor``."""
        f = check_positive(factor, "factor", allow_zero=True)
        return ShipMotion(self.heading_deg, tuple(f * a for a in self.roll_amp_deg),
                          self.roll_period_s, tuple(f * a for a in self.pitch_amp_deg),
                          self.pitch_period_s, tuple(f * a for a in self.yaw_amp_deg),
                          self.yaw_period_s)


def sea_state_motion(sea_state: int, heading_deg: float = 45.0) -> ShipMotion:
    """Representative roll/pitch/yaw of a medium ship (≈ 100–150 m) by Douglas sea state.

    The amplitudes are indicative values for the residual motion of a large ship, not a
    hydrodynamic model: roll 0.5°, 1.2°, 2.5°, 4.5° and pitch about half of it for sea states
    2–5; periods 6–10 s.
    """
    table = {2: 0.5, 3: 1.2, 4: 2.5, 5: 4.5}
    if sea_state not in table:
        raise ValueError(f"sea_state must be one of {sorted(table)}, got {sea_state!r}")
    r = table[sea_state]
    return ShipMotion(heading_deg, (0.8 * r, 0.3 * r), (9.0, 6.5), (0.4 * r, 0.15 * r),
                      (6.0, 4.5), (0.2 * r,), (12.0,))


def ship_attitude(motion: ShipMotion, t: np.ndarray, rng: np.random.Generator
                  ) -> dict[str, np.ndarray]:
    """Heading, pitch, roll (radians) and their rates at times ``t`` for random phases.

    Returns
    -------
    dict
        ``heading``, ``pitch``, ``roll`` and ``heading_rate``, ``pitch_rate``, ``roll_rate``,
        each ``(n,)``.
    """
    if not isinstance(motion, ShipMotion):
        raise TypeError(f"motion must be a ShipMotion, got {type(motion).__name__}")
    tt = as_finite_array(t, "t", ndim=1)
    check_generator(rng)
    out: dict[str, np.ndarray] = {}
    for ax, key in (("yaw", "heading"), ("pitch", "pitch"), ("roll", "roll")):
        amp = np.radians(np.asarray(getattr(motion, f"{ax}_amp_deg"), dtype=float))
        w = 2 * np.pi / np.asarray(getattr(motion, f"{ax}_period_s"), dtype=float)
        ph = rng.uniform(0, 2 * np.pi, len(amp))
        arg = tt[:, None] * w + ph
        out[key] = np.sum(amp * np.sin(arg), axis=1)
        out[f"{key}_rate"] = np.sum(amp * w * np.cos(arg), axis=1)
    out["heading"] = out["heading"] + np.radians(motion.heading_deg)
    return out
