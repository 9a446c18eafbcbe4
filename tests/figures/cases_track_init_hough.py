"""Lint cases of notebook 04's figures that no REPORT figure draws (P04 owns this file)."""

from __future__ import annotations

from typing import Any


def scene_tracks() -> Any:
    import numpy as np
    from eotrack.experiments import track_init_hough as TH
    from eotrack.tracking.initiation import ModifiedHoughInitiator

    scene = TH.planted_scene(np.random.default_rng(1), TH.PlantedConfig())
    tracks = ModifiedHoughInitiator(v_min=3).initiate(scene.frames)
    return TH.plot_scene_tracks(scene, tracks, title="verified initiator: ")


CASES = {"plot_scene_tracks": scene_tracks}
