"""Reference results derived with sympy, shared by the transducer tests."""
import sympy as sp


def fourier_coefficients(expr, th):
    """DC, cos(theta) and cos(2 theta) amplitudes of a 2 pi-periodic expression (sympy)."""
    dc = sp.integrate(expr, (th, 0, 2 * sp.pi)) / (2 * sp.pi)
    first = sp.integrate(expr * sp.cos(th), (th, 0, 2 * sp.pi)) / sp.pi
    second = sp.integrate(expr * sp.cos(2 * th), (th, 0, 2 * sp.pi)) / sp.pi
    return sp.simplify(dc), sp.simplify(first), sp.simplify(second)
