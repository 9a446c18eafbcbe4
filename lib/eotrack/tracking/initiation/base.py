"""The track-initiation interface shared by every initiator.

Every initiator takes a sequence of frames and returns the confirmed tracks::

    tracks = initiator.initiate(frames)

``frames`` is a sequence of ``(time_s, xy)`` with ``xy`` an ``(n, 2)`` array of detections
(pixels; ``n`` may be 0). Frames must be in increasing time order; they need not be evenly
spaced. A :class:`Track` lists its detections as ``(frame_index, detection_index)`` pairs and the
frame index at which it was confirmed.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Protocol, runtime_checkable

import numpy as np

from eotrack.validation import as_points

__all__ = ["Frame", "Initiator", "Track", "validate_frames"]


@dataclass(frozen=True)
class Frame:
    """One frame of detections: time (s) and positions ``(n, 2)``."""

    time_s: float
    xy: np.ndarray


@dataclass
class Track:
    """A confirmed track.

    Attributes
    ----------
    hits
        ``(frame_index, detection_index)`` pairs in frame order.
    confirmed_at
        Frame index at which the track was confirmed.
    info
        Initiator-specific extras (e.g. Hough cell, velocity estimate).
    """

    hits: list[tuple[int, int]]
    confirmed_at: int
    info: dict = field(default_factory=dict)

    def positions(self, frames: Sequence[Frame]) -> np.ndarray:
        """The track's detections ``(k, 2)`` looked up in ``frames``."""
        return np.array([frames[f].xy[d] for f, d in self.hits]).reshape(-1, 2)

    @property
    def frame_indices(self) -> list[int]:
        """Frame index of each hit."""
        return [f for f, _ in self.hits]


@runtime_checkable
class Initiator(Protocol):
    """Anything with ``initiate(frames) -> list[Track]``."""

    def initiate(self, frames: Sequence[tuple[float, np.ndarray]]) -> list[Track]:
        """Confirmed tracks from ``frames``."""
        ...


def validate_frames(frames: Sequence[tuple[float, np.ndarray]] | Sequence[Frame]) -> list[Frame]:
    """Check and normalise a frame sequence.

    Raises
    ------
    TypeError
        If ``frames`` is not a sequence of ``(time_s, xy)`` pairs.
    ValueError
        If times are not finite and strictly increasing, or a frame's detections are not
        ``(n, 2)`` finite numbers.
    """
    if isinstance(frames, np.ndarray) or not isinstance(frames, Sequence):
        raise TypeError("frames must be a sequence of (time_s, xy) pairs, got "
                        f"{type(frames).__name__}")
    out: list[Frame] = []
    for i, fr in enumerate(frames):
        if isinstance(fr, Frame):
            t, xy = fr.time_s, fr.xy
        else:
            try:
                t, xy = fr
            except (TypeError, ValueError):
                raise TypeError(f"frames[{i}] must be a (time_s, xy) pair") from None
        try:
            t = float(t)
        except (TypeError, ValueError):
            raise TypeError(f"frames[{i}] time must be a number, got {t!r}") from None
        if not np.isfinite(t):
            raise ValueError(f"frames[{i}] time must be finite, got {t}")
        if out and t <= out[-1].time_s:
            raise ValueError(f"frames must be in increasing time order: frames[{i}] at {t} s "
                             f"follows {out[-1].time_s} s")
        out.append(Frame(t, as_points(xy, f"frames[{i}] xy")))
    return out
