"""Scoring star extractors: matching to a truth list, completeness at equal false detections,
artificial-star injection into real frames, and the real sky images shipped by installed
packages.

*Completeness at equal false detections* compares two detectors fairly: each is run over a
sweep of thresholds, giving a curve (number of false detections, completeness); one detector's
completeness is interpolated at the other's false-detection counts. On simulated frames a false
detection is one farther than the match radius from every true star. On a real frame there is no
truth list, so stars of the frame's own PSF are injected (an artificial-star test) and
completeness is measured on them, and false detections are counted on the negated frame
(``2·median − I``), where every real star becomes a hole and only noise peaks, cosmic rays and
artefacts can be detected.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any, NamedTuple

import numpy as np
from scipy.spatial import cKDTree

from eotrack.validation import check_generator, check_positive

from .psf import render_gaussian_spots

__all__ = [
    "CompletenessCurve",
    "clean_isolated",
    "completeness_at",
    "completeness_curve",
    "inject_stars",
    "match_positions",
    "real_sky_images",
]


def _pts(a: Any, name: str) -> np.ndarray:
    arr = np.asarray(a, dtype=float)
    if arr.ndim != 2 or arr.shape[1] != 2:
        raise ValueError(f"{name} must have shape (n, 2), got {arr.shape}")
    return arr


def match_positions(found: Any, truth: Any, radius: float = 1.5
                    ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Nearest-neighbour matching within ``radius`` pixels.

    Returns
    -------
    truth_found : numpy.ndarray
        Per true position: a detection lies within ``radius``.
    found_true : numpy.ndarray
        Per detection: a true position lies within ``radius``.
    error : numpy.ndarray
        Per true position: distance to the nearest detection (inf if none).
    """
    f, t = _pts(found, "found"), _pts(truth, "truth")
    r = check_positive(radius, "radius")
    if len(f) == 0 or len(t) == 0:
        return np.zeros(len(t), bool), np.zeros(len(f), bool), np.full(len(t), np.inf)
    d_t, _ = cKDTree(f).query(t)
    d_f, _ = cKDTree(t).query(f)
    return d_t <= r, d_f <= r, d_t


class CompletenessCurve(NamedTuple):
    """Thresholds, false detections and completeness of one detector (one row per threshold)."""

    thresholds: np.ndarray
    n_false: np.ndarray
    completeness: np.ndarray


def completeness_curve(detect: Callable[[np.ndarray, float], np.ndarray], image: Any,
                       truth: Any, targets: Any, thresholds: Any, *, radius: float = 1.5,
                       negative: Any = None) -> CompletenessCurve:
    """Completeness of ``targets`` and false detections over a threshold sweep.

    Parameters
    ----------
    detect
        ``detect(image, threshold) -> xy (n, 2)``.
    image
        The frame.
    truth
        Every known star ``(m, 2)`` (a detection near any of them is not false).
    targets
        Boolean mask over ``truth``: the stars completeness is measured on.
    thresholds
        Threshold values to sweep.
    radius
        Match radius (pixels).
    negative
        If given, false detections are the detections on this image (e.g. the negated real
        frame) instead of the unmatched detections on ``image``.
    """
    t = _pts(truth, "truth")
    tg = np.asarray(targets, dtype=bool)
    if tg.shape != (len(t),):
        raise ValueError(f"targets must be a boolean mask of shape ({len(t)},), got {tg.shape}")
    th = np.asarray(thresholds, dtype=float).ravel()
    nf, comp = [], []
    for v in th:
        xy = _pts(detect(image, float(v)), "detect(...)")
        hit, real, _ = match_positions(xy, t, radius)
        comp.append(float(hit[tg].mean()) if tg.any() else np.nan)
        if negative is None:
            nf.append(int((~real).sum()))
        else:
            nf.append(len(_pts(detect(negative, float(v)), "detect(...)")))
    return CompletenessCurve(th, np.asarray(nf), np.asarray(comp))


def completeness_at(curve: CompletenessCurve, n_false: Any) -> np.ndarray:
    """Completeness of ``curve`` interpolated (in log(1 + false detections)) at ``n_false``.

    Outside the swept range the nearest end is used (a conservative choice for a detector
    whose sweep does not reach the requested count).
    """
    x = np.log1p(np.asarray(curve.n_false, dtype=float))
    y = np.asarray(curve.completeness, dtype=float)
    order = np.argsort(x, kind="stable")
    x, y = x[order], y[order]
    y = np.maximum.accumulate(y)            # completeness cannot fall as more is admitted
    return np.interp(np.log1p(np.asarray(n_false, dtype=float)), x, y)


def inject_stars(image: Any, rng: np.random.Generator, n: int, sigma_px: float,
                 peak_range: tuple[float, float], *, margin: int = 8, min_sep: float = 6.0
                 ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Add ``n`` Gaussian stars at random positions (artificial-star test).

    Peaks are log-uniform in ``peak_range`` (image units); the stars are at least ``min_sep``
    apart from each other. Poisson noise is not added (the frame's own noise dominates).

    Returns
    -------
    image, xy, peak
        The new image (float64), the injected centres ``(n, 2)`` and their peak values.
    """
    check_generator(rng)
    img = np.asarray(image, dtype=float)
    if img.ndim != 2:
        raise ValueError(f"image must be 2-D, got shape {img.shape}")
    s = check_positive(sigma_px, "sigma_px")
    lo, hi = peak_range
    if not 0 < lo <= hi:
        raise ValueError(f"peak_range must be 0 < lo <= hi, got {peak_range}")
    H, W = img.shape
    cand = rng.uniform([margin, margin], [W - 1 - margin, H - 1 - margin], (4 * n, 2))
    keep = []
    tree_pts = np.zeros((0, 2))
    # greedy thinning in blocks (vectorised distances within each block)
    for c in np.array_split(cand, 8):
        if len(tree_pts):
            d, _ = cKDTree(tree_pts).query(c)
            c = c[d >= min_sep]
        if len(c) > 1:
            dd = np.hypot(*(c[:, None, :] - c[None, :, :]).transpose(2, 0, 1))
            np.fill_diagonal(dd, np.inf)
            close = np.triu(dd < min_sep, 1).any(axis=0)
            c = c[~close]
        keep.append(c)
        tree_pts = np.concatenate(keep)
        if len(tree_pts) >= n:
            break
    xy = tree_pts[:n]
    peak = np.exp(rng.uniform(np.log(lo), np.log(hi), len(xy)))
    flux = peak * 2 * np.pi * s * s
    out = img + render_gaussian_spots((H, W), xy, flux, s)
    return out, xy, peak


def clean_isolated(xy: Any, flux: Any, flags: Any, shape: tuple[int, int], *,
                   a: Any = None, b: Any = None, n: int = 40, isolation: float = 10.0,
                   margin: int = 10, size_factor: float = 1.5, min_axis_ratio: float = 0.6
                   ) -> np.ndarray:
    """Indices of the ``n`` brightest clean, isolated stars of a reference catalogue (e.g. SEP's).

    Clean: ``flags == 0``; isolated: no other detection within ``isolation`` pixels; not within
    ``margin`` pixels of the edge. If the semi-axes ``a``, ``b`` are given, only point-like
    objects count as stars (the stellar locus): ``a ≤ size_factor · median(a)`` of the clean
    isolated objects and ``b / a ≥ min_axis_ratio`` — galaxies and undeblended pairs are not
    stars.
    """
    p = _pts(xy, "xy")
    fl = np.asarray(flux, dtype=float)
    fg = np.asarray(flags)
    if len(p) < 2:
        return np.arange(len(p))
    d, _ = cKDTree(p).query(p, k=2)
    H, W = shape
    inside = (p[:, 0] >= margin) & (p[:, 0] <= W - 1 - margin) & \
        (p[:, 1] >= margin) & (p[:, 1] <= H - 1 - margin)
    good = (fg == 0) & (d[:, 1] > isolation) & inside
    if a is not None and b is not None:
        aa, bb = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
        if good.any():
            good &= (aa <= size_factor * np.median(aa[good])) & (bb >= min_axis_ratio * aa)
    ok = np.flatnonzero(good)
    return ok[np.argsort(-fl[ok], kind="stable")[:n]]


def real_sky_images() -> dict[str, np.ndarray]:
    """Real sky frames shipped by installed packages (read offline; see ``data/README.md``).

    * ``"m13"`` — 300×300 16-bit frame of the globular cluster M13 (astropy test data,
      ``astropy/io/fits/hdu/compressed/tests/data/m13.fits``; a crowded real star field);
    * ``"hubble_deep_field"`` — 872×1000 8-bit grey of the Hubble Deep Field
      (``skimage.data.hubble_deep_field``, shipped inside scikit-image; NASA/STScI, public
      domain), galaxies and a few stars.
    """
    from pathlib import Path

    import astropy
    from astropy.io import fits
    from skimage import data as skd
    from skimage.color import rgb2gray

    p = Path(astropy.__file__).parent / "io/fits/hdu/compressed/tests/data/m13.fits"
    with fits.open(p) as h:
        m13 = np.asarray(h[0].data, dtype=float)
    hdf = np.rint(255 * rgb2gray(skd.hubble_deep_field()))
    return {"m13": m13, "hubble_deep_field": hdf}
