"""Tidy interactive panels: readable labels, readouts at the step's precision, no stray reprs.

Every Explore section of the collection builds its panel with :func:`panel`::

    panel = panel(draw, sigma=float_slider("σ (″)", 0.5, 10, 0.5, 3.0),
                  refit=toggle("weighted refit", True))

``draw(**values)`` returns a matplotlib figure; the panel shows it as an image and redraws on
every change (sliders update on release). Assign the result so the cell shows no
``Out[]`` repr. The panel's container carries the CSS class ``eotrack-panel`` so the browser
test can find every panel and time its redraw.
"""

from __future__ import annotations

import decimal
import gc
import io
import math
import numbers
import time
from collections.abc import Callable, Collection, Sequence
from typing import Any

__all__ = ["dropdown", "float_slider", "int_slider", "panel", "readout_format", "toggle"]

PANEL_CLASS = "eotrack-panel"
_STYLE = {"description_width": "initial"}
_LAYOUT = {"width": "340px"}


def _widgets():
    try:
        import ipywidgets
    except ImportError as exc:  # pragma: no cover - ipywidgets is in environment.txt
        raise ImportError("eotrack.notebook.controls needs ipywidgets "
                          "(pip install ipywidgets)") from exc
    return ipywidgets


def readout_format(step: float) -> str:
    """The readout format that shows ``step`` exactly: 0.5 → ``'.1f'``, 0.005 → ``'.3f'``.

    Raises
    ------
    ValueError
        If ``step`` is not a positive finite number.
    """
    if isinstance(step, bool) or not isinstance(step, numbers.Real) or not math.isfinite(step) \
            or not step > 0:
        raise ValueError(f"step must be a positive finite number, got {step!r}")
    exp = decimal.Decimal(repr(float(step))).normalize().as_tuple().exponent
    return f".{max(0, -int(exp))}f"


def _check_range(description: str, lo: float, hi: float, step: float, value: float) -> None:
    if not isinstance(description, str) or not description.strip():
        raise ValueError("description must be a non-empty string (with the unit, e.g. 'σ (″)'), "
                         f"got {description!r}")
    for name, v in (("min", lo), ("max", hi), ("step", step), ("value", value)):
        if isinstance(v, bool) or not isinstance(v, numbers.Real):
            raise TypeError(f"{description}: {name} must be a real number, got {v!r}")
        if not math.isfinite(v):
            raise ValueError(f"{description}: {name} must be finite, got {v!r}")
    if not lo < hi:
        raise ValueError(f"{description}: need min < max, got {lo!r}, {hi!r}")
    if not step > 0:
        raise ValueError(f"{description}: step must be > 0, got {step!r}")
    if not lo <= value <= hi:
        raise ValueError(f"{description}: value {value!r} outside [{lo!r}, {hi!r}]")


def _check_description(description: Any) -> None:
    if not isinstance(description, str) or not description.strip():
        raise ValueError(f"description must be a non-empty string, got {description!r}")


def float_slider(description: str, min: float, max: float, step: float, value: float,
                 **kw: Any):
    """A ``FloatSlider`` that updates on release, shows its whole label and the step's digits."""
    _check_range(description, min, max, step, value)
    w = _widgets()
    return w.FloatSlider(value=value, min=min, max=max, step=step, description=description,
                         readout_format=readout_format(step), continuous_update=False,
                         style=_STYLE, layout=_LAYOUT, **kw)


def int_slider(description: str, min: int, max: int, step: int = 1, value: int | None = None,
               **kw: Any):
    """An ``IntSlider`` that updates on release and shows its whole label."""
    _check_description(description)
    value = min if value is None else value
    for name, v in (("min", min), ("max", max), ("step", step), ("value", value)):
        if isinstance(v, bool) or not isinstance(v, int):
            raise TypeError(f"{description}: {name} must be an int, got {v!r}")
    _check_range(description, min, max, step, value)
    w = _widgets()
    return w.IntSlider(value=value, min=min, max=max, step=step, description=description,
                       continuous_update=False, style=_STYLE, layout=_LAYOUT, **kw)


def toggle(description: str, value: bool = False, **kw: Any):
    """A two-way choice as a checkbox-like toggle button (never a 0/1 slider)."""
    _check_description(description)
    if not isinstance(value, bool):
        raise TypeError(f"{description}: value must be a bool, got {value!r}")
    w = _widgets()
    return w.ToggleButton(value=value, description=description, icon="check",
                          layout={"width": "auto"}, **kw)


def dropdown(description: str, options: Sequence[Any] | dict[str, Any], value: Any = None,
             **kw: Any):
    """A dropdown for a choice among a few named options (a list, or ``{label: value}``)."""
    _check_description(description)
    if isinstance(options, str) or not isinstance(options, dict | Sequence):
        raise TypeError(f"{description}: options must be a list or a dict, got {options!r}")
    if len(options) == 0:
        raise ValueError(f"{description}: options must not be empty")
    w = _widgets()
    opts = options if isinstance(options, dict) else list(options)
    allowed = list(opts.values()) if isinstance(opts, dict) else opts
    if value is None:
        value = allowed[0]
    elif value not in allowed:
        raise ValueError(f"{description}: value {value!r} is not one of {allowed!r}")
    return w.Dropdown(options=opts, value=value, description=description, style=_STYLE,
                      layout=_LAYOUT, **kw)


def panel(draw: Callable[..., Any], *, columns: int = 2, tight: bool = True,
          enabled_when: dict[str, tuple[str, Collection[Any]]] | None = None, **controls: Any):
    """Show ``controls`` above ``draw(**values)``'s figure; redraw on every change; return the box.

    Parameters
    ----------
    draw : callable
        Called with the controls' current values as keyword arguments; returns the matplotlib
        ``Figure`` it made (an ``Axes`` is accepted too; ``None`` means the last new figure).
        Every figure it opens is closed once rendered, so redraws do not leak figures. Keep
        it under 0.3 s (the browser adds about 0.1 s): cache what a control does not change.
        An error on the first draw raises in the cell; an error on a change is shown in the
        panel, under the last good figure.
    columns : int
        Controls per row.
    tight : bool
        Crop the image to the drawn content (as Jupyter's inline backend does, which lays the
        figure out twice). ``False`` renders the figure once at its own size: faster, for
        figures whose layout keeps every label inside the canvas.
    enabled_when : dict, optional
        ``{control: (other, values)}``: ``control`` is greyed out (disabled) unless the
        control ``other`` holds one of ``values`` — for a setting that only matters in some
        states (e.g. a tolerance used by one reading), so a move never silently does nothing.
    **controls
        ipywidgets value widgets, keyed by ``draw``'s parameter names.

    Returns
    -------
    ipywidgets.VBox
        The panel (class ``eotrack-panel``): the rows of controls, an ``Image`` widget holding
        the PNG, and an ``Output`` that shows an error if a redraw fails. The last redraw time
        in seconds is its ``last_draw_s`` attribute.

    Notes
    -----
    The figure goes to the browser as the PNG bytes of an ``Image`` widget: one binary
    message per change, lighter for the browser than clearing and re-rendering an output area
    (the browser test's floor panel shows the browser's share). The image is part of the
    saved widget state, so a stored notebook (and the book) shows the panel's figure before
    anything runs.

    Building a panel runs :func:`gc.collect` and then :func:`gc.freeze`: the objects alive at
    that point (data, caches: often hundreds of thousands) are exempt from later cyclic
    collections, which otherwise scan them all and add a quarter of a second to whichever
    redraw they fall in. Reference counting still frees them as usual; only reference cycles
    among them are no longer collected (:func:`gc.unfreeze` undoes it).
    """
    if not callable(draw):
        raise TypeError(f"draw must be callable, got {type(draw).__name__}")
    if not controls:
        raise ValueError("panel needs at least one control")
    if isinstance(columns, bool) or not isinstance(columns, int) or columns < 1:
        raise ValueError(f"columns must be a positive int, got {columns!r}")
    if not isinstance(tight, bool):
        raise TypeError(f"tight must be a bool, got {type(tight).__name__}")
    w = _widgets()
    import matplotlib.pyplot as plt
    from IPython.display import display
    from matplotlib.figure import Figure

    for name, c in controls.items():
        if not hasattr(c, "value") or not hasattr(c, "observe"):
            raise TypeError(f"control {name!r} is not a value widget: {type(c).__name__}")
    items = list(controls.values())
    rules = {} if enabled_when is None else enabled_when
    if not isinstance(rules, dict):
        raise TypeError(f"enabled_when must be a dict, got {type(rules).__name__}")
    for name, rule in rules.items():
        if name not in controls:
            raise ValueError(f"enabled_when: {name!r} is not one of the controls "
                             f"{sorted(controls)}")
        if not (isinstance(rule, tuple) and len(rule) == 2 and rule[0] in controls
                and rule[0] != name and isinstance(rule[1], Collection)
                and not isinstance(rule[1], str)):
            raise ValueError(f"enabled_when[{name!r}] must be (other control, values), "
                             f"other one of {sorted(set(controls) - {name})}, got {rule!r}")

    def enable(_change: Any = None) -> None:
        for name, (other, values) in rules.items():
            controls[name].disabled = controls[other].value not in values

    def figure(before: set[int]) -> Any:
        """Call draw; return the figure to show (new figures other than it are closed)."""
        try:
            result = draw(**{k: c.value for k, c in controls.items()})
        except BaseException:
            for n in set(plt.get_fignums()) - before:
                plt.close(n)
            raise
        new = [plt.figure(n) for n in sorted(set(plt.get_fignums()) - before)]
        if result is None:
            if not new:
                raise TypeError("draw returned None and drew no new figure; return the "
                                "matplotlib Figure it made")
            result = new[-1]
        elif not isinstance(result, Figure) and isinstance(getattr(result, "figure", None),
                                                               Figure):
            result = result.figure  # an Axes
        if not isinstance(result, Figure):
            for f in new:
                plt.close(f)
            raise TypeError(f"draw must return a matplotlib Figure (or Axes, or None), got "
                            f"{type(result).__name__}")
        for f in new:
            if f is not result:
                plt.close(f)
        return result

    def png() -> bytes:
        """Draw and render the figure to PNG bytes; close it."""
        fig = figure(set(plt.get_fignums()))
        try:
            buf = io.BytesIO()
            fig.savefig(buf, format="png", dpi=fig.dpi,
                        **({"bbox_inches": "tight"} if tight else {}))
            return buf.getvalue()
        finally:
            plt.close(fig)

    # the first draw raises in the cell (so nbval and a reader see the error at once)
    t0 = time.perf_counter()
    image = w.Image(value=png(), format="png")
    # what exists now (the notebook's data and caches) lives as long as the kernel: collect the
    # garbage, then exempt the survivors from the cyclic collector, so a full collection that
    # happens to fall in a redraw scans only the objects made since (not every cached array)
    gc.collect()
    gc.freeze()
    errors = w.Output()
    rows = [w.HBox(items[i:i + columns]) for i in range(0, len(items), columns)]
    box = w.VBox([*rows, image, errors])
    box.add_class(PANEL_CLASS)
    box.last_draw_s = time.perf_counter() - t0
    failed = [False]

    def redraw(_change: Any = None) -> None:
        t0 = time.perf_counter()
        try:
            data = png()
        except Exception:
            # shown under the last good figure (in a kernel, Output prints the traceback and
            # swallows the error; elsewhere it propagates)
            errors.clear_output()
            failed[0] = True
            with errors:
                raise
            return
        image.value = data
        if failed[0]:
            errors.clear_output()
            failed[0] = False
        box.last_draw_s = time.perf_counter() - t0

    enable()
    for c in {id(controls[other]): controls[other] for other, _ in rules.values()}.values():
        c.observe(enable, names="value")  # before the redraw: the state is right when it shows
    for c in items:
        c.observe(redraw, names="value")
    display(box)
    return box
