"""The shared track-initiation interface."""

import numpy as np
import pytest
from eotrack.tracking.initiation import Frame, Initiator, Track, validate_frames


def test_validate_frames_normalises():
    fr = validate_frames([(0, [[1, 2]]), (0.5, np.zeros((0, 2))), Frame(2.0, np.ones((2, 2)))])
    assert [f.time_s for f in fr] == [0.0, 0.5, 2.0]
    assert fr[1].xy.shape == (0, 2)


def test_track_positions():
    fr = validate_frames([(0, [[1, 2], [3, 4]]), (1, [[5, 6]])])
    tr = Track(hits=[(0, 1), (1, 0)], confirmed_at=1)
    np.testing.assert_array_equal(tr.positions(fr), [[3, 4], [5, 6]])
    assert tr.frame_indices == [0, 1]


def test_protocol():
    class Dummy:
        def initiate(self, frames):
            return []

    assert isinstance(Dummy(), Initiator)


@pytest.mark.parametrize(("frames", "exc", "match"), [
    (np.zeros((2, 2)), TypeError, "frames must be a sequence"),
    ([(0.0,)], TypeError, r"frames\[0\] must be a \(time_s, xy\) pair"),
    ([(0.0, [[1, 2]]), (0.0, [[1, 2]])], ValueError, "increasing time order"),
    ([(np.nan, [[1, 2]])], ValueError, "time must be finite"),
    ([("a", [[1, 2]])], TypeError, "time must be a number"),
    ([(0.0, [[1, 2, 3]])], ValueError, r"frames\[0\] xy must have shape \(n, 2\)"),
])
def test_bad_frames(frames, exc, match):
    with pytest.raises(exc, match=match):
        validate_frames(frames)
