"""Beyond the paper: Stone Soup's multi-measurement initiator on the same scenes."""

from __future__ import annotations

from datetime import datetime, timedelta
from typing import Any

import numpy as np
import pandas as pd

from eotrack.montecarlo import TrialRunner
from eotrack.tracking.initiation.base import Track, validate_frames
from eotrack.tracking.initiation.gating import TrackHandOff, canonical_order
from eotrack.validation import check_int, check_positive

from .scenario import (
    ComparisonConfig,
    XuConfig,
    comparison_initiators,
    comparison_scene,
    score_tracks,
    xu_config,
    xu_initiator,
)

__all__ = ["StoneSoupInitiator", "stonesoup_comparison"]


class StoneSoupInitiator:
    """Stone Soup's ``MultiMeasurementInitiator`` behind the common ``initiate(frames)`` interface.

    A 2-D constant-velocity Kalman model (position measured with ``sigma_px``), a single-point
    initiator whose velocity prior is zero-mean with standard deviation ``v_sigma_px_s``, a
    Mahalanobis distance hypothesiser (missed distance ``gate_sigma``), global nearest neighbour
    association, confirmation at ``min_points`` updates and deletion after ``max_misses`` frames
    without an update. Confirmed tracks are handed off exactly as for our initiators.
    """

    def __init__(self, *, min_points: int = 3, max_misses: int = 2, sigma_px: float = 0.5,
                 v_sigma_px_s: float = 120.0, q: float = 1.0, gate_sigma: float = 3.0,
                 handoff_gate_px: float = 5.0) -> None:
        self.min_points = check_int(min_points, "min_points", min_value=2)
        self.max_misses = check_int(max_misses, "max_misses", min_value=1)
        self.sigma_px = check_positive(sigma_px, "sigma_px")
        self.v_sigma_px_s = check_positive(v_sigma_px_s, "v_sigma_px_s")
        self.q = check_positive(q, "q")
        self.gate_sigma = check_positive(gate_sigma, "gate_sigma")
        self.handoff_gate_px = check_positive(handoff_gate_px, "handoff_gate_px")

    def initiate(self, frames) -> list[Track]:
        """Confirmed tracks from ``frames`` (a sequence of ``(time_s, xy)``)."""
        from stonesoup.dataassociator.neighbour import GNNWith2DAssignment
        from stonesoup.deleter.time import UpdateTimeStepsDeleter
        from stonesoup.hypothesiser.distance import DistanceHypothesiser
        from stonesoup.initiator.simple import MultiMeasurementInitiator
        from stonesoup.measures import Mahalanobis
        from stonesoup.models.measurement.linear import LinearGaussian
        from stonesoup.models.transition.linear import (
            CombinedLinearGaussianTransitionModel,
            ConstantVelocity,
        )
        from stonesoup.predictor.kalman import KalmanPredictor
        from stonesoup.types.detection import Detection
        from stonesoup.types.state import GaussianState
        from stonesoup.types.update import Update
        from stonesoup.updater.kalman import KalmanUpdater

        fr = validate_frames(frames)
        perms = [canonical_order(f.xy) for f in fr]
        xys = [f.xy[p] for f, p in zip(fr, perms)]
        work = [type(f)(f.time_s, x) for f, x in zip(fr, xys)]
        trans = CombinedLinearGaussianTransitionModel([ConstantVelocity(self.q)] * 2)
        meas = LinearGaussian(ndim_state=4, mapping=(0, 2),
                              noise_covar=np.eye(2) * self.sigma_px**2)
        predictor = KalmanPredictor(trans)
        updater = KalmanUpdater(meas)
        hyp = DistanceHypothesiser(predictor, updater, measure=Mahalanobis(),
                                   missed_distance=self.gate_sigma)
        prior = GaussianState(np.zeros((4, 1)),
                              np.diag([1.0, self.v_sigma_px_s**2, 1.0, self.v_sigma_px_s**2]))
        ini = MultiMeasurementInitiator(prior_state=prior,
                                        deleter=UpdateTimeStepsDeleter(self.max_misses),
                                        data_associator=GNNWith2DAssignment(hyp),
                                        updater=updater, measurement_model=meas,
                                        min_points=self.min_points)
        t0 = datetime(2016, 1, 1)
        handoff = TrackHandOff(self.handoff_gate_px)
        avail = [np.ones(len(x), dtype=bool) for x in xys]
        for k, f in enumerate(work):
            handoff.claim(k, f.time_s, f.xy, avail[k])
            ts = t0 + timedelta(seconds=f.time_s)
            dets = {Detection(np.array([[x], [y]]), timestamp=ts, measurement_model=meas,
                              metadata={"frame": k, "det": int(d)})
                    for d, (x, y) in enumerate(f.xy) if avail[k][d]}
            sure = ini.initiate(dets, ts)
            for tr in sorted(sure, key=lambda t: (t.state_vector[0, 0], t.state_vector[2, 0])):
                hits = [(s.hypothesis.measurement.metadata["frame"],
                         s.hypothesis.measurement.metadata["det"])
                        for s in tr.states if isinstance(s, Update)]
                if any(not avail[f2][d2] for f2, d2 in hits):
                    continue
                for f2, d2 in hits:
                    avail[f2][d2] = False
                handoff.confirm(hits, k, work, info={"method": "stonesoup"})
        return handoff.tracks(perms)


def _stonesoup_trial(rng: np.random.Generator, cfg: ComparisonConfig, lam: float,
                     pd_: float, xu: XuConfig) -> dict[str, Any]:
    scene = comparison_scene(rng, cfg, lam, pd_)
    out = {}
    for name, ini in (("Stone Soup MultiMeasurementInitiator (3 updates)", StoneSoupInitiator()),
                      ("modified Hough 3/4 (paper)", xu_initiator(xu)),
                      ("modified Hough 3/4 (ours)", xu_initiator(xu, literal=False)),
                      ("logic 3/4", comparison_initiators(cfg, xu)["logic 3/4"])):
        sc = score_tracks(ini.initiate(scene.frames), scene, n=xu.rule_m - 1, m=xu.rule_m)
        out[name] = (sc["correct"], sc["eligible"], sc["false"])
    return out


def stonesoup_comparison(cfg: ComparisonConfig, *, levels: tuple[float, ...] = (0.0, 10.0),
                         n_trials: int = 10, runner: TrialRunner | None = None,
                         xu: XuConfig | None = None) -> pd.DataFrame:
    """Stone Soup's initiator beside ours on the same seeded scenes (P_D nominal)."""
    xu = xu or xu_config()
    runner = runner or TrialRunner(progress=False)
    rows = []
    for lam in levels:
        res = runner.map(_stonesoup_trial, n_trials, seed=cfg.seed + 2,
                         args=(cfg, float(lam), cfg.p_detect_nominal, xu), desc="Stone Soup")
        for name in res[0]:
            c = sum(r[name][0] for r in res)
            e = sum(r[name][1] for r in res)
            f = sum(r[name][2] for r in res)
            rows.append({"clutter": lam, "method": name, "p_correct": c / max(e, 1),
                         "false_per_frame": f / (n_trials * cfg.n_frames)})
    return pd.DataFrame(rows)


