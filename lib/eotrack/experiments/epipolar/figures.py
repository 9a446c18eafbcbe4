"""Figures of Huang, Zhang & Feng: the schematics (sensors and epipolar plane, two-ray
triangulation, the frames of eq. 4), Figs. 3–8, the error-budget checks and the threshold
trade-off drawn by the notebook's widget. Every function returns its figure or axes."""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np
import pandas as pd

from eotrack.geometry.epipolar import fundamental_from_poses
from eotrack.geometry.triangulation import closest_points_two_rays
from eotrack.plotting import get_ax, legend_outside, paper_marker
from eotrack.validation import check_int

from .scenario import PAIR_LABELS, PAIRS, Observation, Scenario, frame_chain
from .trials import ThresholdStudy

__all__ = [
    "TradeoffView",
    "plot_distance_check",
    "plot_epipolar_geometry",
    "plot_fig3",
    "plot_fig4",
    "plot_fig5",
    "plot_fig6",
    "plot_fig8",
    "plot_frame_chain",
    "plot_gate_study",
    "plot_threshold_tradeoff",
    "plot_triangulation",
    "render_maps",
]

EARTH_RADIUS_KM = 6378.137


def _check_pair(scenario: Scenario, pair) -> tuple[int, int]:
    a, b = (check_int(int(v), "pair", min_value=0) for v in pair)
    if a == b or max(a, b) >= len(scenario.cameras):
        raise ValueError(f"pair must be two different sensor indices < {len(scenario.cameras)}, "
                         f"got {pair}")
    return a, b


def _draw_line(ax, line, size) -> None:
    """Draw a u + b v + c = 0 across an image of ``size`` (w, h)."""
    a, b, c = line
    w, h = size
    if abs(b) > abs(a):
        u = np.array([-0.5, w - 0.5])
        v = -(a * u + c) / b
    else:
        v = np.array([-0.5, h - 0.5])
        u = -(b * v + c) / a
    ax.plot(u, v, color="tab:purple", lw=1.5, label="epipolar line")


def plot_epipolar_geometry(scenario: Scenario, pair=(0, 3), target: int = 4, *, fig=None):
    """Schematic from the scenario: the sensors in orbit with their boresights, the baseline
    O₁O₂, the epipolar plane through a target and the plane's trace (the epipolar line) in
    each image. True scale, noise-free."""
    a, b = _check_pair(scenario, pair)
    j = check_int(target, "target", min_value=0)
    from matplotlib.ticker import MaxNLocator

    fig = fig if fig is not None else plt.figure(figsize=(7.5, 5.6))
    gs = fig.add_gridspec(2, 2, width_ratios=(1.4, 1))
    ax = fig.add_subplot(gs[:, 0], projection="3d")
    X = scenario.objects_km[j]
    ca, cb = scenario.cameras[a], scenario.cameras[b]
    u, v = np.mgrid[0:2 * np.pi:24j, 0:np.pi:12j]
    ax.plot_wireframe(EARTH_RADIUS_KM * np.cos(u) * np.sin(v),
                      EARTH_RADIUS_KM * np.sin(u) * np.sin(v), EARTH_RADIUS_KM * np.cos(v),
                      color="0.7", lw=0.4)
    # only the pair's two sensors are labelled, one to each side (the four sensors are
    # within a few thousand km of each other: their labels would overlap); the others are
    # named in the legend
    others = [k for k in range(len(scenario.cameras)) if k not in (a, b)]
    from mpl_toolkits.mplot3d import proj3d

    pts = np.vstack([scenario.objects_km, scenario.sat_km, np.zeros((1, 3))])
    mid = 0.5 * (pts.max(0) + pts.min(0))
    half = 0.5 * (pts.max(0) - pts.min(0)).max()
    ax.set_xlim(mid[0] - half, mid[0] + half)
    ax.set_ylim(mid[1] - half, mid[1] + half)
    ax.set_zlim(mid[2] - half, mid[2] + half)
    sx = {k: proj3d.proj_transform(*scenario.cameras[k].c, ax.get_proj())[0] for k in (a, b)}
    for k, cam in enumerate(scenario.cameras):
        hi = k in (a, b)
        ax.scatter(*cam.c, color="tab:blue" if hi else "0.5", s=30 if hi else 12,
                   label=("other sensors (" + ", ".join(f"O{m + 1}" for m in others) + ")")
                   if k == others[0] else None)
        if hi:  # the label of the sensor left on screen to its left (below), the other's
            # to its right (above): placed from the projection, so they never meet each
            # other; 1.5 labels' height off the point, clear of the other sensors' markers
            left = k == (a if sx[a] <= sx[b] else b)
            from matplotlib.transforms import offset_copy

            shift = offset_copy(ax.transData, fig=fig, x=-6 if left else 6,
                                y=-9 if left else 9, units="points")
            ax.text(*cam.c, f"O{k + 1}", fontsize=9, color="tab:blue", transform=shift,
                    ha="right" if left else "left", va="top" if left else "bottom")
        if hi:
            ax.quiver(*cam.c, *(cam.R[2] * 0.6 * np.linalg.norm(X - cam.c)), color="tab:blue",
                      lw=1, arrow_length_ratio=0.05)
    ax.scatter(*scenario.objects_km.T, color="k", s=6)
    ax.scatter(*X, color="tab:red", s=40)
    ax.text(*X, f"  {scenario.names[j]}", color="tab:red", fontsize=9)
    base_km = float(np.linalg.norm(cb.c - ca.c))
    ax.plot(*np.stack([ca.c, cb.c]).T, color="tab:orange", lw=3,
            label=f"baseline O{a + 1}O{b + 1} ({base_km:,.0f} km: short at this scale)")
    for c in (ca.c, cb.c):
        ax.plot(*np.stack([c, X]).T, color="tab:red", lw=0.8, ls="--")
    from mpl_toolkits.mplot3d.art3d import Poly3DCollection

    ax.add_collection3d(Poly3DCollection([np.stack([ca.c, cb.c, X])], alpha=0.25,
                                         facecolor="tab:purple", edgecolor="tab:purple"))
    for axis in (ax.xaxis, ax.yaxis, ax.zaxis):
        axis.set_major_locator(MaxNLocator(3))
    ax.set_xlabel("X (km)")
    ax.set_ylabel("Y (km)")
    ax.set_zlabel("Z (km)")
    ax.set_title(f"sensors {a + 1}, {b + 1} (blue: boresights),\nepipolar plane through "
                 f"{scenario.names[j]}", fontsize=9)
    F = fundamental_from_poses(ca.K, ca.R, ca.c, cb.K, cb.R, cb.c)
    px = scenario.true_pixels()
    p1 = np.append(px[a, j], 1.0)
    p2 = np.append(px[b, j], 1.0)
    for row, (k, p, line) in enumerate(((a, px[a, j], F.T @ p2), (b, px[b, j], F @ p1))):
        axi = fig.add_subplot(gs[row, 1])
        w, h = scenario.cameras[k].size
        vis = scenario.visible[k]
        axi.plot(*px[k, vis].T, "o", color="0.6", ms=3, label="other objects")
        _draw_line(axi, line, (w, h))
        axi.plot(*p, "o", color="tab:red", ms=6, label=scenario.names[j])
        axi.set_xlim(-0.5, w - 0.5)
        axi.set_ylim(h - 0.5, -0.5)
        axi.set_aspect("equal")
        axi.set_title(f"image {k + 1}: epipolar line of {scenario.names[j]}\n"
                      f"(its image in {b + 1 if k == a else a + 1})", fontsize=9)
        axi.set_xlabel("u (px)")
        axi.set_ylabel("v (px)")
        axi.xaxis.set_major_locator(MaxNLocator(3))
        axi.yaxis.set_major_locator(MaxNLocator(3))

    fig.suptitle("Epipolar geometry of two star sensors (true scale, noise-free)")
    fig.tight_layout(rect=(0, 0.07, 1, 1))
    legend_outside(fig, where="below", ncol=3)
    return fig


def plot_triangulation(scenario: Scenario, obs: Observation, pair=(0, 3), target: int = 4, *,
                       ax=None):
    """Two-ray triangulation of ``target`` from a noisy draw, in a local frame centred on the
    truth (km): the two lines of sight, their closest-approach segment and its midpoint."""
    a, b = _check_pair(scenario, pair)
    j = check_int(target, "target", min_value=0)
    idx = []
    for k in (a, b):
        hit = np.flatnonzero(obs.labels[k] == j)
        if len(hit) == 0:
            raise ValueError(f"{scenario.names[j]} is not seen by sensor {k + 1}")
        idx.append(hit[0])
    ca, cb = obs.cameras[a], obs.cameras[b]
    d1 = ca.rays(obs.points[a][idx[0]][None])[0]
    d2 = cb.rays(obs.points[b][idx[1]][None])[0]
    q1, q2 = closest_points_two_rays(ca.c, d1, cb.c, d2)
    truth = scenario.objects_km[j]
    los = d1 + d2
    e1 = los / np.linalg.norm(los)
    e2 = np.cross(e1, q2 - q1)
    e2 = e2 / np.linalg.norm(e2) if np.linalg.norm(e2) > 0 else np.cross(e1, [0, 0, 1.0])
    e3 = np.cross(e1, e2)
    B = np.stack([e1, e2, e3])

    def loc(p):
        return (np.asarray(p) - truth) @ B.T

    if ax is None:
        fig = plt.figure(figsize=(7, 5.2))
        ax = fig.add_subplot(projection="3d")
    mid = 0.5 * (q1 + q2)
    span = max(3 * np.linalg.norm(mid - truth), 50.0)
    for q, d, c, lab in ((q1, d1, "tab:blue", f"line of sight of sensor {a + 1}"),
                         (q2, d2, "tab:green", f"line of sight of sensor {b + 1}")):
        s = np.linspace(-span, span, 2)
        ax.plot(*loc(q + s[:, None] * d).T, color=c, lw=1.5, label=lab)
    ax.plot(*loc(np.stack([q1, q2])).T, color="tab:red", lw=2.5,
            label=f"closest approach, {np.linalg.norm(q2 - q1):.2f} km")
    ax.scatter(*loc(mid), color="tab:red", marker="x", s=60,
               label=f"estimate (midpoint), error {np.linalg.norm(mid - truth):.1f} km")
    ax.scatter(0, 0, 0, facecolors="none", edgecolors="k", s=60, label="truth")
    ax.set_xlabel("along the lines of sight (km)")
    ax.set_ylabel("across (km)")
    ax.set_zlabel("across (km)")
    from matplotlib.ticker import MaxNLocator

    for axis in (ax.xaxis, ax.yaxis, ax.zaxis):
        axis.set_major_locator(MaxNLocator(3))
    ax.set_title(f"Two-ray triangulation of {scenario.names[j]} (one noisy draw)", fontsize=10)
    legend_outside(ax.figure, where="below", ncol=2)
    return ax


def plot_frame_chain(scenario: Scenario, k: int = 0, *, fig=None):
    """The chain of frames of eq. (4) for sensor ``k``: J2000 → orbit (LVLH) → body → sensor,
    each frame's axes drawn in J2000 (red x, green y, blue z)."""
    ch = frame_chain(scenario, k)
    fig = fig if fig is not None else plt.figure(figsize=(7.5, 3.0))
    y, p, r = np.degrees(ch.yaw_pitch_roll_rad)
    panels = [("J2000", np.eye(3), "reference (ECI)"),
              ("orbit (LVLH)", ch.orbit, "from r, v:\nz nadir, y −h"),
              ("body", ch.body, f"r(Y, P, R), eq. (4):\nY {y:.1f}°, P {p:.1f}°,\n"
               f"R {r:.1f}°".replace("-", "−")),
              ("sensor", ch.sensor, "mounting M\n(assumed),\nz = boresight")]
    rhat = ch.position_km / np.linalg.norm(ch.position_km)
    gs = fig.add_gridspec(1, 7, width_ratios=(1, 0.22, 1, 0.22, 1, 0.22, 1), wspace=0.0)
    steps = (r"$R_\mathrm{orbit}$", r"$r(Y,P,R)$", r"$M$")
    for i, (name, R, sub) in enumerate(panels):
        ax = fig.add_subplot(gs[0, 2 * i], projection="3d")
        for e in np.eye(3):
            ax.plot(*np.stack([np.zeros(3), e]).T, color="0.8", lw=1)
        from mpl_toolkits.mplot3d import proj3d

        ax.set_xlim(-1, 1)
        ax.set_ylim(-1, 1)
        ax.set_zlim(-1, 1)
        # a view per panel in which the frame's three axes point apart on screen (in one view
        # for all, the body's and the sensor's z ran along their x: label and arrow hidden)
        def spread(elev, azim, ax=ax, R=R):
            ax.view_init(elev=elev, azim=azim)
            o = np.array(proj3d.proj_transform(0, 0, 0, ax.get_proj())[:2])
            d = [np.array(proj3d.proj_transform(*row, ax.get_proj())[:2]) - o for row in R]
            ang = [np.degrees(np.arctan2(*v[::-1])) for v in d]
            gaps = [abs((ang[i] - ang[j] + 180) % 360 - 180) for i in range(3) for j in range(i)]
            short = min(np.hypot(*v) for v in d) / max(np.hypot(*v) for v in d)
            return min(gaps) * min(1.0, 2 * short)

        views = [(e, az) for e in (30, 20, 40, 10) for az in range(-60, 300, 15)]
        ax.view_init(*max(views, key=lambda v: spread(*v)))
        placed: list[np.ndarray] = []
        for row, col, lab in zip(R, ("tab:red", "tab:green", "tab:blue"), "xyz"):
            ax.quiver(0, 0, 0, *row, color=col, lw=2, arrow_length_ratio=0.15)
            # the letter beyond the tip, aligned away from the origin as projected; a tip
            # projected within 16 px of an earlier letter gets its letter at mid-arrow
            where = 1.1 * row
            px, py, _ = proj3d.proj_transform(*where, ax.get_proj())
            d = ax.transData.transform((px, py))
            if any(np.hypot(*(d - q)) < 16 for q in placed):
                where = 0.5 * row
                px, py, _ = proj3d.proj_transform(*where, ax.get_proj())
                d = ax.transData.transform((px, py))
            placed.append(d)
            ax.text(*where, lab, color=col, fontsize=9, ha="left" if px >= 0 else "right",
                    va="bottom" if py >= 0 else "top")
        if i == 1:
            ax.quiver(0, 0, 0, *rhat, color="k", lw=1, ls="--", arrow_length_ratio=0.1)
            ax.text(*(1.1 * rhat), "r", fontsize=9)
        ax.set_xlim(-1, 1)
        ax.set_ylim(-1, 1)
        ax.set_zlim(-1, 1)
        ax.set_xticks([])
        ax.set_yticks([])
        ax.set_zticks([])
        ax.set_title(f"{name}\n{sub}", fontsize=9)
        if i < 3:
            axa = fig.add_subplot(gs[0, 2 * i + 1])
            axa.axis("off")
            axa.set_zorder(5)  # its label is drawn over the neighbouring 3-D panels' panes
            axa.annotate("", xy=(0.95, 0.5), xytext=(0.05, 0.5),
                         arrowprops={"arrowstyle": "->", "lw": 2})
            axa.set_title(steps[i], fontsize=9, y=0.36)  # under the arrow, clear of the letters
    fig.suptitle(f"Frames of sensor {k + 1}: "
                 r"$R_\mathrm{sensor} = M\,r(Y, P, R)\,R_\mathrm{orbit}$ (grey: J2000 axes)",
                 fontsize=10, y=1.02)
    return fig


def plot_threshold_tradeoff(study: ThresholdStudy, threshold: float, *, fig=None):
    """The widget's figure: missed and false associations versus L with the error-budget (χ²)
    gate as the recommendation (left), and the distances of accepted pairs (right).

    Kept lean (few ticks, one legend per panel) so a redraw stays well under 0.5 s.
    """
    from matplotlib.ticker import MaxNLocator

    fig = fig if fig is not None else plt.figure(figsize=(7.5, 3.6), dpi=72)
    ax, ax2 = fig.subplots(1, 2)
    th, r = study.curves()
    g = study.gate_px
    ax.axvspan(8, 12, color="0.9", zorder=0, label="paper: 8–12 px")
    ax.plot(th, 100 * r["missed"], ":", label="missed")
    ax.plot(th, 100 * r["false"], "--", label="false")
    ax.plot(th, 100 * r["total"], "-", lw=2, label="total error")
    ax.axvline(g, color="tab:green", lw=4, alpha=0.6, label=f"recommended: χ² gate {g:.1f} px")
    ax.axvline(threshold, color="k", lw=1)
    ax.set_xlabel("threshold L (px)")
    ax.set_ylabel("per true pair (%)")
    ax.set_ylim(0, 100)
    edges, hc, hf = study.histograms()
    ax2.stairs(hc, edges, fill=True, alpha=0.6, label="correct pairs")
    ax2.stairs(hf, edges, fill=True, alpha=0.6, color="tab:red", label="false pairs")
    ax2.axvline(g, color="tab:green", lw=4, alpha=0.6)
    ax2.axvline(threshold, color="k", lw=1)
    ax2.set_xlabel("distance to the line (px)")
    ax2.set_ylabel("accepted pairs")
    ax.set_title("errors versus threshold", fontsize=9)
    ax2.set_title("distances of accepted pairs", fontsize=9)
    for a in (ax, ax2):
        a.xaxis.set_major_locator(MaxNLocator(6))
        a.yaxis.set_major_locator(MaxNLocator(4))
    legend_outside(fig, where="below", ncol=3)
    fig.suptitle(_tradeoff_title(study, threshold), fontsize=9)
    fig.subplots_adjust(left=0.09, right=0.98, bottom=0.36, top=0.80, wspace=0.3)
    return fig


def _tradeoff_title(study: ThresholdStudy, threshold: float) -> str:
    now = study.rates(float(threshold))
    e = study.errors
    return (f"L = {threshold:g} px (black): missed {100 * float(now['missed']):.1f} %, "
            f"false {100 * float(now['false']):.1f} %, total "
            f"{100 * float(now['total']):.1f} %\nattitude ±{e.attitude_arcmin:g}′, "
            f"{e.n_false} false targets/map, {study.n_draws} draws (reduced from 300)")


class TradeoffView:
    """The widget's drawer: one :func:`plot_threshold_tradeoff` figure per error setting,
    built once (call it once per setting beforehand to pre-build them all); a threshold
    change only moves the two black lines and rewrites the title (so a redraw is just the
    rendering).

    Call it with the panel's values: ``TradeoffView(study_fn)(threshold=…, **setting)``, where
    ``study_fn(**setting)`` returns a :class:`~.trials.ThresholdStudy` (cached by the caller,
    e.g. :func:`~.trials.threshold_study`).
    """

    def __init__(self, study_fn) -> None:
        if not callable(study_fn):
            raise TypeError(f"study_fn must be callable, got {type(study_fn).__name__}")
        self._study_fn = study_fn
        self._figs: dict[int, tuple] = {}

    def __call__(self, threshold: float, **setting):
        study = self._study_fn(**setting)
        key = id(study)
        if key not in self._figs:
            fig = plot_threshold_tradeoff(study, threshold)
            plt.close(fig)  # kept by the view, not by pyplot (no stray display)
            marks = [ln for ax in fig.axes for ln in ax.lines if ln.get_color() == "k"]
            self._figs[key] = (fig, marks, study)
        fig, marks, study = self._figs[key]
        for ln in marks:
            ln.set_xdata([threshold, threshold])
        fig.suptitle(_tradeoff_title(study, threshold), fontsize=9)
        return fig


# --------------------------------------------------------------------------- figures
def render_maps(scenario: Scenario, obs: Observation, rng: np.random.Generator, *,
                target_mag: float = 11.0) -> list[np.ndarray]:
    """Star-map images (e⁻) for the four sensors: catalogue + synthetic stars to Mv 13,
    targets and false targets at their centroids."""
    from eotrack.imaging.starfield import (
        StarFieldConfig,
        catalogue_stars_in_view,
        render_star_image,
    )

    cfg = StarFieldConfig(limit_mag=scenario.sensor.limit_mag)
    jyear = 2019.25
    images = []
    for k, cam in enumerate(scenario.cameras):
        stars = catalogue_stars_in_view(cam, rng, config=cfg, jyear=jyear)
        lab = obs.labels[k]
        mags = np.where(lab >= 0, target_mag, rng.uniform(11.5, 12.5, len(lab)))
        xy = np.concatenate([stars.xy, obs.points[k]])
        mag = np.concatenate([stars.mag, mags])
        images.append(render_star_image((cam.size[1], cam.size[0]), xy, mag, rng, config=cfg))
    return images


def plot_fig3(scenario: Scenario, obs: Observation, images: list[np.ndarray], *, fig=None):
    """Fig. 3: the four star maps, GEO objects labelled, false targets boxed."""
    fig = fig if fig is not None else plt.figure(figsize=(8.0, 8.0))
    axes = fig.subplots(2, 2)
    for k, ax in enumerate(axes.ravel()):
        img = images[k]
        lo, hi = np.percentile(img, [5, 99.7])
        # the stretched image as 8-bit grey levels (the grey colour map has 256 levels: the
        # same picture, and an eighth of the data kept in the figure and its pickle)
        grey = np.round(255 * np.clip((img - lo) / (hi - lo), 0, 1) ** 0.5).astype(np.uint8)
        ax.imshow(grey, cmap="gray", vmin=0, vmax=255, origin="upper")
        pts_k = obs.points[k]
        for xy, lab in zip(pts_k, obs.labels[k]):
            if lab >= 0:
                ax.add_patch(plt.Circle(xy, 9, fill=False, ec="tab:orange", lw=1.2))
                # label on the side away from the nearest other point (and inside the image)
                dv = pts_k - xy
                dist = np.hypot(*dv.T)
                dist[dist == 0] = np.inf
                away = -dv[int(np.argmin(dist))] if np.isfinite(dist.min()) else np.ones(2)
                sx = 1 if (away[0] >= 0 and xy[0] < 0.8 * img.shape[1]) or \
                    xy[0] < 0.2 * img.shape[1] else -1
                sy = 1 if away[1] < 0 else -1  # image v grows downwards, points go up
                ax.annotate(scenario.names[lab], xy, xytext=(8 * sx, 8 * sy),
                            textcoords="offset points", color="tab:orange", fontsize=9,
                            ha="left" if sx > 0 else "right",
                            va="bottom" if sy > 0 else "top")
            else:
                ax.add_patch(plt.Rectangle(xy - 9, 18, 18, fill=False, ec="tab:red", lw=1.2))
        ax.set_title(f"Star map {k + 1}")
        ax.set_xticks([])
        ax.set_yticks([])
        ax.grid(False)
    fig.suptitle("Fig. 3 — star maps with GEO objects (circled) and false targets (boxed)")
    fig.tight_layout()
    from matplotlib.lines import Line2D

    key = [Line2D([], [], ls="none", marker="o", ms=9, mfc="none", mec="tab:orange", mew=1.2,
                  label="GEO object (named)"),
           Line2D([], [], ls="none", marker="s", ms=9, mfc="none", mec="tab:red", mew=1.2,
                  label="false target")]
    fig.legend(handles=key, loc="upper center", bbox_to_anchor=(0.5, 0.0), ncol=2,
               frameon=False)
    return fig


def plot_fig4(scenario: Scenario, obs: Observation, matches, *, fig=None):
    """Fig. 4(a)–(f): the six map pairs side by side, lines between associated points
    (green: correct, red: false association)."""
    fig = fig if fig is not None else plt.figure(figsize=(8.0, 6.4))
    axes = fig.subplots(3, 2)
    w, h = scenario.cameras[0].size
    for ax, (a, b), lab in zip(axes.ravel(), PAIRS, PAIR_LABELS):
        first = ax is axes.ravel()[0]
        for k, off in ((a, 0.0), (b, w + 20.0)):
            p, lb = obs.points[k], obs.labels[k]
            ax.add_patch(plt.Rectangle((off - 0.5, -0.5), w, h, fill=False, ec="0.5"))
            ax.plot(p[lb >= 0, 0] + off, p[lb >= 0, 1], "o", ms=4, color="k",
                    label="object image" if first and off == 0 else None)
            ax.plot(p[lb < 0, 0] + off, p[lb < 0, 1], "s", ms=5, mfc="none", color="tab:red",
                    label="false target" if first and off == 0 else None)
        pairs = matches[(a, b)][0]
        la, lb2 = obs.labels[a], obs.labels[b]
        for i, j in pairs:
            ok = la[i] == lb2[j] and la[i] >= 0
            ax.plot([obs.points[a][i, 0], obs.points[b][j, 0] + w + 20],
                    [obs.points[a][i, 1], obs.points[b][j, 1]],
                    color="tab:green" if ok else "tab:red", lw=1, ls="-" if ok else "--")
        ax.set_xlim(-10, 2 * w + 30)
        ax.set_ylim(h + 10, -10)
        ax.set_aspect("equal")
        ax.set_xticks([])
        ax.set_yticks([])
        ax.grid(False)
        title = f"Fig. {lab[:4]} — map {a + 1} | map {b + 1}"
        if not np.any(scenario.visible[a] & scenario.visible[b]):  # note in the title,
            title += ("\nno shared object: no association" if not len(pairs) else  # off the dots
                      f"\nno shared object: all {len(pairs)} line(s) false")
        ax.set_title(title, fontsize=9)
    from matplotlib.lines import Line2D

    handles = [Line2D([], [], color="tab:green", lw=1, label="correct association"),
               Line2D([], [], color="tab:red", lw=1, ls="--", label="false association"),
               Line2D([], [], marker="o", ls="", ms=4, color="k", label="object image"),
               Line2D([], [], marker="s", ls="", ms=5, mfc="none", color="tab:red",
                      label="false target")]
    fig.tight_layout(rect=(0, 0.06, 1, 1))
    legend_outside(fig, where="below", ncol=4, handles=handles,
                   labels=[hd.get_label() for hd in handles])
    return fig


def plot_fig5(thresholds, accuracy, false_rate, miss_rate, error_rate, *, paper=None, ax=None):
    """Fig. 5: association outcome rates versus threshold."""
    ax = get_ax(ax, figsize=(6.4, 4.0))
    ax.plot(thresholds, 100 * accuracy, "-", label="correct (of true pairs)")
    ax.plot(thresholds, 100 * error_rate, "-", lw=2, label="total error (missed + false)")
    ax.plot(thresholds, 100 * false_rate, "--", label="false (of associated pairs)")
    ax.plot(thresholds, 100 * miss_rate, ":", label="missed (of true pairs)")
    if paper is not None:
        lo, hi = paper["best_threshold_px"]
        ax.axvspan(lo, hi, color="0.85", zorder=0, label="paper: best L 8–12 px")
        paper_marker(ax, [np.mean([lo, hi])], [100 * paper["accuracy_at_best"]],
                     label="paper: ≈90 % correct")
    ax.set_xlabel("threshold L (px)")
    ax.set_ylabel("rate (%)")
    ax.set_title("Fig. 5 — association outcome versus threshold")
    legend_outside(ax)
    return ax


def plot_fig6(running: dict, analytic: dict, paper: dict | None = None, *, ax=None,
              title: str = "Fig. 6 — Monte Carlo bound on false association",
              legend: bool = True):
    """Fig. 6: running mean of the bound versus number of simulations, analytic lines
    (dashed), the paper's values (one labelled diamond per L). ``legend=False`` leaves the
    legend to the caller (several panels sharing one: ``legend_outside(fig)``)."""
    ax = get_ax(ax, figsize=(6.4, 4.0))
    for i, (L, curve) in enumerate(running.items()):
        col = f"C{i}"
        # running means solid, analytic bounds thin dashed (one grey key names them all)
        ax.plot(np.arange(1, len(curve) + 1), 100 * curve, color=col, ls="-",
                label=f"L = {L:g} px")
        ax.axhline(100 * analytic[L], color=col, ls="--", lw=0.8)
    # one grey key for the dashed lines of every L (the lint reads it as naming them)
    ax.plot([], [], color="0.3", ls="--", lw=0.8, label="thin dashed: analytic")
    if paper is not None:
        n = paper["n_simulations"]
        vals = 100 * np.asarray(paper["max_false_rate"])
        paper_marker(ax, [n] * len(vals), vals, label="paper (one per L)")
        ax.set_ylim(0, 105)
        order = np.argsort(vals)
        ytext = np.asarray(vals, float)[order].copy()
        for i in range(1, len(ytext)):  # spread the labels 7.5 % of the axis apart
            ytext[i] = max(ytext[i], ytext[i - 1] + 7.5)
        for i, yt in zip(order, ytext):
            Lp = paper["threshold_px"][i]
            ax.text(0.72 * n, yt, f"paper, L = {Lp:g}: {vals[i]:.0f} % ", ha="right",
                    va="center", fontsize=9, color=f"C{i}")
            ax.plot([0.72 * n, 0.985 * n], [yt, vals[i]], color=f"C{i}", lw=0.8)
    ax.set_xlabel("number of simulations")
    ax.set_ylabel("max. false-association rate (%)")
    ax.set_title(title)
    if legend:
        legend_outside(ax)
    return ax


def plot_fig8(scenario: Scenario, estimates: dict[str, dict], *, ax=None,
              paper: dict | None = None):
    """Fig. 8: pair estimates, combined estimate and truth of GEO1 and GEO5 (J2000, km).

    With one pair estimate the combined estimate is that estimate (one marker, said in the
    label). ``paper`` (the ``epipolar.table5`` paper values) adds the paper's mean and truth
    (diamonds) beside ours.
    """
    if ax is None:
        fig = plt.figure(figsize=(6.4, 5.0))
        ax = fig.add_subplot(projection="3d")
    ref = np.asarray(next(iter(estimates.values()))["truth"], float)  # the first truth
    for i, (name, e) in enumerate(estimates.items()):
        col = f"C{i}"
        n_pairs = len(e["pairs"])
        if n_pairs > 1:
            P = np.stack(list(e["pairs"].values())) - ref
            ax.scatter(*P.T, color=col, marker="^", s=40, alpha=0.7,
                       label=f"{name} pair estimates ({n_pairs})")
        ax.scatter(*(e["combined"] - ref), color=col, marker="x", s=70,
                   label=f"{name} combined" + (" (= its one pair estimate)" if n_pairs == 1
                                               else ""))
        if paper is not None:
            rows = dict(zip(paper["pairs"], paper[f"{name.lower()}_km"]))
            ax.scatter(*(np.asarray(rows["mean"]) - ref), color=col, marker="D", s=45,
                       label=f"{name} paper mean (Table 5)")
            ax.scatter(*(np.asarray(rows["truth"]) - ref), color=col, marker="D", s=45,
                       facecolors="none", label=f"{name} paper truth (Table 5)")
        ax.scatter(*(e["truth"] - ref), color=col, marker="o", s=50, facecolors="none",
                   label=f"{name} truth")
        ax.plot(*(np.stack([e["truth"], e["combined"]]) - ref).T, color=col, lw=1, ls=":")
    from matplotlib.ticker import MaxNLocator

    for axis in (ax.xaxis, ax.yaxis, ax.zaxis):
        axis.set_major_locator(MaxNLocator(4))
    first = next(iter(estimates))
    ax.set_xlabel(f"ΔX from {first} truth (km)")
    ax.set_ylabel("ΔY (km)")
    ax.set_zlabel("ΔZ (km)")
    ax.set_title("Fig. 8 — GEO1 and GEO5 in J2000 (dotted: error)")
    legend_outside(ax.figure, where="below", ncol=2)
    return ax




def plot_gate_study(df: pd.DataFrame, *, ax=None, reading: str | None = None,
                    legend: bool = True):
    """Best threshold and error-budget gate versus attitude error.

    ``reading`` ("bound" or "rms") says how the attitude figure is read; by default it comes
    from ``df.attrs["reading"]`` (set by :func:`~.trials.gate_study`). ``legend=False`` leaves
    the legend to the caller (one shared ``legend_outside(fig, where="below")`` for panels).
    """
    reading = reading if reading is not None else df.attrs.get("reading", "bound")
    if reading not in ("bound", "rms"):
        raise ValueError(f"reading must be 'bound' or 'rms', got {reading!r}")
    ax = get_ax(ax, figsize=(5.5, 3.6))
    gate_col = next(c for c in df.columns if c.startswith("gate"))
    ax.plot(df["attitude (′)"], df["best L (px)"], "o-", label="best L (min. total error)")
    ax.plot(df["attitude (′)"], df[gate_col], "s--", label=gate_col)
    ax.axhspan(8, 12, color="0.85", zorder=0, label="paper: 8–12 px")
    what = "uniform bound" if reading == "bound" else "rms"
    ax.set_xlabel(f"attitude error per angle, {what} (arcmin)")
    ax.set_ylabel("threshold (px)")
    ax.set_title(f"Best L and gate, attitude as {reading}", fontsize=10)
    if legend:
        legend_outside(ax, where="below", ncol=2)
    return ax


def plot_distance_check(true_d: np.ndarray, sigma_px: float, *, ax=None):
    """Distances of true pairs (Monte Carlo) against the half-normal of the predicted σ."""
    ax = get_ax(ax, figsize=(5.5, 3.6))
    d = np.asarray(true_d, float)
    ax.hist(d, bins=np.linspace(0, max(4 * sigma_px, d.max()), 40), density=True, alpha=0.6,
            label=f"true pairs, Monte Carlo ({len(d)})")
    x = np.linspace(0, 4 * sigma_px, 200)
    ax.plot(x, 2 * np.exp(-0.5 * (x / sigma_px) ** 2) / (np.sqrt(2 * np.pi) * sigma_px),
            label=f"half-normal, predicted σ = {sigma_px:.2f} px")
    ax.set_xlabel("distance to the epipolar line (px)")
    ax.set_ylabel("density (1/px)")
    ax.set_title("True-pair distances against the predicted half-normal", fontsize=10)
    ax.legend(fontsize=9, loc="upper right")
    return ax

