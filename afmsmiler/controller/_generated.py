"""Closed-form step and ramp responses, 2nd and 3rd order: GENERATED, do not edit.

Written by ``python -m afmsmiler.controller.derivation`` from the sympy derivation in
:mod:`afmsmiler.controller.derivation`, printed by sympy 1.14.0.
``tests/test_controller_derivation.py`` checks these functions numerically against the derivation
(under any sympy), and the text against what the derivation prints when the installed sympy is
the one named here (:data:`SYMPY_VERSION`; another release may print the same formulas in
another order). Each function takes the numerator
coefficients b = (b0, b1, ...) of N(s) / prod(s - p_i) and the roots, and returns
(q0, q1, modes): see ``derive_case``.
"""
# flake8: noqa

#: The sympy release that printed this file.
SYMPY_VERSION = '1.14.0'


def step_o2_distinct(b, p1, p2):
    """step response, order 2, roots: distinct."""
    b0, b1, b2 = b
    x0 = 1/p1
    x1 = 1/p2
    x2 = 1/(p1 - p2)
    return (b0*x0*x1, 0, (x0*x2*(b0 + b1*p1 + b2*p1**2), -x1*x2*(b0 + b1*p2 + b2*p2**2),))


def step_o2_double(b, p):
    """step response, order 2, roots: double."""
    b0, b1, b2 = b
    x0 = p**2
    x1 = 1/x0
    x2 = b2*x0
    return (b0*x1, 0, (-x1*(b0 - x2), (b0 + b1*p + x2)/p,))


def step_o2_complex(b, sigma, omega):
    """step response, order 2, roots: complex."""
    b0, b1, b2 = b
    x0 = omega**2
    x1 = sigma**2
    x2 = 1/(x0 + x1)
    x3 = b2*x0
    return (b0*x2, 0, (x2*(-b0 + b2*x1 + x3), x2*(b0*sigma + b1*x0 + b1*x1 + b2*sigma**3 + sigma*x3)/omega,))


def ramp_o2_distinct(b, p1, p2):
    """ramp response, order 2, roots: distinct."""
    b0, b1, b2 = b
    x0 = p1**2
    x1 = 1/x0
    x2 = p2**2
    x3 = 1/x2
    x4 = b1*p1
    x5 = 1/(p1 - p2)
    return (x1*x3*(b0*p1 + b0*p2 + p2*x4), b0/(p1*p2), (x1*x5*(b0 + b2*x0 + x4), -x3*x5*(b0 + b1*p2 + b2*x2),))


def ramp_o2_double(b, p):
    """ramp response, order 2, roots: double."""
    b0, b1, b2 = b
    x0 = b1*p
    x1 = (2*b0 + x0)/p**3
    x2 = p**2
    x3 = 1/x2
    return (x1, b0*x3, (-x1, x3*(b0 + b2*x2 + x0),))


def ramp_o2_complex(b, sigma, omega):
    """ramp response, order 2, roots: complex."""
    b0, b1, b2 = b
    x0 = omega**2
    x1 = sigma**2
    x2 = x0 + x1
    x3 = x2**(-2)
    x4 = b1*x0
    x5 = x3*(2*b0*sigma + b1*x1 + x4)
    return (x5, b0/x2, (-x5, x3*(-b0*x0 + b0*x1 + b1*sigma**3 + b2*omega**4 + b2*sigma**4 + 2*b2*x0*x1 + sigma*x4)/omega,))


def step_o3_distinct(b, p1, p2, p3):
    """step response, order 3, roots: distinct."""
    b0, b1, b2, b3 = b
    x0 = 1/p1
    x1 = 1/p2
    x2 = 1/p3
    x3 = 1/(p1 - p2)
    x4 = -p3
    x5 = 1/(p1 + x4)
    x6 = 1/(p2 + x4)
    return (-b0*x0*x1*x2, 0, (x0*x3*x5*(b0 + b1*p1 + b2*p1**2 + b3*p1**3), -x1*x3*x6*(b0 + b1*p2 + b2*p2**2 + b3*p2**3), x2*x5*x6*(b0 + b1*p3 + b2*p3**2 + b3*p3**3),))


def step_o3_real_complex(b, p1, sigma, omega):
    """step response, order 3, roots: real_complex."""
    b0, b1, b2, b3 = b
    x0 = 1/p1
    x1 = omega**2
    x2 = sigma**2
    x3 = x1 + x2
    x4 = 1/x3
    x5 = b1*p1
    x6 = p1**2
    x7 = 2*sigma
    x8 = p1*x7
    x9 = 1/(x3 + x6 - x8)
    x10 = b0*p1
    x11 = b1*x1
    x12 = omega**4
    x13 = b3*x12
    x14 = sigma**4
    x15 = b3*x14
    x16 = b2*p1
    x17 = x1*x16
    x18 = sigma**3
    x19 = 2*b3
    x20 = x18*x19
    x21 = x1*x2
    x22 = x4*x9
    return (-b0*x0*x4, 0, (x0*x9*(b0 + b2*x6 + b3*p1**3 + x5), -x22*(b0*x7 + b1*x2 + b3*x1*x8 + p1*x20 - x10 + x11 - x13 - x15 + x16*x2 + x17 - x19*x21), x22*(-b0*x1 + b0*x2 + b1*x18 + b2*x12 + b2*x14 + 2*b2*x21 + b3*sigma**5 + p1*x13 - p1*x15 - sigma*x10 + sigma*x11 + sigma*x13 - sigma*x17 + x1*x20 - x1*x5 - x16*x18 - x2*x5)/omega,))


def step_o3_double_single(b, p, p3):
    """step response, order 3, roots: double_single."""
    b0, b1, b2, b3 = b
    x0 = p**2
    x1 = 1/x0
    x2 = 1/p3
    x3 = p - p3
    x4 = x3**(-2)
    x5 = b2*x0
    x6 = b3*p**3
    return (-b0*x1*x2, 0, (-x1*x4*(2*b0*p - b0*p3 + b1*x0 - b3*p**4 + p3*x5 + 2*p3*x6), (b0 + b1*p + x5 + x6)/(p*x3), x2*x4*(b0 + b1*p3 + b2*p3**2 + b3*p3**3),))


def step_o3_triple(b, p):
    """step response, order 3, roots: triple."""
    b0, b1, b2, b3 = b
    x0 = p**3
    x1 = 1/x0
    x2 = b3*x0
    x3 = b0 + x2
    x4 = p**2
    x5 = b2*x4
    return (-b0*x1, 0, (x1*x3, (-b0 + 2*x2 + x5)/x4, (1/2)*(b1*p + x3 + x5)/p,))


def ramp_o3_distinct(b, p1, p2, p3):
    """ramp response, order 3, roots: distinct."""
    b0, b1, b2, b3 = b
    x0 = p1**2
    x1 = 1/x0
    x2 = p2**2
    x3 = 1/x2
    x4 = p3**2
    x5 = 1/x4
    x6 = b0*p1
    x7 = p2*p3
    x8 = b1*p1
    x9 = 1/(p1 - p2)
    x10 = -p3
    x11 = 1/(p1 + x10)
    x12 = 1/(p2 + x10)
    return (-x1*x3*x5*(b0*x7 + p2*x6 + p3*x6 + x7*x8), -b0/(p1*p2*p3), (x1*x11*x9*(b0 + b2*x0 + b3*p1**3 + x8), -x12*x3*x9*(b0 + b1*p2 + b2*x2 + b3*p2**3), x11*x12*x5*(b0 + b1*p3 + b2*x4 + b3*p3**3),))


def ramp_o3_real_complex(b, p1, sigma, omega):
    """ramp response, order 3, roots: real_complex."""
    b0, b1, b2, b3 = b
    x0 = p1**2
    x1 = 1/x0
    x2 = omega**2
    x3 = sigma**2
    x4 = x2 + x3
    x5 = x4**(-2)
    x6 = b0*x2
    x7 = b0*x3
    x8 = 2*sigma
    x9 = p1*x8
    x10 = b0*x9
    x11 = b1*p1
    x12 = x11*x2
    x13 = x11*x3
    x14 = 1/(x0 + x4 - x9)
    x15 = omega**4
    x16 = b2*x15
    x17 = sigma**4
    x18 = b2*x17
    x19 = sigma**3
    x20 = 2*x19
    x21 = b3*p1
    x22 = x15*x21
    x23 = b2*x2
    x24 = 2*x3
    x25 = x23*x24
    x26 = x2*x21
    x27 = x14*x5
    x28 = sigma**5
    x29 = 3*b3
    return (-x1*x5*(x10 + x12 + x13 + x6 + x7), -b0/(p1*x4), (x1*x14*(b0 + b2*x0 + b3*p1**3 + x11), -x27*(b1*x2*x8 + b1*x20 - x10 - x12 - x13 + x16 + x17*x21 + x18 + x22 + x24*x26 + x25 - x6 + 3*x7), -x27*(-b0*x19 + b1*x15 - b1*x17 - b2*x28 - b3*omega**6 - b3*sigma**6 + p1*x16 + p1*x18 + p1*x25 - p1*x6 + p1*x7 + sigma*x12 - sigma*x16 + sigma*x22 + 3*sigma*x6 + x11*x19 - x15*x29*x3 - x17*x2*x29 - x20*x23 + x20*x26 + x21*x28)/omega,))


def ramp_o3_double_single(b, p, p3):
    """ramp response, order 3, roots: double_single."""
    b0, b1, b2, b3 = b
    x0 = p**3
    x1 = 1/x0
    x2 = p3**2
    x3 = 1/x2
    x4 = b0*p
    x5 = 2*b0*p3
    x6 = b1*p
    x7 = p3*x6
    x8 = p**2
    x9 = 1/x8
    x10 = p - p3
    x11 = x10**(-2)
    x12 = b3*x0
    return (-x1*x3*(x4 + x5 + x7), -b0*x9/p3, (-x1*x11*(2*b1*x8 + b2*x0 + p3*x12 + 3*x4 - x5 - x7), x9*(b0 + b2*x8 + x12 + x6)/x10, x11*x3*(b0 + b1*p3 + b2*x2 + b3*p3**3),))


def ramp_o3_triple(b, p):
    """ramp response, order 3, roots: triple."""
    b0, b1, b2, b3 = b
    x0 = b1*p
    x1 = (3*b0 + x0)/p**4
    x2 = p**3
    x3 = 1/x2
    x4 = b3*x2
    x5 = p**2
    return (-x1, -b0*x3, (x1, -x3*(2*b0 + x0 - x4), (1/2)*(b0 + b2*x5 + x0 + x4)/x5,))


FUNCTIONS = {
    'step_o2_distinct': step_o2_distinct,
    'step_o2_double': step_o2_double,
    'step_o2_complex': step_o2_complex,
    'ramp_o2_distinct': ramp_o2_distinct,
    'ramp_o2_double': ramp_o2_double,
    'ramp_o2_complex': ramp_o2_complex,
    'step_o3_distinct': step_o3_distinct,
    'step_o3_real_complex': step_o3_real_complex,
    'step_o3_double_single': step_o3_double_single,
    'step_o3_triple': step_o3_triple,
    'ramp_o3_distinct': ramp_o3_distinct,
    'ramp_o3_real_complex': ramp_o3_real_complex,
    'ramp_o3_double_single': ramp_o3_double_single,
    'ramp_o3_triple': ramp_o3_triple,
}
