"""Orbit determination from angles: Gauss IOD, robust least-squares fit, angle prediction.

A ground station measures topocentric right ascension and declination of an object; this
module turns those angles into an orbit and predicts the angles at other times:

1. :func:`gauss_iod` — Gauss's angles-only initial orbit determination from three
   observations (Curtis, *Orbital Mechanics for Engineering Students*, 3rd ed., Algorithm 5.5;
   Vallado, *Fundamentals of Astrodynamics and Applications*, 4th ed., Algorithm 52). No
   maintained Python library with an angles-only IOD is installed in this project (poliastro
   is unmaintained and absent), so it is implemented here from those references.
2. :func:`fit_orbit` — the state vector at an epoch fitted to *all* the angles by robust
   non-linear least squares (:func:`scipy.optimize.least_squares` with a robust loss such as
   ``"cauchy"`` or ``"soft_l1"``), started from the best of several Gauss solutions (triplets
   spread over the arc, each scored on all data with the robust loss, so a gross error in one
   triplet does not spoil the start).
3. :meth:`OrbitFit.predict` — the angles at any times from any station positions.

Dynamics: two-body (universal-variable Kepler propagation, vectorised over times) or two-body
plus the J2 zonal term (numerical integration, :func:`scipy.integrate.solve_ivp`, DOP853).
The J2 term takes the frame's z axis as Earth's pole: in GCRS that ignores precession-nutation
since J2000 (about 0.3° by the 2020s), a small error in a small term, acceptable for the
short arcs fitted here but not for precise orbit determination. The Gauss start is Curtis's
Algorithm 5.5 without the iterative refinement of Algorithm 5.6: the least-squares fit that
follows refines it.
Frame: any quasi-inertial geocentric frame in which the station positions are given (GCRS in
this project, :meth:`eotrack.astro.Station.gcrs_km`); km, km/s, s, degrees. Light time and
aberration are ignored (the observations are geometric, like
:func:`eotrack.astro.topocentric_radec`).
"""

from __future__ import annotations

import time
import warnings
from dataclasses import dataclass, field

import numpy as np
from scipy.integrate import solve_ivp
from scipy.optimize import least_squares

from eotrack.validation import as_finite_array, check_choice, check_int, check_positive

from .twobody import EARTH_RADIUS_KM, MU_EARTH_KM3_S2

__all__ = [
    "DYNAMICS",
    "J2_EARTH",
    "ROBUST_LOSSES",
    "OrbitFit",
    "angles_from_positions",
    "fit_orbit",
    "gauss_iod",
    "line_of_sight",
    "propagate_state",
]

#: Earth's J2 zonal coefficient (EGM-96/WGS-84 value).
J2_EARTH = 1.08262668e-3
#: Dynamics of :func:`propagate_state`.
DYNAMICS = ("twobody", "j2")
#: Losses of :func:`scipy.optimize.least_squares` accepted by :func:`fit_orbit`.
ROBUST_LOSSES = ("linear", "huber", "soft_l1", "cauchy", "arctan")
_ARCSEC = 3600.0


# --------------------------------------------------------------------------------------------
# geometry


def line_of_sight(ra_deg: np.ndarray, dec_deg: np.ndarray) -> np.ndarray:
    """Unit line-of-sight vectors ``(n, 3)`` from right ascension and declination (degrees)."""
    ra = np.radians(as_finite_array(ra_deg, "ra_deg", ndim=(0, 1)))
    dec = np.radians(as_finite_array(dec_deg, "dec_deg", ndim=(0, 1)))
    if ra.shape != dec.shape:
        raise ValueError(f"ra_deg and dec_deg must have the same shape, got {ra.shape} and "
                         f"{dec.shape}")
    c = np.cos(dec)
    return np.stack([c * np.cos(ra), c * np.sin(ra), np.sin(dec)], axis=-1)


def angles_from_positions(r_km: np.ndarray, site_km: np.ndarray
                          ) -> tuple[np.ndarray, np.ndarray]:
    """Topocentric RA in [0, 360) and Dec (degrees) of objects at ``r_km`` from ``site_km``.

    Both ``(n, 3)`` (or broadcastable), same frame.
    """
    rho = np.asarray(r_km, float) - np.asarray(site_km, float)
    ra = np.degrees(np.arctan2(rho[..., 1], rho[..., 0])) % 360.0
    dec = np.degrees(np.arctan2(rho[..., 2], np.hypot(rho[..., 0], rho[..., 1])))
    return ra, dec


# --------------------------------------------------------------------------------------------
# propagation


def _stumpff(z: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Stumpff functions C(z), S(z), with series near z = 0."""
    c = np.empty_like(z)
    s = np.empty_like(z)
    pos, neg = z > 1e-6, z < -1e-6
    small = ~(pos | neg)
    sp = np.sqrt(z[pos])
    c[pos] = (1 - np.cos(sp)) / z[pos]
    s[pos] = (sp - np.sin(sp)) / sp**3
    sn = np.sqrt(-z[neg])
    c[neg] = (np.cosh(sn) - 1) / (-z[neg])
    s[neg] = (np.sinh(sn) - sn) / sn**3
    zs = z[small]
    c[small] = 0.5 - zs / 24 + zs**2 / 720
    s[small] = 1 / 6 - zs / 120 + zs**2 / 5040
    return c, s


def _kepler(r0: np.ndarray, v0: np.ndarray, dt: np.ndarray, mu: float) -> np.ndarray:
    """Universal-variable two-body propagation (Curtis Alg. 3.3–3.4), vectorised over ``dt``."""
    r0n = np.linalg.norm(r0)
    vr0 = r0 @ v0 / r0n
    alpha = 2.0 / r0n - v0 @ v0 / mu
    smu = np.sqrt(mu)
    chi = smu * abs(alpha) * dt if alpha > 1e-12 else smu * dt / r0n
    for _ in range(60):
        z = alpha * chi**2
        c, s = _stumpff(z)
        f = (r0n * vr0 / smu * chi**2 * c + (1 - alpha * r0n) * chi**3 * s + r0n * chi
             - smu * dt)
        fp = (r0n * vr0 / smu * chi * (1 - z * s) + (1 - alpha * r0n) * chi**2 * c + r0n)
        step = f / fp
        chi = chi - step
        if np.all(np.abs(step) < 1e-10 * (1 + np.abs(chi))):
            break
    z = alpha * chi**2
    c, s = _stumpff(z)
    ff = 1 - chi**2 / r0n * c
    gg = dt - chi**3 * s / smu
    return ff[:, None] * r0 + gg[:, None] * v0


def _j2_rhs(_t: float, y: np.ndarray, mu: float) -> np.ndarray:
    r = y[:3]
    rn2 = r @ r
    rn = np.sqrt(rn2)
    zr2 = r[2] ** 2 / rn2
    k = 1.5 * J2_EARTH * mu * EARTH_RADIUS_KM**2 / rn**5
    a = -mu * r / rn**3 + k * r * (5 * zr2 - 1)
    a[2] -= 2 * k * r[2]
    return np.r_[y[3:], a]


def propagate_state(r0_km: np.ndarray, v0_km_s: np.ndarray, dt_s: np.ndarray, *,
                    dynamics: str = "twobody", mu: float = MU_EARTH_KM3_S2,
                    rtol: float = 1e-10) -> np.ndarray:
    """Positions (km) at times ``dt_s`` after (or before, if negative) the epoch of a state.

    Parameters
    ----------
    r0_km, v0_km_s
        Position and velocity at the epoch, ``(3,)``.
    dt_s
        Times from the epoch (s), any order and sign, ``(n,)``.
    dynamics
        ``"twobody"`` (universal-variable Kepler, exact for two bodies) or ``"j2"`` (two-body
        plus the J2 zonal term, numerical integration with DOP853).
    mu
        Gravitational parameter (km³/s²).
    rtol
        Relative tolerance of the ``"j2"`` integration.

    Returns
    -------
    numpy.ndarray
        Positions ``(n, 3)``.
    """
    r0 = as_finite_array(r0_km, "r0_km", shape=(3,))
    v0 = as_finite_array(v0_km_s, "v0_km_s", shape=(3,))
    dt = as_finite_array(dt_s, "dt_s", ndim=1)
    check_choice(dynamics, "dynamics", DYNAMICS)
    check_positive(mu, "mu")
    if np.linalg.norm(r0) <= 0:
        raise ValueError("r0_km must be a non-zero position")
    if dynamics == "twobody":
        return _kepler(r0, v0, dt, float(mu))
    out = np.empty((len(dt), 3))
    y0 = np.r_[r0, v0]
    for side in (dt >= 0, dt < 0):
        if not side.any():
            continue
        tt = dt[side]
        # solve_ivp wants strictly monotonic t_eval: integrate to the distinct times (two
        # stations observe at the same instants), then copy each back to its duplicates
        mag, inv = np.unique(np.abs(tt), return_inverse=True)
        te = np.sign(tt[0]) * mag if tt[0] < 0 else mag
        sol = solve_ivp(_j2_rhs, (0.0, float(te[-1]) if te[-1] != 0 else 1e-9), y0,
                        method="DOP853", t_eval=te, rtol=rtol, atol=1e-9, args=(float(mu),))
        if not sol.success:  # e.g. a trial state inside the Earth (fit_orbit catches this)
            raise RuntimeError(f"J2 propagation failed: {sol.message}")
        out[np.flatnonzero(side)] = sol.y[:3].T[inv.ravel()]
    return out


# --------------------------------------------------------------------------------------------
# Gauss initial orbit determination


def gauss_iod(t_s: np.ndarray, ra_deg: np.ndarray, dec_deg: np.ndarray, site_km: np.ndarray,
              *, mu: float = MU_EARTH_KM3_S2) -> list[tuple[np.ndarray, np.ndarray]]:
    """Gauss's angles-only initial orbit from three observations (Curtis Alg. 5.5).

    Parameters
    ----------
    t_s
        Three observation times (s), increasing.
    ra_deg, dec_deg
        Topocentric right ascension and declination (degrees) at those times.
    site_km
        Station positions ``(3, 3)`` (km), same quasi-inertial frame.
    mu
        Gravitational parameter.

    Returns
    -------
    list of (r2, v2)
        One state at the *middle* time per physically admissible root of Gauss's eighth-degree
        polynomial (positive ``r2`` above the Earth's surface with positive slant ranges);
        possibly empty.
    """
    t = as_finite_array(t_s, "t_s", shape=(3,))
    if not (t[0] < t[1] < t[2]):
        raise ValueError(f"t_s must be three increasing times, got {t.tolist()}")
    site = as_finite_array(site_km, "site_km", shape=(3, 3))
    rho_hat = line_of_sight(as_finite_array(ra_deg, "ra_deg", shape=(3,)),
                            as_finite_array(dec_deg, "dec_deg", shape=(3,)))
    tau1, tau3 = t[0] - t[1], t[2] - t[1]
    tau = tau3 - tau1
    p1 = np.cross(rho_hat[1], rho_hat[2])
    p2 = np.cross(rho_hat[0], rho_hat[2])
    p3 = np.cross(rho_hat[0], rho_hat[1])
    d0 = rho_hat[0] @ p1
    if abs(d0) < 1e-14:
        raise ValueError("the three lines of sight are coplanar (D0 = 0): Gauss's method needs "
                         "observations spread over the arc")
    d = np.array([[site[i] @ p for p in (p1, p2, p3)] for i in range(3)])
    a_ = (-d[0, 1] * tau3 / tau + d[1, 1] + d[2, 1] * tau1 / tau) / d0
    b_ = (d[0, 1] * (tau3**2 - tau**2) * tau3 / tau + d[2, 1] * (tau**2 - tau1**2) * tau1
          / tau) / (6 * d0)
    e_ = site[1] @ rho_hat[1]
    r2s = site[1] @ site[1]
    a = -(a_**2 + 2 * a_ * e_ + r2s)
    b = -2 * mu * b_ * (a_ + e_)
    c = -(mu**2) * b_**2
    roots = np.roots([1, 0, a, 0, 0, b, 0, 0, c])
    out = []
    for x in roots:
        if abs(x.imag) > 1e-6 * abs(x) or x.real <= EARTH_RADIUS_KM:
            continue
        r2 = float(x.real)
        r23 = r2**3
        rho1 = ((6 * (d[2, 0] * tau1 / tau3 + d[1, 0] * tau / tau3) * r23
                 + mu * d[2, 0] * (tau**2 - tau1**2) * tau1 / tau3)
                / (6 * r23 + mu * (tau**2 - tau3**2)) - d[0, 0]) / d0
        rho2 = a_ + mu * b_ / r23
        rho3 = ((6 * (d[0, 2] * tau3 / tau1 - d[1, 2] * tau / tau1) * r23
                 + mu * d[0, 2] * (tau**2 - tau3**2) * tau3 / tau1)
                / (6 * r23 + mu * (tau**2 - tau1**2)) - d[2, 2]) / d0
        if min(rho1, rho2, rho3) <= 0:
            continue
        r1v = site[0] + rho1 * rho_hat[0]
        r2v = site[1] + rho2 * rho_hat[1]
        r3v = site[2] + rho3 * rho_hat[2]
        f1 = 1 - 0.5 * mu / r23 * tau1**2
        f3 = 1 - 0.5 * mu / r23 * tau3**2
        g1 = tau1 - mu / (6 * r23) * tau1**3
        g3 = tau3 - mu / (6 * r23) * tau3**3
        v2v = (-f3 * r1v + f1 * r3v) / (f1 * g3 - f3 * g1)
        out.append((r2v, v2v))
    return out


# --------------------------------------------------------------------------------------------
# the robust fit


@dataclass(frozen=True)
class OrbitFit:
    """A fitted orbit: the state at ``epoch_s`` and what the fit left.

    Attributes
    ----------
    epoch_s
        Epoch of the state (s, on the observations' time axis).
    r_km, v_km_s
        Fitted position and velocity at the epoch.
    dynamics
        ``"twobody"`` or ``"j2"``.
    residuals_arcsec
        Observed − fitted ``(n, 2)``: RA·cos(Dec) and Dec (arcsec).
    inliers
        Observations whose residual norm is within ``3 × f_scale``.
    cost
        Final robust cost of :func:`scipy.optimize.least_squares`.
    success
        The optimiser's success flag.
    n_evaluations
        Residual-function evaluations.
    seconds
        Wall time of the fit (IOD included).
    """

    epoch_s: float
    r_km: np.ndarray
    v_km_s: np.ndarray
    dynamics: str
    residuals_arcsec: np.ndarray
    inliers: np.ndarray
    cost: float
    success: bool
    n_evaluations: int
    seconds: float
    extra: dict = field(default_factory=dict)

    def positions(self, t_s: np.ndarray) -> np.ndarray:
        """Object positions (km) at times ``t_s`` (s)."""
        t = as_finite_array(t_s, "t_s", ndim=1)
        return propagate_state(self.r_km, self.v_km_s, t - self.epoch_s,
                               dynamics=self.dynamics)

    def predict(self, t_s: np.ndarray, site_km: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Predicted topocentric RA in [0, 360) and Dec (degrees) at ``t_s`` from ``site_km``.

        Parameters
        ----------
        t_s
            Times (s), ``(n,)``.
        site_km
            Station positions at those times, ``(n, 3)``, the frame of the fit.
        """
        t = as_finite_array(t_s, "t_s", ndim=1)
        site = as_finite_array(site_km, "site_km", shape=(len(t), 3))
        return angles_from_positions(self.positions(t), site)


#: Residual (arcsec) given to every angle of an inadmissible trial state: a J2 trial state
#: inside the Earth, or one whose integration fails. Large and finite, so the least-squares
#: solver rejects the step and shrinks its trust region instead of stopping on an error.
_PENALTY_ARCSEC = 1.0e6
#: Largest plausible geocentric distance of a fitted object (km); beyond it the inputs are
#: most likely in the wrong units.
_MAX_RANGE_KM = 1.0e6


def _residuals(x: np.ndarray, dt: np.ndarray, site: np.ndarray, ra: np.ndarray,
               dec: np.ndarray, cosd: np.ndarray, dynamics: str) -> np.ndarray:
    penalty = np.full(2 * len(dt), _PENALTY_ARCSEC)
    if dynamics != "twobody" and np.linalg.norm(x[:3]) < EARTH_RADIUS_KM:
        return penalty
    try:
        pos = propagate_state(x[:3], x[3:], dt, dynamics=dynamics)
    except RuntimeError:
        return penalty
    if not np.all(np.isfinite(pos)):
        return penalty
    ra_p, dec_p = angles_from_positions(pos, site)
    dra = (ra - ra_p + 180.0) % 360.0 - 180.0
    return np.r_[dra * cosd, dec - dec_p] * _ARCSEC


def fit_orbit(t_s: np.ndarray, ra_deg: np.ndarray, dec_deg: np.ndarray, site_km: np.ndarray,
              *, sigma_arcsec: float = 1.0, loss: str = "cauchy", f_scale: float | None = None,
              dynamics: str = "twobody", epoch_s: float | None = None,
              x0: np.ndarray | None = None, n_triplets: int = 6,
              max_nfev: int = 200) -> OrbitFit:
    """Fit a state vector to topocentric angles by robust least squares.

    Parameters
    ----------
    t_s
        Observation times (s), ``(n,)``, n ≥ 3, non-decreasing: equal times are allowed from
        different stations (two sites observing at the same instants), not from one site.
    ra_deg, dec_deg
        Observed topocentric right ascension and declination (degrees).
    site_km
        Station positions ``(n, 3)`` at the observation times (quasi-inertial frame, km).
    sigma_arcsec
        Standard deviation of the good measurements (arcsec); sets the default ``f_scale``.
    loss
        Robust loss of :func:`scipy.optimize.least_squares` (:data:`ROBUST_LOSSES`).
    f_scale
        Soft inlier scale of the loss (arcsec); default ``2 × sigma_arcsec``.
    dynamics
        ``"twobody"`` or ``"j2"`` (:func:`propagate_state`).
    epoch_s
        Epoch of the fitted state; default: the observation time nearest the middle.
    x0
        Initial state ``(6,)`` at the epoch (km, km/s); default: Gauss IOD
        (:func:`gauss_iod`) on ``n_triplets`` triplets spread over the arc, the candidate
        with the smallest robust cost on all data kept.
    n_triplets
        Triplets tried for the IOD start.
    max_nfev
        Evaluation budget of the least-squares solver.

    Returns
    -------
    OrbitFit

    Raises
    ------
    ValueError
        On bad inputs (including station positions that look like metres), when no triplet
        gives an admissible Gauss solution, or when the fitted distance exceeds 10⁶ km (angles
        in radians, not degrees, or positions in the wrong unit).

    Warns
    -----
    RuntimeWarning
        When fewer than half the observations end as inliers: with good data this points to
        ``sigma_arcsec``/``f_scale`` in the wrong unit (they are arcsec) or to angles that do
        not belong to one object; and when every angle lies within the radian ranges
        ([0, 2π] for RA, [−π/2, π/2] for Dec).
    """
    t0 = time.perf_counter()
    t = as_finite_array(t_s, "t_s", ndim=1)
    n = len(t)
    if n < 3:
        raise ValueError(f"t_s needs at least 3 observations, got {n}")
    if np.any(np.diff(t) < 0):
        raise ValueError("t_s must be non-decreasing (sort the observations by time)")
    ra = as_finite_array(ra_deg, "ra_deg", shape=(n,))
    dec = as_finite_array(dec_deg, "dec_deg", shape=(n,))
    site = as_finite_array(site_km, "site_km", shape=(n, 3))
    same_t = np.flatnonzero(np.diff(t) == 0)
    dup = same_t[np.all(np.abs(site[same_t] - site[same_t + 1]) < 1e-6, axis=1)]
    if dup.size:
        raise ValueError(f"t_s has {dup.size} observation(s) at the time of the previous one "
                         f"from the same site (first at t_s[{dup[0] + 1}] = {t[dup[0] + 1]:g}): "
                         "equal times are allowed only from different stations")
    site_r = float(np.median(np.linalg.norm(site, axis=1)))
    if site_r > 1.0e5:
        raise ValueError(f"site_km must be in km: the median station distance is {site_r:.3g}, "
                         "which looks like metres (a ground station is about 6,378 km from "
                         "the geocentre)")
    sig = check_positive(sigma_arcsec, "sigma_arcsec")
    check_choice(loss, "loss", ROBUST_LOSSES)
    fs = 2.0 * sig if f_scale is None else check_positive(f_scale, "f_scale")
    check_choice(dynamics, "dynamics", DYNAMICS)
    k = check_int(n_triplets, "n_triplets", min_value=1)
    nfev = check_int(max_nfev, "max_nfev", min_value=1)
    ep = float(t[n // 2]) if epoch_s is None else float(epoch_s)
    if not np.isfinite(ep):
        raise ValueError(f"epoch_s must be finite, got {epoch_s}")
    if np.all((ra >= 0) & (ra <= 2 * np.pi)) and np.all(np.abs(dec) <= np.pi / 2):
        warnings.warn("fit_orbit: every ra_deg lies in [0, 2π] and every dec_deg in [−π/2, π/2]; "
                      "are the angles in radians? They must be in degrees", RuntimeWarning,
                      stacklevel=2)
    dt = t - ep
    cosd = np.cos(np.radians(dec))
    args = (dt, site, ra, dec, cosd, dynamics)

    def robust_cost(x: np.ndarray) -> float:
        r = _residuals(x, *args[:5], "twobody") / fs
        rho = {"linear": r**2, "huber": np.where(np.abs(r) <= 1, r**2, 2 * np.abs(r) - 1),
               "soft_l1": 2 * (np.sqrt(1 + r**2) - 1), "cauchy": np.log1p(r**2),
               "arctan": np.arctan(r**2)}[loss]
        return float(np.sum(rho))

    if x0 is not None:
        start = as_finite_array(x0, "x0", shape=(6,))
    else:
        cands = []
        mid = n // 2
        for j in range(k):
            i1 = (j * n) // (4 * k)
            i3 = n - 1 - i1
            i2 = mid + (j % 3) - 1 if 0 < mid + (j % 3) - 1 < n - 1 else mid
            if not (i1 < i2 < i3):
                continue
            tri = np.array([i1, i2, i3])
            try:
                sols = gauss_iod(t[tri], ra[tri], dec[tri], site[tri])
            except ValueError:
                continue
            for r2, v2 in sols:
                # move the state from the triplet's middle time to the epoch
                r_ep = propagate_state(r2, v2, np.array([ep - t[i2], ep - t[i2] + 1.0]))
                x = np.r_[r_ep[0], r_ep[1] - r_ep[0]]
                if np.all(np.isfinite(x)):
                    cands.append((robust_cost(x), x))
        if not cands:
            raise ValueError("no admissible Gauss initial orbit from the observation triplets; "
                             "check the units (ra_deg and dec_deg in degrees, site_km in km, "
                             f"median station distance here {site_r:.4g}) or give x0")
        start = min(cands, key=lambda c: c[0])[1]
    scale = np.r_[np.full(3, max(np.linalg.norm(start[:3]), 1.0) * 1e-3),
                  np.full(3, max(np.linalg.norm(start[3:]), 1e-3) * 1e-3)]
    sol = least_squares(_residuals, start, args=args, loss=loss, f_scale=fs, x_scale=scale,
                        method="trf", max_nfev=nfev)
    res = sol.fun.reshape(2, n).T
    r_fit = float(np.linalg.norm(sol.x[:3]))
    if r_fit > _MAX_RANGE_KM:
        raise ValueError(f"the fitted orbit is {r_fit:.3g} km from the geocentre, implausible "
                         "for an Earth orbit: are ra_deg and dec_deg in degrees (not radians) "
                         "and site_km in km?")
    inl = np.hypot(res[:, 0], res[:, 1]) <= 3 * fs
    if inl.sum() < n / 2:
        warnings.warn(f"fit_orbit: only {int(inl.sum())} of {n} observations are inliers "
                      f"(within 3 × f_scale = {3 * fs:.3g}″); is sigma_arcsec (or f_scale) in "
                      "arcsec, and do all angles belong to one object?", RuntimeWarning,
                      stacklevel=2)
    return OrbitFit(epoch_s=ep, r_km=sol.x[:3].copy(), v_km_s=sol.x[3:].copy(),
                    dynamics=dynamics, residuals_arcsec=res,
                    inliers=inl, cost=float(sol.cost),
                    success=bool(sol.success), n_evaluations=int(sol.nfev),
                    seconds=time.perf_counter() - t0,
                    extra={"x0": start, "loss": loss, "f_scale": fs})
