"""The sky of one night: objects, stations, cameras, the observing plan and the SGP4 truth.

Everything here is deterministic (no random numbers): the plan lists every *burst* — a short
series of frames one station takes of one object during one visit — with the camera attitude
of each frame and the true position and brightness of the target. The random parts (faint
stars, noise) are drawn per burst in :mod:`.pipeline`.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from functools import lru_cache

import numpy as np
from astropy import units as u
from astropy.time import Time

from eotrack.astro import (
    PENUMBRA,
    UMBRA,
    Station,
    earth_shadow,
    propagate_teme,
    satellite,
    sun_position_gcrs,
    teme_to_gcrs,
)
from eotrack.geometry import PinholeCamera
from eotrack.validation import check_int, check_positive

__all__ = ["ARCSEC_PER_RAD", "EARTH_RATE_RAD_S", "Burst", "CapstoneConfig", "NightPlan",
           "StationSpec", "camera_matrix", "make_plan", "with_changes"]

ARCSEC_PER_RAD = 180.0 / np.pi * 3600.0
#: Earth's rotation rate (rad/s) — the sidereal drift of the stars in a GEO-staring mount.
EARTH_RATE_RAD_S = 7.292115e-5


@dataclass(frozen=True)
class StationSpec:
    """A ground station: name, geodetic latitude/longitude (deg) and height (m)."""

    name: str
    lat_deg: float
    lon_deg: float
    height_m: float = 0.0

    def station(self) -> Station:
        """The :class:`eotrack.astro.Station`."""
        return Station(self.lat_deg, self.lon_deg, self.height_m, self.name)


#: Socorro, New Mexico (the LINEAR GEODSS-type site) and Haleakalā, Maui — ≈ 4,900 km apart.
DEFAULT_STATIONS = (StationSpec("Socorro NM", 33.82, -106.66, 1510.0),
                    StationSpec("Haleakala HI", 20.71, -156.26, 3050.0))


@dataclass(frozen=True)
class CapstoneConfig:
    """Settings of the night (all ours; none comes from a paper).

    Attributes
    ----------
    norad_ids
        Objects (sgp4 verification TLEs): 25954 AMC-4 and 28626 XM-3 (station-kept GEO) and
        14128 (an old GEO satellite drifting with 11.4° inclination).
    stations
        The two stations.
    night_start_utc, night_hours
        Window searched for darkness (sun below ``sun_max_alt_deg`` at a station).
    visit_interval_s
        Time between visits of the same object (the revisit cadence).
    burst_frames, frame_interval_s, exposure_s
        Frames per visit, time between them, exposure.
    size_px, pixel_scale_arcsec
        Square detector side and plate scale: 256 px × 15″ = 1.07° field of view.
    psf_sigma_px, zero_point_mag, sky_e, gradient, read_noise_e
        Gaussian PSF σ, magnitude giving 1 e⁻ per exposure, sky background (e⁻/px — the noise
        knob), background gradient across the frame (fraction of ``sky_e``), read noise.
    detect_sigma
        Extraction threshold (local noise σ) of the sky extractor.
    target_mag
        Brightness of a sunlit target (G-band-like magnitude); half as bright in penumbra,
        dark in umbra.
    star_limit_mag, catalogue_mag
        Faintest star rendered; faintest catalogue star used for matching (the Gaia extract
        is complete to G ≈ 10; fainter stars are synthetic and uncatalogued).
    min_elevation_deg, sun_max_alt_deg
        Observing limits.
    pointing_error_arcsec
        The mount points at the TLE prediction with a deterministic offset up to this size,
        so that targets are not always at the frame centre.
    seed
        Root seed of the night.
    """

    norad_ids: tuple[int, ...] = (25954, 28626, 14128)
    stations: tuple[StationSpec, StationSpec] = DEFAULT_STATIONS
    night_start_utc: str = "2006-03-25T00:30:00"
    night_hours: float = 16.0
    visit_interval_s: float = 900.0
    burst_frames: int = 5
    frame_interval_s: float = 20.0
    exposure_s: float = 2.0
    size_px: int = 256
    pixel_scale_arcsec: float = 15.0
    psf_sigma_px: float = 1.0
    zero_point_mag: float = 21.0
    sky_e: float = 400.0
    gradient: float = 0.3
    read_noise_e: float = 8.0
    detect_sigma: float = 4.0
    target_mag: float = 12.5
    star_limit_mag: float = 12.5
    catalogue_mag: float = 10.0
    min_elevation_deg: float = 10.0
    sun_max_alt_deg: float = -12.0
    pointing_error_arcsec: float = 120.0
    seed: int = 20260330
    stage_names: tuple[str, ...] = field(default=("sky", "frames", "extraction", "initiation",
                                                  "association", "triangulation", "prediction"),
                                         repr=False)

    def __post_init__(self) -> None:
        if len(self.norad_ids) < 1:
            raise ValueError("norad_ids must name at least one object")
        if len(self.stations) != 2 or not all(isinstance(s, StationSpec) for s in self.stations):
            raise ValueError("stations must be two StationSpec")
        check_positive(self.night_hours, "night_hours")
        check_positive(self.visit_interval_s, "visit_interval_s")
        check_int(self.burst_frames, "burst_frames", min_value=4)
        check_positive(self.frame_interval_s, "frame_interval_s")
        check_positive(self.exposure_s, "exposure_s")
        if not self.exposure_s < self.frame_interval_s:
            raise ValueError("exposure_s must be shorter than frame_interval_s")
        check_int(self.size_px, "size_px", min_value=64)
        check_positive(self.pixel_scale_arcsec, "pixel_scale_arcsec")
        check_positive(self.psf_sigma_px, "psf_sigma_px")
        check_positive(self.sky_e, "sky_e")
        check_positive(self.read_noise_e, "read_noise_e", allow_zero=True)
        check_positive(self.gradient, "gradient", allow_zero=True)
        if not self.burst_frames * self.frame_interval_s < self.visit_interval_s:
            raise ValueError("a burst (burst_frames × frame_interval_s) must fit in "
                             "visit_interval_s")

    @property
    def fov_deg(self) -> float:
        """Field of view (degrees)."""
        return self.size_px * self.pixel_scale_arcsec / 3600.0

    @property
    def focal_px(self) -> float:
        """Focal length in pixels."""
        return ARCSEC_PER_RAD / self.pixel_scale_arcsec


def with_changes(config: CapstoneConfig | None = None, **changes) -> CapstoneConfig:
    """A copy of ``config`` (default: the defaults) with some fields changed."""
    return replace(config or CapstoneConfig(), **changes)


def camera_matrix(config: CapstoneConfig) -> np.ndarray:
    """Intrinsics K (square pixels, principal point at the frame centre)."""
    f = config.focal_px
    c = (config.size_px - 1) / 2.0
    return np.array([[f, 0, c], [0, f, c], [0, 0, 1.0]])


def _look_at(boresight: np.ndarray) -> np.ndarray:
    """World → camera rotation: z along the boresight, y towards the south on the sky."""
    z = boresight / np.linalg.norm(boresight)
    north = np.array([0.0, 0.0, 1.0])
    x = np.cross(north, z)  # east-ish... pointing so that RA increases to the left
    x /= np.linalg.norm(x)
    y = np.cross(z, x)
    return np.stack([x, y, z])


def _rot_z(angle: np.ndarray) -> np.ndarray:
    c, s = np.cos(angle), np.sin(angle)
    o, i = np.zeros_like(angle), np.ones_like(angle)
    return np.stack([np.stack([c, -s, o], -1), np.stack([s, c, o], -1),
                     np.stack([o, o, i], -1)], -2)


@dataclass(frozen=True)
class Burst:
    """One visit of one object by one station: ``n`` frames.

    Attributes
    ----------
    station, obj, visit
        Indices into the config's stations, objects and the visit grid.
    times_s
        Mid-exposure times of the frames (s from the night's start).
    R
        World (GCRS) → camera rotations ``(n, 3, 3)`` at mid-exposure (GEO-staring: the
        camera turns with the Earth, so the stars drift).
    R_end
        The same at the end of each exposure (for the star trails).
    c_km
        Station GCRS positions ``(n, 3)``.
    target_xy
        True target pixel position per frame ``(n, 2)``.
    target_flux
        Target electrons per frame ``(n,)`` (0 in umbra).
    target_gcrs_km
        True target position per frame ``(n, 3)``.
    """

    station: int
    obj: int
    visit: int
    times_s: np.ndarray
    R: np.ndarray
    R_end: np.ndarray
    c_km: np.ndarray
    target_xy: np.ndarray
    target_flux: np.ndarray
    target_gcrs_km: np.ndarray

    def camera(self, k: int, K: np.ndarray, size: int) -> PinholeCamera:
        """The camera of frame ``k``."""
        return PinholeCamera(K, self.R[k], self.c_km[k], (size, size))


@dataclass(frozen=True)
class NightPlan:
    """The night: visit grid, truth on it, the bursts each station takes.

    Attributes
    ----------
    config
        The settings.
    t0
        Start of the night (astropy ``Time``).
    visit_s
        Visit start times (s from ``t0``).
    dark
        ``(n_stations, n_visits)``: the sun is low enough at the station.
    elevation_deg
        ``(n_stations, n_objects, n_visits)`` elevation of each object.
    shadow
        ``(n_objects, n_visits)`` Earth-shadow state (0 sunlit, 1 penumbra, 2 umbra).
    grid_s, grid_shadow, grid_gcrs_km, grid_station_km
        A fine (1-min) truth grid: times, shadow states ``(n_obj, n)``, object GCRS positions
        ``(n_obj, n, 3)`` and station GCRS positions ``(n_st, n, 3)``.
    bursts
        Every burst to observe (station dark, object above the elevation limit).
    names
        Object labels.
    """

    config: CapstoneConfig
    t0: Time
    visit_s: np.ndarray
    dark: np.ndarray
    elevation_deg: np.ndarray
    shadow: np.ndarray
    grid_s: np.ndarray
    grid_shadow: np.ndarray
    grid_gcrs_km: np.ndarray
    grid_station_km: np.ndarray
    bursts: tuple[Burst, ...]
    names: tuple[str, ...]

    def truth_direction(self, obj: int, station: int, t_s: np.ndarray) -> np.ndarray:
        """True unit topocentric direction ``(n, 3)`` at times ``t_s`` (interpolated, 1-min grid)."""
        t = np.atleast_1d(np.asarray(t_s, float))
        r = np.stack([np.interp(t, self.grid_s, self.grid_gcrs_km[obj][:, i]) for i in range(3)], 1)
        # interpolate the station on its own (Earth rotation is smooth on 1 min)
        c = np.stack([np.interp(t, self.grid_s, self.grid_station_km[station][:, i])
                      for i in range(3)], 1)
        d = r - c
        return d / np.linalg.norm(d, axis=1, keepdims=True)


def _elevation(r_gcrs: np.ndarray, c_gcrs: np.ndarray) -> np.ndarray:
    up = c_gcrs / np.linalg.norm(c_gcrs, axis=-1, keepdims=True)
    d = r_gcrs - c_gcrs
    d = d / np.linalg.norm(d, axis=-1, keepdims=True)
    return np.degrees(np.arcsin(np.clip(np.sum(up * d, -1), -1, 1)))


def make_plan(config: CapstoneConfig | None = None) -> NightPlan:
    """Build the night: truth, darkness, visibility, and every burst's geometry.

    Raises
    ------
    ValueError
        Stage ``sky``: an object never rises above ``min_elevation_deg`` at a station during
        that station's dark hours, or a station has no dark hours at all.
    """
    cfg = CapstoneConfig() if config is None else config
    if not isinstance(cfg, CapstoneConfig):
        raise TypeError(f"config must be a CapstoneConfig, got {type(cfg).__name__}")
    return _plan_cached(cfg)


@lru_cache(maxsize=16)
def _plan_cached(cfg: CapstoneConfig) -> NightPlan:
    t0 = Time(cfg.night_start_utc, scale="utc")
    n_vis = int(cfg.night_hours * 3600 // cfg.visit_interval_s)
    visit_s = np.arange(n_vis) * cfg.visit_interval_s
    grid_s = np.arange(0.0, cfg.night_hours * 3600 + 61.0, 60.0)
    tg = t0 + grid_s * u.s
    stations = [s.station() for s in cfg.stations]
    st_km = np.stack([s.gcrs_km(tg) for s in stations])
    sun = sun_position_gcrs(tg)
    sats = [satellite(n) for n in cfg.norad_ids]
    obj_km = np.stack([teme_to_gcrs(propagate_teme(s, tg)[0], tg) for s in sats])
    shadow_g = np.stack([earth_shadow(r, sun) for r in obj_km])

    def at(t, arr):  # linear interpolation of (n, 3) on the grid
        return np.stack([np.interp(t, grid_s, arr[:, i]) for i in range(3)], -1)

    sun_alt = np.stack([_elevation(at(visit_s, sun), at(visit_s, st_km[i]))
                        for i in range(len(stations))])
    dark = sun_alt < cfg.sun_max_alt_deg
    elev = np.stack([np.stack([_elevation(at(visit_s, obj_km[o]), at(visit_s, st_km[s]))
                               for o in range(len(sats))]) for s in range(len(stations))])
    shadow = np.stack([np.round(np.interp(visit_s, grid_s, sh)).astype(int) for sh in shadow_g])
    for s, spec in enumerate(cfg.stations):
        if not dark[s].any():
            raise ValueError(f"stage 'sky': station {spec.name} has no dark time (sun below "
                             f"{cfg.sun_max_alt_deg}°) between {t0.iso} and "
                             f"{cfg.night_hours} h later")
        for o, nid in enumerate(cfg.norad_ids):
            if not np.any(dark[s] & (elev[s, o] > cfg.min_elevation_deg)):
                raise ValueError(
                    f"stage 'sky': object {nid} never rises above {cfg.min_elevation_deg}° "
                    f"from station {spec.name} during its dark hours (highest "
                    f"{elev[s, o][dark[s]].max():.1f}°); choose another station or object")
    K = camera_matrix(cfg)
    f = cfg.focal_px
    bursts = []
    offs_rng = np.random.default_rng(cfg.seed)  # deterministic pointing offsets
    n_st, n_ob = len(stations), len(sats)
    offsets = offs_rng.uniform(-1, 1, (n_st, n_ob, n_vis, 2)) * cfg.pointing_error_arcsec / 206265
    k = np.arange(cfg.burst_frames)
    for j, tv in enumerate(visit_s):
        t_mid = tv + k * cfg.frame_interval_s
        t_end = t_mid + cfg.exposure_s / 2
        for s in range(n_st):
            if not dark[s, j]:
                continue
            c_mid = at(t_mid, st_km[s])
            for o in range(n_ob):
                if elev[s, o, j] <= cfg.min_elevation_deg:
                    continue
                r_mid = at(t_mid, obj_km[o])
                d0 = r_mid[0] - c_mid[0]
                R0 = _look_at(d0)
                # pointing offset: rotate the boresight slightly in the camera's x/y
                b = R0.T @ np.array([offsets[s, o, j, 0], offsets[s, o, j, 1], 1.0])
                R0 = _look_at(b)
                # GEO staring: camera fixed to the Earth → rotates about z with the Earth
                R_mid = R0 @ np.transpose(_rot_z(EARTH_RATE_RAD_S * (t_mid - t_mid[0])), (0, 2, 1))
                R_end = R0 @ np.transpose(_rot_z(EARTH_RATE_RAD_S * (t_end - t_mid[0])), (0, 2, 1))
                dcam = np.einsum("kij,kj->ki", R_mid, r_mid - c_mid)
                xy = f * dcam[:, :2] / dcam[:, 2:3] + K[0, 2]
                sh = np.round(np.interp(t_mid, grid_s, shadow_g[o])).astype(int)
                flux = 10 ** (-0.4 * (cfg.target_mag - cfg.zero_point_mag)) * \
                    np.where(sh == UMBRA, 0.0, np.where(sh == PENUMBRA, 0.5, 1.0))
                bursts.append(Burst(s, o, j, t_mid, R_mid, R_end, c_mid, xy, flux, r_mid))
    return NightPlan(cfg, t0, visit_s, dark, elev, shadow, grid_s, shadow_g, obj_km, st_km,
                     tuple(bursts), tuple(str(n) for n in cfg.norad_ids))
