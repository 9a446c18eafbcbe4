"""Lint cases of notebook 05's figures that no REPORT figure draws (P05 owns this file).

Each is drawn on the data the notebook draws it on: the committed run's stored study
(``papers_repro/akf_star/ablation_study.npz``; a tiny live run if it is missing), short
seeded simulations, real stars (astropy) and a real frame (M13).
"""

from __future__ import annotations

from functools import lru_cache
from typing import Any


@lru_cache(maxsize=1)
def _study() -> Any:
    from eotrack.experiments import akf_star as A
    from eotrack.montecarlo import TrialRunner
    from eotrack.repro import papers_repro_dir

    path = papers_repro_dir() / A.SLUG / A.STUDY_FILE
    if path.is_file():
        return A.read_study(path)
    return A.run_study(A.AblationConfig(n_seeds=1, n_frames=30),
                       runner=TrialRunner(progress=False), n_consistency=1, n_sensitivity=1,
                       n_centroid_frames=3, explore_seeds=(0,))


def confidence_trace() -> Any:
    from eotrack.experiments import akf_star as A

    st = _study()
    meas = st.session.measurements("cloud", seed=0)
    tr = A.track_measurements(meas, st.ablation.config,
                              variants={"BEAK-ST": A.VARIANT_PARTS["BEAK-ST"]})["BEAK-ST"]
    return A.plot_confidence_trace(meas, tr)


def diurnal_check() -> Any:
    from eotrack.experiments import akf_star as A

    return A.plot_diurnal_check(A.diurnal_check())


def error_curves() -> Any:
    from eotrack.experiments import akf_star as A

    return A.plot_error_curves(_study().ablation, scenario="cloud")


def success_curves() -> Any:
    from eotrack.experiments import akf_star as A

    return A.plot_success_curves(_study().ablation)


def explore_errors() -> Any:
    from eotrack.experiments import akf_star as A

    st = _study()
    errs = st.session.errors("cloud", seed=0, occlusion_frames=25,
                             variants=("Baseline", "BEAK-ST-SKF", "BEAK-ST"))
    return A.plot_explore_errors(
        errs, "cloud occlusion, sequence 0, 25-frame occlusions (one sequence, not the Monte "
        "Carlo)\nconfidence filter: b = 0.970, λ = 10, γ = 3.0, η = 1.0",
        gate_px=st.ablation.config.gate_px)


def extraction_example() -> Any:
    import numpy as np
    from eotrack.experiments import akf_star as A
    from eotrack.imaging import extract_stars, grey_quantiles, simulate_sequence

    seq = simulate_sequence(np.random.default_rng(3), "strong_light", n_frames=11)
    img = seq.images[10]
    g5, g95 = grey_quantiles(img)
    return A.plot_extraction_example(img, extract_stars(img, method="adaptive"),
                                     extract_stars(img, method="global"), g5, g95,
                                     truth=seq.truth[10])


def real_sky() -> Any:
    from eotrack.experiments import akf_star as A
    from eotrack.imaging import extract_stars, real_sky_images

    m13 = real_sky_images()["m13"]
    return A.plot_real_sky(m13, extract_stars(m13).xy,
                           title="M13 (astropy test data): sky extractor")


def sage_husa() -> Any:
    import numpy as np
    from eotrack.experiments import akf_star as A
    from eotrack.tracking.kalman import (
        constant_acceleration_model,
        sage_husa_update,
        sage_husa_weight,
        singer_process_noise,
    )

    dt = 0.2
    F, H = constant_acceleration_model(dt)
    Q = singer_process_noise(dt, 0.7, 4.0)
    g = np.random.default_rng(2)
    tt = np.arange(60) * dt
    zs = np.c_[10 * np.sin(0.7 * tt), 5 * np.cos(0.5 * tt)] + g.normal(0, 0.05, (60, 2))
    out = {}
    for safe in (False, True):
        x, P = np.zeros(6), np.diag([1.0, 1, 50, 50, 20, 20])
        Rk, Qk, eigs = 0.25 * np.eye(2), Q.copy(), []
        for k, z in enumerate(zs):
            P_prev = P
            x, P = F @ x, F @ P @ F.T + Qk
            K = P @ H.T @ np.linalg.inv(H @ P @ H.T + Rk)
            e = z - H @ x
            P_prior = P
            x, P = x + K @ e, (np.eye(6) - K @ H) @ P
            Rk, Qk = sage_husa_update(Rk, Qk, e=e, K=K, H=H, F=F, P_prior=P_prior, P_post=P,
                                      P_prev=P_prev, d=sage_husa_weight(k, 0.97),
                                      safeguard=safe, q_structure=np.diag(Q) > 0,
                                      q_bounds=tuple(np.multiply(
                                          A.STATUS_CONFIDENCE.q_bounds_ratio, Q[4, 4])))
            eigs.append(np.linalg.eigvalsh(Rk)[0])
        out["with safeguard" if safe else "without safeguard"] = np.array(eigs)
    return A.plot_sage_husa(out)


def ship_attitude() -> Any:
    import numpy as np
    from eotrack.experiments import akf_star as A
    from eotrack.geometry.shipboard import sea_state_motion
    from eotrack.geometry.shipboard import ship_attitude as attitude

    t = np.arange(0, 40, 0.2)
    att = attitude(sea_state_motion(3), t, np.random.default_rng(1))
    return A.plot_ship_attitude(t, att, title="Sea state 3 ship attitude (one realisation)")


CASES = {
    "plot_confidence_trace": confidence_trace,
    "plot_diurnal_check": diurnal_check,
    "plot_error_curves": error_curves,
    "plot_explore_errors": explore_errors,
    "plot_extraction_example": extraction_example,
    "plot_real_sky": real_sky,
    "plot_sage_husa": sage_husa,
    "plot_ship_attitude": ship_attitude,
    "plot_success_curves": success_curves,
}
