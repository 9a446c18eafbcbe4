"""A shipborne star-sensor image-sequence simulator with the five scenarios of Sheng 2026.

The sky is real: catalogue stars (Gaia DR3 / Hipparcos via :func:`eotrack.astro.stars_in_field`)
around a reference star, their Alt/Az seen from a ship at sea computed by astropy for every
frame (Earth rotation, no refraction), turned into the camera frame by the ship's roll, pitch
and yaw (:mod:`eotrack.geometry.shipboard`) and projected by a pinhole camera. Each frame is
rendered with a pixel-integrated Gaussian PSF, sky background, photon (shot) noise, read noise
and 8-bit quantisation (the paper's histograms are 0…255).

Scenario knobs (:class:`Scenario`, presets in :func:`scenario`):

* ``strong_light`` — a bright, slightly graded sky that pushes the star towards saturation;
* ``cloud`` — moving cloud masks, opaque and translucent, that cross the reference star and
  hide it for stretches of ``occlusion_frames``; the clouds are faintly lit (moonlight);
* ``sway`` — a rougher sea (larger roll/pitch/yaw);
* ``stray_light`` — structured glare from a source just outside the field: a halo, a ghost ring
  and a streak that move with the ship;
* ``low_snr`` — a fainter star field (thin haze) and a noisier read-out.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from functools import lru_cache

import cv2
import numpy as np

from eotrack.geometry.shipboard import (
    ShipMotion,
    camera_from_level,
    enu_from_azalt,
    project_to_image,
    sea_state_motion,
    ship_attitude,
)
from eotrack.imaging.psf import render_gaussian_spots
from eotrack.validation import check_choice, check_generator, check_int, check_positive

__all__ = [
    "SCENARIOS",
    "Scenario",
    "SensorConfig",
    "ShipSite",
    "StarSequence",
    "scenario",
    "simulate_sequence",
    "sway_acceleration_variance",
]

SCENARIOS = ("strong_light", "cloud", "sway", "stray_light", "low_snr")


@dataclass(frozen=True)
class SensorConfig:
    """The star sensor.

    Attributes
    ----------
    shape
        ``(height, width)`` in pixels.
    fov_deg
        Full field of view across the width (degrees).
    frame_rate_hz
        Frames per second (ΔT = 1/rate).
    psf_sigma_px
        Gaussian PSF standard deviation (pixels).
    ref_mag, ref_flux_e
        A star of magnitude ``ref_mag`` gives ``ref_flux_e`` photo-electrons per frame.
    max_mag
        Faintest catalogue star rendered.
    gain_e_per_dn, bias_dn, read_noise_e
        Read-out: ``DN = bias + electrons / gain + read noise``, clipped to 0…255.
    exposure_s
        Exposure time (≤ frame period); the image motion during it blurs the stars.
    """

    shape: tuple[int, int] = (128, 128)
    fov_deg: float = 10.0
    frame_rate_hz: float = 5.0
    psf_sigma_px: float = 1.0
    ref_mag: float = 2.0
    ref_flux_e: float = 10000.0
    max_mag: float = 6.5
    gain_e_per_dn: float = 10.0
    bias_dn: float = 8.0
    read_noise_e: float = 10.0
    exposure_s: float = 0.1

    def __post_init__(self) -> None:
        if not (isinstance(self.shape, tuple) and len(self.shape) == 2):
            raise ValueError(f"shape must be (height, width), got {self.shape!r}")
        check_int(self.shape[0], "shape[0]", min_value=16)
        check_int(self.shape[1], "shape[1]", min_value=16)
        if not 0 < check_positive(self.fov_deg, "fov_deg") < 90:
            raise ValueError(f"fov_deg must lie in (0, 90), got {self.fov_deg}")
        for name in ("frame_rate_hz", "psf_sigma_px", "ref_flux_e", "gain_e_per_dn"):
            check_positive(getattr(self, name), name)
        check_positive(self.read_noise_e, "read_noise_e", allow_zero=True)
        if not 0 < check_positive(self.exposure_s, "exposure_s") <= self.dt:
            raise ValueError(f"exposure_s must lie in (0, 1/frame_rate_hz], got {self.exposure_s}")

    @property
    def dt(self) -> float:
        """Frame period ΔT (s)."""
        return 1.0 / self.frame_rate_hz

    @property
    def focal_px(self) -> float:
        """Focal length in pixels."""
        return 0.5 * self.shape[1] / np.tan(np.radians(0.5 * self.fov_deg))

    @property
    def pixel_scale_arcsec(self) -> float:
        """Angular size of a pixel at the centre (arcsec)."""
        return float(np.degrees(1.0 / self.focal_px) * 3600.0)


@dataclass(frozen=True)
class ShipSite:
    """Where and when: a ship in the East China Sea on a December night (UTC start time)."""

    lat_deg: float = 30.0
    lon_deg: float = 123.0
    start_utc: str = "2025-12-15T14:00:00"
    target_mag_range: tuple[float, float] = (1.5, 2.6)
    target_alt_range_deg: tuple[float, float] = (40.0, 65.0)


@dataclass(frozen=True)
class Scenario:
    """Scenario knobs (DN are 8-bit grey levels).

    Attributes
    ----------
    name
        Label.
    sea_state
        Douglas sea state of the ship motion (:func:`eotrack.geometry.sea_state_motion`).
    sky_dn
        Sky background level.
    gradient_dn
        Peak-to-peak linear sky gradient across the image (random direction).
    star_scale
        Multiplier of all star fluxes (haze, thin cloud).
    read_noise_scale
        Multiplier of the sensor's read noise.
    n_clouds
        Number of clouds crossing the reference star.
    cloud_opacity
        Opacity range of a cloud (1 = opaque; drawn uniformly).
    cloud_dn
        Brightness of a fully opaque cloud (moonlit), scaled by its opacity.
    occlusion_frames
        Frames for which a cloud covers the reference star.
    stray_dn
        Peak of the stray-light halo at the image edge.
    """

    name: str = "nominal"
    sea_state: int = 3
    sky_dn: float = 20.0
    gradient_dn: float = 0.0
    star_scale: float = 1.0
    read_noise_scale: float = 1.0
    n_clouds: int = 0
    cloud_opacity: tuple[float, float] = (0.5, 1.0)
    cloud_dn: float = 0.0
    occlusion_frames: int = 25
    stray_dn: float = 0.0

    def __post_init__(self) -> None:
        check_int(self.sea_state, "sea_state", min_value=2, max_value=5)
        for name in ("sky_dn", "gradient_dn", "cloud_dn", "stray_dn"):
            check_positive(getattr(self, name), name, allow_zero=True)
        check_positive(self.star_scale, "star_scale")
        check_positive(self.read_noise_scale, "read_noise_scale")
        check_int(self.n_clouds, "n_clouds", min_value=0)
        lo, hi = self.cloud_opacity
        if not 0 <= lo <= hi <= 1:
            raise ValueError(f"cloud_opacity must be 0 <= lo <= hi <= 1, got {self.cloud_opacity}")
        check_int(self.occlusion_frames, "occlusion_frames", min_value=1)


def scenario(name: str, **changes: object) -> Scenario:
    """The preset of one of the paper's five scenarios (``SCENARIOS``), optionally modified."""
    check_choice(name, "name", (*SCENARIOS, "nominal"))
    presets = {
        "nominal": Scenario("nominal"),
        "strong_light": Scenario("strong_light", sky_dn=185.0, gradient_dn=80.0),
        "cloud": Scenario("cloud", n_clouds=3, cloud_opacity=(0.6, 1.0), cloud_dn=25.0,
                          occlusion_frames=10),
        "sway": Scenario("sway", sea_state=5),
        "stray_light": Scenario("stray_light", stray_dn=220.0),
        "low_snr": Scenario("low_snr", star_scale=0.06, read_noise_scale=3.0),
    }
    return replace(presets[name], **changes) if changes else presets[name]


@dataclass
class StarSequence:
    """A simulated sequence.

    Attributes
    ----------
    images
        ``(n, h, w)`` uint8 frames.
    truth
        True position (x, y) of the reference star per frame ``(n, 2)``.
    visible
        Transmission of the cloud layer at the reference star ``(n,)`` (1 = clear).
    star_xy
        True positions of all rendered stars ``(n, n_stars, 2)`` (reference star first).
    star_mag
        Their magnitudes ``(n_stars,)``.
    t
        Frame times from the start (s).
    attitude
        Ship attitude (``heading``, ``pitch``, ``roll`` and rates, radians).
    info
        Scenario, sensor, site and target description.
    """

    images: np.ndarray
    truth: np.ndarray
    visible: np.ndarray
    star_xy: np.ndarray
    star_mag: np.ndarray
    t: np.ndarray
    attitude: dict[str, np.ndarray]
    info: dict[str, object] = field(default_factory=dict)


@lru_cache(maxsize=8)
def _sky(site: ShipSite, n_frames: int, dt: float, fov_deg: float, max_mag: float
         ) -> tuple[np.ndarray, np.ndarray, np.ndarray, dict[str, object]]:
    """Alt/Az (radians) of the reference star (index 0) and its neighbours at every frame."""
    import astropy.units as u
    from astropy.coordinates import AltAz, EarthLocation, SkyCoord
    from astropy.time import Time

    import eotrack.astro as astro

    loc = EarthLocation.from_geodetic(site.lon_deg * u.deg, site.lat_deg * u.deg, 0 * u.m)
    t0 = Time(site.start_utc, scale="utc")
    jyear = float(t0.jyear)
    cat = astro.load_catalog()
    lo, hi = site.target_mag_range
    bright = cat.select((cat.mag >= lo) & (cat.mag <= hi))
    frame0 = AltAz(obstime=t0, location=loc, pressure=0 * u.hPa)
    aa = SkyCoord(bright.ra_deg * u.deg, bright.dec_deg * u.deg).transform_to(frame0)
    alo, ahi = site.target_alt_range_deg
    ok = np.flatnonzero((aa.alt.deg >= alo) & (aa.alt.deg <= ahi))
    if len(ok) == 0:
        raise ValueError("no catalogue star in target_mag_range and target_alt_range_deg at "
                         f"{site.start_utc}")
    j = int(ok[0])  # brightest candidate
    ra0, dec0 = float(bright.ra_deg[j]), float(bright.dec_deg[j])
    field_ = astro.stars_in_field(ra0, dec0, 0.75 * fov_deg, max_mag=max_mag, jyear=jyear)
    sep = np.hypot((field_.ra_deg - ra0) * np.cos(np.radians(dec0)), field_.dec_deg - dec0)
    order = np.argsort(sep, kind="stable")  # reference star first (separation 0)
    field_ = field_.select(order)
    times = t0 + np.arange(n_frames) * dt * u.s
    frames = AltAz(obstime=times[None, :], location=loc, pressure=0 * u.hPa)
    sc = SkyCoord(field_.ra_deg[:, None] * u.deg, field_.dec_deg[:, None] * u.deg)
    altaz = sc.transform_to(frames)
    az = np.radians(altaz.az.deg).T       # (n_frames, n_stars)
    alt = np.radians(altaz.alt.deg).T
    info = {"target_source_id": int(field_.source_id[0]), "target_ra_deg": ra0,
            "target_dec_deg": dec0, "target_mag": float(field_.mag[0]),
            "target_az_deg": float(np.degrees(az[0, 0])),
            "target_alt_deg": float(np.degrees(alt[0, 0]))}
    return az, alt, np.asarray(field_.mag, dtype=float), info


def sway_acceleration_variance(motion: ShipMotion, sensor: SensorConfig) -> float:
    """Per-frame variance of the image acceleration change caused by the sway (pixels²/s⁴).

    Each sinusoid ``A sin ωt`` (A in pixels) has jerk amplitude ``A ω³``; over one frame the
    acceleration changes by about ``jerk · ΔT``, with mean square ``(A ω³ ΔT)²/2``; summed over
    the roll, pitch and yaw components. Used to initialise the Singer ``q_a`` (eq. 34 "from a
    typical sea-state sway spectrum").
    """
    f = sensor.focal_px
    tot = 0.0
    for ax in ("roll", "pitch", "yaw"):
        amp = np.radians(np.asarray(getattr(motion, f"{ax}_amp_deg"))) * f
        w = 2 * np.pi / np.asarray(getattr(motion, f"{ax}_period_s"))
        tot += float(np.sum((amp * w**3 * sensor.dt) ** 2 / 2))
    return tot


def _clouds(rng: np.random.Generator, sc: Scenario, truth: np.ndarray, shape: tuple[int, int]
            ) -> tuple[np.ndarray, np.ndarray]:
    """Cloud opacity ``(n, h, w)`` (0 clear … 1 opaque) and transmission at the truth."""
    n = len(truth)
    h, w = shape
    yy, xx = np.mgrid[0:h, 0:w].astype(np.float32)
    opacity = np.zeros((n, h, w), np.float32)
    at_star = np.zeros(n)
    # crossing times spread over the sequence (after a clear start for initialisation)
    centres = np.linspace(0.25, 0.85, sc.n_clouds) * n if sc.n_clouds else []
    for kc in centres:
        kc = float(kc + rng.uniform(-0.05, 0.05) * n)
        a = rng.uniform(25.0, 35.0)            # semi-axis along the motion (pixels)
        b = rng.uniform(20.0, 30.0)
        speed = 2 * a / sc.occlusion_frames     # pixels per frame: covers the star ~L frames
        ang = rng.uniform(0, 2 * np.pi)
        u = np.array([np.cos(ang), np.sin(ang)])
        op = rng.uniform(*sc.cloud_opacity)
        k = np.arange(n)
        centre = truth.mean(axis=0) + np.outer(k - kc, u) * speed + rng.normal(0, 3, 2)
        reach = max(a, b) * 1.3
        on = np.flatnonzero((centre[:, 0] > -reach) & (centre[:, 0] < w + reach)
                            & (centre[:, 1] > -reach) & (centre[:, 1] < h + reach))
        if len(on):
            c = centre[on].astype(np.float32)
            dx = xx[None] - c[:, 0, None, None]
            dy = yy[None] - c[:, 1, None, None]
            along = (dx * u[0] + dy * u[1]) / a
            across = (dy * u[0] - dx * u[1]) / b
            d = np.sqrt(along * along + across * across)
            cl = op * np.clip((1.0 - d) / 0.3 + 0.5, 0.0, 1.0)
            opacity[on] = 1 - (1 - opacity[on]) * (1 - cl)
        ds = truth - centre
        dd = np.sqrt(((ds @ u) / a) ** 2 + ((ds @ np.array([-u[1], u[0]])) / b) ** 2)
        at_star = 1 - (1 - at_star) * (1 - op * np.clip((1.0 - dd) / 0.3 + 0.5, 0.0, 1.0))
    return opacity, 1 - at_star


def _stray(rng: np.random.Generator, sc: Scenario, shape: tuple[int, int], shift: np.ndarray
           ) -> np.ndarray:
    """Structured glare ``(n, h, w)``: halo, ghost ring and streak from a source off the field."""
    h, w = shape
    n = len(shift)
    ang = rng.uniform(0, 2 * np.pi)
    dist = 0.5 * max(h, w) + rng.uniform(5, 20)
    src = np.array([w / 2 + dist * np.cos(ang), h / 2 + dist * np.sin(ang)])
    yy, xx = np.mgrid[0:h, 0:w].astype(np.float32)
    out = np.empty((n, h, w), np.float32)
    ring_r = rng.uniform(0.45, 0.7) * max(h, w)
    r_edge = dist - 0.5 * max(h, w)
    streak_dir = np.array([np.cos(ang + np.pi / 2 + rng.normal(0, 0.3)),
                           np.sin(ang + np.pi / 2 + rng.normal(0, 0.3))])
    for k in range(n):
        s = src + 0.5 * shift[k]
        dx, dy = xx - s[0], yy - s[1]
        r = np.sqrt(dx * dx + dy * dy)
        halo = 1.0 / (1.0 + ((r - r_edge) / 30.0) ** 2)
        ring = 0.35 * np.exp(-0.5 * ((r - ring_r) / 2.0) ** 2)
        across = dx * streak_dir[1] - dy * streak_dir[0]
        streak = 0.25 * np.exp(-0.5 * (across / 1.5) ** 2) * np.exp(-r / (0.8 * max(h, w)))
        out[k] = sc.stray_dn * (halo + ring + streak)
    return out


def _motion_blur(img: np.ndarray, v: np.ndarray) -> np.ndarray:
    """Convolve with a normalised line of length ``|v|`` pixels along ``v`` (x, y)."""
    length = float(np.hypot(*v))
    if length < 0.5:
        return img
    half = int(np.ceil(length / 2)) + 1
    size = 2 * half + 1
    m = max(2, int(np.ceil(4 * length)))
    t = np.linspace(-0.5, 0.5, m)
    px = half + t * v[0]
    py = half + t * v[1]
    x0, y0 = np.floor(px).astype(int), np.floor(py).astype(int)
    fx, fy = px - x0, py - y0
    idx = np.concatenate([y0 * size + x0, y0 * size + x0 + 1, (y0 + 1) * size + x0,
                          (y0 + 1) * size + x0 + 1])
    wts = np.concatenate([(1 - fx) * (1 - fy), fx * (1 - fy), (1 - fx) * fy, fx * fy])
    kern = np.bincount(idx, wts, minlength=size * size).reshape(size, size).astype(np.float32)
    kern /= kern.sum()
    return cv2.filter2D(img, -1, kern, borderType=cv2.BORDER_CONSTANT)


def simulate_sequence(rng: np.random.Generator, scenario_: Scenario | str = "nominal", *,
                      n_frames: int = 200, sensor: SensorConfig | None = None,
                      site: ShipSite | None = None, motion: ShipMotion | None = None
                      ) -> StarSequence:
    """Simulate ``n_frames`` star-sensor images of one scenario.

    Parameters
    ----------
    rng
        Random generator (ship-motion phases, clouds, glare, noise).
    scenario_
        A :class:`Scenario` or the name of a preset (:data:`SCENARIOS` or ``"nominal"``).
    n_frames
        Number of frames (≥ 2).
    sensor, site
        :class:`SensorConfig` and :class:`ShipSite` (defaults: the documented ones).
    motion
        Ship motion (default: :func:`eotrack.geometry.sea_state_motion` of the scenario).

    Returns
    -------
    StarSequence
    """
    check_generator(rng)
    sc = scenario(scenario_) if isinstance(scenario_, str) else scenario_
    if not isinstance(sc, Scenario):
        raise TypeError(f"scenario_ must be a Scenario or a preset name, got "
                        f"{type(scenario_).__name__}")
    n = check_int(n_frames, "n_frames", min_value=2)
    sensor = SensorConfig() if sensor is None else sensor
    site = ShipSite() if site is None else site
    motion = sea_state_motion(sc.sea_state) if motion is None else motion
    az, alt, mags, info = _sky(site, n, sensor.dt, sensor.fov_deg, sensor.max_mag)
    t = np.arange(n) * sensor.dt
    att = ship_attitude(motion, t, rng)
    h, w = sensor.shape
    R = camera_from_level(att["heading"], att["pitch"], att["roll"],
                          np.radians(info["target_az_deg"] - motion.heading_deg),
                          np.radians(info["target_alt_deg"]))  # (n, 3, 3)
    v = enu_from_azalt(az, alt)                                 # (n, s, 3)
    v_cam = np.einsum("nij,nsj->nsi", R, v)
    xy = project_to_image(v_cam, sensor.focal_px, ((w - 1) / 2, (h - 1) / 2))
    truth = xy[:, 0].copy()
    flux_e = sensor.ref_flux_e * 10 ** (-0.4 * (mags - sensor.ref_mag)) * sc.star_scale
    inside = np.all(np.isfinite(xy), axis=2)
    # all frames in one call: frames stacked vertically with a guard band against bleeding
    pad = int(np.ceil(4 * sensor.psf_sigma_px)) + 1
    hp = h + 2 * pad
    tall = np.zeros((n * hp, w), np.float32)
    kk, ss = np.nonzero(inside)
    pts = xy[kk, ss] + np.c_[np.zeros(len(kk)), kk * hp + pad]
    keep = (xy[kk, ss, 1] > -pad) & (xy[kk, ss, 1] < h + pad - 1)
    render_gaussian_spots((n * hp, w), pts[keep], flux_e[ss[keep]], sensor.psf_sigma_px,
                          out=tall)
    stars = tall.reshape(n, hp, w)[:, pad:pad + h]
    # motion blur: the exposure integrates the field along its image velocity (uniform over a
    # small field), a line kernel per frame
    vel = np.gradient(truth, axis=0) * sensor.exposure_s / sensor.dt     # pixels per exposure
    stars = np.stack([_motion_blur(stars[k], vel[k]) for k in range(n)])
    gain = sensor.gain_e_per_dn
    sky = np.full((h, w), sc.sky_dn * gain, np.float32)
    if sc.gradient_dn > 0:
        ang = rng.uniform(0, 2 * np.pi)
        yy, xx = np.mgrid[0:h, 0:w]
        ramp = ((xx - w / 2) * np.cos(ang) + (yy - h / 2) * np.sin(ang)) / np.hypot(w, h)
        sky = sky + (sc.gradient_dn * gain * ramp).astype(np.float32)
    electrons = stars + sky[None]
    visible = np.ones(n)
    if sc.n_clouds:
        opacity, visible = _clouds(rng, sc, truth, (h, w))
        electrons = electrons * (1 - opacity) + sc.cloud_dn * gain * opacity
    if sc.stray_dn > 0:
        electrons = electrons + gain * _stray(rng, sc, (h, w), truth - truth[0])
    electrons = np.maximum(electrons, 0)
    # shot noise (Gaussian approximation of Poisson) and read noise in one normal draw
    read_e = sensor.read_noise_e * sc.read_noise_scale
    noisy = electrons + np.sqrt(electrons + np.float32(read_e**2)) * \
        rng.standard_normal(electrons.shape, np.float32)
    dn = sensor.bias_dn + noisy / gain
    images = np.clip(np.floor(dn), 0, 255).astype(np.uint8)
    info = {**info, "scenario": sc, "sensor": sensor, "site": site, "motion": motion,
            "flux_e": flux_e, "pixel_scale_arcsec": sensor.pixel_scale_arcsec}
    return StarSequence(images, truth, visible, xy, mags, t, att, info)
