"""Neighbourhood counting and spatial clustering of a binary image (Li et al. 2008, §1).

A small target is a compact blob of a few suspicious pixels; noise pixels are independent and
isolated. The neighbourhood count

    D(i, j) = Σ_{m=−p..p} Σ_{n=−p..p} G(i + m, j + n)

(eq. 3, ``window = 2p + 1``, pixels outside the image count 0) separates the two: a region is
flagged when ``D ≥ S`` (the text's "not fewer than S"; eq. 2 prints ``D > S``, selectable with
``strict=True``).

:func:`neighbourhood_count` uses OpenCV's unnormalised box filter with an integer output (or,
``method="sat"``, a numpy summed-area table); both give exact integer counts at a cost
independent of the window. ``scipy.ndimage.uniform_filter`` computes the same box mean (see
``benchmarks/bench_track_init_ht.py``).
"""

from __future__ import annotations

import cv2
import numpy as np

from eotrack.validation import check_choice, check_int

__all__ = ["candidate_frames", "cluster_candidates", "cluster_mask", "neighbourhood_count"]


def _binary(binary: np.ndarray, name: str = "binary", ndim: tuple[int, ...] = (2,)) -> np.ndarray:
    if not isinstance(binary, np.ndarray):
        binary = np.asarray(binary)
    if binary.ndim not in ndim:
        want = " or ".join(f"{d}-D" for d in ndim)
        raise ValueError(f"{name} must be a {want} image, got shape {binary.shape}")
    if binary.dtype == bool:
        return binary.view(np.uint8)
    if binary.dtype.kind not in "iuf":
        raise TypeError(f"{name} must be a 0/1 or boolean array, got dtype {binary.dtype}")
    if binary.size and not np.all((binary == 0) | (binary == 1)):
        raise ValueError(f"{name} must contain only 0 and 1 (a binary image)")
    return binary.astype(np.uint8, copy=False)


def _window(window: int) -> int:
    w = check_int(window, "window", min_value=1)
    if w % 2 == 0:
        raise ValueError(f"window must be a positive odd side length 2p+1 (1, 3, 5, ...), got {w}")
    return w


def neighbourhood_count(binary: np.ndarray, window: int, *, method: str = "opencv") -> np.ndarray:
    """Eq. (3): number of set pixels in the ``window × window`` box centred on every pixel.

    Parameters
    ----------
    binary
        Binary image ``G`` (0/1 or bool), ``(H, W)``, or a stack ``(T, H, W)`` counted frame by
        frame.
    window
        Box side ``2p + 1`` (positive odd integer). Pixels outside the image count as 0.
    method
        ``"opencv"``: ``cv2.boxFilter`` with an integer (``CV_32S``) output, unnormalised, zero
        border; ``"sat"``: a numpy summed-area table (two cumulative sums, four look-ups per
        pixel). Both are exact integer counts.

    Returns
    -------
    numpy.ndarray
        ``int32`` counts ``D``, same shape as ``binary``.
    """
    g = _binary(binary, ndim=(2, 3))
    w = _window(window)
    check_choice(method, "method", ("opencv", "sat"))
    if method == "opencv":
        frames = g.reshape((-1, *g.shape[-2:]))
        out = np.empty(frames.shape, dtype=np.int32)
        for k, f in enumerate(frames):
            out[k] = cv2.boxFilter(np.ascontiguousarray(f), cv2.CV_32S, (w, w), normalize=False,
                                   borderType=cv2.BORDER_CONSTANT)
        return out.reshape(g.shape)
    p = w // 2
    pad = [(0, 0)] * (g.ndim - 2) + [(p + 1, p), (p + 1, p)]
    sat = np.pad(g, pad).astype(np.int32)
    sat = sat.cumsum(axis=-2, dtype=np.int32).cumsum(axis=-1, dtype=np.int32)
    h, wd = g.shape[-2:]
    return (sat[..., w:w + h, w:w + wd] - sat[..., :h, w:w + wd]
            - sat[..., w:w + h, :wd] + sat[..., :h, :wd])


def cluster_mask(binary: np.ndarray, window: int, s: int, *, strict: bool = False,
                 suspicious_only: bool = True) -> np.ndarray:
    """Eq. (2): indicator ``I`` of the pixels whose neighbourhood count reaches ``S``.

    Parameters
    ----------
    binary
        Binary image ``G`` ``(H, W)`` or stack ``(T, H, W)``.
    window
        Box side ``2p + 1`` (positive odd).
    s
        Count threshold ``S`` (``1 ≤ S ≤ window²``).
    strict
        Use ``D > S`` as eq. (2) prints instead of the text's ``D ≥ S``.
    suspicious_only
        Keep only pixels that are themselves set in ``G`` (the paper counts around each
        suspicious pixel); otherwise every pixel whose box reaches ``S`` is flagged.

    Returns
    -------
    numpy.ndarray
        ``uint8`` indicator, same shape as ``binary``.
    """
    g = _binary(binary, ndim=(2, 3))
    w = _window(window)
    ss = check_int(s, "s", min_value=1, max_value=w * w)
    d = neighbourhood_count(g, w)
    out = (d > ss) if strict else (d >= ss)
    if suspicious_only:
        out &= g.astype(bool)
    return out.astype(np.uint8)


def cluster_candidates(binary: np.ndarray, window: int, s: int, *, strict: bool = False,
                       merge_px: int = 1) -> tuple[np.ndarray, np.ndarray]:
    """Candidate points of one frame: centroids of the clustered regions of :func:`cluster_mask`.

    Flagged pixels whose ``(2·merge_px + 1)``-square dilations touch form one candidate, so a
    target blob with a missed pixel in it still gives one point.

    Parameters
    ----------
    binary
        Binary image ``G`` ``(H, W)``.
    window, s, strict
        As in :func:`cluster_mask`.
    merge_px
        Dilation radius used to group flagged pixels (0: plain 8-connectivity).

    Returns
    -------
    xy : numpy.ndarray
        ``(n, 2)`` centroids of the flagged pixels of each group (x = column, y = row).
    mask : numpy.ndarray
        The clustered indicator image ``I``.
    """
    g = _binary(binary)
    r = check_int(merge_px, "merge_px", min_value=0)
    mask = cluster_mask(g, window, s, strict=strict)
    if not mask.any():
        return np.zeros((0, 2)), mask
    grouped = cv2.dilate(mask, np.ones((2 * r + 1, 2 * r + 1), np.uint8)) if r else mask
    n, labels = cv2.connectedComponents(grouped, connectivity=8)
    lab = labels[mask.astype(bool)]
    rows, cols = np.nonzero(mask)
    cnt = np.bincount(lab, minlength=n)
    keep = cnt > 0
    keep[0] = False
    cx = np.bincount(lab, weights=cols, minlength=n)[keep] / cnt[keep]
    cy = np.bincount(lab, weights=rows, minlength=n)[keep] / cnt[keep]
    return np.column_stack([cx, cy]).astype(float), mask


def candidate_frames(images: np.ndarray, times_s: np.ndarray, p_f: float, window: int, s: int,
                     *, tile: int | None = 16, strict: bool = False,
                     keep_masks: bool = False) -> tuple[list[tuple[float, np.ndarray]],
                                                        np.ndarray | None, np.ndarray | None]:
    """CFAR segmentation + spatial clustering of every frame of a sequence.

    Parameters
    ----------
    images
        ``(T, H, W)`` frames.
    times_s
        ``(T,)`` frame times.
    p_f
        CFAR per-pixel false-alarm probability in (0, 1).
    window, s, strict
        Spatial clustering (see :func:`cluster_mask`).
    tile
        CFAR background tile (see :func:`eotrack.imaging.cfar.tile_background_noise`).
    keep_masks
        Also return the binary images ``G`` and clustered images ``I`` as ``(T, H, W)`` stacks.

    Returns
    -------
    frames : list of (float, numpy.ndarray)
        ``(time_s, xy)`` candidate points per frame, ready for an initiator.
    binary, clustered : numpy.ndarray or None
        The stacks if ``keep_masks``.
    """
    from eotrack.imaging.cfar import cfar_segment

    imgs = np.asarray(images)
    if imgs.ndim != 3:
        raise ValueError(f"images must be a (T, H, W) stack, got shape {imgs.shape}")
    t = np.asarray(times_s, dtype=float)
    if t.shape != (imgs.shape[0],):
        raise ValueError(f"times_s must have shape ({imgs.shape[0]},), got {t.shape}")
    frames = []
    gs, cs = [], []
    for k in range(imgs.shape[0]):
        g = cfar_segment(imgs[k], p_f, tile=tile)
        xy, mask = cluster_candidates(g, window, s, strict=strict)
        frames.append((float(t[k]), xy))
        if keep_masks:
            gs.append(g)
            cs.append(mask)
    if keep_masks:
        return frames, np.stack(gs), np.stack(cs)
    return frames, None, None
