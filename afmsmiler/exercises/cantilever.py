"""Exercise checkers of module (a), cantilever mechanics.

Each checker computes the right answer with :class:`~afmsmiler.cantilever.Cantilever` and returns a
:class:`~afmsmiler.exercises.Feedback`. A placeholder answer (``None``) gets "Not yet" and a hint.
"""
from __future__ import annotations

from ..cantilever import MAX_MODE, Cantilever
from ..validation import check_integer, check_positive, check_range
from . import Feedback, check_close

__all__ = ["DEFAULTS", "check_thickness_for_spring_constant", "check_mode_ratio",
           "check_largest_stress"]

#: The exercises' givens, in one place (SI units).
DEFAULTS = dict(target_k=0.1, length=450e-6, width=50e-6, material="silicon",
                force=100e-9, thickness=2e-6)

_LOCATIONS = ("clamp", "middle", "free end")
_STATES = ("tension", "compression")


def check_thickness_for_spring_constant(thickness, target_k: float = DEFAULTS["target_k"],
                                        length: float = DEFAULTS["length"],
                                        width: float = DEFAULTS["width"],
                                        material: str = DEFAULTS["material"],
                                        rtol: float = 0.03) -> Feedback:
    """Exercise 1: choose a thickness that gives the lever the spring constant ``target_k``.

    Parameters
    ----------
    thickness : float or None
        The student's thickness in m.
    target_k : float
        Wanted spring constant in N/m.
    length, width : float
        The lever's L and w in m.
    material : str
        A key of :data:`afmsmiler.materials.MATERIALS`.
    rtol : float
        Accepted relative error of the resulting k (k ~ h^3, so 3 % in k is 1 % in h).

    Returns
    -------
    Feedback
        Passed when the lever of that thickness has k within ``rtol`` of ``target_k``.
    """
    target_k = check_positive("target_k", target_k, "N/m")
    rtol = check_range("rtol", rtol, 0.0, 1.0, low_inclusive=False)
    hint = ("k = 3 E J / L^3 with J = w h^3 / 12: solve for h, and mind that k grows as h^3. "
            "Give h in metres.")
    if thickness is None:
        return Feedback(False, f"enter a thickness in m. {hint}")
    try:
        h = check_positive("thickness", thickness, "m")
    except ValueError as err:
        return Feedback(False, f"{err}. {hint}")
    k = Cantilever.from_material(material, length, width, h).spring_constant
    return check_close(f"k of the {h * 1e6:.4g} um thick lever", k, target_k, rtol, "N/m", hint)


def check_mode_ratio(ratio, mode: int = 2, rtol: float = 1e-3) -> Feedback:
    """Exercise 2: what is f_n / f_1 for a rectangular cantilever (any size, any material)?

    Parameters
    ----------
    ratio : float or None
        The student's f_mode / f_1.
    mode : int
        The higher mode n (2 to 50).
    rtol : float
        Accepted relative error.

    Returns
    -------
    Feedback
        Compared with the model's f_n / f_1 (the same for every rectangular lever).
    """
    mode = check_integer("mode", mode, 2, MAX_MODE)
    rtol = check_range("rtol", rtol, 0.0, 1.0, low_inclusive=False)
    lever = Cantilever.from_material(DEFAULTS["material"], DEFAULTS["length"], DEFAULTS["width"],
                                     DEFAULTS["thickness"])
    expected = lever.resonance_frequency(mode) / lever.resonance_frequency(1)
    hint = ("f_n is proportional to (b_n L)^2 with b_n L the roots of cos(bL) cosh(bL) = -1; "
            "only the roots matter.")
    if ratio is None:
        return Feedback(False, f"enter f{mode}/f1 as a number. {hint}")
    return check_close(f"f{mode}/f1", ratio, expected, rtol, "", hint)


def check_largest_stress(location, top_surface, force: float = DEFAULTS["force"]) -> Feedback:
    """Exercise 3: where along the lever is the bending stress largest, and is the top surface
    there in tension or in compression when an end force ``force`` acts?

    Parameters
    ----------
    location : str or None
        ``"clamp"``, ``"middle"`` or ``"free end"``.
    top_surface : str or None
        ``"tension"`` or ``"compression"``.
    force : float
        End force in N (positive lifts the tip); not 0.

    Returns
    -------
    Feedback
        Both parts right, or what is wrong.
    """
    force = check_range("force", force, -1.0, 1.0, "N")
    if force == 0:
        raise ValueError("force must be in [-1, 1] N and not 0, got 0")
    lever = Cantilever.from_material(DEFAULTS["material"], DEFAULTS["length"], DEFAULTS["width"],
                                     DEFAULTS["thickness"])
    xs = {"clamp": 0.0, "middle": lever.length / 2, "free end": lever.length}
    top = {k: float(lever.stress(x, lever.thickness / 2, force)) for k, x in xs.items()}
    where = max(top, key=lambda k: abs(top[k]))
    state = "tension" if top[where] > 0 else "compression"
    hint = "Look at the bending moment M(x) = F (L - x) and at sigma = -E z_b z''."
    if location not in _LOCATIONS or top_surface not in _STATES:
        return Feedback(False, f"answer location with one of {_LOCATIONS} and top_surface with "
                               f"one of {_STATES}. {hint}")
    wrong = []
    if location != where:
        wrong.append(f"the stress at the {location} is {abs(top[location]) / 1e6:.3g} MPa, "
                     f"not the largest")
    if top_surface != state:
        wrong.append(f"the top surface is not in {top_surface} for F = {force * 1e9:.3g} nN")
    if wrong:
        return Feedback(False, "; ".join(wrong) + ". " + hint)
    return Feedback(True, f"largest at the {where}: {abs(top[where]) / 1e6:.3g} MPa of "
                          f"{state} on the top surface for F = {force * 1e9:.3g} nN.")
