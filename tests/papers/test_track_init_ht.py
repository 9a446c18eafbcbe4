"""Li et al. (2008) hypothesis-testing track initiation: claims versus results (quick run)."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest
from eotrack.experiments import track_init_ht as exp
from eotrack.repro import Status, load_claims

EXPECTED = {
    "track_init.li_fig1": Status.PARTIAL,  # the pre-stated criterion (the refutation is exploratory)
    "track_init.li_fig2": Status.PARTIAL,
    "track_init.li_experiment": Status.NOT_REPRODUCED,  # 0 of 20 runs: CP upper bound < 50 %
}


@pytest.fixture(scope="module")
def rep():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    r = exp.reproduce(quick=True)
    yield r
    plt.close("all")


def test_one_row_per_claim(rep):
    ids = [c.claim for c in rep.claims]
    assert sorted(ids) == sorted(load_claims("track_init_ht"))
    assert len(ids) == len(set(ids))


@pytest.mark.parametrize("cid", sorted(EXPECTED))
def test_status(rep, cid):
    row = next(c for c in rep.claims if c.claim == cid)
    assert row.status is EXPECTED[cid], row.ours + " | " + row.note


def test_fig1_numbers(rep):
    t = rep.tables["Fig. 1 (formulas and Monte Carlo, S <= 8)"]
    s3 = t[(t["SNR"] == 2) & (t["S"] == 3)].iloc[0]
    # eq. (7) is far above the exact count, which the Monte Carlo follows
    assert s3["P_DA eq.7 (paper)"] > 0.95
    assert 0.03 < s3["P_DA exact"] < 0.08
    assert abs(s3["P_DA MC"] - s3["P_DA exact"]) < 0.005


def test_fig2_numbers(rep):
    t = rep.tables["Fig. 2 (T_h = 5 slice)"]
    assert np.all(t["P_DS eq.12 (T_h=5)"] >= t["P_DT eq.13 (T_h=5)"])
    np.testing.assert_allclose(t["P_DS MC (T_h=5)"], t["P_DS eq.12 (T_h=5)"], atol=0.02)


def test_sequence_numbers(rep):
    t = rep.tables["Sequences: targets, measured vs formulas"]
    main, curved = t.iloc[0], t.iloc[1]
    assert main["pixel P_D (3x3 core)"] > 0.9
    assert main["P_DA measured"] > 0.9 and main["mean coverage"] > 0.9
    assert curved["P_DA measured"] < 0.2  # SNR 2: the 5x5 window rarely reaches S = 7
    assert curved["P_DA eq.7 (paper)"] > 0.9  # ... though eq. (7) says it should
    sweep = rep.tables["Fig. 7 target: recovery vs SNR"]
    assert sweep["recovered share"].iloc[-1] >= 0.5
    pfa = rep.tables["Sequences: P_FA vs S"]
    assert 0.025 < float(rep.claims[2].ours.split("measured ")[1].split(";")[0]) < 0.04
    assert pfa["P_FA measured"].iloc[0] > 0.1


def test_trial_counts_drive_the_run(rep):
    n = exp.trial_counts(quick=True)
    assert rep.settings == {"quick": True, **n.as_dict()}
    assert rep.data["fig1"].mc_n_target == n.fig1_windows
    assert rep.data["fig2"].mc_n == n.fig2_tracks
    assert rep.data["sequences"]["n_runs"] == len(rep.data["sequences"]["runs"]) == n.sequences
    assert f"{n.sequences} simulated" in rep.claims[2].ours
    assert set(rep.data["sweep"]["runs"]) == {n.sweep_runs}
    full = exp.trial_counts()
    assert all(getattr(full, k) >= getattr(n, k) for k in n.as_dict())
    with pytest.raises(TypeError, match="quick"):
        exp.trial_counts(quick="yes")


def test_monte_carlo_agrees_with_closed_forms(rep):
    f1, f2 = rep.data["fig1"], rep.data["fig2"]
    assert f1.agreement("exact") and f1.agreement("pfa")
    assert f1.agreement("paper").fraction_inside < 0.5  # eq. (7) is not the pixel model
    for which in ("pds", "pdt", "pft"):
        assert f2.agreement(which)
    with pytest.raises(ValueError, match="which"):
        f1.agreement("eq7")
    with pytest.raises(ValueError, match="which"):
        f2.agreement("pda")


def test_paper_beside_ours_table(rep):
    t = rep.tables["Figs. 4-7: paper beside ours"]
    ps = exp.paper_settings()
    row = t[t["quantity"].str.startswith("CFAR")].iloc[0]
    assert row["paper"] == ps["cfar_p_f"]
    assert abs(row["ours − paper"]) < 0.01
    assert np.allclose(t["ours − paper"].dropna(), (t["ours"] - t["paper"]).dropna())


def test_initiator_against_formulas(rep):
    t = rep.tables["Beyond: the initiator against eqs. (12)-(13)"].set_index("P_F")
    lo, hi = t.iloc[0], t.iloc[-1]
    assert abs(lo["track with >= T_h target points"] - lo["P_DT eq.13"]) < 0.02
    # nearest-neighbour association loses the target among dense false alarms
    assert hi["track with >= T_h target points"] < hi["P_DT eq.13"] - 0.15


def test_explore_figure_updates_one_figure_in_place():
    import matplotlib

    matplotlib.use("Agg")
    f_a = exp.explore_figure()
    f_b = exp.explore_figure(snr=3.0, window=3, target_pixels=25, s=25, frames=5, min_hits=20,
                             show_eq7=False)
    assert f_a is f_b  # no new figure per redraw
    a1, a2 = f_b.axes
    assert "$S$ = 9" in a1.get_title() and "$T_h$ = 5" in a2.get_title()  # clipped to W_S, T
    assert a1.get_xlim() == (0.5, 9.5) and a2.get_xlim() == (0.5, 5.5)
    labels = [t.get_text() for t in a1.get_legend().get_texts()]
    assert len(labels) == 3 and "chosen $S$" in labels  # eq. (7) hidden; the S mark named


# ---------------------------------------------------------------- statistics rules (MACHINERY.md)
def test_experiment_share_has_at_least_20_runs_and_an_interval(rep):
    n = exp.trial_counts(quick=True).sequences
    assert n >= 20 and exp.trial_counts().sequences >= 20
    m = exp.experiment_measurement(rep.data["sequences"])
    assert m["n_runs"] == n
    share, lo, hi = exp.run_share(m["curved_ok"], n)
    assert lo <= share <= hi
    row = next(c for c in rep.claims if c.claim == "track_init.li_experiment")
    assert f"{m['curved_ok']}/{n} = " in row.ours and "95 % CP [" in row.ours
    # the status is the evaluator's, on the same measurement (no second copy of the logic)
    assert exp.status_experiment(m) is row.status


def test_sweep_is_the_experiment(rep):
    """Fig. 7's sweep runs the experiment's own scene and sequences (common random numbers)."""
    ex, sweep = rep.data["sequences"], rep.data["sweep"]
    st = rep.data["settings"]
    n_sw = int(sweep["runs"].iloc[0])
    row = sweep[sweep["SNR"] == st.curved_snr].iloc[0]
    first = ex["runs"][:n_sw]  # the sweep's runs are the experiment's first n_sw sequences
    assert row["recovered runs"] == sum(r["coverage"][1] >= 0.5 for r in first)
    fr = sum(r["target_frames"][1] for r in first)
    assert row["P_DA measured"] == pytest.approx(sum(r["target_area_det"][1] for r in first) / fr)
    assert list(sweep["SNR"]) == sorted(sweep["SNR"])
    assert np.all(np.diff(sweep["P_DA measured"]) > 0)  # same noise: brighter -> more detected
    assert np.all((sweep["CP low"] <= sweep["recovered share"])
                  & (sweep["recovered share"] <= sweep["CP high"]))


def test_fig7_panels_are_members_of_the_sweep(rep):
    fig = rep.figures["fig7_curved_target_tracks"]
    sweep = rep.data["sweep"]
    titles = [a.get_title() for a in fig.axes]
    assert "paper's SNR" in titles[0]
    for t in titles:
        snr = float(t.split("SNR ")[1].split(" ")[0])
        r = sweep[np.isclose(sweep["SNR"], snr)].iloc[0]
        assert f"all {int(r['runs'])} runs: curved target recovered in {int(r['recovered runs'])}" in t
    for a in fig.axes:
        assert a.get_xlabel() == "x (px)" and a.get_ylabel() == "y (px)"
        labels = [x.get_text() for x in a.get_legend().get_texts()]
        assert "true path (grey)" in labels and "false track" in labels


def test_monte_carlo_checks_are_familywise(rep):
    """Several readings compared at once: Bonferroni-corrected, exact-coverage intervals."""
    f1, f2 = rep.data["fig1"], rep.data["fig2"]
    for cid in ("track_init.li_fig1", "track_init.li_fig2"):
        row = next(c for c in rep.claims if c.claim == cid)
        assert "family-wise 99.9 % Clopper-Pearson intervals (Bonferroni" in row.ours
    m2 = exp.fig2_measurement(f2)
    assert m2["mc_agrees"] == all(bool(f2.agreement(w, familywise=True, method="clopper-pearson"))
                                  for w in ("pds", "pdt", "pft"))
    m1 = exp.fig1_measurement(f1)
    assert m1["mc_agrees_exact"] == bool(f1.agreement("exact", familywise=True,
                                                      method="clopper-pearson"))
    a = f2.agreement("pft", familywise=True, method="clopper-pearson")
    assert a.familywise_bound <= 1e-3 + 1e-12  # the whole curve at 99.9 %


def test_seeds_derive_every_generator():
    assert exp.seeds() == exp.SEEDS
    a, b = exp.seeds(3), exp.seeds(3)
    assert all(a[k].entropy == b[k].entropy and a[k].spawn_key == b[k].spawn_key for k in a)
    assert len({tuple(v.generate_state(2)) for v in a.values()}) == len(a)  # independent
    assert exp.seeds(4)["sequences"].generate_state(1)[0] != a["sequences"].generate_state(1)[0]
    with pytest.raises(TypeError, match="seed"):
        exp.seeds(1.5)
    with pytest.raises(ValueError, match="seed"):
        exp.seeds(-1)
    st = exp.SequenceSettings.from_paper()
    st = type(st)(**{**st.__dict__, "shape": (96, 96), "n_frames": 12, "include_main": False,
                     "curved_first": 0, "curved_frames": 12, "curved_centre": (48.0, 48.0),
                     "curved_radius": 20.0})
    r1 = exp.sequence_experiment(st, 2, seed=exp.seeds(9)["sequences"])
    r2 = exp.sequence_experiment(st, 2, seed=exp.seeds(9)["sequences"])
    assert r1["p_f"] == r2["p_f"] and r1["removed"] == r2["removed"]


def test_bad_input_of_the_new_helpers():
    with pytest.raises(ValueError, match="k"):
        exp.run_share(5, 4)
    with pytest.raises(ValueError):
        exp.run_share(0, 0)
    st = exp.SequenceSettings.from_paper()
    with pytest.raises(ValueError, match="n_runs"):
        exp.snr_sweep(st, [2.0], 0)
    with pytest.raises(ValueError, match="paper_runs"):
        exp.snr_sweep(st, [2.0], 3, paper_runs=[{}])
    p, lo, hi = exp.run_share(0, 24)
    assert p == 0 and lo == 0 and 0.13 < hi < 0.15  # 95 % Clopper-Pearson upper bound
    assert exp.status_experiment({"n_runs": 24, "removed": 0.99, "main_ok": 24,
                                  "curved_ok": 0}) is Status.NOT_REPRODUCED


# ---------------------------------------------------------------- li_fig1: status and exploratory reading
def test_fig1_status_is_the_pre_stated_criterion_and_the_refutation_only_exploratory(rep):
    """The refutation of "a suitable SNR (e.g. 2 or 3) works" was written after results were
    seen: it fires on the evidence, is reported beside the status, and never sets it."""
    claim = load_claims("track_init_ht")["track_init.li_fig1"]
    assert "Contradicted if the Monte Carlo itself reverses the paper's ordering" in claim.criterion
    assert "refutes" not in claim.criterion and "exploratory" not in claim.criterion
    last = claim.history[-1]
    assert last.after_results and "refut" in last.criterion and "restored" in last.reason
    f1 = rep.data["fig1"]
    m = exp.fig1_measurement(f1)
    assert set(m) == {"readings_paper", "readings_exact", "mc_agrees_exact", "mc_agrees_pfa",
                      "reversed"}  # nothing chosen after the results enters the status
    assert not m["reversed"] and exp.status_fig1(m) is Status.PARTIAL
    rf = exp.fig1_refutation(f1)
    assert rf["refuted"] and rf["s_min"] == 3 and max(rf["upper"]) < 0.9
    row = next(c for c in rep.claims if c.claim == "track_init.li_fig1")
    assert row.status is Status.PARTIAL
    assert "Exploratory reading (rule set after results were seen; not the status)" in row.note
    assert "li_fig1, exploratory (not the status)" in rep.text


def test_fig1_exploratory_refutation_fires_on_evidence_and_only_then():
    """The exploratory test fires at the paper's SNRs and not where one SNR does work; the
    pre-stated reversal clause fires on neither."""
    kw = dict(p_f=0.003, window=5, target_pixels=4, n_noise=50_000, n_target=50_000, seed=11)
    f1 = exp.fig1_monte_carlo(snr=[1.0, 2.0, 3.0], **kw)
    assert exp.fig1_refutation(f1)["refuted"]
    assert exp.status_fig1(exp.fig1_measurement(f1)) is Status.PARTIAL
    assert "refutes the paper's" in exp.fig1_exploratory(f1)
    for snrs in ([1.0, 4.0, 5.0], [1.0, 2.0, 5.0]):  # existential: one working SNR suffices
        fb = exp.fig1_monte_carlo(snr=snrs, **kw)
        rfb = exp.fig1_refutation(fb)
        assert not rfb["refuted"] and max(rfb["mc_pda"]) > 0.9
        assert "does not refute" in exp.fig1_exploratory(fb)
        assert not exp.fig1_measurement(fb)["reversed"]
    # robust to the link: the exact count needs P_D >= 0.853 at S = 3 (not printed as an SNR:
    # that is exercise 3's answer)
    pd_need = exp.robust_pd(0.003, 5, 4, 3)
    assert 0.85 < pd_need < 0.856
    from eotrack.tracking import hypothesis as hyp
    assert hyp.area_detection_exact(pd_need, 0.003, 5, 4, 3) >= 0.9 > hyp.area_detection_exact(
        pd_need - 1e-3, 0.003, 5, 4, 3)


def test_fig1_snr1_ratio_is_reported_not_decisive():
    """'P_DA very close to P_FA' at SNR 1: eq. (7) is >= 3,290 x P_FA at S = 3 for every P_D
    (eq. 6 gives P_1 >= 0.061 at P_D = 0), so a ratio cut would decide by its wording alone."""
    f1 = exp.fig1_monte_carlo(snr=[1.0, 2.0, 3.0], p_f=0.003, window=5, target_pixels=4,
                              n_noise=50_000, n_target=50_000, seed=12)
    r7, rx = exp.fig1_readings(f1, f1.pda_paper), exp.fig1_readings(f1, f1.pda_exact)
    assert r7["s_min"] == 3 and 7000 < r7["snr_low_ratio"][1.0] < 9000
    assert 15 < rx["snr_low_ratio"][1.0] < 22
    assert not r7["snr_low_close"] and r7["snr_low_fails"] and r7["all_hold"]
    floor = exp.eq7_ratio_floor(0.003, 5, 4, 3)
    assert 3280 < floor < 3300
    f0 = exp.fig1_monte_carlo(snr=[0.0, 2.0, 3.0], p_f=0.003, window=5, target_pixels=4,
                              n_noise=50_000, n_target=50_000, seed=13)  # P_D = P_F at SNR 0
    assert exp.fig1_readings(f0, f0.pda_paper)["snr_low_ratio"][0.0] >= floor


def test_fig2_is_not_directional_the_gate_model_closes_the_gap(rep):
    """At P_F = 1e-4 the gap P_DS - P_DT is capped at 1 - (1 - P_F)^((M-1) T) = 0.0056 for every
    P_D and T_h, below the 0.01 of the partial band: no data can reverse the paper there."""
    assert not load_claims("track_init_ht")["track_init.li_fig2"].directional
    f2 = rep.data["fig2"]
    ceil = exp.fig2_gap_ceiling(f2.p_f, 3, 7)
    assert ceil[0] == pytest.approx(0.005585, abs=1e-6) and ceil[0] < exp.GAP_LOW
    from eotrack.tracking import hypothesis as hyp
    p_d = np.linspace(0, 1, 101)[:, None, None]
    th = np.arange(1, 8)[None, :, None]
    gap = (hyp.sequence_detection(p_d, f2.p_f[None, None, :], 3, 7, th)
           - hyp.track_detection(p_d, 7, th))
    assert np.all(gap <= ceil[None, None, :] + 1e-12)
    d = f2.mc_pds - f2.mc_pdt  # nested events on the same tracks: never negative
    assert np.all(d >= 0) and np.all(d <= ceil[None, :] + 5 * np.sqrt(ceil / f2.mc_n))


# ---------------------------------------------------------------- the stored sequence study
def _small_settings():
    st = exp.SequenceSettings.from_paper()
    return type(st)(**{**st.__dict__, "shape": (96, 96), "n_frames": 12, "include_main": False,
                       "curved_first": 0, "curved_frames": 12, "curved_centre": (48.0, 48.0),
                       "curved_radius": 20.0})


def test_stored_study_round_trip_equals_the_live_run(tmp_path):
    st = _small_settings()
    snrs = [st.curved_snr + d for d in exp.SWEEP_SNR]
    ex = exp.sequence_experiment(st, 2, seed=7)
    sweep, by_snr = exp.snr_sweep(st, snrs, 2, seed=7, paper_runs=ex["runs"], return_runs=True)
    path = tmp_path / exp.STORED_FILE
    exp.write_stored(path, st, by_snr, n_runs=2, seed=7)
    ex2, sweep2, source = exp.sequence_study(st, 2, 2, seed=7, path=path)
    assert source.startswith("stored run") and exp.code_hash() in source
    pd.testing.assert_frame_equal(sweep2, sweep)
    for key in ("table", "pfa_table", "pft_table"):
        pd.testing.assert_frame_equal(ex2[key], ex[key])
    assert ex2["p_f"] == ex["p_f"] and ex2["removed"] == ex["removed"]
    for a, b in zip(ex2["runs"], ex["runs"]):
        assert a.keys() == b.keys()
        for k in a:
            assert np.array_equal(np.asarray(a[k]), np.asarray(b[k])), k
    # another seed, other settings, other counts: refused, run live (and the reason is said)
    with pytest.raises(ValueError, match="seed"):
        exp.read_stored(path, st, n_runs=2, seed=8, snrs=snrs)
    st_b = type(st)(**{**st.__dict__, "p_f": 0.02})
    with pytest.raises(ValueError, match="settings"):
        exp.read_stored(path, st_b, n_runs=2, seed=7, snrs=snrs)
    _, _, src = exp.sequence_study(st, 2, 2, seed=8, path=path)
    assert src.startswith("live run") and "seed" in src
    _, _, src = exp.sequence_study(st, 2, 1, seed=7, path=path)
    assert src.startswith("live run") and "QUICK" in src
    with pytest.raises(FileNotFoundError, match=r"eotrack\.repro track_init_ht"):
        exp.read_stored(tmp_path / "none.json", st, n_runs=2, seed=7, snrs=snrs)
    with pytest.raises(ValueError, match="n_runs"):
        exp.write_stored(path, st, {st.curved_snr: ex["runs"][:1]}, n_runs=2, seed=7)
    with pytest.raises(ValueError, match="SNR"):
        exp.write_stored(path, st, {9.0: ex["runs"]}, n_runs=2, seed=7)
    with pytest.raises(ValueError, match="runs"):
        exp.pool_runs([], st)


def test_committed_sequence_study_is_current():
    """The stored study notebook 03 reads was written by this code for these settings (else the
    notebook silently falls back to the slow live run): re-run `python -m eotrack.repro
    track_init_ht` after editing any file of stored._CODE."""
    from eotrack.repro import papers_repro_dir

    st = exp.SequenceSettings.from_paper()
    n = exp.trial_counts()
    by_snr = exp.read_stored(papers_repro_dir() / "track_init_ht" / exp.STORED_FILE, st,
                             n_runs=n.sequences, seed=exp.SEEDS["sequences"],
                             snrs=[st.curved_snr + d for d in exp.SWEEP_SNR])
    assert all(len(v) == n.sequences for v in by_snr.values())


def test_bad_input_of_the_store_and_robust_pd(tmp_path):
    st = _small_settings()
    snrs = [st.curved_snr + d for d in exp.SWEEP_SNR]
    for text in ("[]", "{", '{"runs": 1}'):
        p = tmp_path / "bad.json"
        p.write_text(text)
        with pytest.raises(ValueError, match="not a stored study"):
            exp.read_stored(p, st, n_runs=2, seed=7, snrs=snrs)
        _, _, src = exp.sequence_study(st, 2, 2, seed=7, path=p)  # falls back, says why
        assert src.startswith("live run") and "bad.json" in src
    with pytest.raises(ValueError, match="n_runs"):
        exp.write_stored(tmp_path / "x.json", st, {st.curved_snr: []}, n_runs=0, seed=7)
    with pytest.raises(ValueError, match="s must be"):
        exp.robust_pd(0.003, 5, 4, 0)
