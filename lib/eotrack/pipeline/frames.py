"""Frames as FITS files: one image per file, with the header a tracking pipeline needs.

Header keys written by :func:`write_fits` and read by :func:`read_fits`:

=============  ==================================================================  ==========
key            meaning                                                             required
=============  ==================================================================  ==========
``DATE-OBS``   start of the exposure (ISO 8601, UTC; ``TIMESYS = 'UTC'``)          yes
``DATE-AVG``   mid-exposure (the frame's time)                                     no
``EXPTIME``    exposure (s)                                                        yes
``OBSERVAT``   station name (``TELESCOP`` is used if absent, else ``'unknown'``)    no
``SITELAT``    station latitude (deg), ``SITELONG`` longitude (deg, east),          no
               ``SITEELEV`` height (m)
``FRAMEID``    frame label (default: the file name without suffix)                 no
``SEQUENCE``   burst / visit label (frames initiated together)                     no
WCS keys       the mount's **believed** pointing: ``CTYPE1/2 = RA---TAN/DEC--TAN``,  yes
               ``CRVAL``, ``CRPIX``, ``CD`` (or ``PC`` + ``CDELT``)
=============  ==================================================================  ==========

The frame's time is mid-exposure: ``DATE-AVG`` if present, else ``DATE-OBS + EXPTIME/2``.
"""

from __future__ import annotations

import warnings
from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from os import PathLike
from pathlib import Path
from typing import Any

import numpy as np
from astropy import units as u
from astropy.coordinates import EarthLocation
from astropy.io import fits
from astropy.time import Time
from astropy.wcs import WCS, FITSFixedWarning

from eotrack.validation import check_positive

__all__ = ["FitsFrameError", "Frame", "read_fits", "write_fits"]


class FitsFrameError(ValueError):
    """A FITS file that is not a usable frame; the message names the file and the key."""


@dataclass(frozen=True)
class Frame:
    """One image with what the pipeline needs to know about it.

    Attributes
    ----------
    image
        2-D image ``(ny, nx)`` (e⁻ or ADU), finite.
    time
        Mid-exposure time (scalar astropy ``Time``).
    exposure_s
        Exposure (s, > 0).
    station
        Station name (groups frames; copied to the measurements).
    wcs_guess
        The mount's believed pointing as a celestial WCS (e.g.
        :func:`eotrack.astro.astrometry.wcs_from_camera` of the believed attitude).
    frame_id
        Label of the frame (unique within a run; the FITS file name).
    location
        Station position (astropy ``EarthLocation``) or ``None``.
    sequence
        Burst / visit label: frames of one ``(station, sequence)`` are initiated together.
        ``None``: consecutive frames of a station closer than ``max_gap_s`` in time
        (:class:`eotrack.pipeline.PipelineConfig`) form a sequence.
    path
        The file the frame was read from (for messages), or ``None``.
    """

    image: np.ndarray
    time: Time
    exposure_s: float
    station: str
    wcs_guess: WCS
    frame_id: str
    location: EarthLocation | None = None
    sequence: str | None = None
    path: str | None = None

    def __post_init__(self) -> None:
        img = np.asarray(self.image)
        if img.ndim != 2 or min(img.shape) < 1:
            raise ValueError(f"image must be a non-empty 2-D array, got shape {img.shape}")
        if not np.issubdtype(img.dtype, np.number) or np.issubdtype(img.dtype, np.complexfloating):
            raise TypeError(f"image must hold real numbers, got dtype {img.dtype}")
        if not np.all(np.isfinite(img)):
            raise ValueError("image contains NaN or infinite values")
        object.__setattr__(self, "image", img)
        if not isinstance(self.time, Time) or not self.time.isscalar:
            raise TypeError(f"time must be a scalar astropy Time, got {type(self.time).__name__}")
        object.__setattr__(self, "exposure_s", check_positive(self.exposure_s, "exposure_s"))
        if not isinstance(self.station, str) or not self.station:
            raise TypeError(f"station must be a non-empty str, got {self.station!r}")
        if not isinstance(self.wcs_guess, WCS):
            raise TypeError(f"wcs_guess must be an astropy.wcs.WCS, got "
                            f"{type(self.wcs_guess).__name__}")
        if self.wcs_guess.naxis != 2 or not self.wcs_guess.has_celestial:
            raise ValueError(f"wcs_guess must be a 2-axis celestial WCS, got ctype "
                             f"{list(self.wcs_guess.wcs.ctype)}")
        if not isinstance(self.frame_id, str) or not self.frame_id:
            raise TypeError(f"frame_id must be a non-empty str, got {self.frame_id!r}")
        if self.location is not None and not isinstance(self.location, EarthLocation):
            raise TypeError(f"location must be an astropy EarthLocation or None, got "
                            f"{type(self.location).__name__}")
        if self.sequence is not None and not isinstance(self.sequence, str):
            raise TypeError(f"sequence must be a str or None, got {self.sequence!r}")

    @property
    def shape(self) -> tuple[int, int]:
        """``(ny, nx)``."""
        return tuple(self.image.shape)  # type: ignore[return-value]

    @property
    def label(self) -> str:
        """``frame_id`` and, if known, the file — for messages."""
        return f"frame '{self.frame_id}'" + (f" ({self.path})" if self.path else "")


def _safe_name(frame_id: str) -> str:
    bad = set('/\\:*?"<>| ')
    return "".join("_" if c in bad else c for c in frame_id)


def write_fits(frames: Iterable[Frame], directory: str | PathLike, *,
               overwrite: bool = False) -> list[Path]:
    """Write each frame to ``<directory>/<frame_id>.fits`` (float32 image, header as above).

    Parameters
    ----------
    frames
        The frames.
    directory
        Output directory (created if missing).
    overwrite
        Replace existing files (default: refuse with ``FileExistsError``).

    Returns
    -------
    list of pathlib.Path
        The files, in the order of ``frames``.
    """
    d = Path(directory)
    d.mkdir(parents=True, exist_ok=True)
    out = []
    seen: set[str] = set()
    for i, fr in enumerate(frames):
        if not isinstance(fr, Frame):
            raise TypeError(f"frames[{i}] must be a Frame, got {type(fr).__name__}")
        name = _safe_name(fr.frame_id) + ".fits"
        if name in seen:
            raise ValueError(f"frames[{i}]: frame_id {fr.frame_id!r} is not unique")
        seen.add(name)
        hdr = fr.wcs_guess.celestial.to_header()
        start = fr.time - fr.exposure_s / 2 * u.s
        hdr["TIMESYS"] = ("UTC", "time scale of DATE-OBS and DATE-AVG")
        hdr["DATE-OBS"] = (start.utc.isot, "start of the exposure (UTC)")
        hdr["DATE-AVG"] = (fr.time.utc.isot, "mid-exposure (UTC)")
        hdr["EXPTIME"] = (fr.exposure_s, "exposure (s)")
        hdr["OBSERVAT"] = (fr.station, "station")
        if fr.location is not None:
            g = fr.location.to_geodetic()
            hdr["SITELAT"] = (float(g.lat.to_value(u.deg)), "station latitude (deg)")
            hdr["SITELONG"] = (float(g.lon.to_value(u.deg)), "station longitude (deg, east)")
            hdr["SITEELEV"] = (float(g.height.to_value(u.m)), "station height (m)")
        hdr["FRAMEID"] = (fr.frame_id, "frame label")
        if fr.sequence is not None:
            hdr["SEQUENCE"] = (fr.sequence, "burst / visit label")
        hdr["BUNIT"] = "electron"
        path = d / name
        fits.PrimaryHDU(np.asarray(fr.image, np.float32), header=hdr).writeto(
            path, overwrite=overwrite)
        out.append(path)
    return out


def _time(hdr: fits.Header, path: str) -> tuple[Time, float]:
    if "EXPTIME" not in hdr:
        raise FitsFrameError(f"{path}: no exposure time — the header has no EXPTIME")
    try:
        exp = check_positive(float(hdr["EXPTIME"]), "EXPTIME")
    except (TypeError, ValueError) as exc:
        raise FitsFrameError(f"{path}: EXPTIME {hdr['EXPTIME']!r} is not a positive number of "
                             "seconds") from exc
    scale = str(hdr.get("TIMESYS", "UTC")).strip().lower()
    if scale not in ("utc", "tai", "tt", "tdb", "ut1", "gps"):
        raise FitsFrameError(f"{path}: TIMESYS {hdr['TIMESYS']!r} is not a supported time scale")
    for key, shift in (("DATE-AVG", 0.0), ("DATE-OBS", exp / 2)):
        if key in hdr and str(hdr[key]).strip():
            val = str(hdr[key]).strip()
            try:
                if "T" not in val:
                    raise ValueError("no time of day")
                t = Time(val, format="isot", scale=scale)
            except ValueError as exc:
                raise FitsFrameError(f"{path}: {key} {hdr[key]!r} is not an ISO 8601 date and "
                                     "time (YYYY-MM-DDThh:mm:ss[.sss])") from exc
            return (t + shift * u.s).utc, exp
    raise FitsFrameError(f"{path}: no observation time — the header has no DATE-OBS (start of "
                         "the exposure, ISO 8601 UTC) or DATE-AVG")


def _wcs(hdr: fits.Header, path: str) -> WCS:
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", FITSFixedWarning)
        try:
            w = WCS(hdr, naxis=2)
        except Exception as exc:  # astropy raises several types for broken WCS keys
            raise FitsFrameError(f"{path}: no usable pointing — the WCS keys do not parse "
                                 f"({exc})") from exc
    if not w.has_celestial or not str(w.wcs.ctype[0]).startswith("RA"):
        raise FitsFrameError(f"{path}: no pointing — the header has no celestial WCS (CTYPE1/2 "
                             f"= 'RA---TAN'/'DEC--TAN' with CRVAL, CRPIX and CD), got CTYPE "
                             f"{list(w.wcs.ctype)}")
    if not np.all(np.isfinite(w.pixel_scale_matrix)) or \
            abs(np.linalg.det(w.pixel_scale_matrix)) == 0:
        raise FitsFrameError(f"{path}: no pointing — the WCS's CD matrix is singular or missing")
    return w.celestial


def read_fits(paths: Sequence[str | PathLike] | str | PathLike) -> list[Frame]:
    """Read frames written by :func:`write_fits` (or any FITS image with the keys above).

    Parameters
    ----------
    paths
        One path or a sequence of paths (the primary HDU, or the first image HDU, is read).

    Returns
    -------
    list of Frame

    Raises
    ------
    FitsFrameError
        A file without an image, a time (``DATE-OBS``/``DATE-AVG``), an ``EXPTIME`` or a
        celestial WCS — the message names the file and the key.
    FileNotFoundError
        A path that does not exist.
    """
    if isinstance(paths, (str, PathLike)):
        paths = [paths]
    if not isinstance(paths, Sequence):
        raise TypeError(f"paths must be a path or a sequence of paths, got "
                        f"{type(paths).__name__}")
    return [_read_one(p) for p in paths]


def _read_one(p: Any) -> Frame:
    path = Path(p)
    if not path.exists():
        raise FileNotFoundError(f"{path}: no such file")
    try:
        hdul = fits.open(path, memmap=False)
    except OSError as exc:
        raise FitsFrameError(f"{path}: not a FITS file ({exc})") from exc
    with hdul:
        hdu = next((h for h in hdul if h.is_image and h.data is not None and h.data.ndim == 2),
                   None)
        if hdu is None:
            raise FitsFrameError(f"{path}: no 2-D image in any HDU")
        hdr = hdu.header
        image = np.asarray(hdu.data, float)
    t, exp = _time(hdr, str(path))
    w = _wcs(hdr, str(path))
    w.pixel_shape = (image.shape[1], image.shape[0])
    station = str(hdr.get("OBSERVAT", hdr.get("TELESCOP", "unknown"))).strip() or "unknown"
    loc = None
    if all(k in hdr for k in ("SITELAT", "SITELONG")):
        try:
            loc = EarthLocation.from_geodetic(float(hdr["SITELONG"]) * u.deg,
                                              float(hdr["SITELAT"]) * u.deg,
                                              float(hdr.get("SITEELEV", 0.0)) * u.m)
        except (TypeError, ValueError) as exc:
            raise FitsFrameError(f"{path}: SITELAT/SITELONG/SITEELEV are not numbers") from exc
    if not np.all(np.isfinite(image)):
        raise FitsFrameError(f"{path}: the image contains NaN or infinite pixels")
    seq = hdr.get("SEQUENCE")
    return Frame(image, t, exp, station, w, str(hdr.get("FRAMEID", path.stem)), loc,
                 None if seq is None else str(seq), str(path))
