"""The simulated scene of Ning, Zhang & Zhang 2016 (§3) and the experiment settings.

The target's centre of mass at ``[1, 1.2, 10]`` m in the camera frame, attitude angles
``[15°, 20°, 10°]``, focal length 0.01 m; 160–180 feature points on a plane 1 m from the target;
90 % of the points carry image noise of variance 0.02 or 0.1 (mm², as printed), 10 % variance
3 mm² (gross errors). Everything the paper leaves unstated is a field of :class:`Scenario` or
:class:`Settings`.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import Any

import numpy as np
from scipy import stats

from eotrack.pose import (
    RansacConfig,
    attitude_matrix,
    intrinsic_matrix,
    project_points,
    rotation_error_deg,
)
from eotrack.validation import as_points, check_generator, check_int, check_positive

__all__ = [
    "READINGS",
    "SLUG",
    "TITLE",
    "Scenario",
    "Scene",
    "Settings",
    "estimate_point_sigma",
    "make_scene",
    "pose_errors",
    "with_changes",
]

SLUG = "ransac_crlb_pose"
TITLE = ("Ning M., Zhang S., Zhang H. Robust visual navigation of non-cooperative spacecraft with "
         "active feature selection. Aerospace Shanghai 33(6):136-141, 2016. "
         "DOI 10.19328/j.cnki.1006-1630.2016.06.020")

#: Readings of the §2.4 rule: name → (score rule, start test, noise given to the selector).
#: ``noise`` is ``"true"`` (the simulator's σ_i, an oracle), ``"est"`` (σ_i² estimated per point
#: from its residual, :func:`estimate_point_sigma`) or ``"residuals"`` (one σ² estimated from
#: the set's residuals, the paper's eq. (5) model). See :mod:`eotrack.pose.selection`.
READINGS: dict[str, tuple[str, str, str]] = {
    "as printed": ("exact", "paper", "true"),
    "exact": ("exact", "per_point", "true"),
    "pooled": ("pooled", "per_point", "residuals"),
    "sandwich": ("sandwich", "per_point", "true"),
    "sandwich (est. σ)": ("sandwich", "per_point", "est"),
    "tolerance": ("tolerance", "per_point", "true"),
}


@dataclass(frozen=True)
class Scenario:
    """The simulated scene (§3). Defaults are the paper's settings; adopted values say so.

    Attributes
    ----------
    position_m
        Target centre of mass in the camera frame (paper).
    attitude_deg, euler_seq
        Attitude angles (paper) and their sequence (adopted: extrinsic x-y-z).
    focal_m
        Focal length (paper); image coordinates are in mm on the focal plane.
    plane_side_m
        Side of the square feature plane; the paper prints "22 m²", read as 2 m × 2 m.
    plane_offset_m
        The plane is ``Z_t = −plane_offset_m`` in the target frame (faces the camera; paper:
        "1 m from the target").
    n_points
        Inclusive range of the number of features per run (paper: 160–180).
    inlier_variances
        Per-axis noise variances of the well-matched 90 % (paper: 0.02 or 0.1, chosen at random).
    outlier_variance, outlier_fraction
        Variance of the 10 % gross errors (paper: 3).
    noise_unit_mm
        Length (mm) of the unit the variances are printed in: 1.0 = mm² as printed; 0.01 =
        px² for a 10 µm pixel (the "pixel reading", see the notebook's errata).
    """

    position_m: tuple[float, float, float] = (1.0, 1.2, 10.0)
    attitude_deg: tuple[float, float, float] = (15.0, 20.0, 10.0)
    euler_seq: str = "xyz"
    focal_m: float = 0.01
    plane_side_m: float = 2.0
    plane_offset_m: float = 1.0
    n_points: tuple[int, int] = (160, 180)
    inlier_variances: tuple[float, float] = (0.02, 0.1)
    outlier_variance: float = 3.0
    outlier_fraction: float = 0.1
    noise_unit_mm: float = 1.0

    @property
    def R(self) -> np.ndarray:
        """True rotation target → camera."""
        return attitude_matrix(self.attitude_deg, self.euler_seq)

    @property
    def t(self) -> np.ndarray:
        """True translation (m)."""
        return np.asarray(self.position_m, float)

    @property
    def K(self) -> np.ndarray:
        """Intrinsics with image coordinates in mm (``f`` in mm, principal point at 0)."""
        return intrinsic_matrix(self.focal_m * 1e3)

    def sigma_mm(self, variance: Any) -> np.ndarray:
        """Noise standard deviation (image mm) of a printed variance."""
        return np.sqrt(np.asarray(variance, float)) * self.noise_unit_mm


@dataclass(frozen=True)
class Settings:
    """Experiment settings (trial counts, RANSAC, selection readings).

    ``reading`` is the primary reading of the §2.4 rule; the one that decides the statuses is
    fixed in ``papers_repro/ransac_crlb_pose/claims.toml`` (``[protocol]``) before the run.
    """

    n_runs: int = 300            # Figs. 4–5 (paper)
    n_runs_counts: int = 80      # Fig. 6 (paper)
    reading: str = "pooled"      # primary reading (claims.toml [protocol])
    inlier_chi2: float = 0.99    # inlier threshold = χ²₂ quantile × largest inlier variance
    min_inlier_ratio: float = 0.6
    max_draws: int = 500         # RANSAC's preset number of draws (unstated)
    crlb_max_draws: int = 50     # CRLB start draws before falling back to all inliers
    tolerance: float = 0.01      # relative decrease required under the "tolerance" reading
    n_mc_efficiency: int = 200   # Monte Carlo draws per noise level (beyond the paper)
    n_runs_budget: int = 30      # scenes for the budgeted-selection study (beyond the paper)
    seed: int = 20161110
    readings: tuple[str, ...] = ("as printed", "pooled", "sandwich", "sandwich (est. σ)",
                                 "tolerance")

    def ransac_config(self, scenario: Scenario) -> RansacConfig:
        """The paper's RANSAC (:meth:`RansacConfig.paper`: 6-point DLT, first accepted draw)
        for ``scenario`` (threshold in image mm, scales with the unit)."""
        thr = float(np.sqrt(stats.chi2.ppf(self.inlier_chi2, 2)
                            * max(scenario.inlier_variances)) * scenario.noise_unit_mm)
        return RansacConfig.paper(inlier_threshold_px=thr,
                                  min_inlier_ratio=self.min_inlier_ratio,
                                  max_draws=self.max_draws)


@dataclass(frozen=True)
class Scene:
    """One simulated image: model points, noisy image points and the truth."""

    points: np.ndarray
    pixels: np.ndarray
    sigma: np.ndarray
    gross: np.ndarray
    R: np.ndarray
    t: np.ndarray
    K: np.ndarray


def make_scene(rng: np.random.Generator, scenario: Scenario | None = None, *,
               n_points: int | None = None, outlier_fraction: float | None = None) -> Scene:
    """Simulate one image of the paper's scene (§3).

    Parameters
    ----------
    rng
        Generator.
    scenario
        :class:`Scenario` (paper defaults).
    n_points, outlier_fraction
        Override the number of points / the gross-error fraction.
    """
    rng = check_generator(rng)
    sc = scenario or Scenario()
    if not isinstance(sc, Scenario):
        raise TypeError(f"scenario must be a Scenario, got {type(sc).__name__}")
    lo, hi = sc.n_points
    n = int(rng.integers(lo, hi + 1)) if n_points is None else check_int(n_points, "n_points",
                                                                             min_value=6)
    frac = sc.outlier_fraction if outlier_fraction is None else float(outlier_fraction)
    if not 0.0 <= frac < 1.0:
        raise ValueError(f"outlier_fraction must lie in [0, 1), got {frac}")
    half = sc.plane_side_m / 2
    X = np.column_stack([rng.uniform(-half, half, (n, 2)), np.full(n, -sc.plane_offset_m)])
    var = np.asarray(sc.inlier_variances, float)[rng.integers(0, len(sc.inlier_variances), n)]
    gross = np.zeros(n, bool)
    gross[rng.permutation(n)[:round(frac * n)]] = True
    var[gross] = sc.outlier_variance
    sigma = sc.sigma_mm(var)
    u = project_points(X, sc.R, sc.t, sc.K) + rng.normal(size=(n, 2)) * sigma[:, None]
    return Scene(X, u, sigma, gross, sc.R, sc.t, sc.K)


def pose_errors(R: np.ndarray, t: np.ndarray, scene: Scene) -> tuple[float, float]:
    """Position error ``|t̂ − t|`` (m) and attitude error (angle of ``R̂ Rᵀ``, deg)."""
    return float(np.linalg.norm(np.asarray(t, float) - scene.t)), rotation_error_deg(R, scene.R)


def estimate_point_sigma(residuals: Any, *, floor: float = 1e-3) -> np.ndarray:
    """Per-point noise estimated from the reprojection residuals, ``σ̂_i = |r_i| / √2``.

    One image gives each point one 2-vector residual: ``|r_i|²/2`` is an unbiased (if very
    noisy, 2 degrees of freedom) estimate of ``σ_i²`` — the heteroskedasticity-consistent
    ("HC0") input of a sandwich covariance, which a real system can compute without knowing
    the noise. Estimates are floored at ``floor`` × their median so that every σ̂_i > 0.
    """
    r = as_points(residuals, "residuals", dim=2)
    check_positive(floor, "floor")
    s = np.sqrt(np.sum(r * r, axis=1) / 2.0)
    lo = floor * max(float(np.median(s)), 1e-300)
    return np.maximum(s, lo)


def with_changes(scenario: Scenario | None = None, **changes: Any) -> Scenario:
    """A copy of ``scenario`` (default: the paper's) with some fields changed (for widgets)."""
    check_positive(changes.get("noise_unit_mm", 1.0), "noise_unit_mm")
    return replace(scenario or Scenario(), **changes)
