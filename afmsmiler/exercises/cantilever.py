"""Exercise checkers of module (a), cantilever mechanics.

Each checker computes the right answer with :class:`~afmsmiler.cantilever.Cantilever` and returns a
:class:`~afmsmiler.exercises.Feedback`. A placeholder answer (``None``) gets "Not yet" and a hint.
Each is an exercise of notebook 01 (:mod:`afmsmiler.exercises.registry`) whose solution is the
function that computes the checker's reference (:func:`thickness_for_spring_constant`,
:func:`mode_ratio`, :func:`largest_stress`, :func:`tip_slope`).
"""
from __future__ import annotations

import functools
import itertools
import math

import numpy as np

from ..calibration import ThermalSpectrum, thermal_calibration, thermal_spectrum
from ..cantilever import FORCE, LENGTH, MAX_MODE, WIDTH, Cantilever
from ..materials import lookup
from ..parameters import read_only, unit_scale
from ..validation import check_integer, check_range
from . import Feedback, check_close
from .registry import exercise

__all__ = ["DEFAULTS", "thickness_for_spring_constant", "check_thickness_for_spring_constant",
           "mode_ratio", "check_mode_ratio", "largest_stress", "check_largest_stress", "tip_slope",
           "check_tip_slope", "unseen_lever_spectrum", "unseen_lever_spring_constant",
           "check_unseen_lever_calibration"]

#: The exercises' givens, in one place (SI units).
DEFAULTS = read_only(dict(target_k=0.1, length=450e-6, width=50e-6, material="silicon",
                          force=100e-9, thickness=2e-6, unseen_seed=2026))

_LOCATIONS = ("clamp", "middle", "free end")
_STATES = ("tension", "compression")


def _number(quantity: str, unit: str, answer, hint: str):
    """The answer as a float, or the Feedback that says why it is not one."""
    if answer is None:
        return Feedback(False, f"enter {quantity}{' in ' + unit if unit else ''}. {hint}")
    if isinstance(answer, bool):
        return Feedback(False, f"{quantity} must be a number, got {answer!r}. {hint}")
    try:
        value = float(answer)
    except (TypeError, ValueError, OverflowError):  # OverflowError: an int such as 10**400
        return Feedback(False, f"{quantity} must be a number, got {answer!r}. {hint}")
    if not math.isfinite(value):
        return Feedback(False, f"{quantity} must be finite, got {value!r}. {hint}")
    return value


def thickness_for_spring_constant(*, target_k: float = DEFAULTS["target_k"],
                                  length: float = DEFAULTS["length"],
                                  width: float = DEFAULTS["width"],
                                  material: str = DEFAULTS["material"]) -> float:
    """The thickness in m that gives the lever the spring constant ``target_k`` (exercise 1).

    k grows as h^3 (the model's own law, checked against the closed form in the tests): the
    thickness scales a 1 um reference lever of the same L, w and material,
    h = 1 um (target_k / k(1 um))^(1/3).

    Parameters
    ----------
    target_k : float
        Wanted spring constant in N/m, in (0, 10^6].
    length, width : float
        The lever's L and w in m (valid ranges of :data:`afmsmiler.cantilever.PARAMETERS`).
    material : str
        A key of :data:`afmsmiler.materials.MATERIALS`.

    Returns
    -------
    float
        h in m.
    """
    target_k = check_range("target_k", target_k, 0.0, 1e6, "N/m", low_inclusive=False)
    length, width = LENGTH.check(length), WIDTH.check(width)
    lookup(material, "material")  # named as this function's parameter
    reference = Cantilever.from_material(material, length, width, 1e-6)
    return 1e-6 * (target_k / reference.spring_constant) ** (1.0 / 3.0)


@exercise("01.1", "Size a lever", answers=("thickness",), solution=thickness_for_spring_constant)
def check_thickness_for_spring_constant(thickness, *, target_k: float = DEFAULTS["target_k"],
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
        Wanted spring constant in N/m, in (0, 10^6].
    length, width : float
        The lever's L and w in m (valid ranges of :data:`afmsmiler.cantilever.PARAMETERS`).
    material : str
        A key of :data:`afmsmiler.materials.MATERIALS`.
    rtol : float
        Accepted relative error of the resulting k, in (0, 1) (k ~ h^3, so 3 % in k is 1 % in h).

    Returns
    -------
    Feedback
        Passed when the lever of that thickness has k within ``rtol`` of ``target_k``; a
        thickness given in um or nm, or with the wrong sign, is told so (without the answer).
    """
    target_k = check_range("target_k", target_k, 0.0, 1e6, "N/m", low_inclusive=False)
    length, width = LENGTH.check(length), WIDTH.check(width)
    lookup(material, "material")  # named as this checker's parameter
    rtol = check_range("rtol", rtol, 0.0, 1.0, low_inclusive=False, high_inclusive=False)
    hint = ("k = 3 E J / L^3 with J = w h^3 / 12: solve for h, and mind that k grows as h^3. "
            "Give h in metres.")
    h = _number("the thickness h", "m", thickness, hint)
    if isinstance(h, Feedback):
        return h
    reference = Cantilever.from_material(material, length, width, 1e-6)
    expected = thickness_for_spring_constant(target_k=target_k, length=length, width=width,
                                             material=material)
    if 0.5 < h / expected < 2.0 and abs((h / expected) ** 3 - 1.0) <= rtol:
        k = reference.spring_constant * (h / 1e-6) ** 3
        return Feedback(True, f"a {h * unit_scale('um'):.4g} um thick lever has k = {k:.4g} N/m "
                              f"(target {target_k:g} N/m).")
    return check_close("thickness h", h, expected, rtol / 3.0, "m", hint)


def mode_ratio(mode: int = 2) -> float:
    """f_mode / f_1 of a rectangular lever, from the model's resonance frequencies (exercise 2).

    Parameters
    ----------
    mode : int
        The higher mode n (2 to 50).

    Returns
    -------
    float
        The ratio (the same for every rectangular lever: the exercises' default one is used).
    """
    mode = check_integer("mode", mode, 2, MAX_MODE)
    lever = Cantilever.from_material(DEFAULTS["material"], DEFAULTS["length"], DEFAULTS["width"],
                                     DEFAULTS["thickness"])
    return lever.resonance_frequency(mode) / lever.resonance_frequency(1)


@exercise("01.2", "Overtones", answers=("ratio",), solution=mode_ratio)
def check_mode_ratio(ratio, mode: int = 2, rtol: float = 1e-3) -> Feedback:
    """Exercise 2: what is f_n / f_1 for a rectangular cantilever (any size, any material)?

    Parameters
    ----------
    ratio : float or None
        The student's f_mode / f_1.
    mode : int
        The higher mode n (2 to 50).
    rtol : float
        Accepted relative error, in (0, 1).

    Returns
    -------
    Feedback
        Compared with the model's f_n / f_1 (the same for every rectangular lever); the
        inverse ratio f_1 / f_n is told so (without the answer).
    """
    mode = check_integer("mode", mode, 2, MAX_MODE)
    rtol = check_range("rtol", rtol, 0.0, 1.0, low_inclusive=False, high_inclusive=False)
    expected = mode_ratio(mode)
    hint = ("f_n is proportional to (b_n L)^2 with b_n L the roots of cos(bL) cosh(bL) = -1; "
            "only the roots matter.")
    value = _number(f"f{mode}/f1", "", ratio, hint)
    if isinstance(value, Feedback):
        return value
    if value > 0 and abs(value * expected - 1.0) <= rtol:  # the ratio upside down
        return Feedback(False, f"f{mode}/f1 = {value:.4g} is below 1, but mode {mode} rings "
                               f"faster than mode 1: that looks like f1/f{mode}. {hint}")
    return check_close(f"f{mode}/f1", value, expected, rtol, "", hint)


def _top_stresses(force: float) -> dict:
    """The bending stress (Pa) on the top surface at the clamp, the middle and the free end."""
    force = FORCE.check(force)
    if force == 0:
        raise ValueError(f"force must be in [{FORCE.low:g}, {FORCE.high:g}] N and not 0, got 0")
    lever = Cantilever.from_material(DEFAULTS["material"], DEFAULTS["length"], DEFAULTS["width"],
                                     DEFAULTS["thickness"])
    xs = {"clamp": 0.0, "middle": lever.length / 2, "free end": lever.length}
    return {k: float(lever.stress(x, lever.thickness / 2, force)) for k, x in xs.items()}


def largest_stress(force: float = DEFAULTS["force"]) -> tuple[str, str]:
    """Where the bending stress is largest and the top surface's state there (exercise 3).

    Parameters
    ----------
    force : float
        End force in N (positive lifts the tip); not 0.

    Returns
    -------
    (location, top_surface) : tuple of str
        One of ``"clamp"``, ``"middle"``, ``"free end"`` and one of ``"tension"``,
        ``"compression"``, from the model's stress at the three places.
    """
    top = _top_stresses(force)
    where = max(top, key=lambda k: abs(top[k]))
    return where, "tension" if top[where] > 0 else "compression"


@exercise("01.3", "Where does it break?", answers=("location", "top_surface"),
          solution=largest_stress)
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
    force = FORCE.check(force)
    top = _top_stresses(force)
    where, state = largest_stress(force)
    hint = "Look at the bending moment M(x) = F (L - x) and at sigma = -E z_b z''."
    if location not in _LOCATIONS or top_surface not in _STATES:
        return Feedback(False, f"answer location with one of {_LOCATIONS} and top_surface with "
                               f"one of {_STATES}. {hint}")
    wrong = []
    if location != where:
        wrong.append(f"the stress at the {location} is not the largest")
    if top_surface != state:
        wrong.append(f"the top surface is not in {top_surface} for F = "
                     f"{force * unit_scale('nN'):.3g} nN")
    if wrong:
        return Feedback(False, "; ".join(wrong) + ". " + hint)
    return Feedback(True, f"largest at the {where}: {abs(top[where]) * unit_scale('MPa'):.3g} "
                          f"MPa of {state} on the top surface for F = "
                          f"{force * unit_scale('nN'):.3g} nN.")


def tip_slope(*, force: float = DEFAULTS["force"], length: float = DEFAULTS["length"],
              width: float = DEFAULTS["width"], thickness: float = DEFAULTS["thickness"],
              material: str = DEFAULTS["material"]) -> float:
    """The slope theta(L) in rad at the free end under an end force (exercise 4), from the model.

    Parameters
    ----------
    force : float
        End force in N (positive lifts the tip), in [-10^6, 10^6] and not 0.
    length, width, thickness : float
        The lever's L, w and h in m.
    material : str
        A key of :data:`afmsmiler.materials.MATERIALS`.

    Returns
    -------
    float
        :meth:`~afmsmiler.cantilever.Cantilever.slope` at x = L, in rad.
    """
    force = FORCE.check(force)
    if force == 0:
        raise ValueError(f"force must be in [{FORCE.low:g}, {FORCE.high:g}] N and not 0, got 0")
    lever = Cantilever.from_material(material, length, width, thickness)
    return float(lever.slope(lever.length, force))


@exercise("01.4", "What the optical lever reads", answers=("slope",), solution=tip_slope)
def check_tip_slope(slope, *, force: float = DEFAULTS["force"],
                    length: float = DEFAULTS["length"], width: float = DEFAULTS["width"],
                    thickness: float = DEFAULTS["thickness"],
                    material: str = DEFAULTS["material"], rtol: float = 0.01) -> Feedback:
    """Exercise 4: the slope theta(L) at the free end (what an optical lever reads), in rad.

    Parameters
    ----------
    slope : float or None
        The student's theta(L) in rad.
    force : float
        End force in N (positive lifts the tip), in [-10^6, 10^6] and not 0.
    length, width, thickness : float
        The lever's L, w and h in m.
    material : str
        A key of :data:`afmsmiler.materials.MATERIALS`.
    rtol : float
        Accepted relative error, in (0, 1).

    Returns
    -------
    Feedback
        Compared with the model's theta(L); an answer in degrees or mrad, or with the wrong
        sign, is told so (without the answer).
    """
    force = FORCE.check(force)
    if force == 0:
        raise ValueError(f"force must be in [{FORCE.low:g}, {FORCE.high:g}] N and not 0, got 0")
    rtol = check_range("rtol", rtol, 0.0, 1.0, low_inclusive=False, high_inclusive=False)
    expected = tip_slope(force=force, length=length, width=width, thickness=thickness,
                         material=material)
    hint = ("Differentiate z(x) (or use theta(L) = 3 z(L) / (2 L)) and give the angle in "
            "radians, signed like z.")
    value = _number("theta(L)", "rad", slope, hint)
    if isinstance(value, Feedback):
        return value
    return check_close("theta(L)", value, expected, rtol, "rad", hint)


# The unseen lever: a silicon lever in air drawn from these ranges (m) by the exercise's seed.
_UNSEEN_RANGES = dict(length=(150e-6, 450e-6), width=(25e-6, 50e-6), thickness=(1.5e-6, 4e-6))


def unseen_lever_spectrum(seed: int = DEFAULTS["unseen_seed"]) -> ThermalSpectrum:
    """Exercise 5's data: the thermal spectrum of a silicon lever in air the student has not seen.

    Its length, width and thickness are drawn from fixed ranges by ``seed``; the spectrum is
    recorded with the laser spot at the free end, 2^18 bins and 64 averages (a statistical error
    of k well under 1 %).

    Parameters
    ----------
    seed : int
        Picks the lever and the noise, 0 to 2^32 - 1.

    Returns
    -------
    ThermalSpectrum
        What the student calibrates (its ``lever`` attribute is the answer's source: no peeking).
    """
    seed = check_integer("seed", seed, 0, 2 ** 32 - 1)
    rng = np.random.default_rng(seed)
    size = {name: float(rng.uniform(*span)) for name, span in _UNSEEN_RANGES.items()}
    lever = Cantilever.from_material("silicon", **size)
    return thermal_spectrum(lever, "air", points=2 ** 18, averages=64, seed=rng)


# The slips of a thermal calibration and the factor each puts on k (k = share k_B T / (chi^2 A)).
_SLIPS = (
    "mode 1's share of k_B T looks left out (the higher modes carry the rest)",
    "the optical-lever factor looks left out (the detector reads the slope, calibrated on a "
    "lever loaded at its end, not bent in mode 1's shape)",
    "the area looks taken per rad/s where the spectrum is per Hz (or the other way round)",
    "the spectrum looks treated as two-sided where it is one-sided (or the other way round)",
)


@functools.lru_cache(maxsize=8)
def _unseen_calibration(seed: int) -> tuple:
    """(k, mode share, chi) of the thermal calibration of exercise 5's spectrum."""
    calibration = thermal_calibration(unseen_lever_spectrum(seed))
    return calibration.spring_constant, calibration.mode_share, calibration.correction


def unseen_lever_spring_constant(seed: int = DEFAULTS["unseen_seed"]) -> float:
    """Exercise 5's answer from the model: the thermal calibration of the spectrum, in N/m.

    Parameters
    ----------
    seed : int
        The exercise's lever (as given to :func:`unseen_lever_spectrum`).

    Returns
    -------
    float
        k by equipartition from the fitted peak of mode 1, with its share 0.971 of k_B T and the
        optical-lever factor (:func:`~afmsmiler.calibration.thermal_calibration`).
    """
    return _unseen_calibration(check_integer("seed", seed, 0, 2 ** 32 - 1))[0]


@exercise("01.5", "Calibrate a lever you have not seen", answers=("spring_constant",),
          solution=unseen_lever_spring_constant)
def check_unseen_lever_calibration(spring_constant, *, seed: int = DEFAULTS["unseen_seed"],
                                   rtol: float = 0.012) -> Feedback:
    """Exercise 5: calibrate the spring constant of :func:`unseen_lever_spectrum`'s lever.

    The student fits mode 1's peak (e.g. with
    :func:`~afmsmiler.calibration.fit_thermal_spectrum`) and turns its area <z*^2> into k by
    equipartition. The answer is compared with the thermal calibration of the same spectrum
    (:func:`~afmsmiler.calibration.thermal_calibration`, spot at the end).

    Parameters
    ----------
    spring_constant : float or None
        The student's k in N/m.
    seed : int
        The exercise's lever (as given to :func:`unseen_lever_spectrum`).
    rtol : float
        Accepted relative error, in (0, 0.015] (the smallest slip, the forgotten 0.971, is 3 %).

    Returns
    -------
    Feedback
        Passed within ``rtol``; an answer off by the usual slips (the 0.971 mode share, the
        optical-lever factor, Hz vs rad/s, one- vs two-sided spectrum, alone or together) is
        told which, without the answer.
    """
    seed = check_integer("seed", seed, 0, 2 ** 32 - 1)
    rtol = check_range("rtol", rtol, 0.0, 0.015, low_inclusive=False)
    hint = ("Equipartition: the area of mode 1's peak is the mean-square deflection the detector "
            "reports; mind which share of k_B T mode 1 carries and what the optical lever "
            "measures. Give k in N/m.")
    value = _number("the spring constant k", "N/m", spring_constant, hint)
    if isinstance(value, Feedback):
        return value
    expected, share, chi = _unseen_calibration(seed)
    if abs(value / expected - 1.0) <= rtol:
        return Feedback(True, f"k = {value:.4g} N/m: the lever's k from its thermal spectrum.")
    factors = ((1.0 / share,), (chi ** 2,),
               (2.0 * math.pi, 0.5 / math.pi), (2.0, 0.5))
    for count in range(1, len(_SLIPS) + 1):
        for chosen in itertools.combinations(range(len(_SLIPS)), count):
            for combo in itertools.product(*(factors[i] for i in chosen)):
                if abs(value / (expected * math.prod(combo)) - 1.0) <= rtol:
                    said = "; and ".join(_SLIPS[i] for i in chosen)
                    return Feedback(False, f"k = {value:.4g} N/m: {said}. {hint}")
    return check_close("the spring constant k", value, expected, rtol, "N/m", hint)
