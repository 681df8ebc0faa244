"""Exercise checkers of module (f), virtual imaging.

Each checker computes its reference with the library's models (the scanner, the dilation), never
from a stored number, and returns a :class:`~afmsmiler.exercises.Feedback`. A placeholder answer
(``None``) gets "Not yet" and a hint; a unit or sign slip is named (:func:`~afmsmiler.exercises.
diagnose_slip`) without giving the answer. Answers are in SI units.

1. :func:`check_fast_scan`: the fastest scan speed that keeps the RMS error signal below a bound
   on :func:`speed_sample` (constant force, module (c)'s preset (a)).
2. :func:`check_apparent_width` and :func:`check_tip_radius`: a sphere imaged with a paraboloid
   tip (:func:`particle_image`) looks wider; measure the width and find the tip radius back.
3. :func:`check_levelled` and :func:`check_flattening_artefact`: level the tilted scan
   :func:`tilted_image`, and say why line flattening leaves bands beside tall features.

Each checker is an exercise of notebook 06 (:mod:`afmsmiler.exercises.registry`) whose solution
is found as the notebook asks the student to find it, with the library's models
(:func:`fast_scan_speed`, :func:`measured_width`, :func:`tip_radius_from_width`,
:func:`levelled_image`, :func:`flattening_reason`).
"""
from __future__ import annotations

import math
import re
from functools import lru_cache

import numpy as np
from scipy.optimize import brentq

from .. import samples
from ..contact import Parabolic
from ..controller import PRESETS
from ..imaging.corrections import fit_plane, level_plane, mask_features
from ..imaging.dilation import dilate, sphere_apparent_width
from ..imaging.scan_modes import ConstantForce
from ..imaging.scanner import PARAMETERS as SCAN, ScanSettings, scan
from ..parameters import read_only
from ..samples import Sample
from ..validation import check_instance, check_positive
from . import Feedback, check_close, diagnose_slip
from .registry import exercise

__all__ = ["DEFAULTS", "speed_sample", "scan_error", "fastest_speed", "fast_scan_speed",
           "check_fast_scan", "particle_image", "measured_width", "check_apparent_width",
           "tip_radius_from_width", "check_tip_radius", "tilted_image", "substrate_tilt",
           "levelled_image", "check_levelled", "CHOICES", "flattening_reason",
           "check_flattening_artefact"]

#: The exercises' givens, in one place (SI units).
DEFAULTS = read_only(dict(
    # 1. the fastest scan: preset (a)'s loop over small particles, a 200 nm scan of 32 x 8 pixels
    plant="a_good_tracking", tip_radius=10e-9, scan_size=200e-9, pixels=32, lines=8,
    max_rms_error=1e-9, speed_rtol=0.1,
    # 2. a sphere of radius 15 nm on a flat substrate, 1 nm pixels, imaged by a 12 nm paraboloid
    particle_radius=15e-9, particle_pixel=1e-9, particle_pixels=128, width_rtol=0.05,
    radius_rtol=0.1,
    # 3. a 200 nm scan of the particles, tilted by 2 deg along x and 1 deg along y
    tilt=(math.radians(2.0), math.radians(1.0)), level_pixels=64, level_speed=1e-5,
    max_residual_tilt=0.05,
))


#: The radius in m of the tip that made :func:`particle_image` (what exercise 2 asks for).
_TIP_RADIUS = 12e-9


# -- 1. the fastest scan -----------------------------------------------------------------------
def speed_sample() -> Sample:
    """The sample of exercise 1: six particles of radius 10 nm on a 0.2 nm rough substrate.

    Returns
    -------
    Sample
        128 x 128 pixels of 2 nm.
    """
    return samples.particles((128, 128), 2e-9, count=6, radius=10e-9, rms=0.2e-9, seed=2)


def scan_error(speed: float) -> float:
    """RMS error signal (deflection - setpoint) in m of exercise 1's scan at ``speed``.

    The worse of trace and retrace, over the whole image (constant force, preset (a)'s loop, a
    paraboloid tip of :data:`DEFAULTS` ``tip_radius``).

    Parameters
    ----------
    speed : float
        Scan speed in m/s, within the scanner's range (:data:`afmsmiler.imaging.scanner.
        PARAMETERS` ``"scan_speed"``).

    Returns
    -------
    float
        RMS error in m.
    """
    d = DEFAULTS
    settings = ScanSettings(d["scan_size"], pixels=d["pixels"], lines=d["lines"],
                            scan_speed=SCAN["scan_speed"].check(speed))
    result = scan(speed_sample(), Parabolic(radius=d["tip_radius"]),
                  ConstantForce(PRESETS[d["plant"]].loop), settings)
    return max(float(np.sqrt(np.mean(result.images[name] ** 2)))
               for name in ("error trace", "error retrace"))


@lru_cache(maxsize=8)
def fastest_speed(max_rms_error: float = DEFAULTS["max_rms_error"]) -> float:
    """The speed in m/s at which exercise 1's RMS error reaches ``max_rms_error``.

    Brent's method on log(speed) between 1 um/s and 10 mm/s (the error grows with the speed
    there: the loop lags more the faster the topography passes).

    Parameters
    ----------
    max_rms_error : float
        The bound in m, between the errors at the two ends.

    Returns
    -------
    float
        Speed in m/s.

    Raises
    ------
    ValueError
        If the bound is not between the errors at 1 um/s and 10 mm/s.
    """
    lo, hi = math.log(1e-6), math.log(1e-2)

    def excess(log_speed):
        return scan_error(math.exp(log_speed)) - max_rms_error

    a, b = excess(lo), excess(hi)
    if not a < 0 < b:
        raise ValueError(f"max_rms_error must lie between the errors at 1 um/s and 10 mm/s "
                         f"({a + max_rms_error:.3g} m and {b + max_rms_error:.3g} m), got "
                         f"{max_rms_error!r}")
    return math.exp(brentq(excess, lo, hi, xtol=1e-4, maxiter=60))


def fast_scan_speed(max_rms_error: float = DEFAULTS["max_rms_error"],
                    rtol: float = DEFAULTS["speed_rtol"]) -> float:
    """Exercise 1's answer: the fastest speed within the bound, backed off by half of ``rtol``.

    The hint's way: find where the error passes the bound (:func:`fastest_speed`), then back
    off a little, so that the error stays below the bound.

    Parameters
    ----------
    max_rms_error : float
        The bound in m.
    rtol : float
        The checker's tolerance, in (0, 1): the answer is (1 - rtol / 2) times the fastest.

    Returns
    -------
    float
        Speed in m/s.
    """
    max_rms_error = check_positive("max_rms_error", max_rms_error, "m")
    rtol = check_positive("rtol", rtol)
    if rtol >= 1:
        raise ValueError(f"rtol must be in (0, 1), got {rtol!r}")
    return fastest_speed(max_rms_error) * (1.0 - rtol / 2.0)


@exercise("06.1", "The fastest scan", answers=("speed",), solution=fast_scan_speed)
def check_fast_scan(speed, max_rms_error: float = DEFAULTS["max_rms_error"],
                    rtol: float = DEFAULTS["speed_rtol"]) -> Feedback:
    """Exercise 1: the fastest speed whose RMS error signal stays below ``max_rms_error``.

    Parameters
    ----------
    speed : float or None
        The student's scan speed in m/s.
    max_rms_error : float
        The bound in m.
    rtol : float
        How much slower than the fastest speed an answer may be (0.1: at least 90 % of it).

    Returns
    -------
    Feedback
        Passed when the error at ``speed`` (simulated) is at most the bound and ``speed`` is at
        least (1 - rtol) times the fastest speed.
    """
    max_rms_error = check_positive("max_rms_error", max_rms_error, "m")
    rtol = check_positive("rtol", rtol)
    hint = ("Scan faster until the error signal's RMS passes the bound, then back off a little; "
            "the speed in m/s (1 um/s = 1e-6 m/s).")
    if speed is None:
        return Feedback(False, f"enter a scan speed in m/s. {hint}")
    try:
        v = float(speed)
    except (TypeError, ValueError, OverflowError):  # OverflowError: an int such as 10**400
        return Feedback(False, f"speed must be a number in m/s, got {speed!r}.")
    best = fastest_speed(max_rms_error)
    p = SCAN["scan_speed"]
    if not (math.isfinite(v) and p.low <= v <= p.high):
        slip = diagnose_slip(v, best, rtol, "m/s") if math.isfinite(v) else None
        return Feedback(False, slip or f"speed must be in [{p.low:g}, {p.high:g}] m/s, got "
                                       f"{v!r}. {hint}")
    err = scan_error(v)
    shown = f"{p.to_display(v):.4g} {p.display_unit}"
    msg = (f"At {shown} the RMS error signal is {err * 1e9:.3g} nm (bound "
           f"{max_rms_error * 1e9:.3g} nm).")
    if err > max_rms_error:
        slip = diagnose_slip(v, best, rtol, "m/s")
        return Feedback(False, f"{msg} Too fast: the loop cannot follow. " + (slip or hint))
    if v < (1 - rtol) * best:
        slip = diagnose_slip(v, best, rtol, "m/s")
        return Feedback(False, f"{msg} You can scan faster than that. " + (slip or hint))
    return Feedback(True, msg + " That is (close to) the fastest scan within the bound.")


# -- 2. tip dilation widens a nanoparticle -----------------------------------------------------
def particle_image() -> Sample:
    """Exercise 2's image: one sphere on a flat substrate, seen through a paraboloid tip.

    A sphere of radius :data:`DEFAULTS` ``particle_radius`` (top at twice that) centred on a
    flat substrate at height 0, 128 x 128 pixels of 1 nm, dilated by a paraboloid tip whose
    radius the student finds back (:func:`~afmsmiler.imaging.dilation.dilate`).

    Returns
    -------
    Sample
    """
    d = DEFAULTS
    n, dx, r = d["particle_pixels"], d["particle_pixel"], d["particle_radius"]
    x = (np.arange(n) - (n - 1) / 2) * dx
    rho2 = x[None, :] ** 2 + x[:, None] ** 2
    heights = np.where(rho2 < r * r, r + np.sqrt(np.maximum(r * r - rho2, 0.0)), 0.0)
    return dilate(Sample(heights, dx, "a sphere on a flat substrate"),
                  Parabolic(radius=_TIP_RADIUS))


def measured_width() -> float:
    """Exercise 2a's answer measured on :func:`particle_image` as the notebook says.

    The pixels above the substrate (height > 0) on the line through the particle's top,
    times the pixel size.

    Returns
    -------
    float
        W in m.
    """
    image = particle_image()
    top = np.unravel_index(np.argmax(image.heights), image.heights.shape)[0]
    return float(np.count_nonzero(image.heights[top] > 0.0) * image.pixel_size)


@exercise("06.2a", "Tip dilation: the apparent width", answers=("width",),
          solution=measured_width)
def check_apparent_width(width, rtol: float = DEFAULTS["width_rtol"]) -> Feedback:
    """Exercise 2a: the apparent width in m of the particle in :func:`particle_image`.

    Parameters
    ----------
    width : float or None
        The width at the substrate's level in m.
    rtol : float
        Accepted relative error (a pixel or two of the 1 nm grid).

    Returns
    -------
    Feedback
        Against the analytic width of a sphere under a paraboloid
        (:func:`~afmsmiler.imaging.dilation.sphere_apparent_width`).
    """
    rtol = check_positive("rtol", rtol)
    if width is None:
        return Feedback(False, "measure the width of the particle where it leaves the "
                               "substrate (height > 0) on the line through its top, in m.")
    d = DEFAULTS
    expected = sphere_apparent_width(d["particle_radius"], Parabolic(radius=_TIP_RADIUS))
    return check_close("apparent width", width, expected, rtol, "m",
                       hint="Take the line through the particle's top and count the pixels "
                            "above the substrate (times the pixel size).")


def _two_spheres(width: float, particle_radius: float) -> float:
    """The tip radius that two touching spheres give: W = 4 sqrt(R r), so R = W^2 / (16 r)."""
    return width * width / (16.0 * particle_radius)


def tip_radius_from_width() -> float:
    """Exercise 2b's answer: the paraboloid's radius in m that gives the measured width.

    The root R of ``sphere_apparent_width(r, Parabolic(R)) = W`` (Brent's method between 0.1 nm
    and 1 um) for the width :func:`measured_width` finds on the image: the model's forward
    width inverted, not the radius the image was made with.

    Returns
    -------
    float
        R in m.
    """
    r, width = DEFAULTS["particle_radius"], measured_width()
    return float(brentq(lambda radius: sphere_apparent_width(r, Parabolic(radius=radius)) - width,
                        1e-10, 1e-6, xtol=1e-15))


@exercise("06.2b", "Tip dilation: the tip's radius", answers=("radius",),
          solution=tip_radius_from_width)
def check_tip_radius(radius, rtol: float = DEFAULTS["radius_rtol"]) -> Feedback:
    """Exercise 2b: the radius in m of the paraboloid tip that imaged :func:`particle_image`.

    Parameters
    ----------
    radius : float or None
        The student's tip radius R in m.
    rtol : float
        Accepted relative error.

    Returns
    -------
    Feedback
        Against the radius the image was made with. Using the two-spheres formula
        W = 4 sqrt(R r), which the paraboloid's flanks do not follow, is recognised.
    """
    rtol = check_positive("rtol", rtol)
    hint = ("For a paraboloid over a sphere of radius r, with w = W / (2 r): solve "
            "w = (1 + c)^(3/2) / (1 - c)^(1/2) for c in (0, 1), then R = 2 r c^2 / (1 - c).")
    if radius is None:
        return Feedback(False, f"enter the tip radius in m. {hint}")
    d = DEFAULTS
    true = _TIP_RADIUS
    try:
        value = float(radius)
    except (TypeError, ValueError, OverflowError):  # OverflowError: an int such as 10**400
        return Feedback(False, f"radius must be a number in m, got {radius!r}.")
    width = sphere_apparent_width(d["particle_radius"], Parabolic(radius=true))
    spheres = _two_spheres(width, d["particle_radius"])
    if math.isfinite(value) and abs(value - spheres) <= 0.1 * spheres \
            and abs(value - true) > rtol * true:
        return Feedback(False, f"tip radius = {value:.4g} m is what two touching spheres give "
                               "(W = 4 sqrt(R r)); the paraboloid's flanks open wider than a "
                               f"sphere's, so this overestimates R. {hint}")
    return check_close("tip radius", value, true, rtol, "m", hint=hint)


# -- 3. levelling and line flattening ----------------------------------------------------------
def _levelling_scan(tilt) -> Sample:
    d = DEFAULTS
    settings = ScanSettings(d["scan_size"], pixels=d["level_pixels"], scan_speed=d["level_speed"],
                            tilt=tilt)
    result = scan(speed_sample(), Parabolic(radius=d["tip_radius"]),
                  ConstantForce(PRESETS[d["plant"]].loop), settings)
    return result.channels["height trace"]


def tilted_image() -> Sample:
    """Exercise 3's image: the particles of exercise 1 scanned slowly on a tilted sample.

    Constant force at 10 um/s, 64 x 64 pixels over 200 nm, the sample tilted by
    :data:`DEFAULTS` ``tilt`` (2 deg along x, 1 deg along y).

    Returns
    -------
    Sample
        The height trace image.
    """
    return _levelling_scan(DEFAULTS["tilt"])


def substrate_tilt(image: Sample) -> tuple[float, float]:
    """The substrate's slopes (x, y) in an image of exercise 3's scan, the particles left out.

    The substrate is where the same scan of the untilted sample lies within 1 nm of its median:
    the particles stand 20 nm above it.

    Parameters
    ----------
    image : Sample
        An image on the grid of :func:`tilted_image`.

    Returns
    -------
    tuple of float
        (slope_x, slope_y), dimensionless (the tangents of the tilt angles).
    """
    check_instance("image", image, Sample)
    flat = _levelling_scan((0.0, 0.0)).heights
    particles = flat > np.median(flat) + 1e-9
    plane = fit_plane(image, particles)
    return plane.slope_x, plane.slope_y


def levelled_image() -> Sample:
    """Exercise 3a's answer: :func:`tilted_image` levelled with its particles masked out.

    Plane levelled once to find the particles (:func:`~afmsmiler.imaging.corrections.
    mask_features` wants a level image), then levelled again with them left out of the fit.

    Returns
    -------
    Sample
    """
    tilted = tilted_image()
    return level_plane(tilted, mask_features(level_plane(tilted)))


@exercise("06.3a", "Levelling and its artefacts: levelling", answers=("image",),
          solution=levelled_image)
def check_levelled(image, max_residual: float = DEFAULTS["max_residual_tilt"]) -> Feedback:
    """Exercise 3a: a levelled copy of :func:`tilted_image`, its substrate no longer tilted.

    Parameters
    ----------
    image : Sample or None
        The student's levelled image (same grid as :func:`tilted_image`).
    max_residual : float
        Largest substrate slope left, as a fraction of the tilt's (0.05: 5 %).

    Returns
    -------
    Feedback
    """
    max_residual = check_positive("max_residual", max_residual)
    hint = ("Fit a plane and subtract it (level_plane); the particles must not take part in the "
            "fit, or they tilt the plane: mask them (mask_features) and level again.")
    if image is None:
        return Feedback(False, f"level the image and pass the result. {hint}")
    try:
        image = check_instance("image", image, Sample)
    except TypeError as err:
        return Feedback(False, f"{err}.")
    if image.heights.shape != (DEFAULTS["level_pixels"],) * 2:
        return Feedback(False, f"image must be a levelled copy of tilted_image() (shape "
                               f"{(DEFAULTS['level_pixels'],) * 2}), got shape "
                               f"{image.heights.shape}.")
    tilt = np.hypot(*np.tan(DEFAULTS["tilt"]))
    left = float(np.hypot(*substrate_tilt(image)))
    degrees = math.degrees(math.atan(left))
    if left <= max_residual * tilt:
        return Feedback(True, f"the substrate is level to {degrees:.2g} deg.")
    return Feedback(False, f"the substrate is still tilted by {degrees:.2g} deg "
                           f"({100 * left / tilt:.0f}% of the tilt). {hint}")


#: Exercise 3b's choices: why does line flattening leave dark bands beside a tall particle?
CHOICES = read_only({
    "a": "The tip is wider than the particle, so the particle looks broader.",
    "b": "Each line is flattened by its own median or fit, which the particle's pixels pull up: "
         "the lines that cross the particle are lowered more than the others, so the substrate "
         "beside it looks darker (masking the particle out of the fit avoids it).",
    "c": "The feedback loop overshoots at the particle's edges.",
    "d": "Plane levelling tilts the particle.",
})

_RIGHT = "b"
#: Words that say the idea of answer (b) in one's own words: a line's own reference (median,
#: mean, fit, offset) is shifted by the feature.
_LINE = re.compile(r"\b(line|lines|row|rows|scan ?line)\b", re.I)
_REFERENCE = re.compile(r"\b(median|mean|average|fit|fitted|polynomial|offset|background)\b",
                        re.I)
_FEATURE = re.compile(r"\b(particle|feature|tall|high|bump|peak|island)s?\b", re.I)


def flattening_reason() -> str:
    """Exercise 3b's answer: the letter of :data:`CHOICES` that says why.

    Returns
    -------
    str
    """
    return _RIGHT


@exercise("06.3b", "Levelling and its artefacts: line flattening", answers=("answer",),
          solution=flattening_reason)
def check_flattening_artefact(answer) -> Feedback:
    """Exercise 3b: why line flattening creates artefacts around tall features.

    Parameters
    ----------
    answer : str or None
        A letter of :data:`CHOICES`, or the reason in one's own words.

    Returns
    -------
    Feedback
        A letter is judged; a sentence passes when it names the line (row), its reference
        (median, mean, fit, offset) and the tall feature.
    """
    if answer is None:
        return Feedback(False, "choose a letter of CHOICES, or explain in a sentence.")
    if not isinstance(answer, str):
        return Feedback(False, f"answer must be a letter or a sentence, got {answer!r}.")
    text = answer.strip()
    if text.lower() in CHOICES:
        if text.lower() == _RIGHT:
            return Feedback(True, "each line's reference includes the particle.")
        why = {"a": "that is tip dilation: it widens the particle, it does not darken the "
                    "substrate beside it.",
               "c": "loop overshoot shows at the edges along the fast axis in trace and "
                    "retrace differently, and a slow scan has none; the bands are there anyway.",
               "d": "a plane is subtracted from every pixel alike: it does not tilt a feature "
                    "against its substrate."}[text.lower()]
        return Feedback(False, f"{why} Compare the lines that cross the particle with those "
                               "that do not, before and after flatten_lines.")
    if _LINE.search(text) and _REFERENCE.search(text) and _FEATURE.search(text):
        return Feedback(True, "the particle shifts the reference of the lines that cross it.")
    return Feedback(False, "think of what flatten_lines subtracts from each line, and what "
                           "the particle does to it on the lines that cross it.")
