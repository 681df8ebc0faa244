"""Symbolic derivation (sympy) of the contact-mode feedback loop and of its 14 closed forms.

Everything numeric in :mod:`afmsmiler.controller` comes from here:

* :func:`closed_loop` solves the two loop equations

  .. math:: Z_c = P(s)\\,(Z_{np} + T), \\qquad Z_{np} = C(s)\\,(R - Z_c)

  with the plant :math:`P = (b_s s + k_s) / ((m_c + m_s) s^2 + (b_c + b_s) s + (k_c + k_s))` and
  the PID controller :math:`C = K_P + K_I / s + K_D s`, giving :math:`Z_c/T`, :math:`Z_{np}/T`,
  :math:`Z_c/R`, :math:`Z_{np}/R` over the common denominator
  :math:`A s^3 + B s^2 + C s + D` (:func:`denominator_coefficients`).
* :func:`steady_state` takes :math:`s \\to 0` for a constant setpoint R.
* :func:`derive_case` finds, by residues, the inverse Laplace transform of the step (1/s) and
  ramp (1/s^2) responses of a monic second- or third-order transfer function for each root
  structure (distinct real, repeated real, complex pair; three distinct real, real + complex
  pair, double + single real, triple real): 2 x (3 + 4) = 14 cases (:data:`CASES`).
* :func:`generate_code` prints them, with common subexpressions eliminated, as the Python module
  ``afmsmiler/controller/_generated.py``.  Run ``python -m afmsmiler.controller.derivation`` to
  regenerate it, ``... --check`` to verify that the committed file is what the derivation gives.

The result, to compare term by term with the paper's printed equations (which have at least one
typo; their printed form is not reproduced here: this sympy derivation is the reference)::

    Z_c / T  =   s (b_s s + k_s) / den
    Z_np / T = -(b_s s + k_s) (K_D s^2 + K_P s + K_I) / den
    Z_c / R  =  (b_s s + k_s) (K_D s^2 + K_P s + K_I) / den
    Z_np / R =  ((m_c + m_s) s^2 + (b_c + b_s) s + k_c + k_s) (K_D s^2 + K_P s + K_I) / den

    den = A s^3 + B s^2 + C s + D   with
    A = m_c + m_s + b_s K_D
    B = b_c + b_s + b_s K_P + k_s K_D
    C = k_c + k_s + b_s K_I + k_s K_P
    D = k_s K_I

and, for K_I > 0 and a constant setpoint R, Z_c = R and Z_np = (k_c + k_s) R / k_s.
``tests/test_controller_derivation.py`` checks every line above against :func:`closed_loop`,
the denominator against the characteristic polynomial den(P) den(C) + num(P) num(C) that
python-control's ``feedback`` forms from P and C built independently, and the transfer
functions against ``feedback`` at complex frequencies.
"""
from __future__ import annotations

import sys
from dataclasses import dataclass
from functools import lru_cache
from pathlib import Path

import numpy as np
import sympy as sp

from ..validation import check_integer

__all__ = ["SYMBOLS", "plant", "controller", "closed_loop", "denominator_coefficients",
           "steady_state", "Case", "CASES", "derive_case", "check_case", "generate_code", "main"]

s, t = sp.symbols("s t")
m_c, m_s, b_c, b_s, k_c, k_s = sp.symbols("m_c m_s b_c b_s k_c k_s", positive=True)
K_P, K_I, K_D = sp.symbols("K_P K_I K_D", nonnegative=True)

#: The symbols of the loop, by the names :class:`~afmsmiler.controller.ContactLoop` uses.
SYMBOLS = {"s": s, "t": t, "m_c": m_c, "m_s": m_s, "b_c": b_c, "b_s": b_s, "k_c": k_c,
           "k_s": k_s, "kp": K_P, "ki": K_I, "kd": K_D}

GENERATED = Path(__file__).with_name("_generated.py")


def plant():
    """Plant P(s) = Z_c / (Z_np + T) of cantilever and sample moving together in contact.

    Returns
    -------
    sympy.Expr
        (b_s s + k_s) / ((m_c + m_s) s^2 + (b_c + b_s) s + (k_c + k_s)).
    """
    return (b_s * s + k_s) / ((m_c + m_s) * s ** 2 + (b_c + b_s) * s + (k_c + k_s))


def controller():
    """PID controller C(s) = K_P + K_I / s + K_D s acting on the error R - Z_c.

    Returns
    -------
    sympy.Expr
    """
    return K_P + K_I / s + K_D * s


@lru_cache(maxsize=None)
def closed_loop():
    """Solve the two loop equations for Z_c and Z_np as linear functions of T and R.

    Returns
    -------
    dict
        ``{"Zc_T", "Znp_T", "Zc_R", "Znp_R"}`` -> (numerator, denominator), polynomials in s
        (sympy expressions) over the common third-order denominator A s^3 + B s^2 + C s + D.
    """
    Zc, Znp, T, R = sp.symbols("Z_c Z_np T R")
    sol = sp.solve([sp.Eq(Zc, plant() * (Znp + T)), sp.Eq(Znp, controller() * (R - Zc))],
                   [Zc, Znp], dict=True)[0]
    out = {}
    for name, expr, var in (("Zc_T", sol[Zc], T), ("Znp_T", sol[Znp], T),
                            ("Zc_R", sol[Zc], R), ("Znp_R", sol[Znp], R)):
        num, den = sp.fraction(sp.cancel(sp.together(sp.diff(expr, var))))
        # normalise to the common denominator A s^3 + ... with A = m_c + m_s + b_s K_D
        lead = sp.Poly(den, s).LC()
        scale = sp.cancel((m_c + m_s + b_s * K_D) / lead)
        out[name] = (sp.expand(num * scale), sp.expand(den * scale))
    return out


def denominator_coefficients():
    """Coefficients (A, B, C, D) of the closed-loop denominator A s^3 + B s^2 + C s + D.

    Returns
    -------
    tuple of sympy.Expr
        A = m_c + m_s + b_s K_D, B = b_c + b_s + b_s K_P + k_s K_D,
        C = k_c + k_s + b_s K_I + k_s K_P, D = k_s K_I (as derived, not typed).
    """
    den = closed_loop()["Zc_T"][1]
    return tuple(sp.Poly(den, s).all_coeffs())


def steady_state():
    """Steady state of Z_c and Z_np for a constant setpoint R (T = 0), by s -> 0.

    Returns
    -------
    dict
        ``{"Zc": ..., "Znp": ...}`` per unit setpoint, for K_I > 0: 1 and (k_c + k_s) / k_s.
    """
    R = sp.Symbol("R")
    out = {}
    for name, key in (("Zc", "Zc_R"), ("Znp", "Znp_R")):
        num, den = closed_loop()[key]
        out[name] = sp.simplify(sp.limit(num / den, s, 0)) * R
    return out


# --- the 14 closed forms -----------------------------------------------------------------------
@dataclass(frozen=True)
class Case:
    """One closed-form case: system order, root structure and input (step or ramp).

    Parameters
    ----------
    order : int
        2 (K_I = 0, the integrator pole cancels) or 3.
    structure : str
        ``"distinct"``, ``"double"``, ``"complex"`` (order 2); ``"distinct"``,
        ``"real_complex"``, ``"double_single"``, ``"triple"`` (order 3).
    input : str
        ``"step"`` (1/s) or ``"ramp"`` (1/s^2).
    """

    order: int
    structure: str
    input: str

    @property
    def name(self) -> str:
        """Name of the generated function, e.g. ``ramp_o3_real_complex``."""
        return f"{self.input}_o{self.order}_{self.structure}"

    @property
    def root_names(self) -> tuple:
        """Names of the root parameters the generated function takes."""
        return ROOT_PARAMETERS[(self.order, self.structure)]


ROOT_PARAMETERS = {
    (2, "distinct"): ("p1", "p2"),
    (2, "double"): ("p",),
    (2, "complex"): ("sigma", "omega"),
    (3, "distinct"): ("p1", "p2", "p3"),
    (3, "real_complex"): ("p1", "sigma", "omega"),
    (3, "double_single"): ("p", "p3"),
    (3, "triple"): ("p",),
}

#: The 14 cases, in the order of the paper's enumeration: order 2 then 3, step then ramp.
CASES = tuple(Case(order, structure, inp) for order in (2, 3) for inp in ("step", "ramp")
              for (o, structure) in ROOT_PARAMETERS if o == order)


def _case_symbols(case: Case):
    roots = sp.symbols(case.root_names, real=True)
    coeffs = sp.symbols(" ".join(f"b{j}" for j in range(case.order + 1)), real=True)
    return roots, coeffs


def _mode_blocks(case: Case, roots):
    """[(root, multiplicity)] for the case (the complex pair as sigma + i omega only)."""
    st = case.structure
    if st == "distinct":
        return [(r, 1) for r in roots]
    if st == "double":
        return [(roots[0], 2)]
    if st == "complex":
        return [(roots[0] + sp.I * roots[1], 1)]
    if st == "real_complex":
        return [(roots[0], 1), (roots[1] + sp.I * roots[2], 1)]
    if st == "double_single":
        return [(roots[0], 2), (roots[1], 1)]
    return [(roots[0], 3)]  # triple


def _denominator(case: Case, roots):
    st = case.structure
    if st in ("complex", "real_complex"):
        sigma, omega = roots[-2:]
        quad = (s - sigma) ** 2 + omega ** 2
        return quad if case.order == 2 else quad * (s - roots[0])
    return sp.Mul(*[(s - r) ** m for r, m in _mode_blocks(case, roots)])


def _laurent(Y, pole, multiplicity):
    """Coefficients c_j of t^j e^{pole t}, j < multiplicity, from the residue formula."""
    H = sp.cancel(Y * (s - pole) ** multiplicity)
    out = []
    for j in range(multiplicity):
        n = multiplicity - 1 - j
        out.append(sp.diff(H, s, n).subs(s, pole) / (sp.factorial(n) * sp.factorial(j)))
    return out


@lru_cache(maxsize=None)
def derive_case(case: Case):
    """Closed-form step or ramp response of N(s) / den(s) for one root structure.

    The transfer function is monic, den(s) = prod (s - p_i), with numerator
    N(s) = b0 + b1 s + ... + b_n s^n (n = order, so a direct feedthrough b_n is allowed). The
    response to the input 1/s (step) or 1/s^2 (ramp) from rest is, for t >= 0::

        y(t) = q0 + q1 t + sum over modes

    with a mode c_0 e^{p t} (simple real root), (c_0 + c_1 t [+ c_2 t^2]) e^{p t} (double
    [triple] root) or e^{sigma t} (A cos(omega t) + B sin(omega t)) (complex pair sigma +- i omega).

    Parameters
    ----------
    case : Case
        Order, root structure and input.

    Returns
    -------
    dict
        ``roots`` and ``coeffs`` (the sympy symbols taken), ``transform`` Y(s), ``q0``, ``q1``
        and ``modes``: the list of mode coefficients in the order of the generated function's
        output (for a complex pair: A, B).
    """
    roots, coeffs = _case_symbols(case)
    N = sum(b * s ** j for j, b in enumerate(coeffs))
    q = 1 if case.input == "step" else 2
    Y = N / (_denominator(case, roots) * s ** q)
    poly = _laurent(Y, sp.Integer(0), q)
    q0, q1 = (poly[0], sp.Integer(0)) if q == 1 else (poly[0], poly[1])
    modes = []
    for pole, mult in _mode_blocks(case, roots):
        cs = _laurent(Y, pole, mult)
        if sp.im(pole) != 0:
            r = sp.expand_complex(cs[0])
            modes += [2 * sp.re(r), -2 * sp.im(r)]
        else:
            modes += cs
    modes = [sp.factor(sp.cancel(sp.together(m))) for m in modes]
    return {"roots": roots, "coeffs": coeffs, "transform": Y, "q0": sp.factor(sp.cancel(q0)),
            "q1": sp.factor(sp.cancel(q1)), "modes": modes}


def time_response(case: Case):
    """The closed form y(t) of ``case`` as one sympy expression in t (for checks and display).

    Parameters
    ----------
    case : Case
        Order, root structure and input.

    Returns
    -------
    sympy.Expr
    """
    d = derive_case(case)
    y = d["q0"] + d["q1"] * t
    it = iter(d["modes"])
    roots = d["roots"]
    for pole, mult in _mode_blocks(case, roots):
        if sp.im(pole) != 0:
            A, B = next(it), next(it)
            sigma, omega = sp.re(pole), sp.im(pole)
            y += sp.exp(sigma * t) * (A * sp.cos(omega * t) + B * sp.sin(omega * t))
        else:
            y += sum(next(it) * t ** j for j in range(mult)) * sp.exp(pole * t)
    return y


def check_case(case: Case) -> bool:
    """True if the Laplace transform of :func:`time_response` equals Y(s) (exact, symbolic).

    Parameters
    ----------
    case : Case
        Order, root structure and input.

    Returns
    -------
    bool
    """
    d = derive_case(case)
    y = time_response(case)
    Ly = sp.laplace_transform(y, t, s, noconds=True)
    return sp.simplify(sp.together(Ly - d["transform"])) == 0


# --- code generation ---------------------------------------------------------------------------
_HEADER = '''"""Closed-form step and ramp responses, 2nd and 3rd order: GENERATED, do not edit.

Written by ``python -m afmsmiler.controller.derivation`` from the sympy derivation in
:mod:`afmsmiler.controller.derivation`, printed by sympy {version}.
``tests/test_controller_derivation.py`` checks these functions numerically against the derivation
(under any sympy), and the text against what the derivation prints when the installed sympy is
the one named here (:data:`SYMPY_VERSION`; another release may print the same formulas in
another order). Each function takes the numerator
coefficients b = (b0, b1, ...) of N(s) / prod(s - p_i) and the roots, and returns
(q0, q1, modes): see ``derive_case``.
"""
# flake8: noqa

#: The sympy release that printed this file.
SYMPY_VERSION = {version!r}


'''


def generate_code() -> str:
    """Python source of ``_generated.py``: one function per case, with CSE.

    Returns
    -------
    str
    """
    chunks = [_HEADER.format(version=sp.__version__)]
    names = []
    for case in CASES:
        d = derive_case(case)
        exprs = [d["q0"], d["q1"], *d["modes"]]
        repl, reduced = sp.cse(exprs, symbols=sp.numbered_symbols("x"), optimizations="basic")
        args = ", ".join(case.root_names)
        lines = [f"def {case.name}(b, {args}):",
                 f'    """{case.input} response, order {case.order}, roots: {case.structure}."""',
                 "    " + ", ".join(str(c) for c in d["coeffs"]) + (" = b" if len(d["coeffs"]) > 1
                                                                   else ", = b")]
        for sym, expr in repl:
            lines.append(f"    {sym} = {sp.pycode(expr)}")
        q0, q1, *modes = (sp.pycode(e) for e in reduced)
        lines.append(f"    return ({q0}, {q1}, ({', '.join(modes)},))")
        chunks.append("\n".join(lines) + "\n\n\n")
        names.append(case.name)
    chunks.append("FUNCTIONS = {\n" + "".join(f"    {n!r}: {n},\n" for n in names) + "}\n")
    return "".join(chunks)


def sample_roots(case: Case, rng) -> tuple:
    """Random root parameters of ``case``'s structure (stable, of order 1), for numeric checks.

    Parameters
    ----------
    case : Case
        Order, root structure and input.
    rng : numpy.random.Generator
        Random numbers.

    Returns
    -------
    tuple of float
        In the order of :attr:`Case.root_names`: distinct values for distinct roots, a
        negative real part and a positive imaginary part for a complex pair.
    """
    names = case.root_names
    values = -np.sort(rng.uniform(0.2, 3.0, len(names)))[::-1] * np.arange(1, len(names) + 1)
    out = []
    for name, v in zip(names, values):
        out.append(float(rng.uniform(0.3, 4.0)) if name == "omega" else float(v))
    return tuple(out)


def numeric_mismatch(case: Case, samples: int = 20, seed: int = 0) -> float:
    """Largest relative difference between ``_generated``'s function and the derivation.

    The derived expressions (q0, q1 and the mode coefficients of :func:`derive_case`) are turned
    into numpy functions with ``sympy.lambdify`` and compared with the generated function on
    random numerators and roots: a check of the numbers, independent of how a sympy release
    orders the printed text.

    Parameters
    ----------
    case : Case
        Order, root structure and input.
    samples : int
        Random parameter sets, 1 to 1000.
    seed : int
        Seed of the random numbers.

    Returns
    -------
    float
        max |generated - derived| / max(|derived|, 1) over all outputs and samples.
    """
    from ._generated import FUNCTIONS
    samples = check_integer("samples", samples, 1, 1000)
    d = derive_case(case)
    exprs = [d["q0"], d["q1"], *d["modes"]]
    f = sp.lambdify([*d["coeffs"], *d["roots"]], exprs, "numpy")
    rng = np.random.default_rng(seed)
    worst = 0.0
    for _ in range(samples):
        b = tuple(rng.normal(size=len(d["coeffs"])).tolist())
        roots = sample_roots(case, rng)
        q0, q1, modes = FUNCTIONS[case.name](b, *roots)
        got = np.array([q0, q1, *modes], dtype=float)
        want = np.array(f(*b, *roots), dtype=float)
        worst = max(worst, float(np.max(np.abs(got - want) / np.maximum(np.abs(want), 1.0))))
    return worst


def main(argv=None) -> int:
    """Regenerate ``_generated.py`` (default) or, with ``--check``, verify it is up to date.

    The check compares the generated functions with the derivation numerically
    (:func:`numeric_mismatch`, 1e-9), and the text when the installed sympy is the release that
    wrote the file (another release may order the same formulas differently: then the text
    check is skipped and says so).

    Parameters
    ----------
    argv : list of str, optional
        Command-line arguments (``--check``).

    Returns
    -------
    int
        Exit status: 0 when written or up to date, 1 when the committed file differs.
    """
    argv = sys.argv[1:] if argv is None else argv
    code = generate_code()
    if "--check" in argv:
        from ._generated import SYMPY_VERSION
        worst = max(numeric_mismatch(case) for case in CASES)
        ok = worst <= 1e-9
        print(f"{GENERATED.name}: largest difference from the derivation {worst:.2g} "
              f"({'ok' if ok else 'OUT OF DATE'})")
        if SYMPY_VERSION == sp.__version__:
            same = GENERATED.read_text(encoding="utf-8") == code
            ok = ok and same
            print(f"{GENERATED.name} text is {'up to date' if same else 'OUT OF DATE'}")
        else:
            print(f"text check skipped: {GENERATED.name} was printed by sympy {SYMPY_VERSION}, "
                  f"this is sympy {sp.__version__}")
        return 0 if ok else 1
    GENERATED.write_text(code, encoding="utf-8")
    print(f"wrote {GENERATED}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
