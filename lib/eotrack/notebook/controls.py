"""Tidy interactive panels: readable labels, readouts at the step's precision, no stray reprs.

Every Explore section of the collection builds its panel with :func:`panel`::

    panel = panel(draw, sigma=float_slider("σ (″)", 0.5, 10, 0.5, 3.0),
                  refit=toggle("weighted refit", True))

``draw(**values)`` returns a matplotlib figure; the panel shows it in an output area and
redraws on every change (sliders update on release). Assign the result so the cell shows no
``Out[]`` repr. The panel's container carries the CSS class ``eotrack-panel`` so the browser
test can find every panel and time its redraw.
"""

from __future__ import annotations

import decimal
import io
import math
import numbers
import time
from collections.abc import Callable, Sequence
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


def panel(draw: Callable[..., Any], *, columns: int = 2, tight: bool = True, **controls: Any):
    """Show ``controls`` above an output area holding ``draw(**values)``'s figure; return the box.

    Parameters
    ----------
    draw : callable
        Called with the controls' current values as keyword arguments; returns the matplotlib
        ``Figure`` it made (an ``Axes`` is accepted too; ``None`` means the last new figure).
        Every figure it opens is closed after display, so redraws do not leak figures. Keep
        it under 0.5 s: cache what a control does not change. An error on the first draw
        raises in the cell; an error on a change is shown in the panel.
    columns : int
        Controls per row.
    tight : bool
        Crop the image to the drawn content (Jupyter's default, which draws the figure twice).
        ``False`` renders the figure once at its own size: about a third faster, for figures
        whose fixed layout keeps every label inside the canvas.
    **controls
        ipywidgets value widgets, keyed by ``draw``'s parameter names.

    Returns
    -------
    ipywidgets.VBox
        The panel (class ``eotrack-panel``); the last redraw time in seconds is its
        ``last_draw_s`` attribute.
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
    from IPython.display import Image, display
    from matplotlib.figure import Figure

    for name, c in controls.items():
        if not hasattr(c, "value") or not hasattr(c, "observe"):
            raise TypeError(f"control {name!r} is not a value widget: {type(c).__name__}")
    out = w.Output()
    items = list(controls.values())
    rows = [w.HBox(items[i:i + columns]) for i in range(0, len(items), columns)]
    box = w.VBox([*rows, out])
    box.add_class(PANEL_CLASS)

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

    def show(fig: Any) -> None:
        try:
            if tight:
                display(fig)
            else:
                buf = io.BytesIO()
                fig.savefig(buf, format="png", dpi=fig.dpi)
                display(Image(data=buf.getvalue(), format="png"))
        finally:
            plt.close(fig)

    def redraw(_change: Any = None) -> None:
        # a change: errors are shown in the panel's output (the Output widget reports them)
        t0 = time.perf_counter()
        with out:
            out.clear_output(wait=True)
            show(figure(set(plt.get_fignums())))
        box.last_draw_s = time.perf_counter() - t0

    # the first draw raises in the cell (so nbval and a reader see the error at once)
    t0 = time.perf_counter()
    first = figure(set(plt.get_fignums()))
    with out:
        show(first)
    box.last_draw_s = time.perf_counter() - t0
    for c in items:
        c.observe(redraw, names="value")
    display(box)
    return box
