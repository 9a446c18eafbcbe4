"""Track initiation by temporal continuity (hypothesis testing), Li et al. (2008) §2.

Every candidate point opens a hypothesis "a target starts here". The hypothesis follows the
sequence with nearest-neighbour association in a square ``(2 n_k + 1)²`` gate around its
predicted position; after ``T`` frames (the start frame included) it is accepted as a target
track if it collected at least ``T_h`` points, and rejected otherwise (it is dropped as soon as
``T_h`` can no longer be reached). An accepted track keeps growing by the same association and
ends after ``T − T_h + 1`` consecutive misses (from then on no window of ``T`` frames ending at
the last frame can hold ``T_h`` hits). Points taken by a confirmed track start no new hypothesis,
and the hypotheses that shared points with a newly confirmed track are dropped, so one target
gives one track.

The probabilities of this test are :func:`eotrack.tracking.hypothesis.track_false_alarm`
(eq. 9), :func:`~eotrack.tracking.hypothesis.sequence_detection` (eq. 12) and
:func:`~eotrack.tracking.hypothesis.track_detection` (eq. 13).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field

import numpy as np

from eotrack.tracking.initiation.base import Frame, Track, validate_frames
from eotrack.validation import check_choice, check_int

__all__ = ["TemporalContinuityInitiator", "TemporalTestConfig"]


@dataclass(frozen=True)
class TemporalTestConfig:
    """Parameters of the temporal-continuity test (defaults: the paper's experiment).

    Attributes
    ----------
    gate
        Side ``2 n_k + 1`` of the square association region in pixels (``M = gate²``; paper 3).
    frames
        ``T``, frames per hypothesis, start frame included (paper 7).
    min_hits
        ``T_h``, points needed to accept (paper 5).
    predict
        ``"last"``: the gate is centred on the last associated point (a slow target);
        ``"velocity"``: on the constant-velocity prediction from a least-squares fit of the
        track's points (once it has three), which follows faster or curving targets.
    """

    gate: int = 3
    frames: int = 7
    min_hits: int = 5
    predict: str = "velocity"

    def __post_init__(self) -> None:
        g = check_int(self.gate, "gate", min_value=1)
        if g % 2 == 0:
            raise ValueError(f"gate must be a positive odd side length 2n_k+1, got {g}")
        t = check_int(self.frames, "frames", min_value=1)
        th = check_int(self.min_hits, "min_hits", min_value=1)
        if th > t:
            raise ValueError(f"min_hits (T_h = {th}) must be <= frames (T = {t})")
        check_choice(self.predict, "predict", ("last", "velocity"))


@dataclass
class _Hyp:
    start: int
    hits: list[tuple[int, int]] = field(default_factory=list)
    t: list[float] = field(default_factory=list)
    xy: list[np.ndarray] = field(default_factory=list)
    confirmed_at: int = -1
    last_hit_frame: int = 0


class TemporalContinuityInitiator:
    """Hypothesis-testing track initiation over candidate points (see the module docstring).

    Parameters
    ----------
    config
        Test parameters; the paper's ``M = 3 × 3``, ``T = 7``, ``T_h = 5`` by default.

    Attributes
    ----------
    stats
        After :meth:`initiate`: ``hypotheses`` opened, ``confirmed`` tracks,
        ``opened_per_frame`` (hypotheses opened in each frame).
    """

    def __init__(self, config: TemporalTestConfig | None = None) -> None:
        if config is None:
            config = TemporalTestConfig()
        if not isinstance(config, TemporalTestConfig):
            raise TypeError(f"config must be a TemporalTestConfig, got {type(config).__name__}")
        self.config = config
        self.stats: dict[str, int] = {}

    # -- prediction -------------------------------------------------------------------------
    def _predict(self, h: _Hyp, t_now: float) -> np.ndarray:
        if self.config.predict == "last" or len(h.xy) < 3:
            return h.xy[-1]
        xy = np.asarray(h.xy[-self.config.frames:])
        tt = np.asarray(h.t[-self.config.frames:])
        tc = tt - tt.mean()
        v = (tc[:, None] * (xy - xy.mean(axis=0))).sum(axis=0) / (tc @ tc)
        return xy.mean(axis=0) + v * (t_now - tt.mean())

    def initiate(self, frames: Sequence[tuple[float, np.ndarray]] | Sequence[Frame]) -> list[Track]:
        """Confirmed tracks from candidate points.

        Parameters
        ----------
        frames
            ``(time_s, xy)`` per frame, ``xy`` ``(n, 2)`` candidate points in pixels.

        Returns
        -------
        list of Track
            One per accepted hypothesis, in order of confirmation; ``info`` holds ``n_hits`` and
            ``start_frame``.
        """
        fr = validate_frames(frames)
        cfg = self.config
        half = cfg.gate // 2 + 0.5  # a point in a pixel of the gate: |Δ| ≤ n_k (+ rounding)
        max_miss = cfg.frames - cfg.min_hits + 1
        tentative: list[_Hyp] = []
        active: list[_Hyp] = []
        done: list[_Hyp] = []
        opened = np.zeros(len(fr), dtype=int)
        for k, f in enumerate(fr):
            pts = f.xy
            used = np.zeros(len(pts), dtype=bool)
            # 1. confirmed tracks first: nearest point in the gate, each point to one track
            for h in active:
                j = self._nearest(self._predict(h, f.time_s), pts, half, used)
                if j >= 0:
                    used[j] = True
                    self._add(h, k, j, f)
            still = []
            for h in active:
                (still if k - h.last_hit_frame < max_miss else done).append(h)
            active = still
            # 2. tentative hypotheses: nearest point in the gate (points may be shared)
            survivors: list[_Hyp] = []
            if tentative and len(pts):
                pred = np.array([self._predict(h, f.time_s) for h in tentative])
                d = pts[None, :, :] - pred[:, None, :]  # (n_hyp, n_pts, 2)
                ok = (np.abs(d) <= half).all(axis=2) & ~used[None, :]
                d2 = np.where(ok, (d * d).sum(axis=2), np.inf)
                best = np.argmin(d2, axis=1)
                found = np.isfinite(d2[np.arange(len(tentative)), best])
            else:
                best = np.zeros(len(tentative), dtype=int)
                found = np.zeros(len(tentative), dtype=bool)
            for h, j, hit in zip(tentative, best, found):
                if hit:
                    self._add(h, k, int(j), f)
                n_left = cfg.frames - (k - h.start + 1)
                if len(h.hits) >= cfg.min_hits:
                    h.confirmed_at = k
                    survivors.append(h)
                elif len(h.hits) + n_left >= cfg.min_hits and n_left > 0:
                    survivors.append(h)
            # 3. accept: oldest first; drop hypotheses sharing points with an accepted track
            taken: set[tuple[int, int]] = {hit for h in active for hit in h.hits}
            tentative = []
            for h in sorted(survivors, key=lambda h: (h.start, -len(h.hits))):
                if taken.intersection(h.hits):
                    continue
                if h.confirmed_at >= 0:
                    active.append(h)
                    taken.update(h.hits)
                else:
                    tentative.append(h)
            for kk, j in taken:
                if kk == k:
                    used[j] = True
            # 4. every free point opens a hypothesis
            for j in np.flatnonzero(~used):
                h = _Hyp(start=k)
                self._add(h, k, int(j), f)
                if cfg.min_hits <= 1:
                    h.confirmed_at = k
                    active.append(h)
                else:
                    tentative.append(h)
                opened[k] += 1
        done.extend(active)
        done.sort(key=lambda h: (h.confirmed_at, h.start))
        self.stats = {"hypotheses": int(opened.sum()), "confirmed": len(done),
                      "opened_per_frame": opened.tolist()}
        return [Track(hits=list(h.hits), confirmed_at=h.confirmed_at,
                      info={"n_hits": len(h.hits), "start_frame": h.start}) for h in done]

    @staticmethod
    def _add(h: _Hyp, k: int, j: int, f: Frame) -> None:
        h.hits.append((k, j))
        h.t.append(f.time_s)
        h.xy.append(f.xy[j])
        h.last_hit_frame = k

    @staticmethod
    def _nearest(c: np.ndarray, pts: np.ndarray, half: float, used: np.ndarray) -> int:
        if len(pts) == 0:
            return -1
        d = pts - c
        ok = (np.abs(d) <= half).all(axis=1) & ~used
        if not ok.any():
            return -1
        d2 = np.where(ok, (d * d).sum(axis=1), np.inf)
        return int(np.argmin(d2))
