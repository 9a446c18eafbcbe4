"""akf_star figures: every plot of notebook 05 and the REPORT, one function each.

Each function takes ``ax=None`` (or ``axes=None``) and returns the figure it drew on.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from .scenario import SCENARIO_LABELS
from .trials import AblationResult

__all__ = [
    "VARIANT_STYLES",
    "plot_confidence_trace",
    "plot_diurnal_check",
    "plot_error_curves",
    "plot_example_frames",
    "plot_explore_errors",
    "plot_extraction_example",
    "plot_frames_schematic",
    "plot_real_sky",
    "plot_sage_husa",
    "plot_ship_attitude",
    "plot_success_curves",
]

#: line styles that keep coinciding curves apart (Baseline and BEAK-ST-GT are identical where
#: both lose the star: Baseline is drawn wide and dashed underneath, GT thin and dotted on top)
def _variant_styles() -> dict[str, dict[str, Any]]:
    from eotrack.plotting import method_style

    widths = {"Baseline": (2.6, 1), "BEAK-ST-GT": (1.6, 3), "BEAK-ST-SKF": (1.2, 2),
              "BEAK-ST": (1.4, 4)}
    return {v: {"ls": method_style(v).linestyle, "lw": lw, "color": method_style(v).color,
                "zorder": z} for v, (lw, z) in widths.items()}


#: (the house style's colour and line style per variant, eotrack.plotting.method_style)
VARIANT_STYLES: dict[str, dict[str, Any]] = _variant_styles()


def _ax(ax: Any = None, **kw: Any) -> Any:
    from eotrack.plotting import get_ax

    return get_ax(ax, **kw)


def _curves(res: AblationResult, values: np.ndarray, ax: Any) -> None:
    for v, c in zip(res.variants, values):
        ax.plot(np.arange(1, c.size + 1), c, label=v, **VARIANT_STYLES.get(v, {}))
    same = np.allclose(values[res.variants.index("Baseline")],
                       values[res.variants.index("BEAK-ST-GT")], rtol=0.02, atol=1e-3)
    ax.legend(fontsize=8, title="Baseline under GT (same curve)" if same else None,
              title_fontsize=7)


def plot_error_curves(res: AblationResult, ax: Any = None, *, scenario: str | None = None
                      ) -> Any:
    """Fig. 6: mean tracking error per frame (over seeds, and scenarios unless one is given)."""
    ax = _ax(ax, figsize=(6.4, 4.0))
    e = res.errors if scenario is None else res.errors[[res.scenarios.index(scenario)]]
    _curves(res, e.mean(axis=(0, 1)), ax)
    ax.set_xlabel("frame")
    ax.set_ylabel("mean tracking error (px)")
    ax.set_yscale("log")
    ax.set_title("Fig. 6 — mean tracking error over the frames"
                 + (f" ({SCENARIO_LABELS[scenario]})" if scenario else " (all scenarios)")
                 + f", {res.config.n_seeds} sequences")
    return ax.figure


def plot_curves_by_scenario(res: AblationResult, kind: str = "error", axes: Any = None) -> Any:
    """Figs. 6–7 per scenario (one panel each, as the claims are decided): the frame-wise mean
    error (``kind="error"``, log scale) or success rate (``kind="success"``) of the variants."""
    import matplotlib.pyplot as plt

    if kind not in ("error", "success"):
        raise ValueError(f"kind must be 'error' or 'success', got {kind!r}")
    n = len(res.scenarios)
    legend_ax = None
    if axes is None:
        # two rows of three at book width: legible ticks and legend (one cell holds the legend)
        ncol = min(n, 3)
        nrow = -(-(n + 1) // ncol) if n > 1 else 1
        fig, grid = plt.subplots(nrow, ncol, figsize=(2.6 * ncol, 2.5 * nrow + 0.6),
                                 sharex=True, sharey=True, squeeze=False)
        fig.subplots_adjust(wspace=0.3, hspace=0.4, top=0.88, bottom=0.1, left=0.08, right=0.98)
        grid = grid.ravel()
        legend_ax = grid[n] if grid.size > n else None
        for ax in grid[n + 1:]:      # spare cells beyond the legend's: nothing drawn there
            ax.remove()
        axes = grid[:n]
    axes = np.ravel(axes)
    for i, (ax, sc) in enumerate(zip(axes, res.scenarios)):
        e = res.errors[i].astype(float)
        vals = e.mean(axis=0) if kind == "error" else (e <= res.config.epsilon_px).mean(axis=0)
        for v, c in zip(res.variants, vals):
            ax.plot(np.arange(1, c.size + 1), c, label=v, **VARIANT_STYLES.get(v, {}))
        if kind == "error":
            ax.set_yscale("log")
        else:
            ax.set_ylim(-0.02, 1.02)
        ax.set_title(SCENARIO_LABELS.get(sc, sc), fontsize=10)
        ax.tick_params(labelsize=9, labelbottom=True, labelleft=True)
        ax.set_xlabel("frame", fontsize=9)
    ylabel = ("mean tracking error (px)" if kind == "error"
              else f"success rate (e ≤ {res.config.epsilon_px:g} px)")
    for ax in axes:
        ax.set_ylabel(ylabel if kind == "success" else "mean error (px)", fontsize=9)
    handles = axes[0].get_legend_handles_labels()
    if legend_ax is not None:   # a figure legend centred in the spare grid cell
        box = legend_ax.get_position()
        legend_ax.remove()
        axes[0].figure.legend(*handles, loc="center", fontsize=10, frameon=False,
                              title="variant", title_fontsize=10,
                              bbox_to_anchor=(box.x0 + box.width / 2, box.y0 + box.height / 2))
    else:
        axes[0].figure.legend(*handles, loc="lower center", ncol=len(res.variants),
                              fontsize=10, frameon=False)
    axes[0].figure.suptitle(
        ("Fig. 6 — mean tracking error" if kind == "error" else "Fig. 7 — success rate")
        + f" per scenario ({res.config.n_seeds} sequences each)", fontsize=11)
    return axes[0].figure


def plot_success_curves(res: AblationResult, ax: Any = None, *, scenario: str | None = None
                        ) -> Any:
    """Fig. 7: success rate (e ≤ ε) per frame."""
    ax = _ax(ax, figsize=(6.4, 4.0))
    e = res.errors if scenario is None else res.errors[[res.scenarios.index(scenario)]]
    _curves(res, (e <= res.config.epsilon_px).mean(axis=(0, 1)), ax)
    ax.set_xlabel("frame")
    ax.set_ylabel(f"success rate (e ≤ {res.config.epsilon_px:g} px)")
    ax.set_ylim(-0.02, 1.02)
    ax.set_title("Fig. 7 — mean success rate over the frames"
                 + (f" ({SCENARIO_LABELS[scenario]})" if scenario else " (all scenarios)")
                 + f", {res.config.n_seeds} sequences")
    return ax.figure


def plot_example_frames(seed: int = 1, frame: int = 120, *, axes: Any = None) -> Any:
    """One frame of each scenario with the reference star's true position marked."""
    import matplotlib.pyplot as plt

    from eotrack.imaging.star_sensor_sim import SCENARIOS, simulate_sequence

    if axes is None:
        _, axes = plt.subplots(1, len(SCENARIOS), figsize=(1.6 * len(SCENARIOS), 2.0))
    for ax, sc in zip(np.ravel(axes), SCENARIOS):
        seq = simulate_sequence(np.random.default_rng(seed), sc, n_frames=frame + 1)
        ax.imshow(seq.images[frame], cmap="gray", vmin=0, vmax=255)
        ax.plot(*seq.truth[frame], "o", mfc="none", mec="r", ms=12)
        ax.set_title(SCENARIO_LABELS[sc], fontsize=9)
        ax.set_xticks([])
        ax.set_yticks([])
        ax.grid(False)
    return np.ravel(axes)[0].figure


def plot_frames_schematic(heading_deg: float = 30.0, pitch_deg: float = 12.0,
                          roll_deg: float = 20.0, cam_azimuth_deg: float = 40.0,
                          cam_elevation_deg: float = 35.0, ax: Any = None) -> Any:
    """The frames of eqs. (1)–(5) drawn from the library's rotation matrices.

    Level frame N (east, north, up), deck frame B (starboard X, bow Y, deck-up Z) after
    heading ψ, pitch θ and roll φ, and the camera's optical axis Y′ at azimuth β and elevation
    α on the deck. The angles are exaggerated so the rotations are visible.
    """
    import matplotlib.pyplot as plt

    from eotrack.geometry.shipboard import camera_from_level, deck_from_level

    if ax is None:
        fig = plt.figure(figsize=(6.0, 5.2))
        ax = fig.add_subplot(projection="3d")
    psi, th, ph = np.radians([heading_deg, pitch_deg, roll_deg])
    R_nb = deck_from_level(psi, th, ph)                 # rows: deck axes in level coordinates
    R_nc = camera_from_level(psi, th, ph, np.radians(cam_azimuth_deg),
                             np.radians(cam_elevation_deg))
    o = np.zeros(3)
    for vec, lab, c, ls in [((1, 0, 0), "E ($X$)", "k", ":"), ((0, 1, 0), "N ($Y$)", "k", ":"),
                            ((0, 0, 1), "U ($Z$)", "k", ":")]:
        ax.plot(*np.c_[o, vec], color=c, ls=ls, lw=1)
        ax.text(*(1.08 * np.asarray(vec)), lab, fontsize=8)
    # every label beyond its arrow's tip (none on a line; review figs #12b)
    for i, (lab, at, ha) in enumerate((("starboard $X_B$", 1.1, "left"), ("bow $Y_B$", 1.12, "left"),
                                       ("deck-up $Z_B$", 1.1, "right"))):
        v = 0.85 * R_nb[i]
        ax.plot(*np.c_[o, v], color="tab:blue", lw=2)
        ax.text(*(at * v), lab, color="tab:blue", fontsize=8, ha=ha)
    bore = 1.2 * R_nc[1]
    ax.plot(*np.c_[o, bore], color="tab:red", lw=2.5)
    ax.text(*(0.75 * bore), "optical axis $Y'$", color="tab:red", fontsize=8, ha="left",
            va="top")  # under the axis' outer part: beyond its tip it ran past the figure's edge
    for i, lab in ((0, "$X'$"), (2, "$Z'$")):
        v = 0.45 * R_nc[i]
        ax.plot(*np.c_[bore * 0.6, bore * 0.6 + v], color="tab:red", lw=1)
        ax.text(*(bore * 0.6 + 1.3 * v), lab, color="tab:red", fontsize=8, ha="center",
                va="center")
    deck = np.array([[-0.3, -0.6, 0], [0.3, -0.6, 0], [0.3, 0.5, 0], [0, 0.75, 0],
                     [-0.3, 0.5, 0], [-0.3, -0.6, 0]]) @ R_nb
    ax.plot(*deck.T, color="tab:blue", alpha=0.5)
    ax.set_xlim(-1, 1)
    ax.set_ylim(-1, 1)
    ax.set_zlim(-0.3, 1.2)
    ax.set_box_aspect((1, 1, 0.75), zoom=1.45)
    ax.set_axis_off()                                   # no empty panes around the schematic
    ax.set_title(f"Frames: level N → deck B (ψ {heading_deg:g}°, θ {pitch_deg:g}°, "
                 f"φ {roll_deg:g}°) → camera C\n(β {cam_azimuth_deg:g}°, α "
                 f"{cam_elevation_deg:g}°; angles exaggerated)", fontsize=9)
    return ax.figure


def plot_diurnal_check(df: Any, ax: Any = None) -> Any:
    """Altitude rate of real stars: astropy against the correct form and eq. (12) as printed."""
    ax = _ax(ax, figsize=(6.4, 3.6))
    k = 206264.8
    ax.plot(df["astropy_hdot"] * k, df["correct_hdot"] * k, "o", label="correct form")
    ax.plot(df["astropy_hdot"] * k, df["paper_hdot"] * k, "x", label="eq. (12) as printed")
    lim = float(np.abs(df["astropy_hdot"]).max() * k * 1.1)
    ax.plot([-lim, lim], [-lim, lim], "k:", lw=0.8)
    ax.set_xlabel(r"astropy $\dot h$ (arcsec/s)")
    ax.set_ylabel(r"model $\dot h$ (arcsec/s)")
    ax.set_title(f"Altitude rate of {len(df)} real stars")
    ax.legend()
    return ax.figure


def plot_ship_attitude(t: np.ndarray, att: dict[str, np.ndarray], ax: Any = None, *,
                       title: str = "Ship attitude (one realisation)") -> Any:
    """Roll, pitch and yaw (heading minus its mean) against time."""
    ax = _ax(ax, figsize=(6.4, 3.0))
    for k, lab in (("roll", "roll"), ("pitch", "pitch"), ("heading", "yaw")):
        a = np.degrees(np.unwrap(att[k]))
        if k == "heading":
            a = a - a.mean()
        ax.plot(t, a, label=lab)
    ax.set_xlabel("t (s)")
    ax.set_ylabel("angle (deg)")
    ax.set_title(title)
    ax.legend()
    return ax.figure


def plot_extraction_example(img: np.ndarray, adaptive: Any, global_: Any, g5: int, g95: int,
                            truth: np.ndarray | None = None, axes: Any = None) -> Any:
    """Grey histogram with g5/g95 (eqs. 15–18) and the detections of both methods."""
    import matplotlib.pyplot as plt

    if axes is None:
        fig, axes = plt.subplots(1, 2, figsize=(7.2, 3.6))
        fig.subplots_adjust(wspace=0.35)
    a0, a1 = axes
    a0.bar(np.arange(256), np.bincount(np.asarray(img, np.uint8).ravel(), minlength=256),
           width=1)
    for g, nm in ((g5, "g5"), (g95, "g95")):
        a0.axvline(g, color="k", ls=":")
        a0.annotate(nm, (g, 1.0), xycoords=("data", "axes fraction"), xytext=(2, -2),
                    textcoords="offset points", ha="left", va="top", fontsize=9)
    a0.set_xlabel("grey level g")
    a0.set_ylabel("H(g)")
    a0.set_title(f"histogram: g5 = {g5}, g95 = {g95}", fontsize=10)
    a1.imshow(img, cmap="gray")
    a1.plot(*np.asarray(adaptive.xy).T, "+", color="lime", label="adaptive")
    if len(global_.xy):
        a1.plot(*np.asarray(global_.xy).T, "x", color="r", label="global")
    if truth is not None:
        a1.plot(*truth, "o", mfc="none", mec="yellow", ms=12, label="reference star")
    a1.set_title("detections")
    a1.set_xlabel("x (px)")
    a1.set_ylabel("y (px)")
    a1.legend(fontsize=8, loc="upper center", bbox_to_anchor=(0.5, -0.2), ncol=3,
              frameon=False)
    a1.grid(False)
    return a0.figure


def plot_sage_husa(min_eig: dict[str, np.ndarray], ax: Any = None) -> Any:
    """Smallest eigenvalue of the Sage–Husa R estimate per step, with and without safeguard."""
    ax = _ax(ax, figsize=(6.4, 3.0))
    for k, v in min_eig.items():
        ax.plot(v, label=k)
    ax.axhline(0, color="k", lw=0.8)
    ax.set_xlabel("step k")
    ax.set_ylabel("smallest eigenvalue of R (px²)")
    ax.set_title("Sage–Husa R estimate: the failure and the safeguard")
    ax.legend()
    return ax.figure


def plot_confidence_trace(seq: Any, track: Any, axes: Any = None) -> Any:
    """Cloud transmission, confidence C_k, the filter's mode and the error of one track."""
    import matplotlib.pyplot as plt

    if axes is None:
        fig, axes = plt.subplots(2, 1, figsize=(7, 5.8), sharex=True)
        fig.subplots_adjust(hspace=0.75)
    e = np.hypot(*(track.xs[:, :2] - seq.truth).T)
    axes[0].plot(seq.visible, label="cloud transmission at the star")
    axes[0].plot(track.confidence, ".", ms=3, label=r"$C_k$")
    modes = np.asarray(track.modes)
    # one marker shape per mode as well as a colour (green and red alone read alike to a
    # deuteranope)
    for m, (name, col, mk, size) in enumerate((("update", "tab:green", "|", 60),
                                               (r"inflated $R$", "tab:orange", "^", 14),
                                               ("predict only", "tab:red", "x", 20))):
        sel = modes == m
        axes[0].scatter(np.flatnonzero(sel), np.full(int(sel.sum()), -0.1), color=col,
                        marker=mk, s=size, label=f"mode: {name}")
    axes[0].set_ylim(-0.2, 1.05)
    axes[0].set_ylabel("transmission, confidence")
    axes[0].legend(fontsize=8, ncol=3, loc="upper center", bbox_to_anchor=(0.5, -0.12),
                   frameon=False)
    axes[0].set_title("BEAK-ST through clouds (strip at the bottom: the filter's mode)")
    axes[1].semilogy(e + 1e-3)
    axes[1].set_title("its tracking error", fontsize=10)
    axes[1].set_ylabel("error (px)")
    axes[1].set_xlabel("frame")
    return axes[0].figure


def plot_explore_errors(errors: dict[str, np.ndarray], title: str, ax: Any = None, *,
                        gate_px: float | None = None) -> Any:
    """Per-frame errors of the variants on one sequence (the Explore panel's figure).

    The error axis is logarithmic with fixed limits (0.01 px to at least 300 px), so that
    redraws compare at a glance; ``gate_px`` draws the association gate (an estimate above it
    has lost the star). Plain decade labels (no mathtext), no minor ticks and a fixed legend
    place keep a redraw cheap (the panel redraws on every control change).
    """
    from matplotlib.ticker import FixedLocator, FuncFormatter, NullLocator

    ax = _ax(ax, figsize=(6.6, 3.2))
    if not isinstance(errors, dict) or not errors:
        raise ValueError("errors must be a non-empty dict variant -> per-frame errors")
    top = 300.0
    for name, e in errors.items():
        e = np.asarray(e, dtype=float)
        if e.ndim != 1:
            raise ValueError(f"errors[{name!r}] must be 1-D, got shape {e.shape}")
        ax.semilogy(e + 1e-3, label=name, **VARIANT_STYLES.get(name, {}))
        top = max(top, 30.0 * float(np.nanmax(e, initial=0.0)))   # room for the legend
    if gate_px is not None:
        ax.axhline(gate_px, color="0.5", lw=0.8, ls=":", label=f"gate ({gate_px:g} px)")
    ax.set_ylim(1e-2, top)
    ax.yaxis.set_major_locator(FixedLocator(10.0 ** np.arange(-2, np.ceil(np.log10(top)) + 1)))
    ax.yaxis.set_major_formatter(FuncFormatter(lambda v, _: f"{v:g}"))
    ax.yaxis.set_minor_locator(NullLocator())
    ax.set_xlabel("frame")
    ax.set_ylabel("error (px)")
    ax.set_title(title, fontsize=9)
    ax.legend(fontsize=9, loc="upper left", ncol=len(errors) + (gate_px is not None))
    return ax.figure


def plot_real_sky(img: np.ndarray, xy: np.ndarray, ax: Any = None, *,
                  reference: np.ndarray | None = None, title: str = "") -> Any:
    """A real frame (asinh stretch) with our detections and optional reference positions."""
    ax = _ax(ax, figsize=(5.5, 5.5))
    med = np.median(img)
    mad = np.median(np.abs(img - med)) * 1.4826 or 1.0
    ax.imshow(np.arcsinh((img - med) / (3 * mad)), cmap="gray_r", vmin=-1, vmax=5)
    ax.plot(*np.asarray(xy).T, "+", color="tab:red", ms=5, mew=0.8, label="sky extractor")
    if reference is not None:
        ax.plot(*np.asarray(reference).T, "o", mfc="none", mec="tab:blue", ms=9,
                label="clean isolated stars (reference)")
    ax.set_title(title, fontsize=9)
    ax.set_xlabel("x (px)")
    ax.set_ylabel("y (px)")
    ax.legend(fontsize=8, loc="upper center", bbox_to_anchor=(0.5, -0.08), ncol=2,
              frameon=False)
    ax.grid(False)
    return ax.figure
