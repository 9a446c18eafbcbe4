"""akf_star: the committed run's ablation and side studies, stored for notebook 05.

``make repro`` (``reproduce()``, committed run only) writes :data:`STUDY_FILE` into
``papers_repro/akf_star/``: the per-frame errors of the 100-sequence ablation and of every
run made on its sequences (first-commit and tuned settings, CV and re-tuned CA filters), the
measurements of the sequences the Explore panel offers, and the tables of the side studies
(filter consistency, rough-sea sensitivity, centroid accuracy). The notebook reads it
(:func:`read_study`) instead of running the ablation again (≈ 4 min); without the file it runs
a small live study (:func:`run_study`).
"""

from __future__ import annotations

import io
import json
from dataclasses import asdict, dataclass, replace
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd

from eotrack.imaging.star_sensor_sim import SensorConfig, scenario

from .explore import ExploreSession
from .scenario import VARIANTS, AblationConfig
from .trials import (
    AblationResult,
    SequenceMeasurements,
    centroid_bias_table,
    consistency_table,
    run_ablation,
    sensitivity_table,
)

__all__ = ["EXPLORE_OCCLUSIONS", "EXPLORE_SEEDS", "STUDY_FILE", "Study", "read_study",
           "run_study", "small_config",
           "write_study"]

STUDY_FILE = "ablation_study.npz"
#: the reproduction sequences the Explore panel offers (the first three of each scenario) and
#: the cloud occlusion lengths (10: the cloud preset; 25: simulated once more)
EXPLORE_SEEDS = (0, 1, 2)
EXPLORE_OCCLUSIONS = (10, 25)
_FORMAT = 1


@dataclass
class Study:
    """The ablation (with its extra runs), the Explore session on its sequences and the side
    studies' tables (``"consistency"``, ``"sensitivity"``, ``"centroid_bias"``)."""

    ablation: AblationResult
    session: ExploreSession
    tables: dict[str, pd.DataFrame]
    source: str


def run_study(cfg: AblationConfig, *, runner: Any = None, n_consistency: int = 2,
              n_sensitivity: int = 6, n_centroid_frames: int = 60,
              explore_seeds: tuple[int, ...] = EXPLORE_SEEDS) -> Study:
    """Run the ablation with :func:`reproduction_extras`, the Explore sequences and the side
    studies (``make repro`` at the default sizes; the notebook's live fallback smaller)."""
    from . import reproduction_extras

    if not isinstance(cfg, AblationConfig):
        raise TypeError(f"cfg must be an AblationConfig, got {type(cfg).__name__}")
    seeds = tuple(s for s in explore_seeds if s < cfg.n_seeds)
    if not seeds:
        raise ValueError(f"explore_seeds {explore_seeds} must include a sequence index below "
                         f"cfg.n_seeds = {cfg.n_seeds}")
    res = run_ablation(cfg, runner=runner, extras=reproduction_extras(cfg))
    session = ExploreSession(ablation=res)
    session.precompute(seeds=seeds, occlusions=EXPLORE_OCCLUSIONS)
    tables = {"consistency": consistency_table(cfg, n_seeds=n_consistency),
              "sensitivity": sensitivity_table(cfg, n_seqs=n_sensitivity),
              "centroid_bias": centroid_bias_table(n_frames=n_centroid_frames)}
    return Study(res, session, tables, "live run")


# ---- writing ------------------------------------------------------------------------------

def _put_meas(out: dict[str, np.ndarray], pre: str, m: SequenceMeasurements) -> None:
    if asdict(m.sensor) != asdict(SensorConfig()):
        raise ValueError("only sequences of the default SensorConfig can be stored")
    out[f"{pre}/truth"] = np.asarray(m.truth, float)
    out[f"{pre}/x0"] = np.asarray(m.x0, float)
    out[f"{pre}/visible"] = np.asarray(m.visible, float)
    for method, (dets, cimg) in m.detections.items():
        out[f"{pre}/{method}/n"] = np.array([len(d) for d in dets], np.int32)
        out[f"{pre}/{method}/xy"] = (np.concatenate([np.asarray(d, float).reshape(-1, 2)
                                                     for d in dets]) if dets else
                                     np.zeros((0, 2)))
        out[f"{pre}/{method}/c"] = (np.concatenate([np.asarray(c, float).ravel()
                                                    for c in cimg]) if cimg else np.zeros(0))


def _table_json(df: pd.DataFrame) -> str:
    names = [n for n in df.index.names]
    flat = df.reset_index() if any(n is not None for n in names) else df.reset_index(
        names="index")
    return json.dumps({"index": [n if n is not None else "index" for n in names],
                       "data": flat.to_json(orient="split", index=False, double_precision=15)})


def write_study(path: str | Path, study: Study) -> None:
    """Write ``study`` (from :func:`run_study` at ``make repro``'s sizes) to ``path`` (npz)."""
    res, session = study.ablation, study.session
    if res.measurements is None:
        raise ValueError("study.ablation holds no measurements")
    cfg = res.config
    out: dict[str, np.ndarray] = {
        "format": np.array(_FORMAT),
        "config": np.array(json.dumps(asdict(cfg))),
        "scenarios": np.array(res.scenarios), "variants": np.array(res.variants),
        "errors": res.errors.astype(np.float32), "modes": res.modes.astype(np.int8),
        "visible": res.visible.astype(np.float32),
        "extra_names": np.array(list(res.extra)),
        "tables": np.array(json.dumps({k: _table_json(v) for k, v in study.tables.items()})),
    }
    for j, r in enumerate(res.extra.values()):
        out[f"extra/{j}/errors"] = r.errors.astype(np.float32)
    keys = []
    for key, meas in session._fixed.items():
        sc, seed, occ = key[0], key[1], key[2]
        if seed not in EXPLORE_SEEDS or key[3:] != (float(cfg.extraction.k),
                                                    float(cfg.extraction.k_b)):
            continue
        pre = f"meas/{len(keys)}"
        keys.append([sc, int(seed), int(occ)])
        _put_meas(out, pre, meas)
    out["meas_keys"] = np.array(json.dumps(keys))
    Path(path).parent.mkdir(parents=True, exist_ok=True)
    with open(path, "wb") as fh:
        np.savez_compressed(fh, **out)


# ---- reading ------------------------------------------------------------------------------

def _config(d: dict[str, Any]) -> AblationConfig:
    base = AblationConfig(seed=int(d["seed"]), n_seeds=int(d["n_seeds"]),
                          n_frames=int(d["n_frames"]))
    if json.loads(json.dumps(asdict(base))) != d:
        diff = sorted(k for k in d if json.loads(json.dumps(asdict(base)))[k] != d[k])
        raise ValueError(f"the stored study was run with other settings ({diff}) than this "
                         "code's AblationConfig: run `python -m eotrack.repro akf_star` again")
    return base


def _get_meas(z: Any, pre: str, methods: tuple[str, ...]) -> SequenceMeasurements:
    dets = {}
    for method in methods:
        n = z[f"{pre}/{method}/n"]
        cuts = np.cumsum(n)[:-1]
        xy = np.split(z[f"{pre}/{method}/xy"], cuts)
        c = np.split(z[f"{pre}/{method}/c"], cuts)
        dets[method] = ([a.reshape(-1, 2) for a in xy], list(c))
    return SequenceMeasurements(z[f"{pre}/truth"], z[f"{pre}/x0"], SensorConfig(), dets,
                                z[f"{pre}/visible"])


def _read_table(s: str) -> pd.DataFrame:
    d = json.loads(s)
    df = pd.read_json(io.StringIO(d["data"]), orient="split").set_index(d["index"])
    if d["index"] == ["index"]:
        df.index.name = None
    return df


def read_study(path: str | Path) -> Study:
    """Read :func:`write_study` output: the ablation (errors of every run; measurements of the
    Explore sequences only), an Explore session on them and the side studies' tables.

    Raises
    ------
    FileNotFoundError
        If ``path`` does not exist (run ``python -m eotrack.repro akf_star``).
    ValueError
        If the file was written with settings other than this code's.
    """
    from . import reproduction_extras

    path = Path(path)
    if not path.is_file():
        raise FileNotFoundError(f"{path} does not exist: `python -m eotrack.repro akf_star` "
                                "(make repro) writes it")
    with np.load(path, allow_pickle=False) as z:
        if int(z["format"]) != _FORMAT:
            raise ValueError(f"{path}: format {int(z['format'])}, this code reads {_FORMAT}")
        cfg = _config(json.loads(str(z["config"])))
        scenarios = tuple(str(s) for s in z["scenarios"])
        variants = tuple(str(v) for v in z["variants"])
        if variants != VARIANTS:
            raise ValueError(f"{path}: variants {variants}, expected {VARIANTS}")
        errors, modes, vis = z["errors"], z["modes"], z["visible"]
        names = [str(n) for n in z["extra_names"]]
        extras = {name: (c, v) for name, c, v in reproduction_extras(cfg)}
        if names != list(extras):
            raise ValueError(f"{path}: extra runs {names}, this code makes {list(extras)}")
        extra = {name: AblationResult(z[f"extra/{j}/errors"], modes, vis, scenarios,
                                      tuple(extras[name][1]), extras[name][0])
                 for j, name in enumerate(names)}
        keys = json.loads(str(z["meas_keys"]))
        methods = ("global", "adaptive")
        by_key = {(sc, s, o): _get_meas(z, f"meas/{i}", methods)
                  for i, (sc, s, o) in enumerate(keys)}
        tables = {k: _read_table(v) for k, v in json.loads(str(z["tables"])).items()}
    # the ablation's own sequences (preset occlusion) become its measurements
    meas = tuple(tuple(by_key[(sc, s, scenario(sc).occlusion_frames)]
                       for s in EXPLORE_SEEDS if (sc, s, scenario(sc).occlusion_frames) in by_key)
                 for sc in scenarios)
    res = AblationResult(errors, modes, vis, scenarios, VARIANTS, cfg, meas, extra)
    session = ExploreSession(ablation=res)
    for (sc, s, o), m in by_key.items():
        session.add_measurements(sc, s, o, m)
    return Study(res, session, tables, f"stored run ({path.parent.parent.name}/"
                 f"{path.parent.name}/{path.name})")


def small_config(cfg: AblationConfig | None = None) -> AblationConfig:
    """The notebook's live fallback: 3 sequences × 100 frames per scenario."""
    return replace(cfg or AblationConfig(), n_seeds=3, n_frames=100)
