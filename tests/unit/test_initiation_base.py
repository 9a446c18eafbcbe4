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


def test_handoff_confirm_batch_equals_one_by_one():
    import pytest
    from eotrack.tracking.initiation import Frame, TrackHandOff

    rng = np.random.default_rng(4)
    frames = [Frame(float(k), rng.uniform(0, 100, (5, 2))) for k in range(5)]
    hits = [[(0, 1), (1, 2), (3, 0)], [(1, 0), (2, 4), (3, 3), (4, 1)]]
    one, batch = TrackHandOff(5.0), TrackHandOff(5.0)
    for h in hits:
        one.confirm(h, 4, frames, info={"m": 1})
    fi = np.array([[0, 1, 3, -1], [1, 2, 3, 4]])
    di = np.array([[1, 2, 0, -1], [0, 4, 3, 1]])
    batch.confirm_batch(np.maximum(fi, 0), di, 4, frames, info={"m": 1})
    assert [t.hits for t in one.tracks()] == [t.hits for t in batch.tracks()]
    np.testing.assert_allclose(one.predict(5.0), batch.predict(5.0))
    with pytest.raises(ValueError, match="2-D"):
        batch.confirm_batch(np.zeros(3), np.zeros(3), 4, frames)
