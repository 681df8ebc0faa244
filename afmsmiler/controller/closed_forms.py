"""Closed-form step and ramp responses of 2nd- and 3rd-order transfer functions (the 14 cases).

The formulas are derived by residues in :mod:`afmsmiler.controller.derivation` and printed into
``_generated.py``; this module picks the case from the roots of the denominator and packs the
result as a :class:`ClosedForm`: y(t) = q0 + q1 t + Re sum_blocks sum_j c_j t^j e^{p t}.

Picking the case robustly
-------------------------
Close roots make the distinct-root formulas cancel: their residues grow like 1/(p_i - p_j) while
the response stays finite, so a relative separation d loses about eps / d of the peak (eps / d^2
for three close roots), more in a polygon's superposition of many ramps. Roots are therefore
merged into a repeated root (at their mean) when two lie within :data:`MERGE_TOLERANCE`
(relative) of each other, or all three within :data:`TRIPLE_TOLERANCE`; merging at the mean
costs an error second order in d. Measured against python-control over |p| t < 60 (single step
and ramp responses, and polygons of 400 knots): at d = 1e-5 a merged pair is off by 2e-11 of the
peak and a pair kept apart by 1e-10, so 1e-5 balances the two; at 1e-6, the previous threshold,
pairs kept apart in a polygon lost 1.4e-9. Three roots spread by 1e-5 to 1e-3 (relative) fall
between the two remedies (the merge error grows like the spread squared, the cancellation like
its inverse square) and lose up to about 4e-8 of the peak there (1e-8 in polygons), the worst
near :data:`TRIPLE_TOLERANCE`, chosen to balance the two; exact triple roots, pairs at any
distance and clusters tighter than 1e-5 do not.
A complex pair whose imaginary part is that small is treated as a repeated real root; any pair
not merged is complex. Pairs of complex roots never cancel (their residue's imaginary part grows
like 1/omega but multiplies sin(omega t), itself of order omega t).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ._generated import FUNCTIONS

__all__ = ["ClosedForm", "MERGE_TOLERANCE", "TRIPLE_TOLERANCE", "classify_roots", "closed_form",
           "normalise"]

#: Relative distance below which two roots are treated as one repeated (double) root. Computed
#: double roots scatter by about sqrt(eps) ~ 1.5e-8 (relative) around the true one; 1e-5
#: balances the merge error against the cancellation (see the module docstring).
MERGE_TOLERANCE = 1e-5
#: Relative spread below which three roots are one triple root. Computed triple roots scatter by
#: about eps**(1/3) ~ 6e-6, so a much smaller threshold would miss exact triple roots; 3e-4
#: balances the merge error against the cancellation of the distinct-root formula.
TRIPLE_TOLERANCE = 3e-4
# A conjugate pair sigma +- i omega is merged when 2 |omega| <= tol |p|; any pair left is complex,
# so a root counts as complex above a quarter of tol (no gap at tol / 2; real roots computed as
# eigenvalues of a real matrix have no imaginary part at all).
_IMAG_FRACTION = 0.25


@dataclass(frozen=True)
class ClosedForm:
    """y(t) = q0 + q1 t + Re sum over blocks of (sum_j c_j t^j) e^{p t}, for t >= 0.

    Parameters
    ----------
    q0, q1 : float
        Polynomial (forced) part: constant and slope.
    blocks : tuple
        ``(p, coefficients)`` per distinct root p (complex for a complex pair, of which only the
        root with positive imaginary part is kept), with c_j multiplying t^j e^{p t}.
    case : str
        Name of the closed form used (e.g. ``"ramp_o3_real_complex"``).
    feedthrough : float
        Direct feedthrough b_n of the transfer function (its value at s -> infinity).
    """

    q0: float
    q1: float
    blocks: tuple
    case: str
    feedthrough: float = 0.0

    def __call__(self, t):
        """Evaluate y(t) (0 for t < 0, the system starts at rest).

        Parameters
        ----------
        t : array_like
            Time since the input started, in s.

        Returns
        -------
        numpy.ndarray
        """
        t = np.asarray(t, dtype=float)
        tau = np.maximum(t, 0.0)
        y = self.q0 + self.q1 * tau
        for p, cs in self.blocks:
            poly = np.zeros_like(tau, dtype=complex)
            for c in reversed(cs):
                poly = poly * tau + c
            y = y + (poly * np.exp(p * tau)).real
        return np.where(t < 0, 0.0, y)


def normalise(num, den):
    """Monic form of num(s)/den(s): numerator coefficients b0..bn and denominator a0..a_{n-1}.

    Parameters
    ----------
    num, den : array_like
        Polynomial coefficients, highest power first (as numpy and python-control use them);
        deg num <= deg den = n in {2, 3}.

    Returns
    -------
    b : tuple of float
        b0, b1, ..., bn (lowest power first) of num / lead(den), padded with zeros.
    den_monic : numpy.ndarray
        den / lead(den), highest power first.
    """
    num = np.atleast_1d(np.asarray(num, dtype=float))
    den = np.atleast_1d(np.asarray(den, dtype=float))
    n = den.size - 1
    b = np.zeros(n + 1)
    b[:num.size] = num[::-1] / den[0]
    return tuple(b.tolist()), den / den[0]


def classify_roots(roots, tol: float = MERGE_TOLERANCE):
    """Root structure of a 2nd/3rd-order denominator and the parameters of its closed form.

    Parameters
    ----------
    roots : array_like of complex
        The 2 or 3 roots (conjugate pairs for complex roots).
    tol : float
        Relative distance under which roots are merged into a repeated root.

    Returns
    -------
    structure : str
        One of ``distinct``, ``double``, ``complex`` (order 2) or ``distinct``,
        ``real_complex``, ``double_single``, ``triple`` (order 3).
    params : tuple of float
        The roots the generated function takes (see ``derivation.ROOT_PARAMETERS``).
    """
    r = np.asarray(roots, dtype=complex)
    scale = np.maximum(np.abs(r), np.finfo(float).tiny)

    def close(a, b):
        return abs(a - b) <= tol * max(abs(a), abs(b), np.finfo(float).tiny)

    if r.size == 2:
        p1, p2 = r
        if close(p1, p2):
            return "double", (float(np.mean(r).real),)
        if abs(p1.imag) > _IMAG_FRACTION * tol * scale[0]:  # a pair that was not merged
            return "complex", (float(p1.real), float(abs(p1.imag)))
        return "distinct", tuple(sorted(float(x.real) for x in r))
    if r.size != 3:
        raise ValueError(f"roots must hold 2 or 3 values, got {r.size}")
    pairs = [(i, j) for i in range(3) for j in range(i + 1, 3) if close(r[i], r[j])]
    spread = max(abs(r[i] - r[j]) for i in range(3) for j in range(i + 1, 3))
    if len(pairs) >= 2 or spread <= TRIPLE_TOLERANCE * max(np.max(scale), np.finfo(float).tiny):
        return "triple", (float(np.mean(r).real),)
    if len(pairs) == 1:
        i, j = pairs[0]
        k = 3 - i - j
        return "double_single", (float((r[i] + r[j]).real / 2), float(r[k].real))
    cplx = [x for x in r if abs(x.imag) > _IMAG_FRACTION * tol * abs(x)]
    if cplx:
        real = r[np.argmin(np.abs(r.imag))]
        top = max(cplx, key=lambda z: z.imag)
        return "real_complex", (float(real.real), float(top.real), float(abs(top.imag)))
    return "distinct", tuple(sorted(float(x.real) for x in r))


def _blocks(structure, params, modes):
    """Pack generated mode coefficients as (root, coefficients) blocks."""
    if structure == "distinct":
        return tuple((complex(p), (complex(c),)) for p, c in zip(params, modes))
    if structure == "double":
        return ((complex(params[0]), (complex(modes[0]), complex(modes[1]))),)
    if structure == "complex":
        sigma, omega = params
        return ((complex(sigma, omega), (complex(modes[0], -modes[1]),)),)
    if structure == "real_complex":
        p1, sigma, omega = params
        return ((complex(p1), (complex(modes[0]),)),
                (complex(sigma, omega), (complex(modes[1], -modes[2]),)))
    if structure == "double_single":
        return ((complex(params[0]), (complex(modes[0]), complex(modes[1]))),
                (complex(params[1]), (complex(modes[2]),)))
    return ((complex(params[0]), tuple(complex(m) for m in modes)),)  # triple


def closed_form(b, structure: str, params, input: str = "step") -> ClosedForm:
    """Closed-form step or ramp response of the monic system with numerator b and given roots.

    Parameters
    ----------
    b : sequence of float
        Numerator coefficients b0..bn (lowest power first) of the monic system (n = order).
    structure : str
        Root structure, as returned by :func:`classify_roots`.
    params : tuple of float
        Root parameters, as returned by :func:`classify_roots`.
    input : str
        ``"step"`` or ``"ramp"``.

    Returns
    -------
    ClosedForm
    """
    name = f"{input}_o{len(b) - 1}_{structure}"
    q0, q1, modes = FUNCTIONS[name](b, *params)
    return ClosedForm(float(q0), float(q1), _blocks(structure, params, modes), name, float(b[-1]))
