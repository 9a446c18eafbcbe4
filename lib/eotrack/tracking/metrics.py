"""Standard multi-target tracking metrics for track initiation: GOSPA and SIAP.

The tracking community scores a set of tracks against the truth with

* **GOSPA** (generalised optimal sub-pattern assignment; Rahmathullah, García-Fernández &
  Svensson, FUSION 2017) with ``α = 2``: at one time, the minimum over assignments of
  ``(Σ_assigned d(x, y)^p + c^p/2 · (#missed + #false))^{1/p}``, distances cut at ``c``. It splits
  into a *localisation* part (assigned pairs), a *missed* part (truths without an estimate) and a
  *false* part (estimates without a truth), each in cost units (``c^p/2`` per missed or false);
* **SIAP** (Single Integrated Air Picture, Votruba 2001) over a time range: *completeness*
  ``C = Σ_t JT(t) / Σ_t J(t)`` (truth points with at least one associated track over all truth
  points) and *spuriousness* ``S = Σ_t (N(t) − NA(t)) / Σ_t N(t)`` (track points associated to no
  truth over all track points).

Both are computed by Stone Soup (:class:`stonesoup.metricgenerator.ospametric.GOSPAMetric`,
:class:`stonesoup.metricgenerator.tracktotruthmetrics.SIAPMetrics` over a per-time
nearest-truth association within ``c``) from the initiator's tracks (:func:`initiation_metrics`); :func:`gospa_reference` and
:func:`siap_reference` are independent hand implementations (an optimal assignment by
:func:`scipy.optimize.linear_sum_assignment`, a per-time nearest-truth association) used to
cross-check them in the tests.

A track's state at frame ``k`` (from its confirmation frame on) is the constant-velocity least-
squares fit of its detections up to ``k`` evaluated at ``t_k``; a truth is present at ``k``
while its true position is inside the field.
"""

from __future__ import annotations

import datetime as _dt
from collections.abc import Sequence

import numpy as np
from scipy.optimize import linear_sum_assignment

from eotrack.validation import check_positive

from .initiation.base import Track, validate_frames

__all__ = ["gospa", "gospa_reference", "initiation_metrics", "siap_reference",
           "track_states"]

_EPOCH = _dt.datetime(2000, 1, 1)


def _points(a, name: str) -> np.ndarray:
    p = np.asarray(a, dtype=float)
    if p.size == 0:
        return np.zeros((0, 2))
    if p.ndim != 2 or p.shape[1] != 2:
        raise ValueError(f"{name} must have shape (n, 2), got {p.shape}")
    if not np.all(np.isfinite(p)):
        raise ValueError(f"{name} must be finite")
    return p


def _check_cp(c: float, p: float) -> tuple[float, float]:
    c = check_positive(c, "c")
    p = check_positive(p, "p")
    if p < 1:
        raise ValueError(f"p must be >= 1 (GOSPA is a metric for p >= 1), got {p}")
    return c, p


def gospa_reference(estimates: np.ndarray, truths: np.ndarray, *, c: float,
                    p: float = 1.0) -> dict[str, float]:
    """GOSPA (``α = 2``) of point sets by an optimal assignment (hand implementation).

    Parameters
    ----------
    estimates, truths
        ``(n, 2)`` and ``(m, 2)`` positions (pixels).
    c
        Cut-off distance (pixels): a pair farther apart costs as much as a miss plus a false.
    p
        Order, ``p ≥ 1``.

    Returns
    -------
    dict
        ``distance`` (``(loc + missed + false)^{1/p}``), ``localisation``, ``missed``,
        ``false`` (cost units, ``c^p/2`` per missed or false point), ``n_missed``, ``n_false``.
    """
    x = _points(estimates, "estimates")
    y = _points(truths, "truths")
    c, p = _check_cp(c, p)
    half = c**p / 2.0
    loc, n_ass = 0.0, 0
    if len(x) and len(y):
        d = np.minimum(np.hypot(*(x[:, None, :] - y[None, :, :]).transpose(2, 0, 1)), c) ** p
        r, k = linear_sum_assignment(d)
        good = d[r, k] < c**p
        loc = float(d[r, k][good].sum())
        n_ass = int(good.sum())
    n_missed = len(y) - n_ass
    n_false = len(x) - n_ass
    total = loc + half * (n_missed + n_false)
    return {"distance": float(total ** (1.0 / p)), "localisation": loc,
            "missed": half * n_missed, "false": half * n_false,
            "n_missed": int(n_missed), "n_false": int(n_false)}


def gospa(estimates: np.ndarray, truths: np.ndarray, *, c: float,
          p: float = 1.0) -> dict[str, float]:
    """GOSPA (``α = 2``) of point sets computed by Stone Soup's ``GOSPAMetric``.

    Same parameters and keys as :func:`gospa_reference` (``n_missed``/``n_false`` are the
    cost parts divided by ``c^p/2``).
    """
    from stonesoup.metricgenerator.ospametric import GOSPAMetric
    from stonesoup.types.state import State

    x = _points(estimates, "estimates")
    y = _points(truths, "truths")
    c, p = _check_cp(c, p)
    met = GOSPAMetric(p=p, c=c)
    xs = [State(np.r_[v, 0.0, 0.0].reshape(4, 1), timestamp=_EPOCH) for v in x]
    ys = [State(np.r_[v, 0.0, 0.0].reshape(4, 1), timestamp=_EPOCH) for v in y]
    if not xs and not ys:
        return {"distance": 0.0, "localisation": 0.0, "missed": 0.0, "false": 0.0,
                "n_missed": 0, "n_false": 0}
    met.measure = _position_measure()
    g = met.compute_gospa_metric(xs, ys)[0].value
    half = c**p / 2.0
    out = {k: float(g[k]) + 0.0 for k in ("distance", "localisation", "missed", "false")}
    out = {k: (0.0 if v == 0 else v) for k, v in out.items()}  # never −0.0 in a table
    out["n_missed"] = round(out["missed"] / half)
    out["n_false"] = round(out["false"] / half)
    return out


def _position_measure():
    from stonesoup.measures import Euclidean

    return Euclidean(mapping=(0, 1))


def track_states(tracks: Sequence[Track], frames: Sequence) -> list[dict[int, np.ndarray]]:
    """Per track, ``{frame k: position}`` from its confirmation frame to the last frame: the
    constant-velocity least-squares fit of its detections up to ``k`` evaluated at ``t_k``
    (a single detection: that position)."""
    fr = validate_frames(frames)
    times = np.array([f.time_s for f in fr])
    out = []
    for tr in tracks:
        if not isinstance(tr, Track):
            raise TypeError(f"tracks must hold Track objects, got {type(tr).__name__}")
        f_idx = np.array([f for f, _ in tr.hits], dtype=int)
        xy = np.array([fr[f].xy[d] for f, d in tr.hits], dtype=float).reshape(-1, 2)
        states = {}
        for k in range(int(tr.confirmed_at), len(fr)):
            sel = f_idx <= k
            if not np.any(sel):
                continue
            t, p = times[f_idx[sel]], xy[sel]
            if len(t) == 1:
                states[k] = p[0]
                continue
            tc = t - t.mean()
            v = tc @ (p - p.mean(axis=0)) / float(tc @ tc)
            states[k] = p.mean(axis=0) + v * (times[k] - t.mean())
        out.append(states)
    return out


def _truth_present(truth_xy: Sequence[np.ndarray], width: float) -> list[np.ndarray]:
    return [np.all((np.asarray(t, float) >= 0) & (np.asarray(t, float) < width), axis=1)
            if len(t) else np.zeros(0, dtype=bool) for t in truth_xy]


def siap_reference(track_pos: Sequence[dict[int, np.ndarray]], truth_xy: Sequence[np.ndarray],
                   *, threshold: float, width: float, frames_eval: Sequence[int]
                   ) -> dict[str, float]:
    """SIAP completeness and spuriousness by a per-time nearest-truth association (hand
    implementation): a track point is associated when its nearest present truth is within
    ``threshold``."""
    thr = check_positive(threshold, "threshold")
    present = _truth_present(truth_xy, width)
    J = JT = N = NA = 0
    for k in frames_eval:
        y = np.asarray(truth_xy[k], float)[present[k]]
        ids = np.flatnonzero(present[k])
        x = np.array([s[k] for s in track_pos if k in s]).reshape(-1, 2)
        J += len(y)
        N += len(x)
        if len(x) and len(y):
            d = np.hypot(*(x[:, None, :] - y[None, :, :]).transpose(2, 0, 1))
            near = np.argmin(d, axis=1)
            ok = d[np.arange(len(x)), near] <= thr
            NA += int(ok.sum())
            JT += len(set(ids[near[ok]].tolist()))
    return {"completeness": JT / J if J else float("nan"),
            "spuriousness": (N - NA) / N if N else 0.0, "J": J, "JT": JT, "N": N, "NA": NA}


def _siap_stonesoup(track_pos, truth_xy, times, *, threshold, width, frames_eval):
    """SIAP C and S by Stone Soup's ``SIAPMetrics`` over a per-time association: each track
    point is associated, for that time only, with its nearest present truth within
    ``threshold`` (Stone Soup's ``TrackToTruth`` needs associations lasting two or more times,
    which a just-confirmed track does not have)."""
    from stonesoup.metricgenerator.manager import MultiManager
    from stonesoup.metricgenerator.tracktotruthmetrics import SIAPMetrics
    from stonesoup.types.association import AssociationSet, TimeRangeAssociation
    from stonesoup.types.groundtruth import GroundTruthPath, GroundTruthState
    from stonesoup.types.state import State
    from stonesoup.types.time import TimeRange
    from stonesoup.types.track import Track as SSTrack

    thr = check_positive(threshold, "threshold")
    present = _truth_present(truth_xy, width)
    ks = sorted(int(k) for k in frames_eval)
    stamp = {k: _EPOCH + _dt.timedelta(seconds=float(times[k])) for k in ks}
    eps = _dt.timedelta(microseconds=1)
    n_obj = max((len(t) for t in truth_xy), default=0)
    truths: dict[int, GroundTruthPath] = {}
    for j in range(n_obj):
        states = [GroundTruthState(np.r_[truth_xy[k][j], 0.0, 0.0].reshape(4, 1),
                                   timestamp=stamp[k]) for k in ks if present[k][j]]
        if states:
            truths[j] = GroundTruthPath(states)
    tracks, assoc = [], set()
    for s in track_pos:
        states = [State(np.r_[s[k], 0.0, 0.0].reshape(4, 1), timestamp=stamp[k])
                  for k in ks if k in s]
        if not states:
            continue
        tr = SSTrack(states)
        tracks.append(tr)
        for k in ks:
            if k not in s or not np.any(present[k]):
                continue
            ids = np.flatnonzero(present[k])
            d = np.hypot(*(np.asarray(truth_xy[k], float)[ids] - s[k]).T)
            j = int(np.argmin(d))
            if d[j] <= thr:
                assoc.add(TimeRangeAssociation({tr, truths[int(ids[j])]},
                                               TimeRange(stamp[k], stamp[k] + eps)))
    if not tracks and not truths:  # nothing to score (Stone Soup needs one timestamp)
        return float("nan"), 0.0
    meas = _position_measure()
    siap = SIAPMetrics(position_measure=meas, velocity_measure=meas)
    mgr = MultiManager([siap])
    mgr.add_data({"tracks": set(tracks), "groundtruth_paths": set(truths.values())})
    mgr.association_set = AssociationSet(assoc)
    vals = next(iter(mgr.generate_metrics().values()))
    return (float(vals["SIAP Completeness"].value), float(vals["SIAP Spuriousness"].value))


def initiation_metrics(tracks: Sequence[Track], frames: Sequence,
                       truth_xy: Sequence[np.ndarray], *, width: float, c: float = 10.0,
                       p: float = 1.0, first_frame: int = 0) -> dict[str, float]:
    """GOSPA (mean over frames, with its split) and SIAP completeness/spuriousness of an
    initiator's tracks in one scene, by Stone Soup.

    Parameters
    ----------
    tracks
        The initiator's confirmed tracks on ``frames``.
    frames
        The scene's ``(time_s, xy)`` frames.
    truth_xy
        Per frame, the ``(n_objects, 2)`` true positions (present while inside the field).
    width
        Field side (pixels); a truth is present at a frame while inside ``[0, width)²``.
    c, p
        GOSPA cut-off (pixels; also the SIAP association threshold) and order.
    first_frame
        Frames before this are not scored (e.g. ``m − 1``: no ``n/m`` track can exist yet).

    Returns
    -------
    dict
        ``gospa``, ``gospa localisation``, ``gospa missed``, ``gospa false`` (means over the
        scored frames), ``siap completeness``, ``siap spuriousness``.
    """
    fr = validate_frames(frames)
    if len(truth_xy) != len(fr):
        raise ValueError(f"truth_xy must have one array per frame ({len(fr)}), got "
                         f"{len(truth_xy)}")
    w = check_positive(width, "width")
    c, p = _check_cp(c, p)
    if not isinstance(first_frame, (int, np.integer)) or not 0 <= first_frame < len(fr):
        raise ValueError(f"first_frame must be an integer in [0, {len(fr)}), got "
                         f"{first_frame!r}")
    rows = {np.asarray(t, float).reshape(-1, 2).shape[0] for t in truth_xy}
    if len(rows) > 1:
        raise ValueError("truth_xy must give every object at every frame (the same number of "
                         f"rows per frame, got {sorted(rows)}): put an absent object outside "
                         "the field")
    pos = track_states(tracks, fr)
    present = _truth_present(truth_xy, w)
    ks = list(range(int(first_frame), len(fr)))
    acc = {"distance": 0.0, "localisation": 0.0, "missed": 0.0, "false": 0.0}
    for k in ks:
        x = np.array([s[k] for s in pos if k in s]).reshape(-1, 2)
        y = np.asarray(truth_xy[k], float).reshape(-1, 2)[present[k]]
        g = gospa(x, y, c=c, p=p)
        for key in acc:
            acc[key] += g[key]
    n = len(ks)
    times = np.array([f.time_s for f in fr])
    if len(ks) > 1:
        comp, spur = _siap_stonesoup(pos, truth_xy, times, threshold=c, width=w,
                                     frames_eval=ks)
    else:  # Stone Soup's SIAP needs a time range: at one time, the hand count (same rule)
        ref = siap_reference(pos, truth_xy, threshold=c, width=w, frames_eval=ks)
        comp, spur = ref["completeness"], ref["spuriousness"]
    return {"gospa": acc["distance"] / n, "gospa localisation": acc["localisation"] / n,
            "gospa missed": acc["missed"] / n, "gospa false": acc["false"] / n,
            "siap completeness": comp, "siap spuriousness": spur}
