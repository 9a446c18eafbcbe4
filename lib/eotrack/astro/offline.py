"""Keep astropy offline: no IERS download, no remote data, ever.

Measured: ``iers.conf.auto_download = False`` alone is not enough (dates past the bundled table
then raise); ``iers.conf.auto_max_age = None`` is needed too, and
``astropy.utils.data.conf.allow_internet = False`` blocks any other fetch. The IERS tables come
from the pinned ``astropy-iers-data`` package.
"""

from __future__ import annotations

__all__ = ["configure_offline"]


def configure_offline() -> None:
    """Apply the offline settings to astropy (idempotent; run on ``import eotrack.astro``)."""
    from astropy.utils import iers
    from astropy.utils.data import conf as data_conf

    iers.conf.auto_download = False
    iers.conf.auto_max_age = None
    iers.conf.iers_degraded_accuracy = "warn"
    data_conf.allow_internet = False
