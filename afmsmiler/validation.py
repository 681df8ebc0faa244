"""Checks of input at the public boundary of every model.

Every public function of afmsmiler validates its arguments before doing any work and raises a
``ValueError`` whose message names the parameter, the value it got and the valid range, e.g.::

    k_s must be > 0 N/m, got -1.0
    x must be in [0, 0.000125] m, got 0.0002 (at index 3)

The helpers return the value converted to ``float`` (or a float ``ndarray``) so that callers can
write ``length = check_positive("length", length, "m")``.
"""
from __future__ import annotations

import math
import os
from numbers import Real

import numpy as np

__all__ = [
    "check_finite",
    "check_real",
    "check_positive",
    "check_nonnegative",
    "check_range",
    "check_array",
    "check_choice",
    "check_integer",
    "check_instance",
    "check_flag",
    "check_size",
    "check_shape",
    "check_writable_path",
    "MAX_SIZE",
]

#: Default bound of a size parameter (number of points, pixels, mesh segments): about a second
#: of numpy work per pass on a laptop, and 80 MB as a float64 array. A function whose cost grows
#: faster than linearly sets a lower bound of its own.
MAX_SIZE = 10_000_000


def _fmt(value) -> str:
    return f"{value:g}" if isinstance(value, (float, np.floating)) else repr(value)


def _short(value, limit: int = 60) -> str:
    text = repr(value)
    return text if len(text) <= limit else text[:limit - 3] + "..."


def _unit(unit: str) -> str:
    return f" {unit}" if unit else ""


def _in(unit: str) -> str:
    return f" (in {unit})" if unit else ""


def _as_float(name: str, value, valid: str = "a finite number") -> float:
    # np.number would let np.complex128 through, and float() would drop its imaginary part
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, (Real, np.integer,
                                                                    np.floating)):
        if isinstance(value, np.ndarray) and value.ndim == 0:
            return _as_float(name, value.item(), valid)
        raise ValueError(f"{name} must be a real number, got {_short(value)}")
    try:
        return float(value)
    except OverflowError:  # an int beyond float range (10**400): float() raises OverflowError
        raise ValueError(f"{name} must be {valid}, got an integer of {_digits(value)} digits "
                         f"(beyond the float range)") from None


def _digits(value) -> int:
    """The number of decimal digits of an int (without writing out a huge one)."""
    value = abs(int(value))
    return len(str(value)) if value < 10 ** 4000 else int(value.bit_length() * math.log10(2)) + 1


def check_real(name: str, value) -> float:
    """Return ``value`` as float; raise ``ValueError`` unless it is a real number in float range.

    NaN and infinities pass (the caller decides what they mean: a gap in a plotted curve, an
    open end of an interval); a bool, a complex, a string or an integer beyond the float range
    (``10**400``, on which ``float()`` raises ``OverflowError``) is refused, naming ``name``.

    Parameters
    ----------
    name : str
        The parameter's name, as the caller spells it.
    value : float
        The value to check.

    Returns
    -------
    float

    Examples
    --------
    >>> check_real("low", 10**400)
    Traceback (most recent call last):
    ...
    ValueError: low must be a real number in float range, got an integer of 401 digits (beyond the float range)
    """
    return _as_float(name, value, "a real number in float range")


def check_finite(name: str, value, unit: str = "") -> float:
    """Return ``value`` as float; raise ``ValueError`` unless it is a finite real number.

    Parameters
    ----------
    name : str
        The parameter's name, as the caller spells it.
    value : float
        The value to check.
    unit : str
        Its SI unit, for the message.
    """
    x = _as_float(name, value)
    if not math.isfinite(x):
        raise ValueError(f"{name} must be a finite number{_in(unit)}, got {x!r}")
    return x


def check_positive(name: str, value, unit: str = "") -> float:
    """Return ``value`` as float; raise unless it is finite and > 0.

    Parameters
    ----------
    name : str
        The parameter's name, as the caller spells it.
    value : float
        The value to check.
    unit : str
        Its SI unit, for the message.
    """
    x = _as_float(name, value, f"> 0{_unit(unit)} and finite")
    if not (math.isfinite(x) and x > 0):
        raise ValueError(f"{name} must be > 0{_unit(unit)} and finite, got {_fmt(x)}")
    return x


def check_nonnegative(name: str, value, unit: str = "") -> float:
    """Return ``value`` as float; raise unless it is finite and >= 0.

    Parameters
    ----------
    name : str
        The parameter's name, as the caller spells it.
    value : float
        The value to check.
    unit : str
        Its SI unit, for the message.
    """
    x = _as_float(name, value, f">= 0{_unit(unit)} and finite")
    if not (math.isfinite(x) and x >= 0):
        raise ValueError(f"{name} must be >= 0{_unit(unit)} and finite, got {_fmt(x)}")
    return x


def _interval(low, high, low_inclusive, high_inclusive) -> str:
    left = "[" if low_inclusive else "("
    right = "]" if high_inclusive else ")"
    return f"{left}{_fmt(float(low))}, {_fmt(float(high))}{right}"


def _inside(x, low, high, low_inclusive, high_inclusive):
    above = (x >= low) if low_inclusive else (x > low)
    below = (x <= high) if high_inclusive else (x < high)
    return above & below


def check_range(name: str, value, low, high, unit: str = "", *,
                low_inclusive: bool = True, high_inclusive: bool = True) -> float:
    """Return ``value`` as float; raise unless it is finite and inside the interval.

    Parameters
    ----------
    name, unit : str
        The parameter's name and SI unit, for the message.
    value : float
        The value to check.
    low, high : float
        Bounds; ``-inf``/``inf`` for a half-open range.
    low_inclusive, high_inclusive : bool
        Whether the bounds belong to the range.
    """
    x = _as_float(name, value, f"in {_interval(low, high, low_inclusive, high_inclusive)}"
                               f"{_unit(unit)}")
    if not (math.isfinite(x) and _inside(x, low, high, low_inclusive, high_inclusive)):
        raise ValueError(
            f"{name} must be in "
            f"{_interval(low, high, low_inclusive, high_inclusive)}{_unit(unit)}, "
            f"got {_fmt(x)}")
    return x


def check_array(name: str, values, unit: str = "", *, low=-math.inf, high=math.inf,
                low_inclusive: bool = True, high_inclusive: bool = True, ndim: int | None = None,
                min_size: int = 0, increasing: bool = False, nondecreasing: bool = False,
                size: int | None = None, max_size: int | None = MAX_SIZE) -> np.ndarray:
    """Return ``values`` as a float ndarray; raise unless every element is finite and in range.

    Parameters
    ----------
    name, unit : str
        Parameter name and its SI unit, for the error message.
    values : array_like
        The values to check.
    low, high : float
        Bounds (inclusive by default).
    low_inclusive, high_inclusive : bool
        Whether the bounds belong to the range.
    ndim : int, optional
        Required number of dimensions.
    min_size : int
        Minimum number of elements.
    increasing, nondecreasing : bool
        Require strictly increasing (or non-decreasing) values along a 1-D array.
    size : int, optional
        Required number of elements (used for "arrays of the same length" checks).
    max_size : int or None
        Largest number of elements accepted (default :data:`MAX_SIZE`), checked before the
        array is copied; None for no bound.

    Returns
    -------
    numpy.ndarray
        A float copy of ``values``.
    """
    n = getattr(values, "size", None)
    if max_size is not None and isinstance(n, (int, np.integer)) and n > max_size:
        raise ValueError(f"{name} must have at most {max_size} elements, got {n}")
    try:
        raw = np.asarray(values)
    except (TypeError, ValueError):  # ragged nested sequences
        raise ValueError(f"{name} must be an array of real numbers, got {_short(values)}") from None
    if raw.dtype.kind not in "iuf":  # complex (the imaginary part would be lost), bool, str, object
        raise ValueError(f"{name} must be an array of real numbers, got an array of "
                         f"{raw.dtype} ({_short(values)})")
    if max_size is not None and raw.size > max_size:
        raise ValueError(f"{name} must have at most {max_size} elements, got {raw.size}")
    arr = raw.astype(float)
    if ndim is not None and arr.ndim != ndim:
        raise ValueError(f"{name} must be a {ndim}-D array, got shape {arr.shape}")
    if arr.size < min_size:
        raise ValueError(f"{name} must have at least {min_size} elements, got {arr.size}")
    if size is not None and arr.size != size:
        raise ValueError(f"{name} must have {size} elements (same as its companion array), "
                         f"got {arr.size}")
    flat = arr.ravel()
    bad = ~np.isfinite(flat)
    if bad.any():
        i = int(np.argmax(bad))
        raise ValueError(f"{name} must be finite{_in(unit)}, got {float(flat[i])!r} (at index {i})")
    ok = _inside(flat, low, high, low_inclusive, high_inclusive)
    if not ok.all():
        i = int(np.argmin(ok))
        raise ValueError(
            f"{name} must be in "
            f"{_interval(low, high, low_inclusive, high_inclusive)}{_unit(unit)}, "
            f"got {_fmt(float(flat[i]))} (at index {i})")
    if (increasing or nondecreasing) and arr.ndim == 1 and arr.size > 1:
        d = np.diff(arr)
        wrong = (d <= 0) if increasing else (d < 0)
        if wrong.any():
            i = int(np.argmax(wrong))
            kind = "strictly increasing" if increasing else "non-decreasing"
            raise ValueError(f"{name} must be {kind}, but element {i + 1} "
                             f"({_fmt(float(arr[i + 1]))}) "
                             f"follows {_fmt(float(arr[i]))}")
    return arr


def check_choice(name: str, value, choices):
    """Return ``value``; raise unless it is one of ``choices``.

    Parameters
    ----------
    name : str
        The parameter's name.
    value : object
        The value to check.
    choices : collection
        The valid values.
    """
    try:
        ok = bool(value in choices)
    except (TypeError, ValueError):  # unhashable (a list) for a set; an array's ambiguous truth
        ok = False
    if not ok:
        raise ValueError(f"{name} must be one of {sorted(map(str, choices))}, "
                         f"got {_short(value)}")
    return value


def check_integer(name: str, value, low: int = -math.inf, high: int = math.inf) -> int:
    """Return ``value`` as int; raise unless it is an integer in ``[low, high]``.

    Parameters
    ----------
    name : str
        The parameter's name.
    value : int
        The value to check.
    low, high : int
        Inclusive bounds.
    """
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, (int, np.integer)):
        raise ValueError(f"{name} must be an integer in [{low}, {high}], got {_short(value)}")
    if not (low <= value <= high):
        raise ValueError(f"{name} must be an integer in [{low}, {high}], got {_short(value)}")
    return int(value)


def check_size(name: str, value, limit: int = MAX_SIZE, low: int = 1) -> int:
    """Return a size (a number of points, pixels, segments, iterations) as int, bounded.

    Every size parameter has a limit that the machine honours in seconds; the message says so,
    so that a student who asks for ``n_length=10**9`` learns the bound instead of waiting.

    Parameters
    ----------
    name : str
        The parameter's name.
    value : int
        The size to check.
    limit : int
        The largest size accepted (default :data:`MAX_SIZE`).
    low : int
        The smallest size accepted.

    Returns
    -------
    int
        ``value``.

    Raises
    ------
    ValueError
        Unless ``value`` is an integer in ``[low, limit]``.

    Examples
    --------
    >>> check_size("n_length", 10**9, 100_000)  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    ValueError: n_length must be an integer in [1, 100000] (...), got 1000000000
    """
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, (int, np.integer)) \
            or not low <= value <= limit:
        raise ValueError(f"{name} must be an integer in [{low}, {limit}] (a size this machine runs "
                         f"in seconds), got {_short(value)}")
    return int(value)


def check_shape(name: str, value, ndim: int = 2, limit: int = MAX_SIZE,
                low: int = 1) -> tuple[int, ...]:
    """Return an array shape (``(rows, columns)``) as a tuple of ints, its size bounded.

    Parameters
    ----------
    name : str
        The parameter's name.
    value : tuple of int
        The shape: ``ndim`` positive integers (an int is accepted for ``ndim=1``).
    ndim : int
        Required number of dimensions.
    limit : int
        The largest number of elements (the product) accepted.
    low : int
        The fewest elements along each dimension.

    Returns
    -------
    tuple of int

    Raises
    ------
    ValueError
        Unless ``value`` is ``ndim`` positive integers whose product is at most ``limit``.

    Examples
    --------
    >>> check_shape("shape", (64, 64))
    (64, 64)
    """
    if ndim == 1 and isinstance(value, (int, np.integer)) and not isinstance(value, bool):
        value = (value,)
    if not isinstance(value, (tuple, list)) or len(value) != ndim:
        raise ValueError(f"{name} must be a tuple of {ndim} positive integers, got "
                         f"{_short(value)}")
    shape = tuple(check_size(f"{name}[{i}]", v, limit, low) for i, v in enumerate(value))
    total = math.prod(shape)
    if total > limit:
        raise ValueError(f"{name} must have at most {limit} elements in all (a size this machine "
                         f"runs in seconds), got {shape} = {total}")
    return shape


def check_instance(name: str, value, kind, what: str | None = None):
    """Return ``value``; raise ``TypeError`` naming the parameter unless it is a ``kind``.

    Object parameters (``lever``, ``tip``, ``loop``, ``sample``, ...) are checked at the boundary
    like numbers, so a wrong object is named at once instead of failing deep inside with an
    ``AttributeError``.

    Parameters
    ----------
    name : str
        The parameter's name.
    value : object
        The value to check.
    kind : type or tuple of type
        The accepted class(es).
    what : str, optional
        How to name the accepted kind in the message (default: the class names).

    Returns
    -------
    object
        ``value``.

    Examples
    --------
    >>> check_instance("lever", 3.0, str)
    Traceback (most recent call last):
    ...
    TypeError: lever must be a str, got float 3.0
    """
    if not isinstance(value, kind):
        if what is None:
            kinds = kind if isinstance(kind, tuple) else (kind,)
            what = " or ".join(k.__name__ for k in kinds)
        raise TypeError(f"{name} must be a {what}, got {type(value).__name__} {_short(value)}")
    return value


def check_flag(name: str, value) -> bool:
    """Return ``value`` as bool; raise ``TypeError`` naming ``name`` unless it is True or False.

    A switch (``camera=``, ``half=``, ``grid=``) given NaN, a string or an array is refused: its
    truth would be Python's (any non-empty string is true) or numpy's ambiguous one.

    Parameters
    ----------
    name : str
        The parameter's name.
    value : bool
        The value to check (a ``numpy.bool_`` too).

    Returns
    -------
    bool

    Examples
    --------
    >>> check_flag("camera", "no")
    Traceback (most recent call last):
    ...
    TypeError: camera must be True or False, got 'no'
    """
    if not isinstance(value, (bool, np.bool_)):
        raise TypeError(f"{name} must be True or False, got {_short(value)}")
    return bool(value)


def check_writable_path(name: str, path, what: str = "a file") -> str:
    """``path`` as a str naming a file that can be written (its folder exists), before any work.

    Parameters
    ----------
    name : str
        The parameter's name, for the message.
    path : str or os.PathLike
        The file to write.
    what : str
        What the file is, for the message ("a PNG file").

    Returns
    -------
    str

    Raises
    ------
    ValueError
        If ``path`` is not a path, names a folder, or lies in a folder that does not exist.
    """
    try:
        path = os.fspath(path)
    except TypeError:
        raise ValueError(f"{name} must be a str or os.PathLike naming {what}, got "
                         f"{path!r} ({type(path).__name__})") from None
    if isinstance(path, bytes):
        path = os.fsdecode(path)
    if not path or os.path.isdir(path):
        raise ValueError(f"{name} must name a file, got the folder {path!r}")
    parent = os.path.dirname(os.path.abspath(path))
    if not os.path.isdir(parent):
        raise ValueError(f"{name} must be in an existing folder, got {path!r} ({parent!r} does "
                         f"not exist)")
    return path

