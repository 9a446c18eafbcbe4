"""Astrometric calibration of one frame: match its stars to the catalogue, fit a TAN plate solution.

A station knows only where its mount *believes* it points — off by up to a few arcminutes and a
little in roll. It gets its angles from the stars: detected centroids are matched to the Gaia
extract (:mod:`eotrack.astro.catalog`) starting from that believed pointing, and a gnomonic (TAN)
World Coordinate System is fitted to the matched pairs, sigma-clipped — by default in closed
form (the same model and, to ``O(ξ²)``, the same objective as astropy's
:func:`astropy.wcs.utils.fit_wcs_from_points`, which ``fitter="astropy"`` calls instead).

:func:`solve_plate` works in three steps, all vectorised (k-d trees, batched linear algebra):

1. **Offset vote.** For each roll angle of a small grid, every (detection, predicted
   catalogue star) pair closer than the largest pointing error gives a candidate shift; the
   shift shared by the most pairs (counted with a k-d tree, no histogram bins) is the pointing
   error. Chance pairs spread their shifts over the whole search disc, true pairs pile up
   within the centroid noise, so false detections, uncatalogued stars and missed stars only
   raise the vote's background. The peak must stand clear of that background (a Poisson
   bound over all pairs and rolls), or the frame is refused.
2. **Robust start.** The pairs within the match radius after that shift are screened by a
   least-median-of-squares fit of a *similarity* (scale, rotation, shift — a camera with
   square pixels) over all pairs of pairs, so that up to half of them may be wrong.
3. **TAN fit with clipping.** The TAN model (CD matrix and CRPIX, CRVAL at the frame centre)
   is fitted to the inliers — in closed form in the tangent plane, or with
   :func:`astropy.wcs.utils.fit_wcs_from_points` (``fitter="astropy"``) — rejected pairs are
   re-admitted if the fit now accepts them, then the worst pair is dropped while it exceeds
   ``clip_sigma`` robust σ; every detection is re-matched with the fit and the round repeated
   until the matched set is stable.

Conventions: pixel coordinates ``(x = column, y = row)``, 0-based with pixel centres at integers
(astropy's ``origin=0`` and :func:`eotrack.imaging.extract_stars`); RA/Dec in degrees in the
catalogue's frame (ICRS, astrometric). A pinhole camera ``(K, R)`` of :mod:`eotrack.geometry` is
exactly a TAN WCS (:func:`wcs_from_camera`, :func:`camera_from_wcs`).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np
from astropy.wcs import WCS
from scipy.spatial import cKDTree

from eotrack.validation import (
    as_finite_array,
    as_points,
    check_choice,
    check_generator,
    check_int,
    check_positive,
)

from .catalog import StarCatalog, load_catalog

__all__ = [
    "PlateSolution",
    "PlateSolveError",
    "axis_rotation",
    "camera_from_wcs",
    "catalog_in_field",
    "look_at_radec",
    "mount_error_rotation",
    "pixel_scale_arcsec",
    "solve_plate",
    "synthetic_plate_scene",
    "wcs_from_camera",
]

ARCSEC_PER_DEG = 3600.0
_REASONS = ("too_few_detections", "too_few_catalogue_stars", "no_consistent_match",
            "ambiguous_match", "too_few_matches", "poor_fit")


class PlateSolveError(ValueError):
    """A frame's plate solution failed; ``reason`` says why (one of the codes below).

    ``too_few_detections`` (a nearly empty frame: clouds, a wrong exposure),
    ``too_few_catalogue_stars`` (a sparse field or a catalogue too shallow),
    ``no_consistent_match`` (no pointing offset is shared by enough star pairs: the pointing
    error is larger than searched, the wrong catalogue, or only noise detected),
    ``ambiguous_match`` (a second, distinct offset is shared by nearly as many pairs — e.g.
    stars split into several detections each along their trails),
    ``too_few_matches`` (fewer than ``min_stars`` stars survive the sigma clipping),
    ``poor_fit`` (the fitted WCS does not reproduce the stars).
    """

    def __init__(self, reason: str, message: str) -> None:
        if reason not in _REASONS:  # pragma: no cover - internal misuse
            raise ValueError(f"unknown PlateSolveError reason {reason!r}")
        super().__init__(message)
        self.reason = reason


# ------------------------------------------------------------------------------ geometry
def _unit(ra_deg: np.ndarray, dec_deg: np.ndarray) -> np.ndarray:
    ra, de = np.radians(ra_deg), np.radians(dec_deg)
    return np.stack([np.cos(de) * np.cos(ra), np.cos(de) * np.sin(ra), np.sin(de)], -1)


def _radec(v: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    v = v / np.linalg.norm(v, axis=-1, keepdims=True)
    return (np.degrees(np.arctan2(v[..., 1], v[..., 0])) % 360.0,
            np.degrees(np.arcsin(np.clip(v[..., 2], -1.0, 1.0))))


def _separation_arcsec(ra1, dec1, ra2, dec2) -> np.ndarray:
    """Great-circle angle (″) between two sets of positions (degrees), element-wise."""
    a, b = _unit(ra1, dec1), _unit(ra2, dec2)
    cross = np.linalg.norm(np.cross(a, b), axis=-1)
    return np.degrees(np.arctan2(cross, np.sum(a * b, -1))) * ARCSEC_PER_DEG


def _tangent_basis(ra_deg: float, dec_deg: float) -> np.ndarray:
    """Rows: east, north, and the direction itself at (ra, dec)."""
    a, d = np.radians(ra_deg), np.radians(dec_deg)
    e = np.array([-np.sin(a), np.cos(a), 0.0])
    n = np.array([-np.sin(d) * np.cos(a), -np.sin(d) * np.sin(a), np.cos(d)])
    z = np.array([np.cos(d) * np.cos(a), np.cos(d) * np.sin(a), np.sin(d)])
    return np.stack([e, n, z])


def _check_wcs(wcs: Any, name: str) -> WCS:
    if not isinstance(wcs, WCS):
        raise TypeError(f"{name} must be an astropy.wcs.WCS, got {type(wcs).__name__}")
    if wcs.naxis != 2 or not wcs.has_celestial:
        raise ValueError(f"{name} must be a 2-axis celestial WCS (RA---TAN/DEC--TAN or similar), "
                         f"got naxis={wcs.naxis}, ctype={list(wcs.wcs.ctype)}")
    if wcs.wcs.lng != 0 or wcs.wcs.lat != 1:
        raise ValueError(f"{name} must have the longitude (RA) axis first, got ctype "
                         f"{list(wcs.wcs.ctype)}")
    return wcs


def _check_shape(shape: Any, name: str) -> tuple[int, int]:
    if shape is None or len(shape) != 2:
        raise ValueError(f"{name} must be (ny, nx), got {shape!r}")
    return (check_int(shape[0], f"{name}[0]", min_value=1),
            check_int(shape[1], f"{name}[1]", min_value=1))


def pixel_scale_arcsec(wcs: WCS) -> float:
    """Mean plate scale of a celestial WCS (″/px): the square root of the CD determinant."""
    w = _check_wcs(wcs, "wcs")
    return float(np.sqrt(abs(np.linalg.det(w.pixel_scale_matrix))) * ARCSEC_PER_DEG)


def wcs_from_camera(K: Any, R: Any, image_shape: tuple[int, int]) -> WCS:
    """The TAN WCS that is exactly a pinhole camera.

    Parameters
    ----------
    K
        Intrinsics (3×3; any focal lengths and skew).
    R
        World → camera rotation whose rows are the camera's x, y and z (boresight) axes in the
        catalogue's frame (the convention of :mod:`eotrack.geometry.camera`).
    image_shape
        ``(ny, nx)`` of the frame (stored as the WCS's ``pixel_shape``).

    Returns
    -------
    astropy.wcs.WCS
        ``RA---TAN``/``DEC--TAN`` with CRVAL the boresight, CRPIX the principal point (1-based)
        and the CD matrix of the camera, so that ``wcs.world_to_pixel`` equals
        :func:`eotrack.geometry.project_directions` for every direction in front of the camera.

    Raises
    ------
    ValueError
        A boresight at a celestial pole (the TAN axes are undefined there) or bad ``K``/``R``.
    """
    from eotrack.geometry.camera import check_intrinsics
    from eotrack.geometry.rotations import check_rotation

    k = check_intrinsics(K)
    r = check_rotation(R, "R")
    ny, nx = _check_shape(image_shape, "image_shape")
    ra0, de0 = _radec(r[2])
    if np.cos(np.radians(de0)) < 1e-9:
        raise ValueError("R points the boresight at a celestial pole; wcs_from_camera needs a "
                         "boresight with |dec| < 90°")
    e, n, _ = _tangent_basis(float(ra0), float(de0))
    A = np.array([[r[0] @ e, r[0] @ n], [r[1] @ e, r[1] @ n]])
    B = k[:2, :2] @ A                      # px per radian of (ξ, η)
    w = WCS(naxis=2)
    w.wcs.ctype = ["RA---TAN", "DEC--TAN"]
    w.wcs.crval = [float(ra0), float(de0)]
    w.wcs.crpix = [k[0, 2] + 1.0, k[1, 2] + 1.0]
    w.wcs.cd = np.degrees(np.linalg.inv(B))
    w.wcs.radesys = "ICRS"
    w.wcs.set()
    w.pixel_shape = (nx, ny)
    return w


def camera_from_wcs(wcs: WCS) -> tuple[np.ndarray, np.ndarray]:
    """Intrinsics and attitude of the pinhole camera equivalent to a TAN WCS.

    The inverse of :func:`wcs_from_camera`: the principal point is CRPIX − 1, the boresight is
    CRVAL, and the CD matrix is split (RQ decomposition) into an upper-triangular ``K`` (focal
    lengths, skew; ``K[1, 1] < 0`` for a mirrored image) and a proper rotation, so that
    ``eotrack.geometry.project_directions(dirs, K, R)`` reproduces ``wcs.world_to_pixel``.
    Use it to give the epipolar stage (``fundamental_from_poses``) the plate solution.

    Parameters
    ----------
    wcs
        A celestial TAN WCS (SIP distortion terms, if any, are ignored).

    Returns
    -------
    K, R
        ``(3, 3)`` intrinsics and world → camera rotation (rows: camera x, y, z).
    """
    from scipy.linalg import rq

    w = _check_wcs(wcs, "wcs")
    if not all(c.endswith("-TAN") or c.endswith("-TAN-SIP") for c in w.wcs.ctype):
        raise ValueError(f"wcs must use the TAN projection, got ctype {list(w.wcs.ctype)}")
    cd = w.pixel_scale_matrix
    B = np.linalg.inv(np.radians(cd))      # px per radian
    Kp, Q = rq(B)
    if Kp[0, 0] < 0:
        D = np.diag([-1.0, 1.0])
        Kp, Q = Kp @ D, D @ Q
    if np.linalg.det(Q) < 0:
        D = np.diag([1.0, -1.0])
        Kp, Q = Kp @ D, D @ Q
    e, n, z = _tangent_basis(float(w.wcs.crval[0]), float(w.wcs.crval[1]))
    R = np.stack([Q[0, 0] * e + Q[0, 1] * n, Q[1, 0] * e + Q[1, 1] * n, z])
    K = np.array([[Kp[0, 0], Kp[0, 1], w.wcs.crpix[0] - 1.0],
                  [0.0, Kp[1, 1], w.wcs.crpix[1] - 1.0], [0.0, 0.0, 1.0]])
    return K, R


def catalog_in_field(wcs: WCS, image_shape: tuple[int, int] | None = None, *,
                     max_mag: float | None = 10.0, jyear: float | None = None,
                     margin_px: float = 0.0, catalog: StarCatalog | None = None) -> StarCatalog:
    """Catalogue stars that project inside a frame (plus a margin), brightest first.

    Parameters
    ----------
    wcs
        The frame's (believed or solved) celestial WCS.
    image_shape
        ``(ny, nx)``; default ``wcs.pixel_shape`` (reversed).
    max_mag
        Faintest magnitude kept (``None``: all).
    jyear
        Move positions to this Julian epoch by proper motion (default: the catalogue's J2016.0).
    margin_px
        Also keep stars up to this far outside the frame (e.g. the largest pointing error).
    catalog
        The catalogue (default :func:`eotrack.astro.load_catalog`).
    """
    w = _check_wcs(wcs, "wcs")
    if image_shape is None:
        if w.pixel_shape is None:
            raise ValueError("image_shape is needed: the wcs has no pixel_shape")
        image_shape = (w.pixel_shape[1], w.pixel_shape[0])
    ny, nx = _check_shape(image_shape, "image_shape")
    m = check_positive(margin_px, "margin_px", allow_zero=True)
    cat = load_catalog() if catalog is None else catalog
    if not isinstance(cat, StarCatalog):
        raise TypeError(f"catalog must be a StarCatalog, got {type(cat).__name__}")
    cx, cy = (nx - 1) / 2.0, (ny - 1) / 2.0
    ra_c, de_c = w.wcs_pix2world([[cx, cy]], 0)[0]
    radius_deg = (np.hypot(nx, ny) / 2.0 + m) * pixel_scale_arcsec(w) / ARCSEC_PER_DEG * 1.05
    radius_deg = min(radius_deg + 0.01, 80.0)  # + proper motion / rounding head-room
    tree = _sky_index(cat)
    chord = 2.0 * np.sin(np.radians(radius_deg) / 2.0)
    hits = np.sort(np.asarray(tree.query_ball_point(_unit(np.array(ra_c), np.array(de_c)),
                                                    chord), dtype=int))
    near = cat.select(hits)
    if max_mag is not None:
        near = near.select(near.mag <= float(max_mag))
    if jyear is not None:
        near = near.at_epoch(float(jyear))
    if len(near) == 0:
        return near
    x, y = w.wcs_world2pix(near.ra_deg, near.dec_deg, 0)
    inside = (np.isfinite(x) & np.isfinite(y) & (x >= -0.5 - m) & (x <= nx - 0.5 + m)
              & (y >= -0.5 - m) & (y <= ny - 0.5 + m))
    return near.select(inside)


_INDEX: dict[int, tuple[StarCatalog, cKDTree]] = {}


def _sky_index(cat: StarCatalog) -> cKDTree:
    """k-d tree of the catalogue's unit vectors, cached per catalogue object."""
    hit = _INDEX.get(id(cat))
    if hit is not None and hit[0] is cat:
        return hit[1]
    tree = cKDTree(cat.unit_vectors()) if len(cat) else cKDTree(np.zeros((1, 3)) + 2.0)
    if len(_INDEX) >= 4:
        _INDEX.clear()
    _INDEX[id(cat)] = (cat, tree)   # holds ``cat``, so its id is not reused while cached
    return tree


# ------------------------------------------------------------------------------ the solution
@dataclass(frozen=True)
class PlateSolution:
    """A frame's plate solution.

    Attributes
    ----------
    wcs
        The fitted TAN WCS (CD matrix; CRVAL near the matched stars' centre, CRPIX fitted).
    n_matched
        Stars kept after sigma clipping.
    det_index, cat_index
        Matched detection indices (into ``xy_px``) and catalogue indices (into
        ``catalog_radec_deg``), pair by pair.
    residuals_arcsec
        Great-circle residual (″) of each matched star: catalogue position vs the fitted WCS at
        its centroid.
    rms_arcsec
        ``sqrt(mean(residuals_arcsec²))`` — the 2-D RMS (the per-axis RMS is this / √2).
    offset_px
        The shift (px, x and y) the vote found between the believed and the observed star
        positions (after the roll below) — the pointing error in pixels.
    roll_deg
        The roll (deg) of the vote's best grid point (resolution: the grid step).
    n_candidates
        Pairs within the match radius before the first fit.
    fit_cov
        ``(AᵀA)⁻¹`` of the final fit's design ``A = [x, y, 1]`` of the matched stars (px),
        for :meth:`position_error_arcsec`.
    sigma_axis_arcsec
        Per-axis σ of one star's residual, unbiased for the fit's 6 parameters:
        ``rms · √(n / (2n − 6))``.
    scale_factor
        The vote's best grid point of the plate-scale search (observed / believed pixel
        distances; 1 when ``max_scale_error = 0``).
    """

    wcs: WCS
    n_matched: int
    det_index: np.ndarray
    cat_index: np.ndarray
    residuals_arcsec: np.ndarray
    rms_arcsec: float
    offset_px: np.ndarray
    roll_deg: float
    n_candidates: int
    fit_cov: np.ndarray
    sigma_axis_arcsec: float
    scale_factor: float = 1.0

    @property
    def pixel_scale_arcsec(self) -> float:
        """Mean plate scale (″/px) of the fitted WCS."""
        return pixel_scale_arcsec(self.wcs)

    def position_error_arcsec(self, xy: Any) -> np.ndarray:
        """Per-axis 1σ error (″) of the solved WCS itself at pixels ``(n, 2)``.

        The least-squares covariance of the fit propagated to each position:
        ``σ_axis · √([x, y, 1] (AᵀA)⁻¹ [x, y, 1]ᵀ)`` — smallest near the matched stars'
        centroid, growing towards corners they do not cover (an extrapolation). It is the
        error a direction taken from this plate solution inherits, on top of its own
        centroid error.
        """
        p = as_points(xy, "xy")
        h = np.column_stack([p, np.ones(len(p))])
        return self.sigma_axis_arcsec * np.sqrt(np.einsum("ni,ij,nj->n", h, self.fit_cov, h))

    def pixel_to_radec(self, xy: Any) -> tuple[np.ndarray, np.ndarray]:
        """RA and Dec (deg) of pixel positions ``(n, 2)``."""
        p = as_points(xy, "xy")
        if len(p) == 0:
            return np.zeros(0), np.zeros(0)
        ra, dec = self.wcs.wcs_pix2world(p[:, 0], p[:, 1], 0)
        return np.asarray(ra) % 360.0, np.asarray(dec)

    def pixel_to_directions(self, xy: Any) -> np.ndarray:
        """Unit vectors ``(n, 3)`` (catalogue frame) of pixel positions ``(n, 2)``."""
        ra, dec = self.pixel_to_radec(xy)
        return _unit(ra, dec).reshape(-1, 3)

    def radec_to_pixel(self, ra_deg: Any, dec_deg: Any) -> np.ndarray:
        """Pixel positions ``(n, 2)`` of RA/Dec (deg)."""
        ra = as_finite_array(ra_deg, "ra_deg", ndim=1)
        dec = as_finite_array(dec_deg, "dec_deg", ndim=1)
        if len(ra) != len(dec):
            raise ValueError(f"ra_deg and dec_deg must have the same length, got {len(ra)} "
                             f"and {len(dec)}")
        if len(ra) == 0:
            return np.zeros((0, 2))
        x, y = self.wcs.wcs_world2pix(ra, dec, 0)
        return np.column_stack([x, y])


def _gnomonic(radec: np.ndarray, tangent: tuple[float, float]) -> np.ndarray:
    """Standard coordinates ``(ξ, η)`` (rad) of RA/Dec ``(n, 2)`` about ``tangent``."""
    e, n, z = _tangent_basis(*tangent)
    u = _unit(radec[:, 0], radec[:, 1]).reshape(-1, 3)
    w = u @ z
    return np.column_stack([u @ e / w, u @ n / w])


def _affine_wcs(X: np.ndarray, tangent: tuple[float, float]) -> WCS:
    """The TAN WCS of ``(ξ, η) = [x, y, 1] @ X`` (``X`` ``(3, 2)``) about ``tangent``."""
    M = X[:2].T
    wcs = WCS(naxis=2)
    wcs.wcs.ctype = ["RA---TAN", "DEC--TAN"]
    wcs.wcs.crval = [float(tangent[0]), float(tangent[1])]
    wcs.wcs.crpix = -np.linalg.solve(M, X[2]) + 1.0
    wcs.wcs.cd = np.degrees(M)
    wcs.wcs.radesys = "ICRS"
    wcs.wcs.set()
    return wcs


def _fit_linear(xy: np.ndarray, q: np.ndarray, radec: np.ndarray,
                tangent: tuple[float, float]) -> np.ndarray:
    """The TAN model in closed form: linear least squares in the tangent plane.

    With CRVAL fixed at ``tangent``, the stars' standard coordinates ``q = (ξ, η)`` are known
    and the model ``q = M p + t`` (``M`` the CD matrix in radians, ``t = −M·(CRPIX − 1)``) is
    linear; its least-squares solution minimises the tangent-plane residuals, which equal
    astropy's sky residuals (``Δα cos δ``, ``Δδ``) to a relative ``O(ξ²)`` (≈ 10⁻⁴ across a 1°
    field). Returns ``X`` ``(3, 2)`` with ``q = [x, y, 1] @ X``.
    """
    A = np.column_stack([xy, np.ones(len(xy))])
    X, _, rank, sv = np.linalg.lstsq(A, q, rcond=None)
    if rank < 3 or sv[-1] < 1e-9 * sv[0]:
        raise PlateSolveError("poor_fit", f"poor fit: the {len(xy)} matched stars are (nearly) "
                              "collinear, the plate solution is undetermined")
    return X


def _fit_astropy(xy: np.ndarray, q: np.ndarray, radec: np.ndarray,
                 tangent: tuple[float, float]) -> np.ndarray:
    """astropy's ``fit_wcs_from_points`` (TAN, CRVAL at ``tangent``), as the same ``X``."""
    from astropy.coordinates import SkyCoord
    from astropy.wcs.utils import fit_wcs_from_points

    world = SkyCoord(radec[:, 0], radec[:, 1], unit="deg", frame="icrs")
    proj = SkyCoord(tangent[0], tangent[1], unit="deg", frame="icrs")
    w = fit_wcs_from_points((xy[:, 0], xy[:, 1]), world, proj_point=proj, projection="TAN",
                            sip_degree=None)
    M = np.radians(w.pixel_scale_matrix)
    return np.vstack([M.T, -M @ (np.asarray(w.wcs.crpix) - 1.0)])


_FITTERS = {"linear": _fit_linear, "astropy": _fit_astropy}
_RAD_TO_ARCSEC = 180.0 / np.pi * ARCSEC_PER_DEG


def _one_to_one(det: np.ndarray, pred: np.ndarray, radius: float) -> tuple[np.ndarray,
                                                                              np.ndarray]:
    """Mutual nearest neighbours within ``radius``: (detection, prediction) index pairs."""
    if len(det) == 0 or len(pred) == 0:
        return np.zeros(0, int), np.zeros(0, int)
    d1, j = cKDTree(pred).query(det, distance_upper_bound=radius)
    ok = np.isfinite(d1)
    i = np.flatnonzero(ok)
    j = j[ok]
    if len(i) == 0:
        return i, j
    _, back = cKDTree(det).query(pred[j])
    mutual = back == i
    return i[mutual], j[mutual]


def _rotate(p: np.ndarray, centre: np.ndarray, ang: float, scale: float = 1.0) -> np.ndarray:
    """Rotate by ``ang`` (rad) and scale by ``scale`` about ``centre``."""
    c, s = scale * np.cos(ang), scale * np.sin(ang)
    q = p - centre
    return np.column_stack([c * q[:, 0] - s * q[:, 1], s * q[:, 0] + c * q[:, 1]]) + centre


def _vote(det: np.ndarray, pred: np.ndarray, centre: np.ndarray, grid: np.ndarray,
          max_off: float, radius: float
          ) -> tuple[int, tuple[float, float], np.ndarray, float, int, int]:
    """Best (votes, (roll, scale), offset, expected chance votes, pairs, runner-up votes).

    ``grid`` lists the (roll, scale) points searched. Ties between grid points are broken by
    the spread of the winning cluster. The runner-up is the largest peak of the same grid
    point farther than ``1.25 radius`` from the winner.
    """
    tree_d = cKDTree(det)
    best: tuple = (0, (0.0, 1.0), np.zeros(2), 0.0, 0, 0)
    best_score = -np.inf
    for ang, sc in grid:
        pr = _rotate(pred, centre, ang, sc)
        pairs = tree_d.sparse_distance_matrix(cKDTree(pr), max_off, output_type="ndarray")
        if len(pairs) == 0:
            continue
        off = det[pairs["i"]] - pr[pairs["j"]]
        tree_o = cKDTree(off)
        counts = tree_o.query_ball_point(off, radius, return_length=True)
        k = int(np.argmax(counts))
        n = int(counts[k])
        members = tree_o.query_ball_point(off[k], radius)
        centre_off = np.median(off[members], axis=0)
        spread = float(np.mean(np.linalg.norm(off[members] - centre_off, axis=1))) / radius
        score = n - spread
        if score > best_score:
            best_score = score
            # chance votes: uniform over the search disc, or the local background in an
            # annulus (r, 5r) around the peak (offsets pile up towards zero when the search
            # disc is larger than the frame) — whichever is larger
            lam_disc = len(off) * (radius / max_off) ** 2
            ring = len(tree_o.query_ball_point(off[k], 5.0 * radius)) - n
            far = np.linalg.norm(off - centre_off, axis=1) > 1.25 * radius
            second = int(counts[far].max()) if far.any() else 0
            best = (n, (float(ang), float(sc)), centre_off, max(lam_disc, ring / 24.0),
                    len(off), second)
    return best


def solve_plate(xy_px: Any, catalog_radec_deg: Any, wcs_guess: WCS, *,
                image_shape: tuple[int, int] | None = None, match_radius_px: float = 2.0,
                max_offset_arcsec: float = 600.0, max_roll_deg: float = 1.0,
                max_scale_error: float = 0.0, min_stars: int = 6, clip_sigma: float = 3.0,
                max_iter: int = 5, max_vote_stars: int = 150,
                fitter: str = "linear") -> PlateSolution:
    """Match detections to catalogue stars from a believed pointing and fit a TAN WCS.

    Parameters
    ----------
    xy_px
        Detected centroids ``(n, 2)`` (x = column, y = row; brightest first is best — the vote
        uses the ``max_vote_stars`` first). False detections, uncatalogued stars and moving
        objects may be among them.
    catalog_radec_deg
        Catalogue positions ``(m, 2)`` (RA, Dec in degrees, at the frame's epoch; brightest
        first is best), e.g. from :func:`catalog_in_field` with a margin of the largest
        pointing error.
    wcs_guess
        The mount's believed pointing as a celestial WCS (e.g. :func:`wcs_from_camera` of the
        believed attitude). Its plate scale must be right to about 1 %, or searched with
        ``max_scale_error``.
    image_shape
        ``(ny, nx)``; catalogue stars predicted farther than the largest pointing error outside
        it are ignored. Default ``wcs_guess.pixel_shape`` or the detections' bounding box.
    match_radius_px
        Largest distance (px) of a matched pair once the offset and roll are applied (and the
        vote's tolerance).
    max_offset_arcsec
        Largest pointing error searched (″). The vote's chance background grows with its
        square; at 120″ true error, 600″ leaves a wide margin.
    max_roll_deg
        Largest roll error searched (deg), on a grid fine enough that the frame's corners move
        by at most ``match_radius_px`` between grid points.
    max_scale_error
        Largest relative error of the believed plate scale searched (e.g. 0.05 for ±5 %; a
        focal reducer, binning or a wrong CDELT), on a grid as fine as the roll grid; 0
        (default) trusts the believed scale to about 1 %. Each grid point costs one more vote.
    min_stars
        Fewest matched stars accepted (≥ 4: the fit has 6 parameters).
    clip_sigma
        Stars whose residual exceeds ``clip_sigma`` robust per-axis σ are dropped and the fit
        repeated (2-D: the chance of rejecting a good star is ``exp(-clip_sigma²/2)``).
    max_iter
        Largest number of match–fit–clip rounds (each round re-matches every detection with
        the last fit, then clips by backward elimination: the worst star is dropped and the
        fit repeated while its residual exceeds ``clip_sigma`` σ).
    max_vote_stars
        Brightest detections and catalogue stars used in the vote (all are used in the fit).
    fitter
        ``"linear"`` (default): the TAN model (CD matrix and CRPIX, CRVAL at the frame centre)
        fitted in closed form in the tangent plane; ``"astropy"``:
        :func:`astropy.wcs.utils.fit_wcs_from_points` with the same CRVAL (the same model and,
        to ``O(ξ²)``, the same objective — agreement to < 10⁻³ px over the frame is tested —
        but a ``least_squares`` iteration: the whole solve is 5–10× slower).

    Returns
    -------
    PlateSolution

    Raises
    ------
    PlateSolveError
        ``too_few_detections`` / ``too_few_catalogue_stars`` (fewer than ``min_stars``),
        ``no_consistent_match`` (the vote's peak is not above its chance background),
        ``ambiguous_match`` (a second offset, more than ``1.25 match_radius_px`` away, has at
        least ``min_stars`` and 70 % of the winner's votes),
        ``too_few_matches`` (fewer than ``min_stars`` survive clipping), ``poor_fit``.
    TypeError, ValueError
        Bad arguments (named).

    Notes
    -----
    Deterministic (no random numbers). Cost: one k-d tree pair search per (roll, scale) grid
    point, one batched LMedS over the pairs of pairs, and a few closed-form 6-parameter
    least-squares fits (with ``fitter="astropy"``: a ``scipy.optimize.least_squares`` each).
    """
    xy = as_points(xy_px, "xy_px")
    cat = as_points(catalog_radec_deg, "catalog_radec_deg")
    if len(cat) and (np.any(np.abs(cat[:, 1]) > 90.0)):
        raise ValueError("catalog_radec_deg: Dec (second column) must lie in [-90, 90] degrees")
    w0 = _check_wcs(wcs_guess, "wcs_guess")
    r_match = check_positive(match_radius_px, "match_radius_px")
    max_off_as = check_positive(max_offset_arcsec, "max_offset_arcsec")
    max_roll = check_positive(max_roll_deg, "max_roll_deg", allow_zero=True)
    max_scale = check_positive(max_scale_error, "max_scale_error", allow_zero=True)
    if max_scale >= 0.3:
        raise ValueError(f"max_scale_error must be < 0.3 (a relative error), got {max_scale}")
    n_min = check_int(min_stars, "min_stars", min_value=4)
    k_clip = check_positive(clip_sigma, "clip_sigma")
    n_iter = check_int(max_iter, "max_iter", min_value=1, max_value=50)
    n_vote = check_int(max_vote_stars, "max_vote_stars", min_value=n_min)
    check_choice(fitter, "fitter", tuple(_FITTERS))
    fit = _FITTERS[fitter]
    if image_shape is not None:
        ny, nx = _check_shape(image_shape, "image_shape")
    elif w0.pixel_shape is not None:
        nx, ny = (int(v) for v in w0.pixel_shape)
    elif len(xy):
        nx, ny = int(np.ceil(xy[:, 0].max())) + 1, int(np.ceil(xy[:, 1].max())) + 1
    else:
        nx = ny = 1
    if len(xy) < n_min:
        raise PlateSolveError("too_few_detections",
                              f"too few stars: {len(xy)} detection(s) in the frame, need at "
                              f"least {n_min} (clouds, a wrong exposure or threshold?)")
    scale = pixel_scale_arcsec(w0)
    max_off = max_off_as / scale
    # catalogue stars in front of the tangent plane and near the frame
    centre_rd = w0.wcs_pix2world([[(nx - 1) / 2.0, (ny - 1) / 2.0]], 0)[0]
    u_c = _unit(centre_rd[0], centre_rd[1])
    front = _unit(cat[:, 0], cat[:, 1]) @ u_c > np.cos(np.radians(60.0)) if len(cat) else \
        np.zeros(0, bool)
    idx = np.flatnonzero(front)
    px = np.zeros((0, 2))
    if len(idx):
        x, y = w0.wcs_world2pix(cat[idx, 0], cat[idx, 1], 0)
        px = np.column_stack([x, y])
        pad = max_off + r_match
        keep = (np.all(np.isfinite(px), 1) & (px[:, 0] > -0.5 - pad) & (px[:, 0] < nx - 0.5 + pad)
                & (px[:, 1] > -0.5 - pad) & (px[:, 1] < ny - 0.5 + pad))
        idx, px = idx[keep], px[keep]
    if len(idx) < n_min:
        raise PlateSolveError("too_few_catalogue_stars",
                              f"too few catalogue stars: {len(idx)} within the frame and the "
                              f"{max_off_as:g}″ search margin under the believed pointing "
                              f"(RA {centre_rd[0]:.4f}°, Dec {centre_rd[1]:.4f}°), need at least "
                              f"{n_min} (sparse field or catalogue too shallow?)")
    # ---- offset vote over a roll grid
    centre = np.array(w0.wcs.crpix, float) - 1.0
    r_max = max(np.hypot(max(centre[0], nx - 1 - centre[0]), max(centre[1], ny - 1 - centre[1])),
                1.0)
    step = r_match / (2.0 * r_max)   # corners move ≤ r_match/4 from the nearest grid point
    n_roll = int(np.ceil(np.radians(max_roll) / step)) if max_roll > 0 else 0
    rolls = np.linspace(-np.radians(max_roll), np.radians(max_roll), 2 * n_roll + 1) \
        if n_roll else np.zeros(1)
    n_sc = int(np.ceil(max_scale / step)) if max_scale > 0 else 0
    scales = 1.0 + (np.linspace(-max_scale, max_scale, 2 * n_sc + 1) if n_sc else np.zeros(1))
    grid = np.array([(a, c) for c in scales for a in rolls])
    votes, (roll, scale_f), off, lam, n_pairs, second = _vote(
        xy[:n_vote], px[:n_vote], centre, grid, max_off, r_match)
    # Poisson bound on the highest chance peak over all pairs and rolls
    n_tries = max(n_pairs, 1) * len(grid)
    need = max(n_min, _poisson_quantile(lam, 1e-3 / n_tries) + 1)
    if votes < n_min and votes >= _poisson_quantile(lam, 1e-3 / n_tries) + 1:
        raise PlateSolveError("too_few_matches",
                              f"too few matches: the pointing offset ({off[0]:.1f}, "
                              f"{off[1]:.1f}) px is shared by only {votes} star pair(s), need "
                              f"{n_min} ({len(idx)} catalogue stars near the frame, "
                              f"{len(xy)} detections) — a sparse field or a shallow catalogue")
    if votes < need:
        raise PlateSolveError("no_consistent_match",
                              f"no consistent match: the best pointing offset is shared by "
                              f"{votes} star pair(s), need {need} (chance level {lam:.1f}) — "
                              f"is the pointing error larger than {max_off_as:g}″, the roll "
                              f"larger than {max_roll:g}°, the believed plate scale "
                              f"({scale:.4g}″/px) off by more than "
                              f"{max(100 * max_scale, 1):g} %, or the frame only noise?")
    if second >= max(n_min, 0.7 * votes):
        raise PlateSolveError("ambiguous_match",
                              f"ambiguous match: two pointing offsets more than "
                              f"{1.25 * r_match:g} px apart are shared by {votes} and {second} "
                              "star pairs — several detections per star (trailed or doubled "
                              "stars split by the extractor?), a repetitive field, or the "
                              f"believed plate scale ({scale:.4g}″/px) off by more than "
                              f"{max(100 * max_scale, 1):g} %")
    pred = _rotate(px, centre, roll, scale_f) + off
    i_det, j_cat = _one_to_one(xy, pred, r_match)
    n_cand = len(i_det)
    if n_cand < n_min:
        raise PlateSolveError("too_few_matches",
                              f"too few matches: {n_cand} star(s) within {r_match:g} px after "
                              f"the offset ({off[0]:.1f}, {off[1]:.1f}) px, need {n_min}")
    floor_as = 0.01 * scale
    # tangent point: the frame centre under the believed pointing corrected by the vote
    c_px = np.array([(nx - 1) / 2.0, (ny - 1) / 2.0])
    c_guess = _rotate((c_px - off)[None], centre, -roll, 1.0 / scale_f)[0]
    tangent = tuple(float(v) for v in w0.wcs_pix2world([c_guess], 0)[0])
    radec = cat[idx]
    q_all = _gnomonic(radec, tangent)
    parity = float(np.sign(np.linalg.det(w0.pixel_scale_matrix)))

    def residuals(X: np.ndarray, i_d: np.ndarray, j_c: np.ndarray) -> np.ndarray:
        p = np.column_stack([xy[i_d], np.ones(len(i_d))])
        return np.linalg.norm(p @ X - q_all[j_c], axis=1) * _RAD_TO_ARCSEC

    def fit_pairs(i_d: np.ndarray, j_c: np.ndarray) -> np.ndarray:
        return fit(xy[i_d], q_all[j_c], radec[j_c], tangent)

    def clip(i_d: np.ndarray, j_c: np.ndarray, X0: np.ndarray | None = None
             ) -> tuple[np.ndarray, np.ndarray]:
        """Start (LMedS, or the previous round's fit ``X0``), re-admission from the inliers'
        fit, then backward elimination (drop the worst pair while it exceeds k_clip robust σ).
        """
        if X0 is None:
            keep = _lmeds_inliers(xy[i_d], q_all[j_c], k_clip, floor_as, parity)
        else:
            res0 = residuals(X0, i_d, j_c)
            keep = res0 <= k_clip * _robust_sigma(res0, floor_as)
        for _ in range(10):   # re-admit / re-reject from the inliers' fit until stable
            if keep.sum() < 3:
                break
            res = residuals(fit_pairs(i_d[keep], j_c[keep]), i_d, j_c)
            new = res <= k_clip * _robust_sigma(res[keep], floor_as)
            if np.array_equal(new, keep):
                break
            keep = new
        while True:
            if keep.sum() < n_min:
                raise PlateSolveError("too_few_matches",
                                      f"too few matches: {int(keep.sum())} star(s) left after "
                                      f"{k_clip:g}σ clipping, need {n_min}")
            X = fit_pairs(i_d[keep], j_c[keep])
            res = residuals(X, i_d, j_c)
            sig = _robust_sigma(res[keep], floor_as)
            worst = int(np.argmax(np.where(keep, res, -1.0)))
            if res[worst] <= k_clip * sig:
                return X, keep
            keep[worst] = False

    X, keep = clip(i_det, j_cat)
    for _ in range(n_iter - 1):
        # re-match every detection with the fitted model; stop when the matched set is stable
        M, t = X[:2].T, X[2]
        pred = np.linalg.solve(M, (q_all - t).T).T
        i_new, j_new = _one_to_one(xy, pred, r_match)
        if set(zip(i_new.tolist(), j_new.tolist())) == \
                set(zip(i_det[keep].tolist(), j_cat[keep].tolist())):
            break
        i_det, j_cat = i_new, j_new
        X, keep = clip(i_det, j_cat, X)
    i_det, j_cat = i_det[keep], j_cat[keep]
    wcs = _affine_wcs(X, tangent)
    # final fit about the solved frame centre (CRVAL = centre, CRPIX ≈ image centre)
    tangent = tuple(float(v) for v in wcs.wcs_pix2world([c_px], 0)[0])
    q_all = _gnomonic(radec, tangent)
    wcs = _affine_wcs(fit_pairs(i_det, j_cat), tangent)
    res = _residuals(wcs, xy[i_det], radec[j_cat])
    rms = float(np.sqrt(np.mean(res ** 2)))
    if not np.isfinite(rms) or rms > r_match * scale:
        raise PlateSolveError("poor_fit", f"poor fit: residual RMS {rms:.2f}″ over "
                              f"{len(res)} stars exceeds the match radius "
                              f"({r_match * scale:.1f}″)")
    wcs.pixel_shape = (nx, ny)
    A = np.column_stack([xy[i_det], np.ones(len(i_det))])
    n_m = len(i_det)
    return PlateSolution(wcs, n_m, i_det, idx[j_cat], res, rms, np.asarray(off, float),
                         float(np.degrees(roll)), n_cand, np.linalg.inv(A.T @ A),
                         rms * float(np.sqrt(n_m / max(2 * n_m - 6, 1))), float(scale_f))


def _lmeds_inliers(xy: np.ndarray, q: np.ndarray, k_clip: float, floor_arcsec: float,
                   parity: float, max_pairs: int = 20) -> np.ndarray:
    """Inliers of the least-median-of-squares *similarity* fit over pairs of pairs.

    A pinhole camera with square pixels maps the tangent plane to pixels by a similarity
    (scale, rotation, shift; mirrored when ``parity < 0``), fixed by two stars. Every two of
    the first ``max_pairs`` pairs (brightest detections first) give one; the one with the
    smallest median squared residual over all pairs wins (robust to just under 50 %
    outliers), and pairs within ``k_clip`` robust σ of it are the starting inliers. Four
    parameters fitted to the whole field, not six to a corner of it: a cluster of stars cannot
    pass for the field. Deterministic; vectorised.
    """
    n = len(xy)
    if n < 4:
        return np.ones(n, bool)
    zp = xy[:, 0] + 1j * xy[:, 1]
    if parity < 0:
        zp = np.conj(zp)
    zq = q[:, 0] + 1j * q[:, 1]
    m = min(n, max_pairs)
    i, j = np.triu_indices(m, 1)
    dp = zp[j] - zp[i]
    ok = np.abs(dp) > 5.0                 # two stars at least 5 px apart
    if not ok.any():
        return np.ones(n, bool)
    i, j, dp = i[ok], j[ok], dp[ok]
    a = (zq[j] - zq[i]) / dp
    b = zq[i] - a * zp[i]
    r2 = np.abs(a[:, None] * zp[None] + b[:, None] - zq[None]) ** 2 * _RAD_TO_ARCSEC ** 2
    med = np.median(r2, axis=1)
    best = int(np.argmin(med))
    dof = max(2 * n - 4, 1)
    sig = max(float(np.sqrt(med[best] / (2 * np.log(2)) * 2 * n / dof)) * (1 + 5.0 / dof),
              floor_arcsec)
    keep = np.sqrt(r2[best]) <= k_clip * sig
    return keep if keep.sum() >= 3 else np.ones(n, bool)


def _robust_sigma(res: np.ndarray, floor: float) -> float:
    """Per-axis σ of 2-D residuals of a 6-parameter fit: the Rayleigh median, corrected for the
    degrees of freedom the fit used (``2n / (2n − 6)`` in variance) and inflated by
    ``1 + 5 / (2n − 6)`` for small samples."""
    n = len(res)
    dof = max(2 * n - 6, 1)
    var = np.median(res ** 2) / (2 * np.log(2)) * (2 * n) / dof
    # small-sample head-room (as in LMedS): a median of few residuals scatters by tens of %,
    # and clipping at an underestimated σ would throw good stars away
    return max(float(np.sqrt(var)) * (1.0 + 5.0 / dof), floor)


def _residuals(wcs: WCS, xy: np.ndarray, radec: np.ndarray) -> np.ndarray:
    ra, dec = wcs.wcs_pix2world(xy[:, 0], xy[:, 1], 0)
    return _separation_arcsec(ra, dec, radec[:, 0], radec[:, 1])


def _poisson_quantile(lam: float, p_tail: float) -> int:
    """Smallest k with P(Poisson(lam) ≥ k) ≤ p_tail."""
    from scipy.special import pdtrc

    k = np.arange(int(lam + 20.0 * np.sqrt(lam) + 60.0))
    sf = np.r_[1.0, pdtrc(k[:-1], max(lam, 1e-12))]   # P(X ≥ k)
    return int(np.argmax(sf <= p_tail))


# ------------------------------------------------------------------ synthetic fields (tests, benchmarks)
def axis_rotation(axis: int, angle_rad: float) -> np.ndarray:
    """Rotation matrix by ``angle_rad`` about coordinate axis ``axis`` (0, 1, 2)."""
    check_int(axis, "axis", min_value=0, max_value=2)
    c, s = np.cos(float(angle_rad)), np.sin(float(angle_rad))
    i, j = [k for k in range(3) if k != axis]
    m = np.eye(3)
    m[i, i], m[i, j], m[j, i], m[j, j] = c, -s, s, c
    return m


def look_at_radec(ra_deg: float, dec_deg: float) -> np.ndarray:
    """World → camera rotation: z at (ra, dec), x towards the east, y towards the north."""
    if not -90 < float(dec_deg) < 90:
        raise ValueError(f"dec_deg must lie in (-90, 90), got {dec_deg}")
    a, d = np.radians(float(ra_deg)), np.radians(float(dec_deg))
    z = np.array([np.cos(d) * np.cos(a), np.cos(d) * np.sin(a), np.sin(d)])
    x = np.array([-np.sin(a), np.cos(a), 0.0])
    return np.stack([x, np.cross(z, x), z])


def mount_error_rotation(rng: np.random.Generator, error_arcsec: float, roll_deg: float
                         ) -> np.ndarray:
    """A mount's attitude error ``E`` (believed = ``E @ true``): the boresight off by
    ``error_arcsec`` in a random direction, the roll off by ``roll_deg`` (as given; draw the
    sign yourself if it should be random)."""
    g = check_generator(rng)
    e = check_positive(error_arcsec, "error_arcsec", allow_zero=True) / _RAD_TO_ARCSEC
    phi = g.uniform(0, 2 * np.pi)
    return axis_rotation(2, np.radians(float(roll_deg))) @ axis_rotation(
        0, e * np.sin(phi)) @ axis_rotation(1, e * np.cos(phi))


def synthetic_plate_scene(rng: np.random.Generator, ra_deg: float, dec_deg: float, *,
                          scale: float = 15.0, n: int = 256, err_arcsec: float = 120.0,
                          roll_deg: float = 0.3, noise_px: float = 0.1, n_false: int = 10,
                          drop: float = 0.1, max_mag: float = 10.0, mirror: bool = False,
                          catalog=None) -> dict:
    """Detections of a real star field (the packaged Gaia extract) seen by a true camera, and
    the believed WCS (truth turned by a mount error) — the input of :func:`solve_plate`.

    Returns a dict: ``det`` (detections: the seen stars with Gaussian centroid noise
    ``noise_px``, a fraction ``drop`` left out, then ``n_false`` uniform false ones),
    ``true_xy``/``true_radec`` (the seen stars' true pixels and RA/Dec), ``cat`` (catalogue
    RA/Dec around the believed field), ``wg``/``wt`` (believed and true WCS), ``n_in`` (stars
    in the true field), ``n``, ``scale``.
    """
    g = check_generator(rng)
    f = _RAD_TO_ARCSEC / check_positive(scale, "scale")
    K = np.array([[f, 0, (n - 1) / 2], [0, -f if mirror else f, (n - 1) / 2], [0, 0, 1.0]])
    R = look_at_radec(ra_deg, dec_deg)
    Rb = mount_error_rotation(g, err_arcsec, roll_deg) @ R
    wt = wcs_from_camera(K, R, (n, n))
    stars = catalog_in_field(wt, (n, n), max_mag=max_mag, catalog=catalog)
    from eotrack.geometry import project_directions

    xy = project_directions(stars.unit_vectors(), K, R) + g.normal(0, noise_px, (len(stars), 2))
    seen = g.random(len(xy)) > drop
    det = np.vstack([xy[seen], g.uniform(0, n - 1, (n_false, 2))])
    wg = wcs_from_camera(K, Rb, (n, n))
    cat = catalog_in_field(wg, (n, n), max_mag=max_mag, margin_px=err_arcsec / scale * 1.5 + 5,
                           catalog=catalog)
    return dict(det=det, true_xy=xy[seen], true_radec=np.c_[stars.ra_deg, stars.dec_deg][seen],
                cat=np.c_[cat.ra_deg, cat.dec_deg], wg=wg, wt=wt, n_in=len(stars), n=n,
                scale=scale)
