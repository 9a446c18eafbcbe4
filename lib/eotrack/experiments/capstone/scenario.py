"""The sky of one night: objects, stations, cameras, the observing plan and the SGP4 truth.

Everything here is deterministic (no random numbers): the plan lists every *burst* — a short
series of frames one station takes of one object during one visit — with the camera attitude
of each frame and the true position and brightness of the target. The random parts (faint
stars, noise) are drawn per burst in :mod:`.pipeline`.
"""

from __future__ import annotations

import warnings
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

__all__ = ["ARCSEC_PER_RAD", "DEFAULT_CLUSTER", "DETECT_MARGIN", "EARTH_RATE_RAD_S",
           "MIN_FIELD_STARS", "Burst", "CapstoneConfig", "ClusterMember", "NightPlan",
           "StationSpec", "camera_matrix", "check_astrometry", "expected_field_stars",
           "make_plan", "member_satellite", "star_detection_limit_mag", "star_snr",
           "star_trail_px", "with_changes"]

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


@dataclass(frozen=True)
class ClusterMember:
    """An object co-located with a real GEO satellite: its TLE with offset elements.

    The verification TLEs hold no co-located satellites, so a cluster is made from a real TLE
    (``parent``) by offsetting its mean anomaly, right ascension of the ascending node and
    inclination (degrees). For a near-circular, near-equatorial orbit a mean-anomaly (or node)
    offset of Δ moves the object Δ along the GEO belt as seen from the geocentre; an
    inclination offset adds a daily north–south oscillation of that amplitude.
    """

    parent: int
    d_mean_anomaly_deg: float = 0.0
    d_raan_deg: float = 0.0
    d_incl_deg: float = 0.0

    def __post_init__(self) -> None:
        check_int(self.parent, "parent", min_value=1)
        for name in ("d_mean_anomaly_deg", "d_raan_deg", "d_incl_deg"):
            v = getattr(self, name)
            if not (isinstance(v, (int, float)) and np.isfinite(v) and abs(v) < 10.0):
                raise ValueError(f"{name} must be a finite offset below 10° (a co-located "
                                 f"object), got {v!r}")

    @property
    def name(self) -> str:
        """Label: the parent's id and the offsets, e.g. ``28626+0.12M``."""
        parts = [f"{v:+.3g}{k}" for v, k in ((self.d_mean_anomaly_deg, "M"),
                                             (self.d_raan_deg, "Ω"), (self.d_incl_deg, "i"))
                 if v != 0]
        return f"{self.parent}" + ("".join(parts) or "+0M")


def member_satellite(member: ClusterMember):
    """The SGP4 record of a :class:`ClusterMember` (the parent's elements plus the offsets)."""
    from sgp4.api import WGS72, Satrec

    if not isinstance(member, ClusterMember):
        raise TypeError(f"member must be a ClusterMember, got {type(member).__name__}")
    s = satellite(member.parent)
    m = Satrec()
    m.sgp4init(WGS72, "i", s.satnum, s.jdsatepoch + s.jdsatepochF - 2433281.5, s.bstar,
               s.ndot, s.nddot, s.ecco, s.argpo, s.inclo + np.radians(member.d_incl_deg),
               s.mo + np.radians(member.d_mean_anomaly_deg), s.no_kozai,
               s.nodeo + np.radians(member.d_raan_deg))
    return m


#: Two objects co-located with XM-3 (28626, near 85° W): 0.12° east of it along the belt, and
#: 0.1° west of it with 0.06° more inclination — all three in one field, ≈ 30 px apart.
DEFAULT_CLUSTER = (ClusterMember(28626, d_mean_anomaly_deg=0.12),
                   ClusterMember(28626, d_mean_anomaly_deg=-0.10, d_incl_deg=0.06))

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
        14128 (an old GEO satellite drifting with 11.4° inclination). Each is the centre of
        its own field.
    cluster
        Co-located objects (:class:`ClusterMember`) made from one of ``norad_ids``: they
        share their parent's field, so one burst sees several objects a few tenths of a degree
        apart (the association's hard case).
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
    star_limit_mag, catalogue_mag, astrometry_mag
        Faintest star rendered; faintest star of the real Gaia extract (complete to G ≈ 10;
        fainter stars are synthetic, following its count slope); faintest star in the chain's
        catalogue. A 1° field at high galactic latitude holds only ≈ 5 stars to G = 10 — too
        few for a plate solution — so the synthetic stars to ``astrometry_mag`` are listed in
        the catalogue too, standing in for the full Gaia DR3 (complete to G ≈ 20) that a real
        station would use; the fainter synthetic stars stay uncatalogued (only their motion
        marks them as stars). ``None`` (default): chosen from the field —
        ``astrometry_mag`` keeps the expected number of catalogue stars per field at that of
        the 1.07° field (256 px × 15″) at G ≤ 11.5 (the whole-sky count slope of the Gaia
        extract), but no fainter than the stars the frames can detect
        (:func:`star_detection_limit_mag`); ``star_limit_mag`` one magnitude fainter. Read the
        values used from :attr:`astrometry_limit` and :attr:`render_limit`.
    min_elevation_deg, sun_max_alt_deg
        Observing limits.
    pointing_error_arcsec, roll_error_deg
        The mount is commanded to the field object's TLE prediction and *believes* it points
        there; its true attitude is off by a deterministic offset up to ``pointing_error_arcsec``
        per axis and a roll up to ``roll_error_deg``. The renderer uses the true attitude; the
        chain gets only the believed one and solves the plate from the stars.
    cloud_frames, cloud_transmission
        Frames ``(station, field, visit, frame)`` behind a thick cloud that passes only
        ``cloud_transmission`` of the light: too few stars for a plate solution (bad input the
        chain must survive; one by default).
    seed
        Root seed of the night.
    """

    norad_ids: tuple[int, ...] = (25954, 28626, 14128)
    cluster: tuple[ClusterMember, ...] = DEFAULT_CLUSTER
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
    star_limit_mag: float | None = None
    catalogue_mag: float = 10.0
    astrometry_mag: float | None = None
    min_elevation_deg: float = 10.0
    sun_max_alt_deg: float = -12.0
    pointing_error_arcsec: float = 120.0
    roll_error_deg: float = 0.1
    cloud_frames: tuple[tuple[int, int, int, int], ...] = ((1, 0, 30, 2),)
    cloud_transmission: float = 0.001
    seed: int = 20260330
    stage_names: tuple[str, ...] = field(default=("sky", "frames", "extraction", "initiation",
                                                  "association", "triangulation", "prediction"),
                                         repr=False)

    def __post_init__(self) -> None:
        if len(self.norad_ids) < 1:
            raise ValueError("norad_ids must name at least one object")
        if not all(isinstance(m, ClusterMember) for m in self.cluster):
            raise TypeError("cluster must be a tuple of ClusterMember")
        for m in self.cluster:
            if m.parent not in self.norad_ids:
                raise ValueError(f"cluster member {m.name}: its parent {m.parent} must be one "
                                 f"of norad_ids {self.norad_ids} (it shares the parent's field)")
        for name in ("astrometry_mag", "star_limit_mag"):
            v = getattr(self, name)
            if v is not None and not (isinstance(v, (int, float)) and np.isfinite(v)):
                raise TypeError(f"{name} must be a finite number or None, got {v!r}")
        a = self.catalogue_mag if self.astrometry_mag is None else self.astrometry_mag
        lim = a if self.star_limit_mag is None else self.star_limit_mag
        if not self.catalogue_mag <= a <= lim:
            raise ValueError("magnitudes must satisfy catalogue_mag ≤ astrometry_mag ≤ "
                             f"star_limit_mag, got {self.catalogue_mag}, {self.astrometry_mag}, "
                             f"{self.star_limit_mag}")
        check_positive(self.pointing_error_arcsec, "pointing_error_arcsec", allow_zero=True)
        check_positive(self.roll_error_deg, "roll_error_deg", allow_zero=True)
        if not 0.0 <= self.cloud_transmission <= 1.0:
            raise ValueError(f"cloud_transmission must lie in [0, 1], got "
                             f"{self.cloud_transmission}")
        if not all(len(c) == 4 for c in self.cloud_frames):
            raise ValueError("cloud_frames must hold (station, field, visit, frame) tuples")
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
    def astrometry_limit(self) -> float:
        """Faintest star of the chain's catalogue (G): ``astrometry_mag``, or chosen from the
        field when it is None (see the class notes)."""
        if self.astrometry_mag is not None:
            return float(self.astrometry_mag)
        _, b = _sky_counts()
        ref = _REF_DEPTH_MAG + np.log10(_REF_FIELD_DEG2 / self.fov_deg ** 2) / b
        return float(max(self.catalogue_mag, min(ref, star_detection_limit_mag(self))))

    @property
    def render_limit(self) -> float:
        """Faintest star rendered (G): ``star_limit_mag`` or ``astrometry_limit + 1``."""
        if self.star_limit_mag is not None:
            return float(self.star_limit_mag)
        return self.astrometry_limit + 1.0

    @property
    def fov_deg(self) -> float:
        """Field of view (degrees)."""
        return self.size_px * self.pixel_scale_arcsec / 3600.0

    @property
    def focal_px(self) -> float:
        """Focal length in pixels."""
        return ARCSEC_PER_RAD / self.pixel_scale_arcsec

    @property
    def object_names(self) -> tuple[str, ...]:
        """Labels of every object: the field objects, then the cluster members."""
        return tuple(str(n) for n in self.norad_ids) + tuple(m.name for m in self.cluster)

    @property
    def field_of(self) -> tuple[int, ...]:
        """Index (into ``norad_ids``) of the field each object is seen in."""
        return tuple(range(len(self.norad_ids))) + tuple(self.norad_ids.index(m.parent)
                                                          for m in self.cluster)


#: the reference field for the catalogue depth: 256 px × 15″ holds ≈ 30 stars to G ≤ 11.5
_REF_DEPTH_MAG = 11.5
_REF_FIELD_DEG2 = (256 * 15.0 / 3600.0) ** 2
#: a catalogue star must reach this trail matched-filter SNR to count as detectable
DETECT_MARGIN = 2.0


@lru_cache(maxsize=1)
def _sky_counts() -> tuple[float, float]:
    """Whole-sky ``log₁₀ N(<G) = a + b G`` of the packaged Gaia extract over G 7–10, with
    ``a`` per square degree."""
    from eotrack.astro import load_catalog
    from eotrack.imaging.starfield import star_count_slope

    a, b = star_count_slope(load_catalog().mag, 7.0, 10.0)
    return a - np.log10(4 * np.pi * (180 / np.pi) ** 2), b


def star_trail_px(config: CapstoneConfig, dec_deg: float = 0.0) -> float:
    """Length (px) of a star's trail over one exposure of the GEO-staring camera."""
    return float(EARTH_RATE_RAD_S * config.exposure_s * ARCSEC_PER_RAD
                 * np.cos(np.radians(dec_deg)) / config.pixel_scale_arcsec)


def star_snr(config: CapstoneConfig, mag) -> np.ndarray:
    """Matched-filter SNR of a star of magnitude ``mag`` drawn as its trail over one exposure
    (at the equator): ``F / sqrt(F + (sky + read²) A)``, ``A = 1 / Σ k²`` the noise-equivalent
    area of the unit-sum trail template (the filter :func:`eotrack.imaging.trails.extract_trailed`
    applies; a point's ``4π σ²`` when the trail is short)."""
    from eotrack.imaging.trails import trail_profile

    s = config.psf_sigma_px
    L = star_trail_px(config)
    h = int(np.ceil(L / 2 + 4 * s))
    g = np.arange(-h, h + 1, dtype=float)
    k = trail_profile(g[None, :], g[:, None], (L, 0.0), s)
    area = float(k.sum() ** 2 / (k ** 2).sum())
    f = 10 ** (-0.4 * (np.asarray(mag, float) - config.zero_point_mag))
    return f / np.sqrt(f + (config.sky_e + config.read_noise_e ** 2) * area)


def star_detection_limit_mag(config: CapstoneConfig) -> float:
    """Faintest star (G) whose :func:`star_snr` reaches ``detect_sigma + DETECT_MARGIN``."""
    m = np.linspace(5.0, 22.0, 1701)
    ok = star_snr(config, m) >= config.detect_sigma + DETECT_MARGIN
    return float(m[ok].max()) if ok.any() else float(m[0])


def expected_field_stars(config: CapstoneConfig, mag: float | None = None) -> float:
    """Expected catalogue stars per field brighter than ``mag`` (default: the fainter-bound
    of ``astrometry_limit`` and the detection limit) from the whole-sky counts — fields at low
    galactic latitude hold more, near the poles fewer (≈ ×2 either way)."""
    a, b = _sky_counts()
    m = min(config.astrometry_limit, star_detection_limit_mag(config)) if mag is None \
        else float(mag)
    return float(10 ** (a + b * m) * config.fov_deg ** 2)


#: fewer expected detectable catalogue stars per field than this warns (a plate solution
#: needs 6 matched stars; a field of half the average density must still hold them)
MIN_FIELD_STARS = 12.0


def check_astrometry(config: CapstoneConfig) -> str | None:
    """A warning message when the configuration's frames cannot hold enough detectable
    catalogue stars for a plate solution (``expected_field_stars < MIN_FIELD_STARS``), else
    None. :func:`make_plan` emits it as a :class:`UserWarning`."""
    n = expected_field_stars(config)
    if n >= MIN_FIELD_STARS:
        return None
    lim = star_detection_limit_mag(config)
    return (f"stage 'astrometry' will fail in most frames: a {config.fov_deg:.2f}° field "
            f"({config.size_px} px × {config.pixel_scale_arcsec:g}″) holds about {n:.1f} "
            f"detectable catalogue stars (G ≤ {min(config.astrometry_limit, lim):.1f}; the "
            f"trailed stars are detected to G ≈ {lim:.1f} against {config.sky_e:g} e⁻/px), "
            f"fewer than {MIN_FIELD_STARS:g} — widen the field (size_px), lower the sky "
            "background per pixel (sky_e) or, if the catalogue is the limit, deepen "
            "astrometry_mag")


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
    """One visit of one field by one station: ``n`` frames.

    Attributes
    ----------
    station, obj, visit
        Indices into the config's stations, field objects (``norad_ids``) and the visit grid.
    objs
        Every object in the field (the field object first, then its cluster members), as
        indices into :attr:`NightPlan.names`.
    times_s
        Mid-exposure times of the frames (s from the night's start).
    R
        TRUE world (GCRS) → camera rotations ``(n, 3, 3)`` at mid-exposure (GEO-staring: the
        camera turns with the Earth, so the stars drift). For rendering and scoring only.
    R_end
        The same at the end of each exposure (for the star trails; rendering only).
    R_believed
        The mount's BELIEVED attitude ``(n, 3, 3)``: the commanded pointing at the field
        object's TLE prediction. The true attitude is this rotated by the mount error. The
        chain starts its plate solution from it.
    c_km
        Station GCRS positions ``(n, 3)``.
    target_xy
        True pixel position of each field object per frame ``(n_objs, n, 2)``.
    target_flux
        Electrons per frame ``(n_objs, n)`` (0 in umbra).
    target_gcrs_km
        True object positions ``(n_objs, n, 3)``.
    """

    station: int
    obj: int
    visit: int
    objs: tuple[int, ...]
    times_s: np.ndarray
    R: np.ndarray
    R_end: np.ndarray
    R_believed: np.ndarray
    c_km: np.ndarray
    target_xy: np.ndarray
    target_flux: np.ndarray
    target_gcrs_km: np.ndarray

    def camera(self, k: int, K: np.ndarray, size: int) -> PinholeCamera:
        """The TRUE camera of frame ``k`` (rendering and scoring only)."""
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
        Every burst to observe (station dark, field object above the elevation limit).
    names
        Object labels (field objects, then cluster members).
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

    def tle_direction(self, obj: int, station: int, t_s: np.ndarray) -> np.ndarray:
        """The station's TLE prediction of the object's unit topocentric direction ``(n, 3)``
        — what the chain may use (catalogue correlation, the χ² association model). The
        truth of this sky *is* the SGP4 propagation of the TLEs, so it equals
        :meth:`truth_direction` here (errata); a real TLE is off by tens of arcseconds."""
        return self.truth_direction(obj, station, t_s)

    def tle_sunlit(self, obj: int, t_s: float) -> bool:
        """The object is predicted outside the umbra at ``t_s`` (its TLE orbit and the Sun:
        the shadow grid, nearest minute) — the station's own knowledge."""
        return bool(np.round(np.interp(float(t_s), self.grid_s, self.grid_shadow[obj])) != 2)


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

    Warns
    -----
    UserWarning
        The frames cannot hold enough detectable catalogue stars for a plate solution
        (:func:`check_astrometry`; the message names the settings to change).
    """
    cfg = CapstoneConfig() if config is None else config
    if not isinstance(cfg, CapstoneConfig):
        raise TypeError(f"config must be a CapstoneConfig, got {type(cfg).__name__}")
    msg = check_astrometry(cfg)
    if msg is not None:
        warnings.warn(msg, UserWarning, stacklevel=2)
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
    sats = [satellite(n) for n in cfg.norad_ids] + [member_satellite(m) for m in cfg.cluster]
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
    offs_rng = np.random.default_rng(cfg.seed)  # deterministic mount errors
    n_st, n_fld = len(stations), len(cfg.norad_ids)
    offsets = offs_rng.uniform(-1, 1, (n_st, n_fld, n_vis, 2)) * cfg.pointing_error_arcsec \
        / ARCSEC_PER_RAD
    rolls = np.radians(offs_rng.uniform(-1, 1, (n_st, n_fld, n_vis)) * cfg.roll_error_deg)
    members = [[o for o, fo in enumerate(cfg.field_of) if fo == fld] for fld in range(n_fld)]
    k = np.arange(cfg.burst_frames)
    for j, tv in enumerate(visit_s):
        t_mid = tv + k * cfg.frame_interval_s
        t_end = t_mid + cfg.exposure_s / 2
        for s in range(n_st):
            if not dark[s, j]:
                continue
            c_mid = at(t_mid, st_km[s])
            spin_mid = np.transpose(_rot_z(EARTH_RATE_RAD_S * (t_mid - t_mid[0])), (0, 2, 1))
            spin_end = np.transpose(_rot_z(EARTH_RATE_RAD_S * (t_end - t_mid[0])), (0, 2, 1))
            for fld in range(n_fld):
                if elev[s, fld, j] <= cfg.min_elevation_deg:
                    continue
                objs = members[fld]
                r_mid = np.stack([at(t_mid, obj_km[o]) for o in objs])
                # the mount is commanded to (and believes it points at) the TLE prediction
                Rb0 = _look_at(r_mid[0, 0] - c_mid[0])
                # its true attitude: off by a small rotation in x/y and a roll about z
                bore = Rb0.T @ np.array([offsets[s, fld, j, 0], offsets[s, fld, j, 1], 1.0])
                R0 = _rot_z(np.array(rolls[s, fld, j])) @ _look_at(bore)
                # GEO staring: camera fixed to the Earth → rotates about z with the Earth
                R_mid = R0 @ spin_mid
                R_end = R0 @ spin_end
                R_bel = Rb0 @ spin_mid
                dcam = np.einsum("kij,okj->oki", R_mid, r_mid - c_mid[None])
                xy = f * dcam[..., :2] / dcam[..., 2:3] + K[0, 2]
                sh = np.stack([np.round(np.interp(t_mid, grid_s, shadow_g[o])).astype(int)
                               for o in objs])
                flux = 10 ** (-0.4 * (cfg.target_mag - cfg.zero_point_mag)) * \
                    np.where(sh == UMBRA, 0.0, np.where(sh == PENUMBRA, 0.5, 1.0))
                bursts.append(Burst(s, fld, j, tuple(objs), t_mid, R_mid, R_end, R_bel, c_mid,
                                    xy, flux, r_mid))
    return NightPlan(cfg, t0, visit_s, dark, elev, shadow, grid_s, shadow_g, obj_km, st_km,
                     tuple(bursts), cfg.object_names)
