"""Scenario of Huang, Zhang & Feng (Tables 1–3): sensors, objects, the error model and one draw.

Four LEO satellites (Table 1 elements, two-body states at 2019-04-01 04:00:00 UTC, J2000 ≈
GCRS), each with a 2°×2°, 512×512 star sensor (Table 2), and nine GEO objects. The objects and
pointings are *built* from the paper's Table 3: sensor 4 sees all nine, so each object is placed
where sensor 4's line of sight through its Table 3 pixel meets the GEO shell (sensor 4 aimed so
that GEO1 lands on its Table 5 true position); sensors 1–3 are then turned to the rotation that
best reproduces their Table 3 pixels while showing exactly the objects Table 3 lists (25 px
margins). Table 3 is not geometrically consistent — no attitude of sensors 1–3 meets their
pixels, even without the visibility constraint — so the pixels of maps 1–3 differ from the
paper's (the notebook's Table 3 section measures by how much); the visibility pattern is
exact. GEO5 therefore follows Table 3, not Table 5 (the two disagree; see the notebook).

Errors (§2.1): attitude angles (yaw, pitch, roll of eq. 4) uniform within ±1′, positions uniform
in a 0.2 km ball, centroid jitter 10 µrad rms per axis (the paper's "10 mrad" is an erratum),
three false targets per map (the paper does not give the number), lens distortion in the true
projection (ignored by the associator, as in the paper).
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from functools import lru_cache
from itertools import combinations

import numpy as np
import pandas as pd
from scipy.optimize import least_squares
from scipy.spatial.transform import Rotation

from eotrack.astro.twobody import elements_to_state, line_of_sight_clear, place_on_shell
from eotrack.geometry.camera import PinholeCamera, intrinsics_from_fov
from eotrack.geometry.distortion import opencv_coefficients
from eotrack.geometry.rotations import euler_321_from_matrix, look_at, rotation_321
from eotrack.repro import load_claims
from eotrack.validation import check_generator, check_int, check_positive

__all__ = [
    "ARCMIN",
    "EPOCH_UTC",
    "PAIRS",
    "PAIR_LABELS",
    "SLUG",
    "ST_APS2_2",
    "TITLE",
    "ErrorConfig",
    "FrameChain",
    "Observation",
    "Scenario",
    "SensorConfig",
    "build_scenario",
    "draw_observation",
    "frame_chain",
    "nominal_draw",
    "orbit_frame",
    "perturbed_scenario",
    "repointed_scenario",
    "sensor_table",
]

SLUG = "epipolar"
TITLE = ("Huang Q.S., Zhang Y.S., Feng F. Space target synchronization association method under "
         "distributed star sensors. Chinese Journal of Scientific Instrument. "
         "DOI 10.19650/j.cnki.cjsi.J1905157")
EPOCH_UTC = "2019-04-01T04:00:00"
PAIRS: tuple[tuple[int, int], ...] = tuple(combinations(range(4), 2))  # (a)…(f) of Fig. 4
PAIR_LABELS = ("4(a) 1-2", "4(b) 1-3", "4(c) 1-4", "4(d) 2-3", "4(e) 2-4", "4(f) 3-4")
ARCMIN = np.pi / (180 * 60)


# --------------------------------------------------------------------------- configuration
def _table2() -> dict:
    """Table 2 as printed (``papers_repro/epipolar/claims.toml``, claim ``epipolar.table2``)."""
    return load_claims(SLUG)["epipolar.table2"].paper


_T2 = _table2()["experiment"]


@dataclass(frozen=True)
class SensorConfig:
    """A star sensor; the defaults are the experiment's sensor of Table 2 (right column), read
    from ``claims.toml`` (claim ``epipolar.table2``)."""

    fov_deg: float = float(_T2["fov_deg"])
    resolution_px: int = int(_T2["resolution_px"])
    principal_point_px: tuple[float, float] = tuple(float(x) for x in _T2["principal_point_px"])
    radial: tuple[float, float] = tuple(float(x) for x in _T2["radial"])
    tangential: tuple[float, float] = tuple(float(x) for x in _T2["tangential"])
    accuracy_xy_arcsec: float = float(_T2["accuracy_xy_arcsec"])
    accuracy_z_arcsec: float = float(_T2["accuracy_z_arcsec"])
    nea_arcsec: float = float(_T2["nea_arcsec"])
    limit_mag: float = float(_T2["limit_mag"])

    def __post_init__(self) -> None:
        check_positive(self.fov_deg, "fov_deg")
        check_int(self.resolution_px, "resolution_px", min_value=2)

    @property
    def K(self) -> np.ndarray:
        """Intrinsics from field of view and resolution (eq. 7)."""
        n = self.resolution_px
        return intrinsics_from_fov(self.fov_deg, self.fov_deg, n, n, *self.principal_point_px)

    @property
    def dist(self) -> np.ndarray:
        """OpenCV distortion coefficients (k1, k2, p1, p2)."""
        return opencv_coefficients(self.radial, self.tangential)


@dataclass(frozen=True)
class ErrorConfig:
    """Errors injected into a draw (§2.1; defaults are the paper's, jitter per the erratum).

    Attributes
    ----------
    attitude_arcmin
        Bound of the uniform noise on each attitude angle (yaw, pitch, roll).
    position_km
        Radius of the uniform ball of sensor-position noise.
    jitter_urad
        Line-of-sight jitter: centroid noise, rms per axis (µrad).
    n_false
        False targets per map (uniform over the image).
    quantize
        Report centroids rounded to whole pixels (as Table 3 prints them).
    """

    attitude_arcmin: float = 1.0
    position_km: float = 0.2
    jitter_urad: float = 10.0
    n_false: int = 3
    quantize: bool = False

    def __post_init__(self) -> None:
        check_positive(self.attitude_arcmin, "attitude_arcmin", allow_zero=True)
        check_positive(self.position_km, "position_km", allow_zero=True)
        check_positive(self.jitter_urad, "jitter_urad", allow_zero=True)
        check_int(self.n_false, "n_false", min_value=0)

    def noise_free(self) -> ErrorConfig:
        """Same false targets, no attitude/position/jitter noise."""
        return replace(self, attitude_arcmin=0.0, position_km=0.0, jitter_urad=0.0)


# --------------------------------------------------------------------------- scenario
@dataclass(frozen=True)
class Scenario:
    """The true geometry: sensors, objects and who sees whom."""

    cameras: tuple[PinholeCamera, ...]
    objects_km: np.ndarray
    visible: np.ndarray
    sat_km: np.ndarray
    names: tuple[str, ...]
    paper_px: np.ndarray
    los_clear: np.ndarray
    sensor: SensorConfig = field(default_factory=SensorConfig)

    def true_pixels(self) -> np.ndarray:
        """``(4, 9, 2)`` pixel positions of every object in every map (distorted lens)."""
        return np.stack([cam.project(self.objects_km) for cam in self.cameras])


def _paper_tables() -> tuple[dict, np.ndarray, list[str]]:
    claims = load_claims(SLUG)
    t1 = claims["epipolar.table1"].paper
    t3 = claims["epipolar.table3"].paper
    px = np.full((4, len(t3["targets"]), 2), np.nan)
    for k in range(4):
        for j, uv in enumerate(t3[f"map{k + 1}"]):
            if len(uv):
                px[k, j] = uv
    return t1, px, list(t3["targets"])


def _min_rotation(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Smallest rotation taking unit vector a to unit vector b."""
    axis = np.cross(a, b)
    s = np.linalg.norm(axis)
    if s < 1e-15:
        return np.eye(3)
    ang = np.arctan2(s, float(a @ b))
    return Rotation.from_rotvec(axis / s * ang).as_matrix()


def _kabsch(w: np.ndarray, a: np.ndarray) -> np.ndarray:
    """Rotation R minimising Σ |a_i − R w_i|² (rows are unit vectors)."""
    u, _, vt = np.linalg.svd(w.T @ a)
    d = np.diag([1.0, 1.0, np.sign(np.linalg.det(vt.T @ u.T))])
    return vt.T @ d @ u.T


def _fit_attitude(X: np.ndarray, c: np.ndarray, K: np.ndarray, px: np.ndarray,
                  visible: np.ndarray, size: int, margin: float = 25.0) -> np.ndarray:
    """World→camera rotation matching the listed pixels with the visibility pattern enforced."""
    idx = np.flatnonzero(visible)
    rays = np.linalg.solve(K, np.column_stack([px[idx], np.ones(len(idx))]).T).T
    rays /= np.linalg.norm(rays, axis=1, keepdims=True)
    w = X[idx] - c
    w /= np.linalg.norm(w, axis=1, keepdims=True)
    r0 = _kabsch(w, rays)
    Xc0 = X - c

    def residuals(x: np.ndarray) -> np.ndarray:
        R = Rotation.from_rotvec(x).as_matrix() @ r0
        Xc = Xc0 @ R.T
        uv = Xc[:, :2] / Xc[:, 2:] @ K[:2, :2].T + K[:2, 2]
        e = (uv - np.nan_to_num(px))[visible].ravel()
        edge = np.stack([uv[:, 0], size - uv[:, 0], uv[:, 1], size - uv[:, 1]])
        inside_out = np.min(edge + margin, axis=0)  # > 0: inside the grown box
        inside_in = np.min(edge - margin, axis=0)  # > 0: inside the shrunk box
        pen = np.where(visible, np.maximum(0, -inside_in), np.maximum(0, inside_out))
        return np.concatenate([e, 50.0 * pen])

    best = None
    for roll in np.radians(np.arange(-40.0, 41.0, 20.0)):
        sol = least_squares(residuals, r0[2] * roll, x_scale=1e-3)
        if best is None or sol.cost < best.cost:
            best = sol
    return Rotation.from_rotvec(best.x).as_matrix() @ r0


@lru_cache(maxsize=4)
def build_scenario(sensor: SensorConfig = SensorConfig()) -> Scenario:
    """Build the Tables 1–3 scenario (deterministic, cached); see the module docstring.

    The objects and pointings are always those built from Table 3 with the paper's
    experiment sensor (``SensorConfig()``: Table 3's pixels are that sensor's). Another
    ``sensor`` views *the same* objects from the same pointings with its own intrinsics,
    image size and distortion; ``visible`` is then recomputed (who sees whom can differ from
    Table 3, e.g. a 20° field sees all nine objects in every map).
    """
    if not isinstance(sensor, SensorConfig):
        raise TypeError(f"sensor must be a SensorConfig, got {type(sensor).__name__}")
    paper = _paper_scenario()
    if sensor == SensorConfig():
        return paper
    n = sensor.resolution_px
    cams = tuple(PinholeCamera(sensor.K, c.R, c.c, (n, n), sensor.dist) for c in paper.cameras)
    seen = np.stack([cam.sees(paper.objects_km) for cam in cams])
    los_ok = line_of_sight_clear(paper.sat_km[:, None, :], paper.objects_km[None, :, :])
    return replace(paper, cameras=cams, visible=seen, los_clear=los_ok, sensor=sensor)


@lru_cache(maxsize=1)
def _paper_scenario() -> Scenario:
    """The scenario of Tables 1–3 with the paper's experiment sensor."""
    sensor = SensorConfig()
    t1, px, names = _paper_tables()
    sat, _ = elements_to_state(t1["a_km"], t1["e"], t1["i_deg"], t1["raan_deg"], t1["argp_deg"],
                               t1["nu_deg"])
    visible = ~np.isnan(px[..., 0])
    K = sensor.K
    n = sensor.resolution_px
    t5 = load_claims(SLUG)["epipolar.table5"].paper
    geo1 = np.asarray(t5["geo1_km"][-1], float)  # the paper's true GEO1 position (anchor)
    radius = float(np.linalg.norm(geo1))
    # sensor 4: boresight towards GEO1, image "up" = south so that GEO5 (below GEO1 in the
    # map-4 column of Table 3) lies north of GEO1 as in Table 5; then turned so that GEO1's
    # Table 3 pixel looks exactly at its Table 5 position.
    r4 = look_at(geo1 - sat[3], up=(0.0, 0.0, -1.0))
    pix = np.linalg.solve(K, np.append(px[3, 0], 1.0))
    pix /= np.linalg.norm(pix)
    los = r4 @ (geo1 - sat[3])
    r4 = _min_rotation(los / np.linalg.norm(los), pix) @ r4
    cam4 = PinholeCamera(K, r4, sat[3], (n, n), sensor.dist)
    objects = place_on_shell(sat[3], cam4.rays(px[3]), radius)
    cams = []
    for k in range(3):
        R = _fit_attitude(objects, sat[k], K, px[k], visible[k], n)
        cams.append(PinholeCamera(K, R, sat[k], (n, n), sensor.dist))
    cams.append(cam4)
    seen = np.stack([cam.sees(objects, margin_px=5.0) for cam in cams])
    if not np.array_equal(seen, visible):
        raise RuntimeError("scenario construction failed to reproduce Table 3's visibility")
    los_ok = line_of_sight_clear(sat[:, None, :], objects[None, :, :])
    return Scenario(tuple(cams), objects, visible, sat, tuple(names), px, los_ok, sensor)


# --------------------------------------------------------------------------- other placements
def repointed_scenario(scenario: Scenario, objects_km, *, margin_px: float = 25.0) -> Scenario:
    """The scenario with the objects moved to ``objects_km`` and every sensor re-pointed so that
    each map still sees exactly its Table 3 objects (``margin_px`` inside the edges).

    A sensor that still sees exactly its objects (5 px inside the edges, the check of
    :func:`build_scenario`) keeps its pointing; any other gets the least-squares rotation that
    keeps the objects as close as possible to their present pixels under the visibility
    constraint (the construction of :func:`build_scenario`): a moved object that leaves an
    image drags its sensor's pointing just far enough to bring it back. Raises ``ValueError`` for a wrong shape and
    ``RuntimeError`` if the visibility pattern cannot be kept.
    """
    X = np.asarray(objects_km, float)
    if X.shape != scenario.objects_km.shape or not np.all(np.isfinite(X)):
        raise ValueError(f"objects_km must be a finite array of shape "
                         f"{scenario.objects_km.shape}, got {X.shape}")
    m = check_positive(margin_px, "margin_px", allow_zero=True)
    cams = []
    for k, cam in enumerate(scenario.cameras):
        if np.array_equal(cam.sees(X, margin_px=min(5.0, m)), scenario.visible[k]):
            cams.append(cam)  # still sees exactly its objects: pointing unchanged
            continue
        target = cam.project(X)
        R = _fit_attitude(X, cam.c, cam.K, target, scenario.visible[k], cam.size[0], margin=m)
        cams.append(PinholeCamera(cam.K, R, cam.c, cam.size, cam.dist))
    seen = np.stack([cam.sees(X, margin_px=min(5.0, m)) for cam in cams])
    if not np.array_equal(seen, scenario.visible):
        raise RuntimeError("re-pointing cannot keep Table 3's visibility for these positions")
    los_ok = line_of_sight_clear(scenario.sat_km[:, None, :], X[None, :, :])
    return replace(scenario, cameras=tuple(cams), objects_km=X, los_clear=los_ok)


def perturbed_scenario(scenario: Scenario, rng: np.random.Generator, *, max_km: float = 15.0,
                       keep: tuple[int, ...] = (0,), margin_px: float = 10.0,
                       max_tries: int = 1000) -> Scenario:
    """The scenario with every object not in ``keep`` moved by a uniform offset within
    ±``max_km`` per axis, sensors unchanged, redrawn until every map sees exactly its Table 3
    objects (``margin_px`` inside the edges). Raises ``RuntimeError`` after ``max_tries``."""
    check_generator(rng)
    check_positive(max_km, "max_km")
    n_tries = check_int(max_tries, "max_tries", min_value=1)
    move = np.ones(len(scenario.objects_km), bool)
    move[list(keep)] = False
    for _ in range(n_tries):
        X = scenario.objects_km.copy()
        X[move] += rng.uniform(-max_km, max_km, (int(move.sum()), 3))
        if all(np.array_equal(c.sees(X, margin_px=margin_px), scenario.visible[k])
               for k, c in enumerate(scenario.cameras)):
            los_ok = line_of_sight_clear(scenario.sat_km[:, None, :], X[None, :, :])
            return replace(scenario, objects_km=X, los_clear=los_ok)
    raise RuntimeError(f"no placement within ±{max_km:g} km kept the visibility pattern "
                       f"in {n_tries} tries")


# --------------------------------------------------------------------------- one draw
@dataclass(frozen=True)
class Observation:
    """One draw: centroids per map, their truth labels (object index, −1 = false target), and
    the cameras as the associator knows them (noisy attitude and position, no distortion)."""

    points: tuple[np.ndarray, ...]
    labels: tuple[np.ndarray, ...]
    cameras: tuple[PinholeCamera, ...]


def draw_observation(rng: np.random.Generator, scenario: Scenario,
                     errors: ErrorConfig = ErrorConfig()) -> Observation:
    """Draw false targets, attitude/position errors and centroid jitter for one instant.

    The false targets are drawn first, so a noise-free draw with the same seed
    (``errors.noise_free()``) has the same false targets.
    """
    check_generator(rng)
    n_maps = len(scenario.cameras)
    size = scenario.cameras[0].size
    false_xy = [np.column_stack([rng.uniform(-0.5, size[0] - 0.5, errors.n_false),
                                 rng.uniform(-0.5, size[1] - 0.5, errors.n_false)])
                for _ in range(n_maps)]
    att = rng.uniform(-1.0, 1.0, (n_maps, 3)) * errors.attitude_arcmin * ARCMIN
    v = rng.normal(size=(n_maps, 3))
    v /= np.linalg.norm(v, axis=1, keepdims=True)
    pos = v * (errors.position_km * rng.uniform(size=(n_maps, 1)) ** (1 / 3))
    true_px = scenario.true_pixels()
    pts, labels, cams = [], [], []
    for k, cam in enumerate(scenario.cameras):
        idx = np.flatnonzero(scenario.visible[k])
        sigma = errors.jitter_urad * 1e-6 * cam.K[0, 0]
        xy = true_px[k, idx] + rng.normal(0.0, 1.0, (len(idx), 2)) * sigma
        allxy = np.concatenate([xy, false_xy[k]])
        lab = np.concatenate([idx, -np.ones(errors.n_false, int)])
        order = rng.permutation(len(lab))
        allxy, lab = allxy[order], lab[order]
        if errors.quantize:
            allxy = np.rint(allxy)
        y, p, r = euler_321_from_matrix(cam.R)
        R_meas = rotation_321(y + att[k, 0], p + att[k, 1], r + att[k, 2])
        pts.append(allxy)
        labels.append(lab)
        cams.append(PinholeCamera(cam.K, R_meas, cam.c + pos[k], cam.size, None))
    return Observation(tuple(pts), tuple(labels), tuple(cams))




def nominal_draw(scenario: Scenario, seed: int = 2019, errors: ErrorConfig = ErrorConfig()
                 ) -> tuple[Observation, Observation]:
    """The displayed draw (noisy) and its noise-free twin (same false targets)."""
    obs = draw_observation(np.random.default_rng(seed), scenario, errors)
    obs0 = draw_observation(np.random.default_rng(seed), scenario, errors.noise_free())
    return obs, obs0


# --------------------------------------------------------------------------- Table 2
#: The reference sensor of Table 2 (left column, from ``claims.toml``); the experiment's sensor
#: is ``SensorConfig()``.
ST_APS2_2 = SensorConfig(fov_deg=float(_table2()["reference"]["fov_deg"]),
                         resolution_px=int(_table2()["reference"]["resolution_px"]),
                         principal_point_px=tuple(float(x) for x in
                                                  _table2()["reference"]["principal_point_px"]),
                         limit_mag=float(_table2()["reference"]["limit_mag"]))

def sensor_table(sensors: dict[str, SensorConfig] | None = None) -> pd.DataFrame:
    """Table 2 from the configs: one column per sensor, with the derived focal length (eq. 7)
    and pixel scale."""
    if sensors is None:
        t2 = _table2()
        sensors = {t2["reference"]["name"]: ST_APS2_2, t2["experiment"]["name"]: SensorConfig()}
    cols = {}
    for name, s in sensors.items():
        if not isinstance(s, SensorConfig):
            raise TypeError(f"sensors[{name!r}] must be a SensorConfig, got {type(s).__name__}")
        fx = float(s.K[0, 0])
        cols[name] = {
            "field of view (°)": f"{s.fov_deg:g} × {s.fov_deg:g}",
            "resolution (px)": f"{s.resolution_px} × {s.resolution_px}",
            "accuracy X, Y / Z (″)": f"{s.accuracy_xy_arcsec:g} / {s.accuracy_z_arcsec:g}",
            "sensitivity (Mv)": f"{s.limit_mag:g}",
            "principal point u0, v0 (px)": f"({s.principal_point_px[0]:g}, "
                                           f"{s.principal_point_px[1]:g})",
            "radial distortion p1, p2": f"{s.radial[0]:.3g}, {s.radial[1]:.3g}",
            "tangential distortion q1, q2": f"{s.tangential[0]:.3g}, {s.tangential[1]:.3g}",
            "noise-equivalent angle (″)": f"{s.nea_arcsec:g}",
            "f/dx from eq. (7) (px)": f"{fx:.1f}",
            "pixel scale (″/px)": f"{np.degrees(1 / fx) * 3600:.2f}",
        }
    return pd.DataFrame(cols)


# --------------------------------------------------------------------------- frames of eq. (4)
def orbit_frame(r_km, v_km_s) -> np.ndarray:
    """J2000 → orbit (LVLH) rotation: z to nadir, y against the orbit normal, x ≈ along track."""
    r = np.asarray(r_km, float)
    v = np.asarray(v_km_s, float)
    if r.shape != (3,) or v.shape != (3,):
        raise ValueError(f"r_km and v_km_s must be 3-vectors, got {r.shape} and {v.shape}")
    h = np.cross(r, v)
    if not np.all(np.isfinite(h)) or np.linalg.norm(h) == 0:
        raise ValueError("r_km and v_km_s must be finite and not parallel")
    z = -r / np.linalg.norm(r)
    y = -h / np.linalg.norm(h)
    return np.stack([np.cross(y, z), y, z])


@dataclass(frozen=True)
class FrameChain:
    """J2000 → orbit → body → sensor: ``R_sensor = mounting · body_from_orbit · orbit``."""

    orbit: np.ndarray
    body_from_orbit: np.ndarray
    mounting: np.ndarray
    yaw_pitch_roll_rad: tuple[float, float, float]
    position_km: np.ndarray

    @property
    def body(self) -> np.ndarray:
        """J2000 → body."""
        return self.body_from_orbit @ self.orbit

    @property
    def sensor(self) -> np.ndarray:
        """J2000 → sensor (the camera's ``R``)."""
        return self.mounting @ self.body


def frame_chain(scenario: Scenario, k: int, *,
                mounting_ypr_deg: tuple[float, float, float] = (0.0, 20.0, 0.0)) -> FrameChain:
    """Split sensor ``k``'s J2000 → sensor rotation into the chain of eq. (4).

    The orbit frame follows from the Table 1 state; the sensor's mounting on the body is not
    given in the paper, so an illustrative one is assumed (``mounting_ypr_deg``, passed to
    :func:`~eotrack.geometry.rotation_321`); the body attitude angles (Y, P, R) of eq. (4) are
    then whatever makes the product equal the camera's rotation. Only the product enters F.
    """
    k = check_int(k, "k", min_value=0)
    if k >= len(scenario.cameras):
        raise ValueError(f"k must be < {len(scenario.cameras)}, got {k}")
    t1 = load_claims(SLUG)["epipolar.table1"].paper
    r, v = elements_to_state(t1["a_km"], t1["e"], t1["i_deg"], t1["raan_deg"], t1["argp_deg"],
                             t1["nu_deg"])
    orbit = orbit_frame(r[k], v[k])
    mount = rotation_321(*np.radians(np.asarray(mounting_ypr_deg, float)))
    body_from_orbit = mount.T @ scenario.cameras[k].R @ orbit.T
    ypr = tuple(float(x) for x in euler_321_from_matrix(body_from_orbit))
    return FrameChain(orbit, rotation_321(*ypr), mount, ypr, r[k])
