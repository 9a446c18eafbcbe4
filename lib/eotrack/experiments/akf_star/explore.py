"""akf_star Explore panel: the reproduction's sequences, re-filtered without simulating again.

A sequence is named by its scenario, its index ``seed`` among the ablation's sequences of that
scenario (:func:`.trials.sequence_seed`) and, for the cloud scenario, the occlusion length.
With the same index and the scenario's preset occlusion it *is* the ablation's sequence; with
another occlusion length it is the same draw (ship motion, noise, cloud shapes) with clouds that
move at another speed — the only simulation input that changes.

What a control changes decides what is recomputed:

* scenario, seed, occlusion → a different sequence: its measurements come from the ablation
  (:attr:`.trials.AblationResult.measurements`) or from :meth:`ExploreSession.precompute`; the
  clouds change the images themselves (they dim every star and add moonlit sky), so another
  occlusion length is a new simulation and extraction, done once in ``precompute``;
* filter settings (b, λ, γ, η) → only the confidence filter is run again, on the stored
  centroids; the standard-KF variants ignore these settings and are cached.
"""

from __future__ import annotations

from dataclasses import replace
from functools import lru_cache
from typing import Any

import numpy as np
import pandas as pd

from eotrack.imaging.star_sensor_sim import SCENARIOS, StarSequence, scenario, simulate_sequence
from eotrack.montecarlo import trial_generators
from eotrack.tracking.kalman import ConfidenceConfig
from eotrack.validation import check_choice, check_int

from .scenario import VARIANT_PARTS, VARIANTS, AblationConfig
from .trials import (
    AblationResult,
    SequenceMeasurements,
    measure_sequence,
    sequence_seed,
    track_measurements,
)

__all__ = ["ExploreSession", "isolate_confidence"]

_Key = tuple[str, int, int, float, float]


def _frozen(a: np.ndarray) -> np.ndarray:
    a = np.asarray(a, dtype=float)
    a.setflags(write=False)
    return a


class ExploreSession:
    """Measurements and per-variant errors of the ablation's sequences, for the Explore panel.

    Parameters
    ----------
    n_frames
        Frames per sequence (default: the ablation's, or 200 without one).
    maxsize
        Sequences measured on demand (outside the ablation and :meth:`precompute`) kept in
        memory.
    ablation
        An :class:`.trials.AblationResult` with its measurements: its sequences and its
        standard-KF errors are used as they are (no simulation, no extraction, no filtering);
        its configuration becomes the session's.

    Attributes
    ----------
    config
        The :class:`AblationConfig` (filters, extraction, root seed).
    n_simulated
        Number of sequences this session has simulated (0 when every request was served from
        the ablation or the precomputed ones).
    """

    def __init__(self, n_frames: int | None = None, maxsize: int = 16, *,
                 ablation: AblationResult | None = None) -> None:
        check_int(maxsize, "maxsize", min_value=1)
        if ablation is not None:
            if not isinstance(ablation, AblationResult):
                raise TypeError(f"ablation must be an AblationResult, got "
                                f"{type(ablation).__name__}")
            if ablation.measurements is None:
                raise ValueError("ablation holds no measurements (run_ablation keeps them)")
            if n_frames is not None and int(n_frames) != ablation.config.n_frames:
                raise ValueError(f"n_frames must match the ablation's "
                                 f"{ablation.config.n_frames}, got {n_frames}")
            self.config = ablation.config
            self.scenarios: tuple[str, ...] = tuple(ablation.scenarios)
        else:
            n = 200 if n_frames is None else check_int(n_frames, "n_frames", min_value=2)
            self.config = AblationConfig(n_frames=n)
            self.scenarios = SCENARIOS
        self.n_frames = self.config.n_frames
        self.n_simulated = 0
        self._fixed: dict[_Key, SequenceMeasurements] = {}
        self._fixed_standard: dict[_Key, dict[str, np.ndarray]] = {}
        self._measured = lru_cache(maxsize=maxsize)(self._measure)
        self._standard = lru_cache(maxsize=4 * maxsize)(self._make_standard)
        self._confidence = lru_cache(maxsize=512)(self._make_confidence)
        if ablation is not None:
            ex = self.config.extraction
            kf = [(j, v) for j, v in enumerate(ablation.variants) if VARIANT_PARTS[v][1] == "kf"]
            for i, sc in enumerate(self.scenarios):
                for k, meas in enumerate(ablation.measurements[i]):
                    key = (sc, k, scenario(sc).occlusion_frames, float(ex.k), float(ex.k_b))
                    self._fixed[key] = meas
                    self._fixed_standard[key] = {v: _frozen(ablation.errors[i, k, j])
                                                 for j, v in kf}

    # ---- keys and sequences ---------------------------------------------------------------

    def _key(self, scenario_name: str, seed: int, occlusion_frames: int, k: float | None,
             k_b: float | None) -> _Key:
        check_choice(scenario_name, "scenario_name", self.scenarios)
        seed = check_int(seed, "seed", min_value=0)
        occ = check_int(occlusion_frames, "occlusion_frames", min_value=1)
        preset = scenario(scenario_name)
        if preset.n_clouds == 0:        # no clouds: the occlusion length changes nothing
            occ = preset.occlusion_frames
        ex = self.config.extraction
        return (scenario_name, seed, occ, float(ex.k if k is None else k),
                float(ex.k_b if k_b is None else k_b))

    def _rng(self, scenario_name: str, seed: int) -> np.random.Generator:
        root = sequence_seed(self.config, self.scenarios.index(scenario_name))
        return trial_generators(root, seed + 1)[seed]

    def _cfg(self, key: _Key, confidence: ConfidenceConfig | None = None) -> AblationConfig:
        cfg = replace(self.config, extraction=replace(self.config.extraction, k=key[3],
                                                      k_b=key[4]))
        return cfg if confidence is None else replace(cfg, confidence=confidence)

    def _measure(self, key: _Key) -> SequenceMeasurements:
        sc = scenario(key[0], occlusion_frames=key[2])
        self.n_simulated += 1
        return measure_sequence(self._rng(key[0], key[1]), sc, self._cfg(key))

    def _measurements(self, key: _Key) -> SequenceMeasurements:
        return self._fixed[key] if key in self._fixed else self._measured(key)

    def _make_standard(self, key: _Key) -> dict[str, np.ndarray]:
        if key in self._fixed_standard:
            return self._fixed_standard[key]
        meas = self._measurements(key)
        kf = {v: p for v, p in VARIANT_PARTS.items() if p[1] == "kf"}
        res = track_measurements(meas, self._cfg(key), variants=kf)
        return {v: _frozen(np.hypot(*(r.xs[:, :2] - meas.truth).T)) for v, r in res.items()}

    def _make_confidence(self, key: _Key, variant: str, confidence: ConfidenceConfig
                         ) -> np.ndarray:
        meas = self._measurements(key)
        res = track_measurements(meas, self._cfg(key, confidence),
                                 variants={variant: VARIANT_PARTS[variant]})[variant]
        return _frozen(np.hypot(*(res.xs[:, :2] - meas.truth).T))

    # ---- public ---------------------------------------------------------------------------

    def precompute(self, scenarios: tuple[str, ...] | None = None, seeds: tuple[int, ...] = (0,),
                   occlusions: tuple[int, ...] = ()) -> int:
        """Measure every (scenario, seed, occlusion) the panel offers and cache the standard-KF
        errors, so that no later request simulates; returns the number of new simulations.

        Sequences of the ablation are reused; for scenarios without clouds the occlusion
        lengths are all the same sequence.
        """
        before = self.n_simulated
        scenarios = self.scenarios if scenarios is None else tuple(scenarios)
        for sc in scenarios:
            for s in seeds:
                for occ in (occlusions or (scenario(sc).occlusion_frames,)):
                    key = self._key(sc, s, occ, None, None)
                    if key not in self._fixed:
                        self._fixed[key] = self._measure(key)
                    self._standard(key)
        return self.n_simulated - before

    def add_measurements(self, scenario_name: str, seed: int, occlusion_frames: int,
                         meas: SequenceMeasurements) -> None:
        """Use stored measurements (e.g. read from the committed run's file) for one sequence
        at the configuration's extraction thresholds; a sequence already held is kept."""
        if not isinstance(meas, SequenceMeasurements):
            raise TypeError(f"meas must be SequenceMeasurements, got {type(meas).__name__}")
        if len(meas.truth) != self.n_frames:
            raise ValueError(f"meas has {len(meas.truth)} frames, the session {self.n_frames}")
        key = self._key(scenario_name, seed, occlusion_frames, None, None)
        self._fixed.setdefault(key, meas)

    def measurements(self, scenario_name: str, seed: int = 0, occlusion_frames: int = 10
                     ) -> SequenceMeasurements:
        """The (cached) measurements of one sequence."""
        return self._measurements(self._key(scenario_name, seed, occlusion_frames, None, None))

    def sequence(self, scenario_name: str, seed: int = 0, occlusion_frames: int = 10
                 ) -> StarSequence:
        """The simulated sequence itself, images included (simulated again on every call)."""
        key = self._key(scenario_name, seed, occlusion_frames, None, None)
        sc = scenario(key[0], occlusion_frames=key[2])
        self.n_simulated += 1
        return simulate_sequence(self._rng(key[0], key[1]), sc, n_frames=self.n_frames)

    def errors(self, scenario_name: str = "cloud", *, seed: int = 0, occlusion_frames: int = 10,
               k: float | None = None, k_b: float | None = None,
               confidence: ConfidenceConfig | None = None,
               variants: tuple[str, ...] = VARIANTS) -> dict[str, np.ndarray]:
        """Per-frame errors (pixels, read-only arrays) of ``variants`` on one sequence.

        Parameters
        ----------
        scenario_name
            One of the session's scenarios.
        seed
            Index of the sequence among the ablation's sequences of that scenario.
        occlusion_frames
            Frames a cloud hides the star (cloud scenario only; ignored elsewhere).
        k, k_b
            Extraction thresholds (default: the configuration's).
        confidence
            Settings of the confidence filter (default: the configuration's); only the
            confidence-filter variants depend on them and only they are re-run.
        variants
            Variants to return (among ``VARIANTS``).
        """
        unknown = set(variants) - set(VARIANTS)
        if unknown:
            raise ValueError(f"variants must be among {VARIANTS}, got {sorted(unknown)}")
        if confidence is not None and not isinstance(confidence, ConfidenceConfig):
            raise TypeError(f"confidence must be a ConfidenceConfig, got "
                            f"{type(confidence).__name__}")
        key = self._key(scenario_name, seed, occlusion_frames, k, k_b)
        confidence = confidence or self.config.confidence
        standard = self._standard(key)
        out: dict[str, Any] = {}
        for v in VARIANTS:
            if v in variants:
                out[v] = standard[v] if v in standard else self._confidence(key, v, confidence)
        return out


def isolate_confidence(session: ExploreSession, scenario_name: str = "sway",
                       seeds: tuple[int, ...] = (0, 1, 2)) -> pd.DataFrame:
    """The confidence AKF's two mechanisms isolated on stored sequences: BEAK-ST re-filtered with
    the Sage–Husa adaptation on/off (``adaptive_noise``) × the motion gating on/off (η = 0 makes
    C_motion ≡ 1), everything else as the session's settings. Returns, per combination, the
    number of sequences lost (final error beyond the gate) and the median of their mean errors."""

    if not isinstance(session, ExploreSession):
        raise TypeError(f"session must be an ExploreSession, got {type(session).__name__}")
    if not seeds:
        raise ValueError("seeds must name at least one sequence")
    c0 = session.config.confidence
    rows = {}
    for sh in (True, False):
        for gate in (True, False):
            cc = replace(c0, adaptive_noise=sh, eta=c0.eta if gate else 0.0)
            errs = [session.errors(scenario_name, seed=k, confidence=cc,
                                   variants=("BEAK-ST",))["BEAK-ST"] for k in seeds]
            rows[("on" if sh else "off", "on" if gate else "off")] = {
                f"lost (of {len(seeds)})": int(sum(e[-1] > session.config.gate_px
                                                   for e in errs)),
                "median of mean errors (px)": float(np.median([e.mean() for e in errs]))}
    out = pd.DataFrame(rows).T
    out.index.names = ["Sage–Husa", "motion gating"]
    return out
