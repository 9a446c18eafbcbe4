"""Input validation shared by the public functions.

Every public function of the library checks its arguments with these helpers so that bad input
raises a ``ValueError`` or ``TypeError`` naming the argument and what is allowed, instead of a
silent NaN or an error deep inside numpy.
"""

from __future__ import annotations

from collections.abc import Sequence
from numbers import Integral, Real
from typing import Any

import numpy as np

__all__ = [
    "as_finite_array",
    "as_points",
    "check_choice",
    "check_generator",
    "check_int",
    "check_positive",
    "check_probability",
    "check_same_length",
]


def as_finite_array(
    value: Any,
    name: str,
    *,
    ndim: int | Sequence[int] | None = None,
    shape: tuple[int | None, ...] | None = None,
    min_size: int = 0,
    allow_nan: bool = False,
    dtype: Any = float,
) -> np.ndarray:
    """Convert ``value`` to a float array and check it.

    Parameters
    ----------
    value
        Anything ``numpy.asarray`` accepts.
    name
        Argument name used in error messages.
    ndim
        Allowed number(s) of dimensions.
    shape
        Required shape; ``None`` entries match any length.
    min_size
        Minimum number of elements along the first axis.
    allow_nan
        Whether NaN entries are allowed (infinite values never are).
    dtype
        Target dtype.

    Returns
    -------
    numpy.ndarray
        The converted array.
    """
    if isinstance(value, (str, bytes)):
        raise TypeError(f"{name} must be numeric array-like, got {type(value).__name__}")
    try:
        arr = np.asarray(value, dtype=dtype)
    except (TypeError, ValueError) as exc:
        raise TypeError(f"{name} must be numeric array-like: {exc}") from None
    if ndim is not None:
        allowed = (ndim,) if isinstance(ndim, Integral) else tuple(ndim)
        if arr.ndim not in allowed:
            raise ValueError(
                f"{name} must have {' or '.join(map(str, allowed))} dimension(s), "
                f"got shape {arr.shape}"
            )
    if shape is not None:
        if arr.ndim != len(shape) or any(
            s is not None and s != a for s, a in zip(shape, arr.shape, strict=False)
        ):
            want = "(" + ", ".join("n" if s is None else str(s) for s in shape) + ")"
            raise ValueError(f"{name} must have shape {want}, got {arr.shape}")
    if arr.ndim and arr.shape[0] < min_size:
        raise ValueError(f"{name} needs at least {min_size} entries, got {arr.shape[0]}")
    if np.issubdtype(arr.dtype, np.floating) or np.issubdtype(arr.dtype, np.complexfloating):
        bad = np.isinf(arr) if allow_nan else ~np.isfinite(arr)
        if np.any(bad):
            what = "infinite" if allow_nan else "NaN or infinite"
            raise ValueError(f"{name} contains {what} values")
    return arr


def as_points(value: Any, name: str, dim: int = 2) -> np.ndarray:
    """Return ``value`` as a finite ``(n, dim)`` float array (``n`` may be 0)."""
    arr = as_finite_array(value, name)
    if arr.size == 0:
        return np.zeros((0, dim))
    if arr.ndim == 1 and arr.shape[0] == dim:
        raise ValueError(f"{name} must have shape (n, {dim}); got a single point {arr.shape}: "
                         f"wrap it as [[...]]")
    if arr.ndim != 2 or arr.shape[1] != dim:
        raise ValueError(f"{name} must have shape (n, {dim}), got {arr.shape}")
    return arr


def check_probability(
    value: Any, name: str, *, open_low: bool = False, open_high: bool = False
) -> float:
    """Check that ``value`` is a real number in [0, 1] (optionally open at either end)."""
    if isinstance(value, bool) or not isinstance(value, Real):
        raise TypeError(f"{name} must be a real number, got {type(value).__name__}")
    v = float(value)
    lo_ok = v > 0 if open_low else v >= 0
    hi_ok = v < 1 if open_high else v <= 1
    if not (np.isfinite(v) and lo_ok and hi_ok):
        lo = "(0" if open_low else "[0"
        hi = "1)" if open_high else "1]"
        raise ValueError(f"{name} must lie in {lo}, {hi}, got {value!r}")
    return v


def check_positive(value: Any, name: str, *, allow_zero: bool = False) -> float:
    """Check that ``value`` is a finite real number > 0 (or >= 0)."""
    if isinstance(value, bool) or not isinstance(value, Real):
        raise TypeError(f"{name} must be a real number, got {type(value).__name__}")
    v = float(value)
    if not np.isfinite(v) or v < 0 or (v == 0 and not allow_zero):
        rel = ">= 0" if allow_zero else "> 0"
        raise ValueError(f"{name} must be finite and {rel}, got {value!r}")
    return v


def check_int(value: Any, name: str, *, min_value: int | None = None,
              max_value: int | None = None) -> int:
    """Check that ``value`` is an integer within the given bounds."""
    if isinstance(value, bool) or not isinstance(value, Integral):
        raise TypeError(f"{name} must be an integer, got {type(value).__name__}")
    v = int(value)
    if min_value is not None and v < min_value:
        raise ValueError(f"{name} must be >= {min_value}, got {v}")
    if max_value is not None and v > max_value:
        raise ValueError(f"{name} must be <= {max_value}, got {v}")
    return v


def check_choice(value: Any, name: str, choices: Sequence[str]) -> str:
    """Check that ``value`` is one of ``choices``."""
    if not isinstance(value, str):
        raise TypeError(f"{name} must be a string, one of {list(choices)}, got "
                        f"{type(value).__name__}")
    if value not in choices:
        raise ValueError(f"{name} must be one of {list(choices)}, got {value!r}")
    return value


def check_generator(rng: Any, name: str = "rng") -> np.random.Generator:
    """Check that ``rng`` is a ``numpy.random.Generator`` (no global state, no bare seeds)."""
    if not isinstance(rng, np.random.Generator):
        raise TypeError(
            f"{name} must be a numpy.random.Generator (e.g. numpy.random.default_rng(seed)), "
            f"got {type(rng).__name__}"
        )
    return rng


def check_same_length(name_a: str, a: np.ndarray, name_b: str, b: np.ndarray) -> None:
    """Raise if ``a`` and ``b`` differ in length along the first axis."""
    if len(a) != len(b):
        raise ValueError(f"{name_a} and {name_b} must have the same length, got {len(a)} and "
                         f"{len(b)}")
