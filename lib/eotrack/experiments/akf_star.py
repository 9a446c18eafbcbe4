"""Paper akf_star: adaptive anti-occlusion star tracking on a ship (Sheng 2026) — the ablation.

Four variants (Baseline, BEAK-ST-GT, BEAK-ST-SKF, BEAK-ST) × five scenarios (strong light,
cloud occlusion, ship sway, stray light, low SNR) × seeds × 200 frames of a simulated real-sky
shipborne star-sensor sequence (:mod:`eotrack.imaging.star_sensor_sim`): adaptive or global
extraction (:mod:`eotrack.imaging.extraction`), then a standard or confidence-gated adaptive
Kalman filter (:mod:`eotrack.tracking.kalman`) with nearest-neighbour association. Metrics:
the per-frame error ``e_i`` (eq. 47), its mean ``E`` (eq. 48), success ``e_i ≤ ε`` and the rate
``P_s`` (eqs. 49–50), and a continuity measure (estimate inside the association gate).
"""

from __future__ import annotations

from dataclasses import asdict, dataclass, field
from typing import Any

import numpy as np
import pandas as pd

from eotrack.geometry.shipboard import sea_state_motion
from eotrack.imaging.extraction import ExtractionConfig, extract_stars, image_confidence
from eotrack.imaging.star_sensor_sim import (
    SCENARIOS,
    SensorConfig,
    StarSequence,
    simulate_sequence,
    sway_acceleration_variance,
)
from eotrack.montecarlo import TrialRunner, run_trials
from eotrack.repro import ClaimResult, Reproduction, Status, load_claims
from eotrack.tracking.kalman import (
    ConfidenceConfig,
    ConfidenceKalmanFilter,
    KalmanFilter,
    TrackResult,
    constant_acceleration_model,
    constant_velocity_model,
    singer_process_noise,
    track_nearest,
    white_acceleration_noise,
)
from eotrack.validation import check_choice

SLUG = "akf_star"
TITLE = ("Sheng Y.S., Adaptive anti-occlusion star tracking algorithm for ships based on a "
         "physical model, Intelligent Computer and Applications 16(4):195-202, 2026, "
         "DOI 10.20169/j.issn.2095-2163.26010403")

VARIANTS = ("Baseline", "BEAK-ST-GT", "BEAK-ST-SKF", "BEAK-ST")
#: variant -> (extraction method, filter kind)
VARIANT_PARTS: dict[str, tuple[str, str]] = {
    "Baseline": ("global", "kf"),
    "BEAK-ST-GT": ("global", "akf"),
    "BEAK-ST-SKF": ("adaptive", "kf"),
    "BEAK-ST": ("adaptive", "akf"),
}
SCENARIO_LABELS = {"strong_light": "strong light", "cloud": "cloud occlusion",
                   "sway": "ship sway", "stray_light": "stray light", "low_snr": "low SNR"}

__all__ = [
    "SCENARIO_LABELS",
    "SLUG",
    "TITLE",
    "VARIANTS",
    "VARIANT_PARTS",
    "AblationConfig",
    "AblationResult",
    "claim_results",
    "make_filter",
    "plot_error_curves",
    "plot_example_frames",
    "plot_success_curves",
    "reproduce",
    "run_ablation",
    "track_sequence",
]


@dataclass(frozen=True)
class AblationConfig:
    """Settings of the ablation (the paper gives none of these except the 200 frames).

    Attributes
    ----------
    n_frames, n_seeds
        Frames per sequence and sequences per scenario.
    epsilon_px
        Success threshold ε of eq. (49) (not given by the paper; adopted).
    gate_px, gate_sigma, gate_max_px, hold_after
        Association gate and track maintenance (see
        :func:`eotrack.tracking.kalman.track_nearest`); continuity counts frames whose estimate
        lies within ``gate_px`` of the truth.
    r_px2
        Initial measurement variance R (pixels²) of every filter.
    prior_sea_state
        Sea state whose sway spectrum initialises the Singer ``q_a`` (all scenarios — the filter
        does not know the scenario).
    singer_period_s
        Sway period setting the Singer α = 2π / period.
    cv_q
        White-acceleration density of the constant-velocity filter (beyond the paper).
    snr_ref, flux_tol
        Parameters of our ``C_img`` (:func:`eotrack.imaging.image_confidence`).
    extraction, confidence
        Extraction and confidence-filter settings.
    seed
        Root seed.
    """

    n_frames: int = 200
    n_seeds: int = 20
    epsilon_px: float = 2.0
    gate_px: float = 10.0
    gate_sigma: float = 4.0
    gate_max_px: float = 30.0
    hold_after: int = 5
    r_px2: float = 0.25
    prior_sea_state: int = 3
    singer_period_s: float = 9.0
    cv_q: float = 400.0
    snr_ref: float = 8.0
    flux_tol: float = 0.7
    extraction: ExtractionConfig = field(default_factory=ExtractionConfig)
    confidence: ConfidenceConfig = field(default_factory=ConfidenceConfig)
    seed: int = 20260404


def make_filter(kind: str, x0: np.ndarray, sensor: SensorConfig, cfg: AblationConfig
                ) -> KalmanFilter:
    """Build a filter: ``"kf"`` standard CA + Singer Q, ``"akf"`` the confidence-gated adaptive
    filter, ``"cv"`` a constant-velocity filter (beyond the paper)."""
    check_choice(kind, "kind", ("kf", "akf", "cv"))
    dt = sensor.dt
    motion = sea_state_motion(cfg.prior_sea_state)
    qa = sway_acceleration_variance(motion, sensor)
    alpha = 2 * np.pi / cfg.singer_period_s
    sigma_w = float(np.sqrt(2 * alpha * qa / -np.expm1(-2 * alpha * dt)))
    f = sensor.focal_px
    amps = [(np.radians(np.asarray(getattr(motion, f"{a}_amp_deg"))) * f,
             2 * np.pi / np.asarray(getattr(motion, f"{a}_period_s")))
            for a in ("roll", "pitch", "yaw")]
    v2 = sum(float(np.sum((A * w) ** 2) / 2) for A, w in amps)
    a2 = sum(float(np.sum((A * w * w) ** 2) / 2) for A, w in amps)
    R = cfg.r_px2 * np.eye(2)
    if kind == "cv":
        F, H = constant_velocity_model(dt)
        Q = white_acceleration_noise(dt, cfg.cv_q)
        P0 = np.diag([1.0, 1.0, v2, v2])
        return KalmanFilter(F, H, Q, R, np.r_[x0[:2], 0.0, 0.0], P0)
    F, H = constant_acceleration_model(dt)
    Q = singer_process_noise(dt, alpha, sigma_w)
    P0 = np.diag([1.0, 1.0, v2, v2, a2, a2])
    xx = np.r_[x0[:2], np.zeros(4)]
    if kind == "kf":
        return KalmanFilter(F, H, Q, R, xx, P0)
    return ConfidenceKalmanFilter(F, H, Q, R, xx, P0, cfg.confidence)


def _detect(seq: StarSequence, method: str, cfg: AblationConfig
            ) -> tuple[list[np.ndarray], list[np.ndarray]]:
    """Per-frame centroids and C_img for one extraction method."""
    dets, infos = [], []
    for img in seq.images:
        r = extract_stars(img, method=method, config=cfg.extraction, return_info=True)
        dets.append(r.xy)
        infos.append(r)
    # reference flux of the designated star: median over the first frames (the operator
    # designates the reference star at start-up; the clouds arrive later)
    ref = []
    for k in range(min(5, len(dets))):
        if len(dets[k]):
            d = np.hypot(*(dets[k] - seq.truth[k]).T)
            j = int(np.argmin(d))
            if d[j] < 3:
                ref.append(infos[k].flux[j])
    flux_ref = float(np.median(ref)) if ref else float(np.median(
        np.concatenate([i.flux for i in infos if len(i)] or [np.ones(1)])))
    c_img = [image_confidence(i.snr, i.flux, flux_ref, snr_ref=cfg.snr_ref,
                              flux_tol=cfg.flux_tol) for i in infos]
    return dets, c_img


def track_sequence(seq: StarSequence, cfg: AblationConfig, rng: np.random.Generator, *,
                   variants: dict[str, tuple[str, str]] | None = None
                   ) -> dict[str, TrackResult]:
    """Run each variant (extraction method, filter kind) on one sequence.

    The filters start from the designated star's position with a 0.3 px error (drawn from
    ``rng``), zero velocity and acceleration.
    """
    variants = VARIANT_PARTS if variants is None else variants
    sensor = seq.info["sensor"]
    x0 = seq.truth[0] + rng.normal(0, 0.3, 2)
    cache: dict[str, tuple[list[np.ndarray], list[np.ndarray]]] = {}
    out = {}
    for name, (method, kind) in variants.items():
        if method not in cache:
            cache[method] = _detect(seq, method, cfg)
        dets, c_img = cache[method]
        filt = make_filter(kind, x0, sensor, cfg)
        res = track_nearest(filt, dets, gate_px=cfg.gate_px, gate_sigma=cfg.gate_sigma,
                            gate_max_px=cfg.gate_max_px, hold_after=cfg.hold_after,
                            c_img=c_img)
        res.extra["n_detections"] = np.array([len(d) for d in dets])
        out[name] = res
    return out


def _trial(rng: np.random.Generator, scenario: str, cfg: AblationConfig) -> dict[str, Any]:
    seq = simulate_sequence(rng, scenario, n_frames=cfg.n_frames)
    res = track_sequence(seq, cfg, rng)
    err = np.stack([np.hypot(*(r.xs[:, :2] - seq.truth).T) for r in res.values()])
    modes = np.stack([r.modes for r in res.values()])
    return {"errors": err.astype(np.float32), "modes": modes, "visible": seq.visible}


@dataclass
class AblationResult:
    """Errors of the ablation.

    Attributes
    ----------
    errors
        ``(n_scenarios, n_seeds, n_variants, n_frames)`` per-frame errors e_i (pixels).
    modes
        Filter modes, same shape (int8).
    visible
        Cloud transmission at the reference star ``(n_scenarios, n_seeds, n_frames)``.
    scenarios, variants
        Axis labels.
    config
        The :class:`AblationConfig`.
    """

    errors: np.ndarray
    modes: np.ndarray
    visible: np.ndarray
    scenarios: tuple[str, ...]
    variants: tuple[str, ...]
    config: AblationConfig

    def mean_error(self) -> pd.DataFrame:
        """Table 1: mean error E (eq. 48) per scenario and variant."""
        return self._frame(self.errors.mean(axis=(1, 3)))

    def success_rate(self, epsilon_px: float | None = None) -> pd.DataFrame:
        """Table 2: success rate P_s (eqs. 49–50) at ε."""
        eps = self.config.epsilon_px if epsilon_px is None else epsilon_px
        return self._frame((self.errors <= eps).mean(axis=(1, 3)))

    def continuity(self) -> pd.DataFrame:
        """Fraction of frames whose estimate lies within the association gate of the truth."""
        return self._frame((self.errors <= self.config.gate_px).mean(axis=(1, 3)))

    def lost_fraction(self) -> pd.DataFrame:
        """Fraction of sequences whose estimate ends farther than ``gate_px`` from the truth
        (the track was lost and not re-acquired)."""
        return self._frame((self.errors[..., -1] > self.config.gate_px).mean(axis=1))

    def median_error(self) -> pd.DataFrame:
        """Median error per scenario and variant (robust companion of Table 1)."""
        return self._frame(np.median(self.errors, axis=(1, 3)))

    def _frame(self, a: np.ndarray) -> pd.DataFrame:
        return pd.DataFrame(a, index=[SCENARIO_LABELS.get(s, s) for s in self.scenarios],
                            columns=list(self.variants))


def run_ablation(cfg: AblationConfig | None = None, *, runner: TrialRunner | None = None,
                 scenarios: tuple[str, ...] = SCENARIOS) -> AblationResult:
    """Run the four variants on ``cfg.n_seeds`` sequences of each scenario."""
    cfg = AblationConfig() if cfg is None else cfg
    errs, modes, vis = [], [], []
    for i, sc in enumerate(scenarios):
        out = run_trials(_trial, cfg.n_seeds, seed=cfg.seed + i, args=(sc, cfg), runner=runner,
                         desc=f"akf_star {sc}")
        errs.append(np.stack([o["errors"] for o in out]))
        modes.append(np.stack([o["modes"] for o in out]))
        vis.append(np.stack([o["visible"] for o in out]))
    return AblationResult(np.stack(errs), np.stack(modes), np.stack(vis), tuple(scenarios),
                          VARIANTS, cfg)


# --------------------------------------------------------------------------------------------
# figures
# --------------------------------------------------------------------------------------------

def plot_error_curves(res: AblationResult, ax: Any = None, *, scenario: str | None = None
                      ) -> Any:
    """Fig. 6: mean tracking error per frame (over seeds, and scenarios unless one is given)."""
    from eotrack.plotting import get_ax

    ax = get_ax(ax)
    e = res.errors if scenario is None else res.errors[[res.scenarios.index(scenario)]]
    curve = e.mean(axis=(0, 1))
    for v, c in zip(res.variants, curve):
        ax.plot(np.arange(1, c.size + 1), c, label=v, lw=1.3 if v == "BEAK-ST" else 0.9)
    ax.set_xlabel("frame")
    ax.set_ylabel("mean tracking error (px)")
    ax.set_yscale("log")
    ax.set_title("Fig. 6 — mean tracking error over the frames"
                 + (f" ({SCENARIO_LABELS[scenario]})" if scenario else " (all scenarios)"))
    ax.legend(fontsize=8)
    return ax


def plot_success_curves(res: AblationResult, ax: Any = None, *, scenario: str | None = None
                        ) -> Any:
    """Fig. 7: success rate (e ≤ ε) per frame."""
    from eotrack.plotting import get_ax

    ax = get_ax(ax)
    e = res.errors if scenario is None else res.errors[[res.scenarios.index(scenario)]]
    curve = (e <= res.config.epsilon_px).mean(axis=(0, 1))
    for v, c in zip(res.variants, curve):
        ax.plot(np.arange(1, c.size + 1), c, label=v, lw=1.3 if v == "BEAK-ST" else 0.9)
    ax.set_xlabel("frame")
    ax.set_ylabel(f"success rate (e ≤ {res.config.epsilon_px:g} px)")
    ax.set_ylim(-0.02, 1.02)
    ax.set_title("Fig. 7 — mean success rate over the frames"
                 + (f" ({SCENARIO_LABELS[scenario]})" if scenario else " (all scenarios)"))
    ax.legend(fontsize=8)
    return ax


def plot_example_frames(seed: int = 1, frame: int = 120, *, axes: Any = None) -> Any:
    """One frame of each scenario with the reference star's true position marked."""
    import matplotlib.pyplot as plt

    if axes is None:
        _, axes = plt.subplots(1, len(SCENARIOS), figsize=(3.0 * len(SCENARIOS), 3.2))
    for ax, sc in zip(np.ravel(axes), SCENARIOS):
        seq = simulate_sequence(np.random.default_rng(seed), sc, n_frames=frame + 1)
        ax.imshow(seq.images[frame], cmap="gray", vmin=0, vmax=255)
        ax.plot(*seq.truth[frame], "o", mfc="none", mec="r", ms=12)
        ax.set_title(SCENARIO_LABELS[sc], fontsize=9)
        ax.set_xticks([])
        ax.set_yticks([])
        ax.grid(False)
    return axes


# --------------------------------------------------------------------------------------------
# claims
# --------------------------------------------------------------------------------------------

def _paper_table(claim: Any, key: str) -> pd.DataFrame:
    p = claim.paper
    return pd.DataFrame(p[key], index=p["scenarios"], columns=p["variants"])


def _side_by_side(ours: pd.DataFrame, paper: pd.DataFrame, fmt: int) -> pd.DataFrame:
    cols = {}
    for v in ours.columns:
        cols[f"{v} paper"] = paper[v].to_numpy()
        cols[f"{v} ours"] = ours[v].round(fmt).to_numpy()
    return pd.DataFrame(cols, index=ours.index)


def _claims(res: AblationResult, claims: dict[str, Any]) -> list[ClaimResult]:
    E = res.mean_error()
    Ps = res.success_rate()
    C = res.continuity()
    out = []
    n_sc = len(E)

    # Table 1
    best = (E.idxmin(axis=1) == "BEAK-ST")
    worst = (E.idxmax(axis=1) == "Baseline")
    ours = "; ".join(f"{s}: " + "/".join(f"{x:.2f}" for x in row) for s, row in E.iterrows())
    st = Status.REPRODUCED if best.all() and worst.all() else (
        Status.PARTIAL if best.sum() >= 3 else Status.NOT_REPRODUCED)
    note = "" if st is Status.REPRODUCED else (
        f"BEAK-ST lowest in {best.sum()}/{n_sc} scenarios ({', '.join(E.index[~best]) or '-'} "
        f"not), Baseline highest in {worst.sum()}/{n_sc}.")
    note += (" Absolute errors differ from the paper's (simulated star sensor, not OTB100 "
             "frames); Baseline/GT errors are large where the global threshold loses the star.")
    out.append(ClaimResult.from_claim(claims["akf_star.table1"], status=st, note=note.strip(),
                                      ours="mean error px (Baseline/GT/SKF/BEAK-ST) " + ours))

    # Table 2
    top = Ps.max(axis=1)
    best2 = Ps["BEAK-ST"] >= top - 0.005
    worst2 = Ps["Baseline"] <= Ps.min(axis=1) + 0.005
    ours = "; ".join(f"{s}: " + "/".join(f"{x:.3f}" for x in row) for s, row in Ps.iterrows())
    st = Status.REPRODUCED if best2.all() and worst2.all() else (
        Status.PARTIAL if best2.sum() >= 3 else Status.NOT_REPRODUCED)
    note = "" if st is Status.REPRODUCED else (
        f"BEAK-ST highest in {best2.sum()}/{n_sc}, Baseline lowest in {worst2.sum()}/{n_sc}.")
    note += f" ε = {res.config.epsilon_px:g} px adopted (the paper does not state ε)."
    out.append(ClaimResult.from_claim(claims["akf_star.table2"], status=st, note=note.strip(),
                                      ours=f"success rate at ε={res.config.epsilon_px:g} px " + ours))

    # ablation pattern
    lab = {v: k for k, v in SCENARIO_LABELS.items()}
    p = claims["akf_star.ablation_pattern"].paper
    holds = {}
    for s in p["threshold_helps_most"]:
        holds[s] = bool(E.loc[s, "BEAK-ST-SKF"] < E.loc[s, "BEAK-ST-GT"])
    for s in p["confidence_helps_most"]:
        holds[s] = bool(E.loc[s, "BEAK-ST-GT"] < E.loc[s, "BEAK-ST-SKF"])
    n_hold = sum(holds.values())
    st = Status.REPRODUCED if n_hold == len(holds) and best.all() else (
        Status.PARTIAL if n_hold >= 3 else Status.NOT_REPRODUCED)
    desc = ", ".join(f"{s} {'yes' if h else 'no'}" for s, h in holds.items())
    note = "" if st is Status.REPRODUCED else (
        f"reading holds in {n_hold}/{len(holds)} scenarios ({desc}); BEAK-ST best in "
        f"{best.sum()}/{n_sc}.")
    _ = lab
    out.append(ClaimResult.from_claim(claims["akf_star.ablation_pattern"], status=st,
                                      ours=f"{n_hold}/{len(holds)} readings hold: {desc}",
                                      note=note))

    # Figs. 6-7
    curve = res.errors.mean(axis=(0, 1))                        # (V, n)
    i_b = res.variants.index("BEAK-ST")
    frac6 = float(np.mean(np.argmin(curve, axis=0) == i_b))
    st = Status.REPRODUCED if frac6 >= 0.8 else (Status.PARTIAL if frac6 >= 0.5
                                                 else Status.NOT_REPRODUCED)
    out.append(ClaimResult.from_claim(
        claims["akf_star.fig6"], status=st, ours=f"BEAK-ST lowest in {100 * frac6:.0f} % of frames",
        note="" if st is Status.REPRODUCED else
        f"BEAK-ST's mean-error curve is the lowest in only {100 * frac6:.0f} % of the frames."))
    sc = (res.errors <= res.config.epsilon_px).mean(axis=(0, 1))
    frac7 = float(np.mean(sc[i_b] >= sc.max(axis=0) - 0.01))
    st = Status.REPRODUCED if frac7 >= 0.8 else (Status.PARTIAL if frac7 >= 0.5
                                                 else Status.NOT_REPRODUCED)
    out.append(ClaimResult.from_claim(
        claims["akf_star.fig7"], status=st,
        ours=f"BEAK-ST highest (±0.01) in {100 * frac7:.0f} % of frames",
        note="" if st is Status.REPRODUCED else
        f"BEAK-ST's success curve is the highest in only {100 * frac7:.0f} % of the frames."))

    # headline
    cont = C["BEAK-ST"]
    red = 1 - E["BEAK-ST"].mean() / E["Baseline"].mean()
    ok_c = bool((cont > claims["akf_star.headline"].paper["continuity_min"]).all())
    ok_r = bool(0.25 <= red <= 0.60)
    st = Status.REPRODUCED if ok_c and ok_r else (
        Status.PARTIAL if ok_c or ok_r or red > 0.25 else Status.NOT_REPRODUCED)
    ours = (f"continuity of BEAK-ST {cont.min():.3f}-{cont.max():.3f} over the scenarios; mean "
            f"error {E['BEAK-ST'].mean():.2f} px vs Baseline {E['Baseline'].mean():.2f} px "
            f"({100 * red:.0f} % lower); BEAK-ST success rate {Ps['BEAK-ST'].min():.3f}-"
            f"{Ps['BEAK-ST'].max():.3f}")
    note = ("Continuity is our definition (estimate within the "
            f"{res.config.gate_px:g} px gate, occluded frames included); the paper's 40 % and its "
            "own Table 1 (52 %) disagree, and no Table 2 rate reaches 0.95, so 'continuity' must "
            "be a looser measure than the success rate.")
    if not ok_c:
        note += f" Continuity below 0.95 in {int((cont <= 0.95).sum())} scenario(s)."
    if not ok_r:
        note += (f" Error reduction {100 * red:.0f} % (outside 25-60 %): "
                 + ("the global-threshold Baseline loses the star altogether under strong and "
                    "stray light." if red > 0.6 else "smaller than the paper's."))
    out.append(ClaimResult.from_claim(claims["akf_star.headline"], status=st, ours=ours,
                                      note=note))
    return out


def claim_results(res: AblationResult) -> list[ClaimResult]:
    """One scorecard row per claim id, from an ablation result."""
    return _claims(res, load_claims(SLUG))


def reproduce(*, quick: bool = False, runner: TrialRunner | None = None) -> Reproduction:
    """Run the ablation (20 seeds × 200 frames × 5 scenarios; quick: 4 seeds × 120 frames)."""
    import matplotlib.pyplot as plt

    cfg = AblationConfig(n_seeds=4, n_frames=120) if quick else AblationConfig()
    claims = load_claims(SLUG)
    res = run_ablation(cfg, runner=runner)
    E, Ps, C = res.mean_error(), res.success_rate(), res.continuity()
    tables = {
        "Table 1 — mean tracking error (px), paper vs ours":
            _side_by_side(E, _paper_table(claims["akf_star.table1"], "mean_error_px"), 2),
        f"Table 2 — success rate (ε = {cfg.epsilon_px:g} px), paper vs ours":
            _side_by_side(Ps, _paper_table(claims["akf_star.table2"], "success_rate"), 3),
        f"Continuity (estimate within {cfg.gate_px:g} px of the truth)": C.round(3),
        "Median tracking error (px)": res.median_error().round(2),
        "Lost tracks (fraction of sequences ending > gate from the truth)":
            res.lost_fraction().round(3),
    }
    fig6, ax6 = plt.subplots(figsize=(6.4, 4.0))
    plot_error_curves(res, ax=ax6)
    fig7, ax7 = plt.subplots(figsize=(6.4, 4.0))
    plot_success_curves(res, ax=ax7)
    text = (
        "Data: the paper used 'the first 200 frames of OTB100 sequences' (generic visual "
        "tracking data); we simulate a shipborne star sensor instead — real Gaia/Hipparcos "
        "stars around a 2nd-magnitude reference star seen from 30°N 123°E, astropy Alt/Az, "
        "roll/pitch/yaw as sums of sinusoids, Gaussian PSF with motion blur, shot and read "
        "noise, 8-bit output, 128×128 px, 10° field, 5 Hz. Not stated by the paper and adopted "
        f"here: ε = {cfg.epsilon_px:g} px, the association gate, C_img (SNR × flux "
        "consistency), ω, η, γ, λ and the growth of Q during occlusion "
        "(see eotrack.tracking.kalman.ConfidenceConfig). No parameter was tuned to the paper's "
        "numbers. Adopted after inspecting track losses (for robustness, and stated here as "
        "such): γ = 5 instead of the 99 % χ² value 3 (γ = 3 lost the star in rough-sea "
        "sequences), R ≤ 1 px² and q_a within [1, 16]× its sea-state prior in the Sage–Husa "
        "safeguard, an association gate capped at 30 px, and holding the last position after "
        "5 frames without a measurement (all variants). Mean errors are sensitive to the few "
        "sequences in which a track is lost; see the median and lost-track tables.")
    settings = {"n_seeds": cfg.n_seeds, "n_frames": cfg.n_frames, "epsilon_px": cfg.epsilon_px,
                "gate_px": cfg.gate_px, "gate_sigma": cfg.gate_sigma,
                "gate_max_px": cfg.gate_max_px, "hold_after": cfg.hold_after,
                "confidence": asdict(cfg.confidence),
                "extraction": asdict(cfg.extraction), "quick": quick}
    return Reproduction(SLUG, TITLE, _claims(res, claims), tables,
                        {"fig6_mean_tracking_error": fig6, "fig7_success_rate": fig7},
                        text, settings)
