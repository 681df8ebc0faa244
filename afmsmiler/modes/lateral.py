"""Lateral force (friction force) microscopy: torsion, the lateral signal, loops and maps.

A tip of height h (apex to the lever's mid-plane) sliding over a sample feels a lateral force
F_L at its apex, perpendicular to the lever's long axis. Its torque F_L h twists the lever about
that axis by phi = F_L h / k_phi, with the torsional stiffness of a thin rectangular beam of
length L, width w, thickness t and shear modulus G (Saint-Venant torsion of a thin plate,
w >> t: Timoshenko and Goodier, *Theory of Elasticity*; the expression used for AFM levers by
Neumeister and Ducker, Rev. Sci. Instrum. 65, 2527 (1994), in its thin-plate limit)::

    k_phi = G w t^3 / (3 L)          (N m / rad)
    k_t   = k_phi / h^2 = G w t^3 / (3 L h^2)      (N/m, lateral force per apex displacement)

For a plate of finite w / t the factor 1/3 becomes about 1/3 (1 - 0.630 t / w) (Roark's
*Formulas for Stress and Strain*, torsion of a rectangular section; 2.5 % less for w / t = 25,
the default lever); this model keeps the thin-plate value. The torsional stiffness is the
lever's own, :attr:`afmsmiler.planform.Lever.torsional_stiffness` (module (a)), for every
planform: a :class:`~afmsmiler.planform.Lever` (pointed, V-shaped) brings its shear modulus
and tip height; a rectangular :class:`~afmsmiler.cantilever.Cantilever` is given G here,
by default G = E / (2 (1 + nu)) of the isotropic silicon preset (:func:`shear_modulus`; a <110>
silicon lever's true 50.9 GPa is the material preset's
:attr:`~afmsmiler.materials.Material.shear_modulus`).

The twist tilts the reflecting end sideways, so the reflected beam turns by 2 phi and the spot
moves across the four-quadrant photodiode by D tan(2 phi): exactly the optical lever of module
(b) (:class:`~afmsmiler.transducers.optical.OpticalBeamDeflection`) turned by 90 degrees, whose
left-minus-right signal is erf(sqrt(2) s / w_spot) (:meth:`LateralLever.signal`).

Friction and slope (Ogletree, Carpick and Salmeron, Rev. Sci. Instrum. 67, 3298 (1996)): on a
surface inclined by theta along the scan, at a load F_N and friction coefficient mu, the
lateral force the lever exerts while the tip slides forwards (s = +1, trace) or backwards
(s = -1, retrace) is, to first order in theta and mu (``model="linear"``)::

    F_L = F_N (s mu + tan(theta))

(friction flips sign with the scan direction, the slope term does not), and exactly, from the
balance of the normal and friction forces on the tilted contact (``model="wedge"``)::

    F_L = F_N (sin(theta) + s mu cos(theta)) / (cos(theta) - s mu sin(theta))

so that half the trace-minus-retrace difference is the friction force mu F_N (exactly in the
linear model; mu F_N (1 + tan^2 theta) / (1 - mu^2 tan^2 theta) on the wedge) and half the sum
the slope term. At each turn-around the tip sticks until the lever has loaded the friction force
in the other direction: the force then changes at the lateral stiffness (the lever's k_t, or
its series with the contact's; Carpick, Ogletree and Salmeron, Appl. Phys. Lett. 70, 1548
(1997)) over a support travel
of 2 mu F_N / k_t, the vertical edges of a friction loop.

Module (g) of the AFM SMILER toolkit ("AFM SMILER: A Scale Model Interactive Learning Extended
Reality Toolkit for Atomic Force Microscopy Created with Digital Twin Technology") only animates
the lateral twist; this module computes what the lateral-force mode measures.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..cantilever import Cantilever
from ..planform import Lever
from ..imaging.scan_modes import Mode, ModeLine, ScanPlan
from ..materials import MATERIALS, Material, lookup
from ..parameters import Parameter, read_only
from ..samples import Sample
from ..samples.sample import check_shape
from ..transducers.optical import OpticalBeamDeflection
from ..validation import check_array, check_choice, check_instance, check_integer

__all__ = ["LateralLever", "FrictionLoop", "FrictionImages", "LateralForceMode",
           "shear_modulus", "lateral_force", "friction_loop", "friction_scan", "friction_sample",
           "PARAMETERS", "MODELS", "SHEAR_MODULUS", "TIP_HEIGHT", "NORMAL_FORCE",
           "FRICTION_COEFFICIENT", "LATERAL_STIFFNESS", "LATERAL_NOISE", "TILT", "LATERAL_FORCE",
           "MAX_LATERAL_FORCE"]

#: The two ways of combining friction and slope (module notes).
MODELS = ("linear", "wedge")

# -- the parameter vocabulary of the lateral-force mode --------------------------------------
#: Shear modulus G; default that of the silicon preset, E<110> / (2 (1 + nu)) = 79.4 GPa.
SHEAR_MODULUS = Parameter(name="shear_modulus", unit="Pa", display_unit="GPa",
                          default=MATERIALS["silicon"].youngs_modulus
                          / (2 * (1 + MATERIALS["silicon"].poisson_ratio)), low=1.0, high=1e13,
                          slider_low=10e9, slider_high=200e9, label="shear modulus G")
#: Tip height h, from the apex to the lever's mid-plane.
TIP_HEIGHT = Parameter(name="tip_height", unit="m", display_unit="um", default=15e-6, low=1e-9,
                       high=1e-3, slider_low=1e-6, slider_high=30e-6, label="tip height h")
#: Normal load F_N that the feedback keeps constant.
NORMAL_FORCE = Parameter(name="normal_force", unit="N", display_unit="nN", default=20e-9,
                         low=0.0, high=1e-3, low_inclusive=False, slider_low=1e-9,
                         slider_high=200e-9, label="normal load F_N")
#: Friction coefficient mu (kinetic, Amontons: friction = mu F_N).
FRICTION_COEFFICIENT = Parameter(name="friction_coefficient", unit="", default=0.2, low=0.0,
                                 high=10.0, slider_low=0.0, slider_high=1.0,
                                 label="friction coefficient mu")
#: Lateral stiffness of the stuck tip at a turn-around: the lever's k_t (about 100 N/m for the
#: default lever and tip, :class:`LateralLever`), or its series with the contact's.
LATERAL_STIFFNESS = Parameter(name="lateral_stiffness", unit="N/m", default=100.0, low=0.0,
                              high=1e6, low_inclusive=False, slider_low=1.0, slider_high=1000.0,
                              log=True, label="lateral stiffness")
#: RMS noise of the lateral force channels.
LATERAL_NOISE = Parameter(name="lateral_noise", unit="N", display_unit="nN", default=0.0,
                          low=0.0, high=1e-3, slider_low=0.0, slider_high=2e-9,
                          label="lateral noise (RMS)")
#: Tilt of the synthetic sample along the fast axis (a sample plane not levelled).
TILT = Parameter(name="tilt", unit="rad", display_unit="deg", default=0.0,
                 low=-math.radians(60), high=math.radians(60), slider_low=-math.radians(20),
                 slider_high=math.radians(20), label="sample tilt")

#: Every user-settable quantity of the lateral-force mode, by keyword name (read-only).
PARAMETERS = read_only({p.name: p for p in (SHEAR_MODULUS, TIP_HEIGHT, NORMAL_FORCE,
                                            FRICTION_COEFFICIENT, LATERAL_STIFFNESS,
                                            LATERAL_NOISE, TILT)})


def shear_modulus(material: str | Material) -> float:
    """Shear modulus G = E / (2 (1 + nu)) in Pa of an isotropic material.

    Parameters
    ----------
    material : str or Material
        A key of :data:`afmsmiler.materials.MATERIALS` or a Material.

    Returns
    -------
    float
        G in Pa (79.4 GPa for the silicon preset, 102 GPa for silicon nitride).
    """
    m = lookup(material, "material")
    return m.youngs_modulus / (2 * (1 + m.poisson_ratio))


#: The largest lateral force in N a lever's twist is computed for: 1 mN, a million times an AFM
#: tip's nN friction (a larger value is a unit slip, and its twist would overflow).
MAX_LATERAL_FORCE = 1e-3
#: The lateral (friction) force at the tip apex that twists the lever, as a control.
LATERAL_FORCE = Parameter(name="lateral_force", unit="N", display_unit="nN", default=100e-9,
                          low=-MAX_LATERAL_FORCE, high=MAX_LATERAL_FORCE, slider_low=-500e-9,
                          slider_high=500e-9, label="friction force at the apex F_L")

@dataclass(frozen=True)
class LateralLever:
    """A rectangular lever with a tip, twisted by the lateral force at the apex.

    Parameters
    ----------
    lever : Cantilever or Lever
        The lever (module (a)): a rectangular Cantilever (length L, width w, thickness t), or a
        :class:`~afmsmiler.planform.Lever` of any planform.
    tip_height : float or None
        Tip height h in m, apex to the lever's mid-plane; None: the Lever's
        :attr:`~afmsmiler.planform.Lever.apex_lever_arm` (h_tip + t/2), or
        :data:`TIP_HEIGHT`'s default for a Cantilever.
    shear_modulus : float or None
        Shear modulus G of the lever's material in Pa; None: the Lever's, or
        :data:`SHEAR_MODULUS`'s default for a Cantilever (:func:`shear_modulus`).
    optics : OpticalBeamDeflection or None
        The optical lever reading the twist (module (b)); None: its defaults.

    Raises
    ------
    TypeError
        If ``lever`` or ``optics`` is of the wrong type.
    ValueError
        If a number is out of range (:data:`PARAMETERS`).

    Examples
    --------
    >>> from afmsmiler.cantilever import Cantilever
    >>> lever = Cantilever.from_material("silicon", length=450e-6, width=50e-6, thickness=2e-6)
    >>> lat = LateralLever(lever, tip_height=15e-6)
    >>> round(lat.spring_constant, 1)  # N/m: G w t^3 / (3 L h^2), some 500 times k
    104.6
    """

    lever: Cantilever | Lever
    tip_height: float | None = None
    shear_modulus: float | None = None
    optics: OpticalBeamDeflection | None = None

    def __post_init__(self):
        lever = check_instance("lever", self.lever, (Cantilever, Lever), "Cantilever or Lever")
        planform = isinstance(lever, Lever)
        h = (lever.apex_lever_arm if planform else TIP_HEIGHT.default) \
            if self.tip_height is None else self.tip_height
        g = (lever.shear_modulus if planform else SHEAR_MODULUS.default) \
            if self.shear_modulus is None else self.shear_modulus
        object.__setattr__(self, "tip_height", TIP_HEIGHT.check(h))
        object.__setattr__(self, "shear_modulus", SHEAR_MODULUS.check(g))
        # module (a)'s lever carries the torsion: a Cantilever becomes its rectangular Lever; a
        # Lever of this G is used as it is, so its torsion (a frame model, 1.5-6.5 ms) is solved
        # once per lever, not once per LateralLever (a panel makes one per move)
        if planform and lever.shear_modulus == self.shear_modulus:
            body = lever
        else:
            body = (lever.with_(shear_modulus=self.shear_modulus) if planform
                    else Lever.from_cantilever(lever, self.shear_modulus))
        object.__setattr__(self, "_body", body)
        optics = OpticalBeamDeflection() if self.optics is None else self.optics
        object.__setattr__(self, "optics", check_instance("optics", optics,
                                                          OpticalBeamDeflection))

    @property
    def body(self) -> Lever:
        """The lever as module (a)'s :class:`~afmsmiler.planform.Lever` (with this G)."""
        return self._body

    @property
    def torsional_stiffness(self) -> float:
        """k_phi in N m/rad (torque per twist angle at the tip): the lever's
        :attr:`~afmsmiler.planform.Lever.torsional_stiffness`, G w t^3 / (3 L) for a rectangle."""
        return self._body.torsional_stiffness

    @property
    def spring_constant(self) -> float:
        """Lateral spring constant k_t = k_phi / h^2 in N/m (force per apex displacement)."""
        return self.torsional_stiffness / self.tip_height ** 2

    def twist(self, lateral_force):
        """Twist angle phi = F_L h / k_phi in rad of the free end.

        Parameters
        ----------
        lateral_force : float or array_like
            Lateral force F_L in N at the apex, within +-:data:`MAX_LATERAL_FORCE` (1 mN).

        Returns
        -------
        float or ndarray
            phi in rad.
        """
        f = check_array("lateral_force", lateral_force, "N", low=-MAX_LATERAL_FORCE,
                        high=MAX_LATERAL_FORCE)
        phi = f * self.tip_height / self.torsional_stiffness
        return phi if f.ndim else float(phi)

    def signal(self, lateral_force):
        """Lateral photodiode signal ((A + C) - (B + D)) / (A + B + C + D) for a lateral force.

        Parameters
        ----------
        lateral_force : float or array_like
            Lateral force F_L in N at the apex (the twist must stay below pi / 4).

        Returns
        -------
        float or ndarray
            erf(sqrt(2) s / w_spot), s = D tan(2 phi) (module (b)'s optical lever, turned).

        Raises
        ------
        ValueError
            If a twist reaches pi / 4, naming ``lateral_force`` and its limit.
        """
        phi = self.twist(lateral_force)
        if np.any(np.abs(phi) >= math.pi / 4):
            limit = math.pi / 4 * self.torsional_stiffness / self.tip_height
            raise ValueError(f"lateral_force must be within +-{limit:g} N (a twist of pi/4, "
                             f"beyond which the beam misses the detector), got "
                             f"{np.max(np.abs(lateral_force)):g} N")
        out = self.optics.split_signal(self.optics.spot_displacement(phi))
        return out if np.ndim(out) else float(out)


def lateral_force(slope, friction_coefficient, direction, *,
                  normal_force: float = NORMAL_FORCE.default, model: str = "linear"):
    """Lateral force F_L in N on a sliding tip (friction plus slope).

    Parameters
    ----------
    slope : float or array_like
        Surface angle theta in rad along the scan direction x (atan of dh/dx), in (-pi/2, pi/2).
    friction_coefficient : float or array_like
        mu (broadcasts against ``slope``), in [0, 10].
    direction : int
        +1 (trace, tip moving towards +x) or -1 (retrace).
    normal_force : float
        Normal load F_N in N.
    model : str
        ``"linear"``: F_N (s mu + tan theta); ``"wedge"``: the exact balance on the tilted
        contact, F_N (sin theta + s mu cos theta) / (cos theta - s mu sin theta) (module notes).

    Returns
    -------
    float or ndarray
        F_L in N, the force the lever exerts on the tip along +x to drag it (positive on a
        flat trace).

    Raises
    ------
    ValueError
        Naming the argument out of range; for the wedge, where the contact locks
        (cos theta - s mu sin theta <= 0: friction cone reached).
    """
    theta = check_array("slope", slope, "rad", low=-math.pi / 2, high=math.pi / 2,
                        low_inclusive=False, high_inclusive=False)
    mu = check_array("friction_coefficient", friction_coefficient, "",
                     low=FRICTION_COEFFICIENT.low, high=FRICTION_COEFFICIENT.high)
    s = check_choice("direction", check_integer("direction", direction, -1, 1), (1, -1))
    load = NORMAL_FORCE.check(normal_force)
    check_choice("model", model, MODELS)
    if model == "linear":
        out = load * (s * mu + np.tan(theta))
    else:
        denominator = np.cos(theta) - s * mu * np.sin(theta)
        if np.any(denominator <= 0):
            raise ValueError("slope and friction_coefficient lock the contact (cos(theta) - s mu "
                             "sin(theta) <= 0: mu tan(theta) >= 1 going uphill); the wedge model "
                             "needs mu tan(theta) < 1")
        out = load * (np.sin(theta) + s * mu * np.cos(theta)) / denominator
    return out if out.ndim else float(out)


@dataclass(frozen=True)
class FrictionLoop:
    """Trace and retrace lateral force along one line (:func:`friction_loop`).

    Attributes
    ----------
    x : ndarray
        Support position along the line in m (increasing; the retrace runs back over it).
    trace, retrace : ndarray
        Lateral force F_L in N at each x on the way out and back.
    normal_force : float
        The load F_N in N.
    lateral_stiffness : float
        Stiffness in N/m of the stuck phases at the turn-arounds.
    """

    x: np.ndarray
    trace: np.ndarray
    retrace: np.ndarray
    normal_force: float
    lateral_stiffness: float

    @property
    def friction(self) -> np.ndarray:
        """(trace - retrace) / 2 in N: the friction force (mu F_N)."""
        return (self.trace - self.retrace) / 2

    @property
    def slope_term(self) -> np.ndarray:
        """(trace + retrace) / 2 in N: the slope term (F_N tan theta)."""
        return (self.trace + self.retrace) / 2

    @property
    def friction_coefficient(self) -> np.ndarray:
        """Friction / F_N (dimensionless): mu where the tip slides both ways."""
        return self.friction / self.normal_force

    @property
    def dissipated_energy(self) -> float:
        """Area of the loop in J: the work friction dissipates over one trace-retrace cycle."""
        d = self.trace - self.retrace
        return float(np.sum(0.5 * (d[1:] + d[:-1]) * np.diff(self.x)))


def _stick(slide, start, stiffness, travel):
    """Rows of ``slide`` (sliding force along each pass, in pass order) with the stuck start:
    the force rises from ``start`` by stiffness x travel until it meets the sliding curve."""
    line = start[:, None] + stiffness * travel[None, :]
    met = line >= slide
    first = np.where(met.any(axis=1), np.argmax(met, axis=1), slide.shape[1])
    stuck = np.arange(slide.shape[1])[None, :] < first[:, None]
    return np.where(stuck, line, slide)


def _passes(heights, mu, pixel_size, normal_force, stiffness, model, name="heights"):
    """Trace and retrace lateral forces of (rows, pixels) heights and mu, the stuck starts
    included (each trace starting from the row's own retrace end: a steady loop). ``name`` is
    the caller's parameter that holds the heights: a surface with a vertical slope (which no
    tip can slide along) is refused naming it."""
    with np.errstate(over="ignore", invalid="ignore"):
        slope = np.arctan(np.gradient(heights, pixel_size, axis=-1))
    steepest = float(np.max(np.abs(slope))) if slope.size else 0.0
    if not steepest < math.pi / 2:
        raise ValueError(f"{name} must have slopes below 90 degrees along the scan (a tip cannot "
                         f"slide up a wall), got a slope of {math.degrees(steepest):.6g} degrees")
    slide_t = lateral_force(slope, mu, 1, normal_force=normal_force, model=model)
    slide_r = lateral_force(slope, mu, -1, normal_force=normal_force, model=model)
    slide_t, slide_r = np.atleast_2d(slide_t), np.atleast_2d(slide_r)
    travel = np.arange(slide_t.shape[1]) * pixel_size
    trace = _stick(slide_t, slide_r[:, 0], stiffness, travel)
    # the retrace, in its own order (from the last column back), falls from the trace's end
    retrace = -_stick(-slide_r[:, ::-1], -trace[:, -1], stiffness, travel)[:, ::-1]
    return trace, retrace


def friction_loop(heights, friction_coefficient, pixel_size: float, *,
                  normal_force: float = NORMAL_FORCE.default,
                  lateral_stiffness: float = LATERAL_STIFFNESS.default,
                  model: str = "linear") -> FrictionLoop:
    """Friction loop (trace and retrace lateral force) of a tip scanning one line.

    Parameters
    ----------
    heights : array_like
        Surface height in m along the line, 2 to 2^20 pixels.
    friction_coefficient : float or array_like
        mu, one value or one per pixel.
    pixel_size : float
        Spacing of the pixels in m.
    normal_force : float
        Load F_N in N, held constant by the feedback.
    lateral_stiffness : float
        Stiffness in N/m while the tip sticks at a turn-around (the lever's
        :attr:`LateralLever.spring_constant`, or its series with the contact's), up to 10^6.
    model : str
        ``"linear"`` or ``"wedge"`` (:func:`lateral_force`).

    Returns
    -------
    FrictionLoop

    Raises
    ------
    ValueError
        Naming the argument out of range, before any work.

    Notes
    -----
    The slope is theta = atan(dh/dx) by second-order differences. Sliding, F_L follows
    :func:`lateral_force`; at each start of a pass the tip sticks and F_L changes by
    lateral_stiffness x travel from the other pass's end value until it meets the sliding
    value (a steady loop: the trace starts where the retrace ends). The tip's lag behind the
    support while sliding (F_L / k_t, below a nanometre) is neglected.

    Examples
    --------
    On a flat line the loop is a parallelogram, mu F_N high, stuck over 2 mu F_N / k:

    >>> loop = friction_loop(np.zeros(101), 0.2, 1e-9, normal_force=10e-9,
    ...                      lateral_stiffness=1.0)
    >>> loop.trace[[0, 2, 4, 100]] / 1e-9  # nN
    array([-2.,  0.,  2.,  2.])
    """
    h = check_array("heights", heights, "m", ndim=1, min_size=2, max_size=1 << 20)
    mu = check_array("friction_coefficient", friction_coefficient, "",
                     low=FRICTION_COEFFICIENT.low, high=FRICTION_COEFFICIENT.high)
    if mu.ndim and mu.shape != h.shape:
        raise ValueError(f"friction_coefficient must be one value or one per pixel "
                         f"({h.size}), got shape {mu.shape}")
    px = check_array("pixel_size", pixel_size, "m", low=0.0, low_inclusive=False, ndim=0).item()
    load = NORMAL_FORCE.check(normal_force)
    k = LATERAL_STIFFNESS.check(lateral_stiffness)
    check_choice("model", model, MODELS)
    trace, retrace = _passes(h, mu, px, load, k, model)
    return FrictionLoop(np.arange(h.size) * px, trace[0], retrace[0], load, k)


@dataclass(frozen=True)
class FrictionImages:
    """Lateral-force images of a scan (:func:`friction_scan`), all Samples in N or mu.

    Attributes
    ----------
    trace, retrace : Sample
        Lateral force F_L in N (noise included), columns in increasing x for both.
    normal_force : float
        The load F_N in N.
    """

    trace: Sample
    retrace: Sample
    normal_force: float

    @property
    def friction(self) -> Sample:
        """Friction map (trace - retrace) / 2 in N."""
        return self.trace.with_heights((self.trace.heights - self.retrace.heights) / 2,
                                       name="friction (trace - retrace) / 2")

    @property
    def slope_term(self) -> Sample:
        """Slope (topography) map (trace + retrace) / 2 in N."""
        return self.trace.with_heights((self.trace.heights + self.retrace.heights) / 2,
                                       name="slope term (trace + retrace) / 2")

    @property
    def friction_coefficient(self) -> Sample:
        """Friction map over the load, mu (dimensionless)."""
        mu = (self.trace.heights - self.retrace.heights) / (2 * self.normal_force)
        return Sample(mu, self.trace.pixel_size, "friction coefficient",
                      self.trace.pixel_size_y, channel="friction coefficient", unit="")


def _lateral_sample(values, like: Sample, name):
    return Sample(values, like.pixel_size, name, like.pixel_size_y, channel=name, unit="N")


def friction_scan(topography: Sample, friction: Sample, *,
                  normal_force: float = NORMAL_FORCE.default,
                  lateral_stiffness: float = LATERAL_STIFFNESS.default,
                  lateral_noise: float = LATERAL_NOISE.default, model: str = "linear",
                  seed: int | None = 0) -> FrictionImages:
    """Trace and retrace lateral-force images of a sample with a friction-coefficient map.

    Parameters
    ----------
    topography : Sample
        Heights in m (an image, or a line).
    friction : Sample
        Friction coefficient mu on the same grid (unit ``""``).
    normal_force : float
        Load F_N in N (ideal feedback: constant).
    lateral_stiffness : float
        Stiffness in N/m of the stuck phases at the turn-arounds (:func:`friction_loop`).
    lateral_noise : float
        RMS in N of white Gaussian noise added to each trace and retrace pixel.
    model : str
        ``"linear"`` or ``"wedge"`` (:func:`lateral_force`).
    seed : int or None
        Seed of the noise (numpy's default_rng); None draws fresh noise on every call.

    Returns
    -------
    FrictionImages

    Notes
    -----
    Every line is a steady loop (:func:`friction_loop`, row by row, vectorised over the rows):
    the first pixel of the trace and the last of the retrace are always in the stuck
    turn-around (more of them when 2 mu F_N / lateral_stiffness exceeds a pixel; 0.08 nm at
    the defaults), so the friction map is 0 in the first and last columns, as on an instrument.

    Raises
    ------
    TypeError
        If ``topography`` or ``friction`` is not a Sample.
    ValueError
        Naming the argument out of range or a grid that differs, before any work.
    """
    check_instance("topography", topography, Sample)
    check_instance("friction", friction, Sample)
    if topography.unit != "m":
        raise ValueError(f"topography must hold heights in m, got unit {topography.unit!r}")
    if friction.unit != "":
        raise ValueError(f"friction must hold friction coefficients (unit ''), got unit "
                         f"{friction.unit!r}")
    if (friction.shape != topography.shape or friction.pixel_size != topography.pixel_size
            or friction.pixel_size_y != topography.pixel_size_y):
        raise ValueError(f"friction must be on the grid of topography {topography.shape} at "
                         f"{topography.pixel_size:g} m, got {friction.shape} at "
                         f"{friction.pixel_size:g} m")
    mu = check_array("friction", friction.heights, "", low=FRICTION_COEFFICIENT.low,
                     high=FRICTION_COEFFICIENT.high)
    load = NORMAL_FORCE.check(normal_force)
    k = LATERAL_STIFFNESS.check(lateral_stiffness)
    noise = LATERAL_NOISE.check(lateral_noise)
    check_choice("model", model, MODELS)
    if seed is not None:
        seed = check_integer("seed", seed, 0)
    trace, retrace = _passes(topography.heights, mu, topography.pixel_size, load, k, model,
                             "topography")
    trace, retrace = trace.reshape(mu.shape), retrace.reshape(mu.shape)
    if noise > 0:
        rng = np.random.default_rng(seed)
        trace = trace + rng.normal(0.0, noise, trace.shape)
        retrace = retrace + rng.normal(0.0, noise, retrace.shape)
    return FrictionImages(_lateral_sample(trace, topography, "lateral trace"),
                          _lateral_sample(retrace, topography, "lateral retrace"), load)


def friction_sample(shape=(64, 64), pixel_size: float = 10e-9, *,
                    coefficients=(0.1, 0.4), tilt: float = TILT.default,
                    bump_height: float = 0.0) -> tuple[Sample, Sample]:
    """A synthetic two-material sample: topography and friction-coefficient map.

    Material B (``coefficients[1]``) fills a centred disc of a third of the width and a stripe
    along the slow axis over the last quarter of the columns; material A the rest. The
    topography is a plane tilted by ``tilt`` along the fast axis plus, if ``bump_height`` is
    set, a smooth cosine ridge along the slow axis over the second quarter of the columns (a
    topographic feature made of material A: its slopes must not show in the friction map).

    Parameters
    ----------
    shape : int or tuple of int
        Pixels of a line, or (rows, columns) of an image.
    pixel_size : float
        Pixel spacing in m.
    coefficients : tuple of float
        mu of materials A and B.
    tilt : float
        Tilt of the sample plane along x in rad.
    bump_height : float
        Height of the ridge in m (0: none), at most the image's width.

    Returns
    -------
    tuple of Sample
        (topography in m, friction coefficient map, unit ``""``).

    Raises
    ------
    ValueError
        Naming the argument out of range.

    Examples
    --------
    >>> topo, mu = friction_sample((8, 16), 1e-9, coefficients=(0.1, 0.3))
    >>> sorted(set(mu.heights.ravel().tolist()))
    [0.1, 0.3]
    """
    shape = check_shape(shape)
    px = check_array("pixel_size", pixel_size, "m", low=0.0, low_inclusive=False, high=1.0,
                     ndim=0).item()
    mu = check_array("coefficients", coefficients, "", low=FRICTION_COEFFICIENT.low,
                     high=FRICTION_COEFFICIENT.high, size=2)
    tilt = TILT.check(tilt)
    rows, cols = (1, shape[0]) if len(shape) == 1 else shape
    width = (cols - 1) * px
    bump = check_array("bump_height", bump_height, "m", low=-width, high=width, ndim=0).item()
    x = np.arange(cols) * px
    y = np.arange(rows) * px
    xx, yy = np.meshgrid(x, y)
    cx, cy = x[-1] / 2, y[-1] / 2
    b = ((xx - cx) ** 2 + (yy - cy) ** 2 <= (x[-1] / 6) ** 2) | (xx >= 0.75 * x[-1])
    coeff = np.where(b, mu[1], mu[0])
    heights = math.tan(tilt) * xx
    if bump:
        u = (xx - 0.25 * x[-1]) / (0.125 * x[-1])  # -1..1 over the second quarter
        heights = heights + np.where(np.abs(u) < 1, bump * 0.5 * (1 + np.cos(np.pi * u)), 0.0)
    if len(shape) == 1:
        heights, coeff = heights[0], coeff[0]
    topo = Sample(heights, px, "two-material sample")
    return topo, Sample(coeff, px, "friction coefficient", channel="friction coefficient",
                        unit="")


class LateralForceMode(Mode):
    """Lateral force microscopy as an imaging mode of module (f)'s scanner.

    Contact mode with an ideal feedback (the height channel is the apex surface, the load is
    constant), and the lateral force of :func:`lateral_force` on trace and retrace with the
    stuck turn-arounds of :func:`friction_loop`.

    Parameters
    ----------
    friction : Sample
        Friction coefficient map (unit ``""``) on the grid of the sample being scanned; the
        scanner's apex positions pick the nearest pixel.
    normal_force : float
        Load F_N in N.
    lateral_stiffness : float
        Stiffness in N/m of the stuck phases.
    model : str
        ``"linear"`` or ``"wedge"``.

    Raises
    ------
    TypeError
        If ``friction`` is not a Sample.
    ValueError
        Naming the argument out of range.

    Notes
    -----
    Channels: ``"height trace"`` (m, the apex surface), ``"lateral trace"`` and
    ``"lateral retrace"`` (N). The slope is that of the apex surface (the sample dilated by the
    tip) along the fast axis. The scanner adds its sensor noise to the height only.
    """

    channels = ("height trace", "lateral trace", "lateral retrace")
    units = read_only({"lateral trace": "N", "lateral retrace": "N"})

    def __init__(self, friction: Sample, *, normal_force: float = NORMAL_FORCE.default,
                 lateral_stiffness: float = LATERAL_STIFFNESS.default, model: str = "linear"):
        self.friction = check_instance("friction", friction, Sample)
        if friction.unit != "":
            raise ValueError(f"friction must hold friction coefficients (unit ''), got unit "
                             f"{friction.unit!r}")
        self.mu = check_array("friction", np.atleast_2d(friction.heights), "",
                              low=FRICTION_COEFFICIENT.low, high=FRICTION_COEFFICIENT.high)
        self.normal_force = NORMAL_FORCE.check(normal_force)
        self.lateral_stiffness = LATERAL_STIFFNESS.check(lateral_stiffness)
        self.model = check_choice("model", model, MODELS)

    def __repr__(self) -> str:
        return (f"LateralForceMode({self.friction.name!r}, normal_force={self.normal_force!r}, "
                f"lateral_stiffness={self.lateral_stiffness!r}, model={self.model!r})")

    def _mu(self, x, y):
        f = self.friction
        ny = f.pixel_size_y or f.pixel_size
        i = np.clip(np.rint(y / ny).astype(int), 0, self.mu.shape[0] - 1)
        j = np.clip(np.rint(x / f.pixel_size).astype(int), 0, self.mu.shape[1] - 1)
        return self.mu[i, j]

    def line(self, plan: ScanPlan, row: int, state=None) -> ModeLine:
        """Height and lateral force along line ``row``, trace and retrace.

        Parameters
        ----------
        plan : ScanPlan
            The scan.
        row : int
            Line index.
        state : object
            Unused (each line is a steady loop).

        Returns
        -------
        ModeLine
        """
        row = self._row(plan, row)
        mu_t = self._mu(plan.x_trace[row], plan.y_trace[row])
        mu_r = self._mu(plan.x_retrace[row], plan.y_retrace[row])
        heights = np.stack((plan.trace[row], plan.retrace[row]))
        mu = np.stack((mu_t, mu_r))
        trace, _ = _passes(heights[:1], mu[:1], plan.pixel_size, self.normal_force,
                           self.lateral_stiffness, self.model)
        _, retrace = _passes(heights[1:], mu[1:], plan.pixel_size, self.normal_force,
                             self.lateral_stiffness, self.model)
        return ModeLine({"height trace": plan.trace[row].copy(), "lateral trace": trace[0],
                         "lateral retrace": retrace[0]}, state)
