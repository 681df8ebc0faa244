"""The surface the tip apex follows: grey-scale dilation of the sample by the tip, and its inverse.

A rigid tip whose surface lies t(u) >= 0 above its apex at the horizontal offset u (t(0) = 0),
lowered onto a sample of heights s(x) until it touches, stops with its apex at::

    i(x) = max_u [ s(x + u) - t(u) ]                                        (the image)

the grey-scale dilation of s by the reflected tip (Villarrubia, J. Res. Natl. Inst. Stand.
Technol. 102, 425 (1997); in mathematical morphology i = s (+) b with the structuring
function b(y) = -t(-y), what ``scipy.ndimage.grey_dilation(s, structure=b)`` computes). All four
tips of module (d) are symmetric, t(-u) = t(u). Its inverse is the reconstruction (Villarrubia's
"surface reconstruction", a grey-scale erosion)::

    r(x) = min_u [ i(x - u) + t(u) ]                                        (the reconstruction)

r = (s (+) b) (-) b is the morphological closing of s: r >= s everywhere (deep narrow holes the
tip cannot enter are bridged over), and r = s wherever the tip really touched, which is what the
certainty map marks.

The tip on the pixel grid (:func:`tip_surface`): t(u, v) from :meth:`Tip.profile` at
rho = sqrt(u^2 + v^2) for the bodies of revolution (paraboloid, sphere, cone) and at
rho = max(|u|, |v|) for the four-sided pyramid, whose base edges lie along x and y (rho is then
the distance from the axis perpendicular to a face). A sphere sits on a cylindrical shank of its
own radius R (the tip's outline in module (d)): beyond rho = R the tip is a vertical wall, as tall
as needed.

Cutting the tip at the sample's height range H = max s - min s is exact: a tip point with
t(u) >= H gives s(x + u) - t(u) <= max s - H = min s <= s(x), never more than the apex's own
term (u = 0), so only the tip below H matters, and the grid of :func:`tip_surface` is clipped
there.

Two paths compute the same image:

- the general path, for any tip: a loop over the tip's pixels with t < H, each a vectorised
  maximum over the whole image; its work is (tip pixels) x (image pixels), bounded by
  :data:`MAX_WORK`;
- the paraboloid's separable path: t(u, v) = (u^2 + v^2) / (2 R) = t_x(u) + t_y(v), so the 2-D
  dilation is a 1-D dilation by the parabola u^2 / (2 R) along every row followed by one along
  every column. Each 1-D dilation is either the lower envelope of parabolas, computed in O(N) per
  line whatever the tip's size by the algorithm of Felzenszwalb and Huttenlocher ("Distance
  transforms of sampled functions", Theory of Computing 8, 415 (2012)), vectorised
  across the lines with NumPy; or, for windows of up to :data:`WINDOW_LIMIT` pixels (the offsets
  d with d^2 dx^2 / (2 R) below the cut), the direct maximum over the window, w whole-image
  passes, which NumPy runs faster than the envelope's Python loop over the pixels of a line.
  Both are exact; which one runs changes only the time.

Image edges: only sample points inside the image are touched (the sample outside the image is
unknown), the same as scipy's ``mode="constant", cval=-inf``. A tip wider than the image where it
has risen by H (its footprint at the cut) is refused with a ValueError naming ``tip``: such an
image would show the tip's shape more than the sample's.
"""
from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from ..contact.tips import MAX_EXTENT, RADIUS, Conical, Parabolic, Pyramidal, Spherical, Tip
from ..samples.sample import MAX_PIXELS, Sample
from ..validation import (check_instance, check_integer, check_nonnegative, check_positive,
                          check_range)

__all__ = ["tip_surface", "dilate", "erode", "certainty_map", "estimate_tip_radius",
           "sphere_apparent_width", "tip_radius_from_width", "MAX_TIP_PIXELS", "MAX_WORK",
           "DEFAULT_HALF_WIDTH", "WINDOW_LIMIT"]

#: The most pixels of a tip grid (:func:`tip_surface`): 2048 x 2048, 32 MB as float64.
MAX_TIP_PIXELS = MAX_PIXELS
#: The most (tip pixels below the cut) x (image pixels) of the general path (a loop over the tip's
#: pixels, each a vectorised pass over the image, about 1.2 ns per pixel here): 2^30, about 1.3 s
#: of NumPy work on this machine (a 512 x 512 image under a 35 x 35-pixel pyramid takes 0.4 s).
MAX_WORK = 1 << 30
#: Without ``max_height``, :func:`tip_surface` cuts the tip at its height this many pixels (along
#: x) from the apex (or at its full height R for a sphere that fits in that distance).
DEFAULT_HALF_WIDTH = 32

#: The paraboloid's separable path takes the direct window (w whole-image passes, about 3 ns per
#: pixel per pixel of window here) for windows up to this many pixels from the apex, and the O(N)
#: envelope beyond (about 0.7 us per pixel in NumPy, whatever the window): the crossover measured
#: by ``benchmarks/bench_dilation.py``.
WINDOW_LIMIT = 200

_BISECTIONS = 200
_MAX_HALF_WIDTH = 2.0 ** 40
_DEPTH = 16
_SCALAR_LINES = 16


def _cut_radius(tip: Tip, max_height: float) -> float:
    """Largest rho in m with profile(rho) <= max_height: closed forms, else bisection."""
    top = tip.max_profile_radius
    if isinstance(tip, Parabolic):
        return min(math.sqrt(2.0 * tip.radius * max_height), top)
    if isinstance(tip, Spherical):
        h = min(max_height, tip.radius)
        return math.sqrt(h * (2.0 * tip.radius - h))
    if isinstance(tip, Conical):
        return min(max_height * math.tan(tip.half_angle), top)
    if isinstance(tip, Pyramidal):
        return min(max_height * math.tan(tip.face_angle), top)
    if tip._profile(np.array(top)) <= max_height:
        return float(top)
    lo, hi = 0.0, float(top)
    for _ in range(_BISECTIONS):
        mid = 0.5 * (lo + hi)
        if mid in (lo, hi):
            break
        if tip._profile(np.array(mid)) <= max_height:
            lo = mid
        else:
            hi = mid
    return lo


def _half_widths(tip: Tip, dx: float, dy: float | None, max_height: float):
    """(n_x, n_y, rho_cut): the tip's grid reaches n pixels from the apex along each axis."""
    rho_cut = _cut_radius(tip, max_height)

    def pixels(d):  # capped, so that a tiny pixel size cannot overflow the conversion
        return int(math.floor(min(rho_cut / d * (1.0 + 1e-12), _MAX_HALF_WIDTH)))

    return pixels(dx), 0 if dy is None else pixels(dy), rho_cut


def _rho(tip: Tip, u: np.ndarray, v: np.ndarray) -> np.ndarray:
    """The distance from the axis at which the profile is read (max-norm for a faceted tip)."""
    if tip.faces == 4:
        return np.maximum(np.abs(u), np.abs(v))
    return np.hypot(u, v)


def _tip_grid(tip: Tip, dx: float, dy: float | None, max_height: float) -> np.ndarray:
    """t on the grid (2-D, or 1-D along x if dy is None), clipped at max_height (unchecked)."""
    nx, ny, rho_cut = _half_widths(tip, dx, dy, max_height)
    pixels = (2 * nx + 1) * (2 * ny + 1)
    if pixels > MAX_TIP_PIXELS:
        raise ValueError(
            f"max_height, pixel_size, pixel_size_y: a tip cut at max_height = {max_height:g} m "
            f"is {2 * rho_cut:g} m wide, {2 * nx + 1} x {2 * ny + 1} pixels of pixel_size = "
            f"{dx:g} m x pixel_size_y = {dy if dy is not None else dx:g} m; at most "
            f"{MAX_TIP_PIXELS} pixels (lower max_height or use larger pixels)")
    u = np.arange(-nx, nx + 1) * dx
    v = np.arange(-ny, ny + 1) * (0.0 if dy is None else dy)
    rho = _rho(tip, u[None, :], v[:, None])
    inside = rho <= tip.max_profile_radius * (1.0 + 1e-12)  # the equator, to round-off
    t = np.where(inside, tip._profile(np.minimum(rho, tip.max_profile_radius)), np.inf)
    t = np.minimum(t, max_height)
    return t[0] if dy is None else t


def tip_surface(tip, pixel_size, pixel_size_y=None, *, max_height=None) -> np.ndarray:
    """The tip's height above its apex on a pixel grid centred on the apex, in m.

    Parameters
    ----------
    tip : Tip
        A tip of module (d) (:mod:`afmsmiler.contact.tips`).
    pixel_size : float
        Grid spacing along x (columns) in m, > 0.
    pixel_size_y : float, optional
        Grid spacing along y (rows) in m; default ``pixel_size``.
    max_height : float, optional
        Height in m at which the tip is cut, >= 0: the grid reaches as far from the apex as the
        tip stays below it, and heights above it are clipped to it (a sphere, on its cylindrical
        shank, is clipped beyond its radius). :func:`dilate` cuts at the sample's height range,
        which is exact. Default: the tip's height :data:`DEFAULT_HALF_WIDTH` (32) pixels from the
        apex along x, or its radius R for a sphere narrower than that.

    Returns
    -------
    numpy.ndarray
        t[row, column] in m, >= 0, of odd shape (2 n_y + 1, 2 n_x + 1), apex (0) at the centre.
        Rows along y, columns along x; the pyramid's base edges lie along x and y.

    Raises
    ------
    TypeError
        If ``tip`` is not a :class:`~afmsmiler.contact.tips.Tip`.
    ValueError
        If a pixel size is not finite and positive, ``max_height`` is negative, or the grid
        would exceed :data:`MAX_TIP_PIXELS` pixels (naming ``max_height``).

    Examples
    --------
    >>> from afmsmiler.contact.tips import Parabolic
    >>> t = tip_surface(Parabolic(radius=10e-9), 1e-9, max_height=2e-9)
    >>> t.shape, float(t[6, 6]), float(t[6, 7])
    ((13, 13), 0.0, 5e-11)
    """
    check_instance("tip", tip, Tip)
    dx = check_positive("pixel_size", pixel_size, "m")
    dy = dx if pixel_size_y is None else check_positive("pixel_size_y", pixel_size_y, "m")
    if max_height is None:
        rho = min(DEFAULT_HALF_WIDTH * dx, tip.max_profile_radius)
        max_height = float(tip._profile(np.array(rho)))
    else:
        max_height = check_nonnegative("max_height", max_height, "m")
    return _tip_grid(tip, dx, dy, max_height)


def _check_fits(image: Sample, tip: Tip, height: float) -> None:
    """A tip whose footprint at the cut is wider than the image is an error naming ``tip``."""
    h = image.heights
    dy = None if h.ndim == 1 else image.pixel_size_y
    nx, ny, _ = _half_widths(tip, image.pixel_size, dy, height)
    sides = (2 * nx + 1,) if h.ndim == 1 else (2 * ny + 1, 2 * nx + 1)
    for k, n, d, name in zip(sides[::-1], h.shape[::-1], (image.pixel_size, dy), ("x", "y")):
        if k > n:
            raise ValueError(
                f"tip: at the sample's height range ({height:g} m) the tip is {k} pixels "
                f"({(k - 1) * d:g} m) wide along {name}, wider than the image ({n} pixels, "
                f"{(n - 1) * d:g} m); use a sharper tip or a larger image")


def _kernel(image: Sample, tip: Tip, height: float) -> np.ndarray:
    """The tip grid for ``image`` cut at ``height``, checked to fit in the image."""
    _check_fits(image, tip, height)
    dy = None if image.heights.ndim == 1 else image.pixel_size_y
    return _tip_grid(tip, image.pixel_size, dy, height)


def _offsets(t: np.ndarray, height: float, image_pixels: int):
    """The (offset, t) pairs of the tip pixels below the cut, after checking the work bound."""
    centre = tuple(k // 2 for k in t.shape)
    active = np.argwhere(t < height) if height > 0 else np.zeros((0, t.ndim), int)
    work = (len(active) + 1) * image_pixels
    if work > MAX_WORK:
        raise ValueError(
            f"tip: {len(active)} tip pixels below the sample's height range ({height:g} m) "
            f"x {image_pixels} image pixels = {work} exceeds the general path's bound "
            f"MAX_WORK = {MAX_WORK}; use larger pixels, a smaller image or a Parabolic tip "
            f"(separable, no bound)")
    for idx in active:
        off = tuple(int(i - c) for i, c in zip(idx, centre))
        if any(off):
            yield off, float(t[tuple(idx)])


def _slices(off: tuple[int, ...], shape: tuple[int, ...]):
    """(destination, source) slices with dst[x] <- src[x + off], both inside the image."""
    dst, src = [], []
    for o, n in zip(off, shape):
        dst.append(slice(max(0, -o), n - max(0, o)))
        src.append(slice(max(0, o), n + min(0, o)))
    return tuple(dst), tuple(src)


def _dilate_general(h: np.ndarray, t: np.ndarray, height: float) -> np.ndarray:
    """max_u [h(x + u) - t(u)] over the tip pixels with t < height (the apex term included)."""
    out = h.copy()
    for off, tu in _offsets(t, height, h.size):
        dst, src = _slices(off, h.shape)
        np.maximum(out[dst], h[src] - tu, out=out[dst])
    return out


def _envelope_lines(g: np.ndarray, a: float) -> np.ndarray:
    """f[l, q] = max_p [g[l, p] - a (q - p)^2] along the last axis (Felzenszwalb-Huttenlocher).

    The lower envelope of the parabolas (q - p)^2 + h(p), h = -g / a (Felzenszwalb and
    Huttenlocher, Theory of Computing 8, 415 (2012)), built for all lines at once:
    a loop over q in Python, each step vectorised over the lines. The lines whose stack must pop
    test the top :data:`_DEPTH` entries at once, so a step rarely takes more than one extra pass.
    The winning parabola at each q is found for all lines in one ``searchsorted`` and the value
    computed from it as g[p] - a (q - p)^2, the same expression as the general path. O(N) per
    line, whatever the tip's size. Up to :data:`_SCALAR_LINES` lines, the algorithm runs line by
    line in plain Python (:func:`_envelope_scalar`), faster there.
    """
    lines, n = g.shape
    if n == 1:
        return g.copy()
    if lines <= _SCALAR_LINES:
        return np.array([_envelope_scalar(line, a) for line in g]).reshape(g.shape)
    return _envelope_vector(g, a)


def _envelope_vector(g: np.ndarray, a: float) -> np.ndarray:
    """:func:`_envelope_lines` vectorised over the lines (a loop over q, n >= 2)."""
    lines, n = g.shape
    rows = np.arange(lines)
    hh = (-g / a + np.arange(n, dtype=float) ** 2).ravel()   # h(p) + p^2, flat
    off, offz = rows * n, rows * (n + 1)   # each line's start in v and hh, and in z
    v = np.zeros(lines * n, dtype=np.intp)  # the envelope's parabolas (their p), a stack a line
    z = np.empty(lines * (n + 1))           # the envelope's breakpoints
    z[offz] = -np.inf
    k = np.zeros(lines, dtype=np.intp)      # top of each line's stack
    steps = np.arange(_DEPTH)
    for q in range(1, n):
        hq = hh[off + q]
        vk = v[off + k]
        s = (hq - hh[off + vk]) / (2.0 * (q - vk))
        pop = s <= z[offz + k]
        if pop.any():
            idx = np.flatnonzero(pop)
            kk, hqi, oi, ozi = k[idx] - 1, hq[idx], off[idx, None], offz[idx, None]
            while True:  # at most n / _DEPTH passes: every pass pops _DEPTH or stops
                # the top _DEPTH entries, clipped at the bottom one, whose z = -inf stops it
                kb = np.maximum(kk[:, None] - steps, 0)
                vb = v[oi + kb]
                sb = (hqi[:, None] - hh[oi + vb]) / (2 * q - 2 * vb)
                stay = sb > z[ozi + kb]
                found = stay.any(axis=1)
                j = np.argmax(stay, axis=1)
                if found.all():
                    k[idx] = kk - j
                    s[idx] = sb[np.arange(idx.size), j]
                    break
                j = j[found]
                done = idx[found]
                k[done] = kk[found] - j
                s[done] = sb[found, j]
                nf = ~found
                idx, kk, hqi, oi, ozi = idx[nf], kk[nf] - _DEPTH, hqi[nf], oi[nf], ozi[nf]
        k += 1
        v[off + k] = q
        z[offz + k] = s
    # the parabola that wins at q is the last one whose breakpoint z[j] < q: count the
    # breakpoints z[1..k] below q, for all lines in one searchsorted (lines shifted apart)
    zz = z.reshape(lines, n + 1)[:, 1:n].copy()
    zz[np.arange(1, n)[None, :] > k[:, None]] = np.inf
    shift = rows[:, None] * (n + 2.0)
    zz = np.clip(zz, -1.0, n) + shift
    qq = np.arange(n, dtype=float)[None, :] + shift
    j = np.searchsorted(zz.ravel(), qq.ravel(), side="left").reshape(lines, n)
    j -= rows[:, None] * (n - 1)
    p = v.reshape(lines, n)[rows[:, None], j]
    return g[rows[:, None], p] - a * (np.arange(n)[None, :] - p) ** 2


def _envelope_scalar(g: np.ndarray, a: float) -> np.ndarray:
    """One line of :func:`_envelope_lines` in plain Python floats, the paper's algorithm as printed.

    For a few lines NumPy's per-call cost makes the vectorised loop slower than this one.
    """
    n = g.shape[0]
    hh = (-g / a + np.arange(n, dtype=float) ** 2).tolist()
    v, z = [0], [-math.inf]
    for q in range(1, n):
        hq = hh[q]
        while True:
            p = v[-1]
            s = (hq - hh[p]) / (2.0 * (q - p))
            if s > z[-1]:
                break
            v.pop()
            z.pop()
        v.append(q)
        z.append(s)
    q = np.arange(n)
    p = np.asarray(v)[np.searchsorted(np.asarray(z[1:]), q, side="left")]
    return g[p] - a * (q - p) ** 2


def _window_axis0(g: np.ndarray, a: float, w: int) -> np.ndarray:
    """f[q] = max_{|d| <= w} [g[q + d] - a d^2] along axis 0: w whole-array passes.

    Along axis 0 of a C-ordered array every pass reads and writes contiguous blocks, about three
    times faster than along the last axis. Inside, the offsets +d and -d share their subtraction:
    max(g[q + d], g[q - d]) - a d^2 (the same floats, as rounding is monotone).
    """
    out = g.copy()
    n = g.shape[0]
    tmp = np.empty_like(g)
    for d in range(1, min(w, n - 1) + 1):
        c = a * d * d
        if 2 * d < n:
            t = tmp[:n - 2 * d]
            np.maximum(g[2 * d:], g[:n - 2 * d], out=t)
            t -= c
            np.maximum(out[d:n - d], t, out=out[d:n - d])
        e = min(d, n - d)  # the edges, where only one of q + d and q - d is in the image
        np.maximum(out[:e], g[d:d + e] - c, out=out[:e])
        np.maximum(out[n - e:], g[n - e - d:n - d] - c, out=out[n - e:])
    return out


def _parabola_axis(g: np.ndarray, axis: int, a: float, height: float,
                   method: str) -> np.ndarray:
    """The exact 1-D paraboloid dilation of ``g`` along ``axis``, by the window or the envelope.

    Only offsets d with a d^2 < height can win (the cut), so a window of w = sqrt(height / a)
    pixels is exact. Up to :data:`WINDOW_LIMIT` pixels its w whole-image passes are faster in
    NumPy than the envelope's Python loop over q; beyond, the envelope's O(N) wins.
    """
    w = int(math.floor(math.sqrt(height / a) * (1.0 + 1e-12))) if height > 0 else 0
    if method == "window" or (method == "auto" and w <= WINDOW_LIMIT):
        moved = np.ascontiguousarray(np.moveaxis(g, axis, 0))
        return np.moveaxis(_window_axis0(moved, a, w), 0, axis)
    moved = np.ascontiguousarray(np.moveaxis(g, axis, -1))
    out = _envelope_lines(moved.reshape(-1, moved.shape[-1]), a).reshape(moved.shape)
    return np.moveaxis(out, -1, axis)


def _dilate_parabolic(h: np.ndarray, radius: float, dx: float, dy: float, height: float,
                      method: str = "auto") -> np.ndarray:
    """The separable paraboloid dilation: rows by u^2 / (2R), then columns by v^2 / (2R).

    The cut at ``height`` (the sample's range) stays exact for the second pass: the first one
    leaves the maximum unchanged and raises the minimum, so its range is at most ``height``.
    """
    out = _parabola_axis(h, h.ndim - 1, dx * dx / (2.0 * radius), height, method)
    if h.ndim == 2:
        out = _parabola_axis(out, 0, dy * dy / (2.0 * radius), height, method)
    return np.ascontiguousarray(out)


def _range(h: np.ndarray) -> float:
    return float(np.max(h) - np.min(h))


def _check_heights(name: str, image) -> Sample:
    """A Sample of heights in m: a tip dilates topography, not a deflection or phase channel."""
    check_instance(name, image, Sample)
    unit = getattr(image, "unit", "m")
    if unit != "m":
        raise ValueError(f"{name} must hold heights in m, got a "
                         f"{getattr(image, 'channel', '')!r} channel in {unit!r}")
    return image


def _checked(name: str, image, tip) -> tuple[Sample, Tip]:
    _check_heights(name, image)
    check_instance("tip", tip, Tip)
    return image, tip


def dilate(sample, tip) -> Sample:
    """The surface the tip apex follows: i(x) = max_u [s(x + u) - t(u)] (grey dilation).

    Exact for any tip of module (d). A :class:`~afmsmiler.contact.tips.Parabolic` tip takes the
    separable O(N)-per-line path (Felzenszwalb and Huttenlocher, Theory of Computing 8, 415
    (2012)); the others a loop over the tip's pixels below the sample's height range, whose work
    (tip pixels x image pixels) is bounded by :data:`MAX_WORK`.

    Parameters
    ----------
    sample : Sample
        The surface s in m: a line (1-D, dilated along x) or an image (2-D; pixel sizes along x
        and y may differ).
    tip : Tip
        The tip (:mod:`afmsmiler.contact.tips`); a pyramid's base edges lie along x and y.

    Returns
    -------
    Sample
        The image i in m, on the same grid and with the same pixel sizes (and the sample's other
        fields); i >= s.

    Raises
    ------
    TypeError
        If ``sample`` is not a Sample or ``tip`` not a Tip.
    ValueError
        Naming ``sample`` if its values are not heights in m (``unit`` other than "m");
        naming ``tip``, if at the sample's height range the tip is wider than the image, or (not
        a paraboloid) the work exceeds :data:`MAX_WORK`.

    Examples
    --------
    >>> import numpy as np
    >>> from afmsmiler.samples import Sample
    >>> from afmsmiler.contact.tips import Parabolic
    >>> spike = Sample(np.r_[np.zeros(5), 1e-9, np.zeros(5)], 1e-9)
    >>> np.round(dilate(spike, Parabolic(radius=2e-9)).heights * 1e9, 3)[3:8]
    array([0.  , 0.75, 1.  , 0.75, 0.  ])
    """
    sample, tip = _checked("sample", sample, tip)
    h = sample.heights
    height = _range(h)
    if isinstance(tip, Parabolic):
        _check_fits(sample, tip, height)
        out = _dilate_parabolic(h, tip.radius, sample.pixel_size, sample.pixel_size_y, height)
    else:
        out = _dilate_general(h, _kernel(sample, tip, height), height)
    return replace(sample, heights=out)


def _erode_array(i: np.ndarray, image: Sample, tip: Tip) -> np.ndarray:
    """min_u [i(x - u) + t(u)] = -max_u [-i(x + u) - t(-u)]: a dilation by the reflected tip."""
    height = _range(i)
    if isinstance(tip, Parabolic):
        _check_fits(image, tip, height)
        return -_dilate_parabolic(-i, tip.radius, image.pixel_size, image.pixel_size_y, height)
    t = _kernel(image, tip, height)
    return -_dilate_general(-i, t[(slice(None, None, -1),) * t.ndim], height)  # t(-u)


def erode(image, tip) -> Sample:
    """The reconstruction r(x) = min_u [i(x - u) + t(u)] of the surface from its image.

    Villarrubia's surface reconstruction (J. Res. NIST 102, 425 (1997)), a grey-scale
    erosion by the tip. Applied to an image of a surface s, ``erode(dilate(s, tip), tip)`` is the
    morphological closing of s: it is >= s everywhere (narrow holes the tip cannot enter stay
    bridged), and equals s where :func:`certainty_map` is True.

    Parameters
    ----------
    image : Sample
        The image i in m (1-D or 2-D), e.g. from :func:`dilate` or a scan.
    tip : Tip
        The tip that made it.

    Returns
    -------
    Sample
        The reconstruction r in m, on the image's grid; r <= i.

    Raises
    ------
    TypeError
        If ``image`` is not a Sample or ``tip`` not a Tip.
    ValueError
        As :func:`dilate` (naming ``tip``).
    """
    image, tip = _checked("image", image, tip)
    return replace(image, heights=_erode_array(image.heights, image, tip))


def certainty_map(image, tip) -> np.ndarray:
    """Where the tip really touched the surface: Villarrubia's certainty map.

    With the apex at x0 the tip touches the reconstruction r (:func:`erode`) at the points
    x0 + u where r(x0 + u) - t(u) = i(x0). Where it touches at a single point, that point of r is
    certain: the true surface is there (Villarrubia, J. Res. NIST 102, 425 (1997)).
    Elsewhere r is only an upper bound of the surface. Equality is tested to a few units of
    round-off of the image's heights. Work as the general path of :func:`dilate`
    (:data:`MAX_WORK`), for every tip.

    Parameters
    ----------
    image : Sample
        The image i in m (1-D or 2-D).
    tip : Tip
        The tip that made it.

    Returns
    -------
    numpy.ndarray of bool
        Shaped like the image: True where the reconstruction is certain.

    Raises
    ------
    TypeError
        If ``image`` is not a Sample or ``tip`` not a Tip.
    ValueError
        As :func:`dilate` (naming ``tip``), and if the work exceeds :data:`MAX_WORK`.
    """
    image, tip = _checked("image", image, tip)
    i = image.heights
    height = _range(i)
    t = _kernel(image, tip, height)
    r = -_dilate_general(-i, t[(slice(None, None, -1),) * t.ndim], height)  # as erode
    tol = 8.0 * np.finfo(float).eps * (float(np.max(np.abs(i))) + height)
    # the apex term (u = 0) first, then every other tip pixel below the cut
    contacts = (r >= i - tol).astype(np.int64)
    where = np.zeros(i.shape + (i.ndim,), dtype=np.int64)  # offset of the (last) contact
    for off, tu in _offsets(t, height, i.size):
        dst, src = _slices(off, i.shape)
        touch = r[src] - tu >= i[dst] - tol
        contacts[dst] += touch
        where[dst][touch] = off
    certain = np.zeros(i.shape, dtype=bool)
    x0 = np.argwhere(contacts == 1)
    if len(x0):
        hit = x0 + where[tuple(x0.T)]
        certain[tuple(hit.T)] = True
    return certain


def estimate_tip_radius(image, *, peaks=1) -> float:
    """Blind estimate of a paraboloid tip's radius R in m from the image's sharpest peaks.

    The image is a maximum of inverted tips, i(x) = max_u [s(x + u) - t(u)], so with a
    paraboloid every second difference of the image along x is >= -dx^2 / R (exactly: the
    inverted parabola through any pixel lies below the image at its neighbours), and along y
    >= -dy^2 / R. Each local maximum therefore bounds R from above,
    R <= dx^2 / (-second difference), with equality at a peak made by a feature sharper than the
    tip, where the image is the inverted tip itself. This is the paraboloid form of blind tip
    estimation (Villarrubia, J. Res. NIST 102, 425 (1997): the estimate is an upper
    bound of the tip, exact where the sample has sharp spikes).

    Parameters
    ----------
    image : Sample
        The image in m (1-D or 2-D), at least 3 pixels along each axis used.
    peaks : int
        How many of the sharpest local maxima to use, 1 to 10000: the result is the median of
        their bounds (1, the default, gives the tightest upper bound; more, robustness against
        noise).

    Returns
    -------
    float
        The estimated radius R in m (inf if the image has no strict local maximum).

    Raises
    ------
    TypeError
        If ``image`` is not a Sample.
    ValueError
        If ``peaks`` is out of range or the image has fewer than 3 pixels along x.
    """
    _check_heights("image", image)
    peaks = check_integer("peaks", peaks, 1, 10_000)
    i = image.heights
    if i.shape[-1] < 3 or (i.ndim == 2 and i.shape[0] < 3):
        raise ValueError(f"image must have at least 3 pixels along each axis, got {i.shape}")
    i2 = i if i.ndim == 2 else i[None, :]
    c = i2[1:-1, 1:-1] if i.ndim == 2 else i2[:, 1:-1]
    left, right = (i2[1:-1, :-2], i2[1:-1, 2:]) if i.ndim == 2 else (i2[:, :-2], i2[:, 2:])
    dxx = left + right - 2.0 * c
    peak = (c > left) & (c > right)
    with np.errstate(divide="ignore"):
        bound = np.where(dxx < 0, image.pixel_size ** 2 / -dxx, np.inf)
        if i.ndim == 2:
            up, down = i2[:-2, 1:-1], i2[2:, 1:-1]
            dyy = up + down - 2.0 * c
            peak &= (c > up) & (c > down)
            bound = np.minimum(bound, np.where(dyy < 0, image.pixel_size_y ** 2 / -dyy, np.inf))
    radii = np.sort(bound[peak])
    if radii.size == 0:
        return math.inf
    return float(np.median(radii[:peaks]))


def sphere_apparent_width(particle_radius, tip) -> float:
    """Apparent width in m of a sphere of radius r lying on a flat substrate, imaged by ``tip``.

    The width of the image at the substrate's level: twice the distance X0 from the sphere's
    axis at which the tip, its apex on the substrate, touches the sphere.

    - Paraboloid of radius R (derived in the module's tests with sympy): the tip's surface
      z = (x - X0)^2 / (2 R) is tangent to the sphere x^2 + (z - r)^2 = r^2 at slope m, with
      c = 1 / sqrt(1 + m^2) the root in (0, 1] of 2 r c^2 + R c - R = 0::

          c = (sqrt(R^2 + 8 r R) - R) / (4 r),   m = sqrt(1 - c^2) / c,   W = 2 m (R + r c)

      (W -> 4 sqrt(R r) (1 + ...) for R >> r and W -> 2 r + 2 sqrt(2 r R) for R << r).
    - Sphere of radius R on a cylindrical shank of radius R: the two spheres touch,
      W = 4 sqrt(R r), if R >= r (the classic result, e.g. Markiewicz and Goh, Langmuir 10, 5
      (1994)); for R < r the shank meets the particle's equator first, W = 2 (r + R).

    Parameters
    ----------
    particle_radius : float
        The sphere's radius r in m, in (0, 100] (the tips'
        :data:`~afmsmiler.contact.tips.MAX_EXTENT`).
    tip : Parabolic or Spherical
        The tip.

    Returns
    -------
    float
        W in m.

    Raises
    ------
    TypeError
        If ``tip`` is neither a Parabolic nor a Spherical tip.
    ValueError
        If ``particle_radius`` is outside (0, 100] m.
    """
    r = check_range("particle_radius", particle_radius, 0.0, MAX_EXTENT, "m", low_inclusive=False)
    check_instance("tip", tip, (Parabolic, Spherical))
    big_r = tip.radius
    if isinstance(tip, Spherical):
        return 4.0 * math.sqrt(big_r * r) if big_r >= r else 2.0 * (r + big_r)
    # c = (sqrt(R^2 + 8 r R) - R) / (4 r) and 1 - c, written free of cancellation
    root = math.sqrt(big_r * big_r + 8.0 * r * big_r)
    c = 2.0 * big_r / (root + big_r)
    one_minus_c = 8.0 * r * big_r / (root + big_r) ** 2
    m = math.sqrt(one_minus_c * (1.0 + c)) / c
    return 2.0 * m * (big_r + r * c)


def tip_radius_from_width(particle_radius, width) -> float:
    """The paraboloid tip radius R in m that images a sphere of radius r with apparent width W.

    Inverts :func:`sphere_apparent_width` for a :class:`~afmsmiler.contact.tips.Parabolic` tip
    (W grows monotonically with R, from 2 r for a sharp tip; for R >> r, R -> W^2 / (16 r)), by
    Brent's method on log R over the tips' radius range.

    Parameters
    ----------
    particle_radius : float
        The sphere's radius r in m, in (0, 100] (its height on the substrate is 2 r).
    width : float
        Its apparent width W in m (the image's width at the substrate's level).

    Returns
    -------
    float
        R in m.

    Raises
    ------
    ValueError
        If ``particle_radius`` is out of range, or ``width`` is not what a paraboloid of radius
        1 pm to 1 cm (:data:`~afmsmiler.contact.tips.RADIUS`) gives: a width of 2 r or less
        means a tip sharper than any (or a particle flattened by the tip).

    Examples
    --------
    >>> from afmsmiler.contact.tips import Parabolic
    >>> w = sphere_apparent_width(10e-9, Parabolic(radius=20e-9))
    >>> round(tip_radius_from_width(10e-9, w) * 1e9, 9)
    20.0
    """
    from scipy.optimize import brentq

    r = check_range("particle_radius", particle_radius, 0.0, MAX_EXTENT, "m", low_inclusive=False)
    w = check_positive("width", width, "m")
    low, high = RADIUS.low, RADIUS.high
    w_low = sphere_apparent_width(r, Parabolic(radius=low))
    w_high = sphere_apparent_width(r, Parabolic(radius=high))
    if not w_low <= w <= w_high:
        raise ValueError(f"width must be in [{w_low:g}, {w_high:g}] m for a sphere of "
                         f"particle_radius {r:g} m and a paraboloid of radius {low:g} to "
                         f"{high:g} m, got {w:g}")

    def radius(log_r):  # exp(log(R)) may round beyond the range's ends
        return min(max(math.exp(log_r), low), high)

    def excess(log_r):
        return sphere_apparent_width(r, Parabolic(radius=radius(log_r))) - w

    return radius(brentq(excess, math.log(low), math.log(high), xtol=1e-14,
                         rtol=4 * np.finfo(float).eps, maxiter=200))
