"""Module (a) for levers as they are sold: rectangular, pointed and V-shaped planforms.

A lever of thickness t, Young's modulus E, shear modulus G and density rho is clamped at x = 0 and
lies in the xy-plane, symmetric about the x axis; its tip sits on that axis at x = x_tip, a
height h_tip below the lever's underside. Three planforms are modelled:

* ``"rectangular"``: width w from the clamp to the free end x = L;
* ``"pointed"``: width w, the last ``point_length`` a of it narrowing linearly to a point at x = L
  (Olympus AC160TS, AC240TS; NanoWorld Arrow);
* ``"v_shaped"``: two arms of width ``arm_width`` (across the arm) meeting at the apex x = L; the
  outer edges run from (0, +-w/2) to (L, 0), w the total width at the clamp, so that each arm makes
  the half-angle theta = atan(w / (2 L)) with the axis; the inner edges meet at
  x_j = L - arm_width / sin(theta), beyond which the lever is a solid triangle (Bruker MLCT, DNP,
  SNL).

The method (why a frame of beams): the lever is a grid of one-dimensional members in its plane,
each an Euler-Bernoulli beam in bending (Hermite cubic elements, exact for a uniform beam's
static deflection at the nodes; frequencies converge as h^4) and a St-Venant strip in torsion
(linear elements, torsional frequencies converge as h^2), with bending and twist coupled where
members meet at an angle. Each node carries the deflection w and the two slopes dw/dx, dw/dy;
a member along the unit vector a bends with the slope along a and twists with the slope across
it. Rectangular and pointed levers are one straight member of varying width (then flexure and
torsion decouple); a V-shaped lever is its two arms, rigidly joined to the solid triangle at
x_j, the triangle being a straight member of linearly varying width. Stiffness and consistent
mass are integrated exactly (4-point Gauss for the linear width) and assembled vectorised; the
modes come from ``scipy.linalg.eigh`` of the symmetric half of the lever (flexural modes are
symmetric about the axis, torsional ones antisymmetric). For a uniform rectangle the flexural
results equal the closed forms of :class:`~afmsmiler.cantilever.Cantilever` (k = 3 E J / L^3
to the solve's rounding, 1e-9; f_n from :func:`~afmsmiler.cantilever.eigenvalue` to the discretisation error), and
the torsional ones Saint-Venant's k_phi = G w t^3 / (3 L) exactly and
f_n = (2 n - 1) / (4 L) sqrt(G J / (rho I_p)), J = w t^3 / 3, I_p = (w t^3 + w^3 t) / 12
(Timoshenko, *Vibration Problems in Engineering*; for AFM levers Green and Sader,
J. Appl. Phys. 92, 6262 (2002)).

Why the arms must be oblique members: the parallel-beam approximation (Albrecht, Akamine, Carver
and Quate, J. Vac. Sci. Technol. A 8, 3386 (1990)) replaces a V by a rectangle of width twice the
arm's, k = E t^3 arm_width / (2 L^3); a straight beam of the V's cross-section width is no better
(the arms' cut is arm_width / cos(theta) wide). Both ignore that each arm is a beam of length
L / cos(theta) twisted by the joint: Sader, Rev. Sci. Instrum. 66, 4583 (1995) shows that the
parallel-beam approximation overestimates k, increasingly so for wide, short levers, and gives
(:func:`sader_v_spring_constant`)::

    k = E t^3 b / (2 L^3) cos(theta) [1 + 4 b^3 / d^3 (3 cos(theta) - 2)]^-1

with b the arm width and d the total width at the clamp. For a pair of narrow arms the frame of
two oblique beams has the closed form (derived with sympy in ``tests/test_planform.py``)
k = 2 E I cos^3(theta) / L^3 [12 - 36 cos^2 / (4 cos^2 + (G J / E I) sin^2)], which this model
reproduces; see :func:`parallel_beam_error`.

Validity (a V-shaped lever is a plate): the members are thin beams, so the model needs
L >= 10 t (shear deformation below about 1 %), widths >= 5 t (thin-strip torsion; the factor
1/3 of J is 1/3 (1 - 0.63 t / w), Roark's *Formulas for Stress and Strain*, 13 % lower at
w = 5 t) and, for a V, arms longer than about three widths: for wide arms the region where the
arms meet bends as a plate, which a frame of beams with a rigid joint makes too stiff. Against
Sader's formula the frame's k is 1 to 5 % higher for narrow arms (arm width <= L / 20, theta 11
to 32 deg) and up to 14 % higher for arms L / 4 wide; for the MLCT and SNL presets 8 to 10 %
(``tests/test_planform.py``). Where a point narrows to nothing its twist and in-plane bending
are those of the tip's base (:attr:`Lever.stiff_width`).

Lateral (in-plane) bending of a rectangle: k_lat = E t w^3 / (4 L^3) (the same beam on edge);
of a pointed lever the same member with E t b(x)^3 / 12; of a V-shaped lever the two arms as
bars, 2 E t arm_width sin^2(theta) cos(theta) / L (the arms' in-plane bending, of relative size
(arm_width / arm length)^2, neglected). A friction force F_L at the tip apex twists the lever
about its axis with the lever arm h_tip + t/2 (apex to the mid-plane), so that the apex moves
sideways as against a spring k_phi / (h_tip + t/2)^2 (Neumeister and Ducker, Rev. Sci. Instrum.
65, 2527 (1994); Ogletree, Carpick and Salmeron, Rev. Sci. Instrum. 67, 3298 (1996)).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from functools import cached_property

import numpy as np
from scipy.linalg import cho_factor, cho_solve, eigh
from scipy.sparse import csr_matrix

from .cantilever import LENGTH, MAX_MODE, THICKNESS, WIDTH, Cantilever
from .materials import DENSITY, YOUNGS_MODULUS, Material, lookup
from .parameters import Parameter, read_only
from .validation import check_choice, check_instance, check_integer, check_range

__all__ = ["Lever", "Modes", "PLANFORMS", "PRESETS", "preset", "sader_v_spring_constant",
           "parallel_beam_spring_constant", "parallel_beam_error", "PARAMETERS",
           "SHEAR_MODULUS", "TIP_HEIGHT", "TIP_POSITION", "POINT_LENGTH", "ARM_WIDTH",
           "LIMITS"]

#: The planforms the model knows.
PLANFORMS = ("rectangular", "pointed", "v_shaped")

#: Shear modulus G (default: the silicon preset's, 50.9 GPa for a <110> lever).
SHEAR_MODULUS = Parameter(name="shear_modulus", unit="Pa", display_unit="GPa", default=50.9e9,
                          low=1.0, high=1e13, slider_low=10e9, slider_high=200e9,
                          label="shear modulus G")
#: Tip height h_tip, from the lever's underside to the apex (as datasheets print it).
TIP_HEIGHT = Parameter(name="tip_height", unit="m", display_unit="um", default=15e-6, low=0.0,
                       high=1e-3, slider_low=0.0, slider_high=30e-6, label="tip height h_tip")
#: Tip position x_tip along the axis from the clamp (must lie on the lever: checked per lever).
TIP_POSITION = Parameter(name="tip_position", unit="m", display_unit="um", default=450e-6,
                         low=1e-9, high=1.0, slider_low=20e-6, slider_high=1000e-6,
                         label="tip position x_tip")
#: Length a of a pointed lever's triangular end.
POINT_LENGTH = Parameter(name="point_length", unit="m", display_unit="um", default=20e-6,
                         low=1e-9, high=1.0, slider_low=1e-6, slider_high=200e-6,
                         label="point length a")
#: Width of each arm of a V-shaped lever, across the arm.
ARM_WIDTH = Parameter(name="arm_width", unit="m", display_unit="um", default=20e-6, low=1e-9,
                      high=1.0, slider_low=2e-6, slider_high=60e-6, label="arm width b")

#: Every user-settable quantity of the planform model, by keyword name (read-only).
PARAMETERS = read_only({p.name: p for p in (LENGTH, WIDTH, THICKNESS, YOUNGS_MODULUS, DENSITY,
                                            SHEAR_MODULUS, TIP_HEIGHT, TIP_POSITION,
                                            POINT_LENGTH, ARM_WIDTH)})

#: Validity and size limits: L / t and width / t at least, the V's half-angle range (degrees),
#: elements per lever at most (400: a call of about 0.3 s).
LIMITS = read_only(dict(length_per_thickness=10.0, width_per_thickness=5.0,
                        min_half_angle=2.0, max_half_angle=60.0, max_elements=400))

_GAUSS_S, _GAUSS_W = np.polynomial.legendre.leggauss(4)
_GAUSS_S = 0.5 * (_GAUSS_S + 1.0)  # on [0, 1]
_GAUSS_W = 0.5 * _GAUSS_W


@dataclass(frozen=True)
class Modes:
    """Flexural or torsional modes of a :class:`Lever`, in SI units.

    Attributes
    ----------
    frequencies : ndarray, shape (n,)
        Frequencies in Hz (undamped, in vacuum), ascending.
    x, y : ndarray, shape (nodes,)
        Node positions in m of the lever's half y >= 0 (the other half is its mirror image).
    shapes : ndarray, shape (n, nodes)
        Flexural modes: the deflection w at the nodes, normalised to +1 at the tip; torsional
        modes: the rotation about the lever's axis (the slope dw/dy) at the nodes, normalised to
        +1 at the tip.
    kind : str
        ``"flexural"`` or ``"torsional"``.
    """

    frequencies: np.ndarray
    x: np.ndarray
    y: np.ndarray
    shapes: np.ndarray
    kind: str


@dataclass(frozen=True)
class _Mesh:
    xy: np.ndarray        # (nodes, 2)
    i: np.ndarray         # (elements,) first node
    j: np.ndarray         # (elements,) second node
    b0: np.ndarray        # (elements,) width at node i (full width of the member)
    b1: np.ndarray        # width at node j
    share: np.ndarray     # 0.5 for a member on the axis (half model), 1 for an arm
    tip: int              # node of the tip
    clamped: np.ndarray   # nodes at x = 0
    slaves: tuple         # (slave node, master node on the axis): rigid joints


@dataclass(frozen=True)
class Lever:
    """A clamped lever of a given planform, with its tip: bending, twist and modes (SI units).

    Use the constructors :meth:`rectangular`, :meth:`pointed`, :meth:`v_shaped` (from a
    material) or :func:`preset` (a vendor's probe).

    Parameters
    ----------
    planform : str
        ``"rectangular"``, ``"pointed"`` or ``"v_shaped"`` (:data:`PLANFORMS`).
    length : float
        Length L in m, clamp to free end (to the point or apex).
    width : float
        Width w in m; for a V-shaped lever the total width at the clamp.
    thickness : float
        Thickness t in m, at most L / 10 and width / 5 (arm width / 5) (:data:`LIMITS`).
    youngs_modulus : float
        Young's modulus E in Pa.
    density : float
        Density rho in kg/m^3.
    shear_modulus : float
        Shear modulus G in Pa.
    tip_position : float or None
        Distance x_tip of the tip from the clamp in m, on the lever's axis; None: at the free
        end (x_tip = L).
    tip_height : float
        Tip height h_tip in m, from the lever's underside to the apex.
    point_length : float
        Length in m of a pointed lever's triangular end, in (0, L] (ignored by other planforms:
        0).
    arm_width : float
        Width in m of each arm of a V-shaped lever, across the arm (ignored by other planforms:
        0).
    name : str
        A label (the vendor's product name for a preset).
    source : str
        Where the numbers come from.
    coating : Material or None
        A reflective coating on the lever's back (gold, aluminium), or None.
    coating_thickness : float
        Its thickness in m, at most thickness / 2 (0 without a coating).
    elements : int
        Elements of the frame model along the lever, 4 to LIMITS['max_elements'] (the default
        48 gives f_1..f_3 of a rectangle to better than 1e-6).

    Raises
    ------
    ValueError
        Naming the parameter, its value and its valid range: a dimension out of range, a lever
        too thick for thin-beam theory, a tip outside the lever (for a V-shaped lever: between
        the arms), arms too wide to leave a V, a half-angle outside
        [LIMITS['min_half_angle'], LIMITS['max_half_angle']] degrees.

    Examples
    --------
    >>> lever = Lever.rectangular("silicon", length=125e-6, width=30e-6, thickness=4e-6)
    >>> round(lever.spring_constant, 1)  # N/m, equal to Cantilever's 3 E J / L^3
    41.5
    """

    planform: str
    length: float
    width: float
    thickness: float
    youngs_modulus: float
    density: float
    shear_modulus: float = SHEAR_MODULUS.default
    tip_position: float | None = None
    tip_height: float = TIP_HEIGHT.default
    point_length: float = 0.0
    arm_width: float = 0.0
    name: str = ""
    source: str = field(default="", repr=False)
    elements: int = field(default=48, repr=False)
    coating: Material | None = None
    coating_thickness: float = 0.0

    def __post_init__(self):
        check_choice("planform", self.planform, PLANFORMS)
        for key in ("length", "width", "thickness", "youngs_modulus", "density",
                    "shear_modulus", "tip_height"):
            object.__setattr__(self, key, PARAMETERS[key].check(getattr(self, key)))
        check_instance("name", self.name, str)
        check_instance("source", self.source, str)
        object.__setattr__(self, "elements", check_integer("elements", self.elements, 4,
                                                           LIMITS["max_elements"]))
        if self.coating is None:
            _unused("coating_thickness", self.coating_thickness, "uncoated")
        else:
            check_instance("coating", self.coating, Material)
            object.__setattr__(self, "coating_thickness", check_range(
                "coating_thickness", self.coating_thickness, 0.0, self.thickness / 2, "m"))
        length, t = self.length, self.thickness
        tip = length if self.tip_position is None else TIP_POSITION.check(self.tip_position)
        if self.planform == "pointed":
            object.__setattr__(self, "point_length", check_range(
                "point_length", self.point_length, 0.0, length, "m", low_inclusive=False))
        else:
            _unused("point_length", self.point_length, self.planform)
        if self.planform == "v_shaped":
            b = ARM_WIDTH.check(self.arm_width)
            object.__setattr__(self, "arm_width", b)
            theta = math.degrees(math.atan(self.width / (2 * length)))
            lo, hi = LIMITS["min_half_angle"], LIMITS["max_half_angle"]
            if not lo <= theta <= hi:
                raise ValueError(
                    f"width must give a half-angle atan(width / (2 length)) in [{lo:g}, {hi:g}] "
                    f"deg, in [{2 * length * math.tan(math.radians(lo)):g}, "
                    f"{2 * length * math.tan(math.radians(hi)):g}] m for length {length:g} m, "
                    f"got {self.width:g} m ({theta:.3g} deg)")
            widest = self.width / 2 * math.cos(math.radians(theta))
            if b >= widest:
                raise ValueError(
                    f"arm_width must be < width / 2 cos(theta) = {widest:g} m, so that the arms "
                    f"meet at the apex and leave a V open at the clamp, got {b:g} m")
            narrow = b
        else:
            _unused("arm_width", self.arm_width, self.planform)
            narrow = self.width
        if t > length / LIMITS["length_per_thickness"]:
            raise ValueError(f"thickness must be in (0, length / {LIMITS['length_per_thickness']:g}"
                             f"] = (0, {length / LIMITS['length_per_thickness']:g}] m for thin-beam"
                             f" theory, got {t:g} m")
        if t > narrow / LIMITS["width_per_thickness"]:
            what = "arm_width" if self.planform == "v_shaped" else "width"
            raise ValueError(f"thickness must be in (0, {what} / {LIMITS['width_per_thickness']:g}"
                             f"] = (0, {narrow / LIMITS['width_per_thickness']:g}] m for thin-strip "
                             f"torsion, got {t:g} m")
        low = self.solid_from if self.planform == "v_shaped" else 0.0
        if not low < tip <= length:
            where = (" (between x_j, where the arms meet, and the apex: the tip must sit on "
                     "material)" if self.planform == "v_shaped" else "")
            raise ValueError(f"tip_position must be in ({low:g}, {length:g}] m{where}, got {tip:g} m")
        object.__setattr__(self, "tip_position", tip)

    # -- construction ---------------------------------------------------------------------
    @classmethod
    def rectangular(cls, material: str | Material, length: float = LENGTH.default,
                    width: float = WIDTH.default, thickness: float = THICKNESS.default, *,
                    tip_position: float | None = None,
                    tip_height: float = TIP_HEIGHT.default, coating: str | Material | None = None,
                    coating_thickness: float = 0.0) -> "Lever":
        """A rectangular lever of a material (the planform of :class:`Cantilever`).

        Parameters
        ----------
        material : str or Material
            A key of :data:`afmsmiler.materials.MATERIALS` or a Material (E, rho, G).
        length : float
            Length L in m.
        width : float
            Width w in m.
        thickness : float
            Thickness t in m.
        tip_position : float or None
            Tip position from the clamp in m; None: at the free end.
        tip_height : float
            Tip height in m (underside to apex).
        coating : str or Material or None
            A reflective coating on the back (a key of MATERIALS: ``"gold"``, ``"aluminium"``).
        coating_thickness : float
            Its thickness in m (0 without a coating).

        Returns
        -------
        Lever
        """
        m = lookup(material, "material")
        return cls("rectangular", length, width, thickness, m.youngs_modulus, m.density,
                   m.shear_modulus, tip_position, tip_height, coating=_coating(coating),
                   coating_thickness=coating_thickness)

    @classmethod
    def pointed(cls, material: str | Material, length: float = LENGTH.default,
                width: float = WIDTH.default, thickness: float = THICKNESS.default,
                point_length: float = POINT_LENGTH.default, *,
                tip_position: float | None = None,
                tip_height: float = TIP_HEIGHT.default, coating: str | Material | None = None,
                coating_thickness: float = 0.0) -> "Lever":
        """A rectangular lever whose last ``point_length`` narrows to a point at x = L.

        Parameters
        ----------
        material : str or Material
            A key of :data:`afmsmiler.materials.MATERIALS` or a Material.
        length : float
            Length L in m, clamp to point.
        width : float
            Width w in m of the rectangular part.
        thickness : float
            Thickness t in m.
        point_length : float
            Length a in m of the triangular end, in (0, L].
        tip_position : float or None
            Tip position from the clamp in m; None: at the point.
        tip_height : float
            Tip height in m (underside to apex).
        coating : str or Material or None
            A reflective coating on the back (a key of MATERIALS: ``"gold"``, ``"aluminium"``).
        coating_thickness : float
            Its thickness in m (0 without a coating).

        Returns
        -------
        Lever
        """
        m = lookup(material, "material")
        return cls("pointed", length, width, thickness, m.youngs_modulus, m.density,
                   m.shear_modulus, tip_position, tip_height, point_length=point_length,
                   coating=_coating(coating), coating_thickness=coating_thickness)

    @classmethod
    def v_shaped(cls, material: str | Material, length: float = 200e-6,
                 arm_width: float = ARM_WIDTH.default, width: float | None = None,
                 thickness: float = 0.6e-6, *, half_angle: float | None = None,
                 tip_position: float | None = None,
                 tip_height: float = TIP_HEIGHT.default, coating: str | Material | None = None,
                 coating_thickness: float = 0.0) -> "Lever":
        """A V-shaped lever: two arms of width ``arm_width`` meeting at the apex x = L.

        Parameters
        ----------
        material : str or Material
            A key of :data:`afmsmiler.materials.MATERIALS` or a Material.
        length : float
            Length L in m, clamp to apex along the axis.
        arm_width : float
            Width of each arm across the arm in m.
        width : float or None
            Total width at the clamp in m (outer edge to outer edge); None: from
            ``half_angle``, or 160 um without one.
        thickness : float
            Thickness t in m.
        half_angle : float or None
            Angle theta in rad between each arm's outer edge and the axis, in (0, pi/2): the
            width is then 2 L tan(theta); given with ``width``, the two must agree (else the
            arms would not meet at the apex).
        tip_position : float or None
            Tip position from the clamp in m, on the solid apex; None: at the apex.
        tip_height : float
            Tip height in m (underside to apex).
        coating : str or Material or None
            A reflective coating on the back (a key of MATERIALS: ``"gold"``, ``"aluminium"``).
        coating_thickness : float
            Its thickness in m (0 without a coating).

        Returns
        -------
        Lever
        """
        m = lookup(material, "material")
        if half_angle is not None:
            theta = check_range("half_angle", half_angle, 0.0, math.pi / 2, "rad",
                                low_inclusive=False, high_inclusive=False)
            length = LENGTH.check(length)
            opening = 2 * length * math.tan(theta)
            if width is not None and not math.isclose(WIDTH.check(width), opening,
                                                      rel_tol=1e-9):
                raise ValueError(
                    f"half_angle must agree with width: arms of length {length:g} m at "
                    f"{half_angle:g} rad meet at the apex only for width = 2 length "
                    f"tan(half_angle) = {opening:g} m, got width {width:g} m (the arms would "
                    f"not meet)")
            width = opening
        elif width is None:
            width = 160e-6
        return cls("v_shaped", length, width, thickness, m.youngs_modulus, m.density,
                   m.shear_modulus, tip_position, tip_height, arm_width=arm_width,
                   coating=_coating(coating), coating_thickness=coating_thickness)

    @classmethod
    def from_cantilever(cls, cantilever: Cantilever,
                        shear_modulus: float = SHEAR_MODULUS.default) -> "Lever":
        """The rectangular Lever of a :class:`~afmsmiler.cantilever.Cantilever`.

        Parameters
        ----------
        cantilever : Cantilever
            The rectangular lever of module (a).
        shear_modulus : float
            Its shear modulus G in Pa (a Cantilever carries none).

        Returns
        -------
        Lever
        """
        check_instance("cantilever", cantilever, Cantilever)
        c = cantilever
        return cls("rectangular", c.length, c.width, c.thickness, c.youngs_modulus, c.density,
                   shear_modulus)

    def with_(self, **changes) -> "Lever":
        """A copy with some fields changed (validated again).

        Parameters
        ----------
        **changes
            Field names and new values (``tip_position=...``, ``thickness=...``); a tip at the
            free end stays at the free end when the length changes.

        Returns
        -------
        Lever
        """
        unknown = set(changes) - set(self.__dataclass_fields__)
        if unknown:
            raise TypeError(f"changes must name fields of Lever, got {sorted(unknown)}")
        if "tip_position" not in changes and self.tip_position == self.length:
            changes["tip_position"] = None  # a tip at the free end stays there
        return replace(self, **changes)

    # -- geometry -------------------------------------------------------------------------
    @property
    def half_angle(self) -> float:
        """Half-angle theta = atan(w / (2 L)) of a V-shaped lever in rad (0 for the others)."""
        return math.atan(self.width / (2 * self.length)) if self.planform == "v_shaped" else 0.0

    @property
    def solid_from(self) -> float:
        """x_j in m where a V's arms meet, L - arm_width / sin(theta) (0 for the others)."""
        if self.planform != "v_shaped":
            return 0.0
        return self.length - self.arm_width / math.sin(self.half_angle)

    @property
    def stiff_width(self) -> float:
        """Width in m below which a point is taken as stiffened by the tip, in twist and in-plane.

        Where a pointed end or a V's apex narrows towards zero width, its torsional and in-plane
        rigidities (proportional to b and b^3) vanish, and a torque or side force applied by a tip
        sitting there would meet an infinite compliance; in fact the tip's base, which is part of
        the lever there, stiffens it. The point is therefore given the rigidities of this width:
        the larger of LIMITS['width_per_thickness'] t (below which thin-strip torsion fails) and
        the base of a pyramid of the tip's height with {111} faces at 54.74 deg to the lever, as
        KOH etching makes them (Albrecht et al., J. Vac. Sci. Technol. A 8, 3386 (1990)),
        2 h_tip / tan(54.74 deg) = 1.41 h_tip; never more than the lever's widest section, so
        that a rectangle is untouched. The bending stiffness and the mass keep the true width.
        """
        widest = (2 * self.arm_width / math.cos(self.half_angle) if self.planform == "v_shaped"
                  else self.width)
        base = 2 * self.tip_height / math.tan(math.atan(math.sqrt(2)))
        return min(widest, max(LIMITS["width_per_thickness"] * self.thickness, base))

    @property
    def apex_lever_arm(self) -> float:
        """Lever arm h_tip + t / 2 in m from the tip apex to the mid-plane."""
        return self.tip_height + self.thickness / 2

    @property
    def area(self) -> float:
        """Plan-view area in m^2."""
        if self.planform == "rectangular":
            return self.length * self.width
        if self.planform == "pointed":
            return self.width * (self.length - self.point_length / 2)
        # the outer triangle w L / 2 less the open V between the arms' inner edges, a triangle
        # of base 2 (w/2 - b / cos(theta)) at the clamp and apex x_j
        return self.width * self.length / 2 - (self.width / 2 - self.arm_width
                                               / math.cos(self.half_angle)) * self.solid_from

    @property
    def mass(self) -> float:
        """Mass in kg: rho t A, plus the coating's."""
        return self.section[2] * self.area

    @cached_property
    def section(self) -> tuple:
        """Section properties per unit width: (D_b in N m, D_t in N m, mu in kg/m^2, i_z in kg).

        Bending rigidity D_b = int E (z - z_n)^2 dz about the neutral plane z_n, torsional
        rigidity D_t = 4 int G (z - z_g)^2 dz (Saint-Venant thin strip, layered; z_g the
        G-weighted mid-plane), mass per area mu = int rho dz and rotary inertia
        i_z = int rho (z - z_m)^2 dz, through the lever and its coating. Uncoated:
        E t^3 / 12, G t^3 / 3, rho t, rho t^3 / 12.
        """
        layers = [(self.youngs_modulus, self.shear_modulus, self.density, 0.0, self.thickness)]
        if self.coating is not None and self.coating_thickness > 0:
            c = self.coating
            layers.append((c.youngs_modulus, c.shear_modulus, c.density, self.thickness,
                           self.thickness + self.coating_thickness))

        def moment(k, about):  # int P (z - about)^2 dz over the layers, P = column k
            return sum(ly[k] * ((ly[4] - about) ** 3 - (ly[3] - about) ** 3) / 3 for ly in layers)

        def centre(k):
            return (sum(ly[k] * (ly[4] ** 2 - ly[3] ** 2) / 2 for ly in layers)
                    / sum(ly[k] * (ly[4] - ly[3]) for ly in layers))

        mu = sum(ly[2] * (ly[4] - ly[3]) for ly in layers)
        return (moment(0, centre(0)), 4 * moment(1, centre(1)), mu, moment(2, centre(2)))

    # -- the frame model ------------------------------------------------------------------
    def _mesh(self, elements: int) -> _Mesh:
        L = self.length
        if self.planform == "v_shaped":
            xj, th, b = self.solid_from, self.half_angle, self.arm_width
            n_arm = max(2, round(elements * (xj / math.cos(th)) / (xj / math.cos(th) + L - xj)))
            n_axis = max(2, elements - n_arm)
            axis_x = _stations([xj, self.tip_position, L], n_axis)
            offset = b / (2 * math.cos(th))
            y0 = self.width / 2 - offset
            s = np.linspace(0.0, 1.0, n_arm + 1)
            arm = np.column_stack([s * xj, y0 + s * (offset - y0)])
            xy = np.vstack([arm, np.column_stack([axis_x, np.zeros_like(axis_x)])])
            na = n_arm + 1
            i = np.concatenate([np.arange(n_arm), na + np.arange(axis_x.size - 1)])
            j = i + 1
            wa = np.full(n_arm, b)
            tri = 2 * (L - axis_x) * math.tan(th)
            b0 = np.concatenate([wa, tri[:-1]])
            b1 = np.concatenate([wa, tri[1:]])
            share = np.concatenate([np.ones(n_arm), np.full(axis_x.size - 1, 0.5)])
            tip = na + int(np.argmin(np.abs(axis_x - self.tip_position)))
            return _Mesh(xy, i, j, b0, b1, share, tip, np.array([0]), ((n_arm, na),))
        marks = [0.0, self.tip_position, L]
        if self.planform == "pointed":
            marks.append(L - self.point_length)
        x = _stations(marks, elements)
        if self.planform == "pointed":
            bx = self.width * np.clip((L - x) / self.point_length, 0.0, 1.0)
        else:
            bx = np.full(x.size, self.width)
        xy = np.column_stack([x, np.zeros_like(x)])
        i = np.arange(x.size - 1)
        return _Mesh(xy, i, i + 1, bx[:-1], bx[1:], np.full(i.size, 0.5),
                     int(np.argmin(np.abs(x - self.tip_position))), np.array([0]), ())

    def _matrices(self, mesh: _Mesh):
        """Global stiffness and mass (3 dof per node: w, dw/dx, dw/dy) of the half lever."""
        d_b, d_t, mu, i_z = self.section
        d = mesh.xy[mesh.j] - mesh.xy[mesh.i]
        ell = np.hypot(d[:, 0], d[:, 1])
        ax, ay = d[:, 0] / ell, d[:, 1] / ell
        s = _GAUSS_S
        b = mesh.b0[:, None] * (1 - s) + mesh.b1[:, None] * s            # (e, g)
        share = mesh.share[:, None]
        ei = d_b * b * share
        # the point (a member on the axis narrowing to zero) is stiffened by the tip's base
        b_stiff = np.where(share < 1, np.maximum(b, self.stiff_width), b)
        gj = d_t * b_stiff * share
        ra = mu * b * share
        rip = (i_z * b + mu * b ** 3 / 12) * share
        le = ell[:, None]
        # Hermite cubics on s in [0, 1]; dofs (w1, slope1, w2, slope2), slope = dw/dx_local
        z = 0 * le
        n = np.stack([1 - 3 * s ** 2 + 2 * s ** 3 + z, (s - 2 * s ** 2 + s ** 3) * le,
                      3 * s ** 2 - 2 * s ** 3 + z, (-s ** 2 + s ** 3) * le], axis=1)  # (e, 4, g)
        dd = np.stack([(-6 + 12 * s) + z, (-4 + 6 * s) * le, (6 - 12 * s) + z,
                       (-2 + 6 * s) * le], axis=1) / le[:, None] ** 2            # (e, 4, g)
        kb = np.einsum("eag,ebg,eg,g->eab", dd, dd, ei, _GAUSS_W) * ell[:, None, None]
        mb = np.einsum("eag,ebg,eg,g->eab", n, n, ra, _GAUSS_W) * ell[:, None, None]
        lin = np.stack([1 - s + z, s + z], axis=1)                      # (e, 2, g)
        kt = (np.einsum("eg,g->e", gj, _GAUSS_W) / ell)[:, None, None] * np.array(
            [[1.0, -1.0], [-1.0, 1.0]])
        mt = np.einsum("eag,ebg,eg,g->eab", lin, lin, rip, _GAUSS_W) * ell[:, None, None]
        ne = ell.size
        k6 = np.zeros((ne, 6, 6))
        m6 = np.zeros((ne, 6, 6))
        bend, twist = [0, 1, 3, 4], [2, 5]  # local (w1, sa1, sn1, w2, sa2, sn2)
        k6[:, np.ix_(bend, bend)[0], np.ix_(bend, bend)[1]] = kb
        m6[:, np.ix_(bend, bend)[0], np.ix_(bend, bend)[1]] = mb
        k6[:, np.ix_(twist, twist)[0], np.ix_(twist, twist)[1]] = kt
        m6[:, np.ix_(twist, twist)[0], np.ix_(twist, twist)[1]] = mt
        # local slopes from global (w, dw/dx, dw/dy): s_a = a . grad w, s_n = n . grad w
        r = np.zeros((ne, 3, 3))
        r[:, 0, 0] = 1.0
        r[:, 1, 1], r[:, 1, 2] = ax, ay
        r[:, 2, 1], r[:, 2, 2] = -ay, ax
        tr = np.zeros((ne, 6, 6))
        tr[:, :3, :3] = r
        tr[:, 3:, 3:] = r
        kg = np.einsum("eia,eij,ejb->eab", tr, k6, tr)
        mg = np.einsum("eia,eij,ejb->eab", tr, m6, tr)
        dofs = np.concatenate([3 * mesh.i[:, None] + np.arange(3),
                               3 * mesh.j[:, None] + np.arange(3)], axis=1)       # (e, 6)
        size = 3 * mesh.xy.shape[0]
        K = np.zeros((size, size))
        M = np.zeros((size, size))
        rows = np.broadcast_to(dofs[:, :, None], kg.shape)
        cols = np.broadcast_to(dofs[:, None, :], kg.shape)
        np.add.at(K, (rows, cols), kg)
        np.add.at(M, (rows, cols), mg)
        return K, M

    def _reduction(self, mesh: _Mesh, kind: str) -> np.ndarray:
        """Matrix C with u_full = C u_free: clamp, symmetry on the axis, rigid joints."""
        nodes = mesh.xy.shape[0]
        free = np.ones((nodes, 3), bool)
        free[mesh.clamped] = False
        on_axis = np.abs(mesh.xy[:, 1]) <= 1e-12 * self.length
        if kind == "flexural":   # symmetric: dw/dy = 0 on the axis
            free[on_axis, 2] = False
        else:                    # antisymmetric: w = dw/dx = 0 on the axis
            free[on_axis, 0] = False
            free[on_axis, 1] = False
        slaves = {s: m for s, m in mesh.slaves}
        for s in slaves:
            free[s] = False
        index = -np.ones((nodes, 3), int)
        index[free] = np.arange(int(free.sum()))
        # the free slopes are carried as L dw/dx, L dw/dy (metres, as w) so that the reduced
        # matrices are well conditioned: a rectangle's k then equals 3 E J / L^3 to 1e-14
        scale = np.array([1.0, 1.0 / self.length, 1.0 / self.length])
        C = np.zeros((3 * nodes, int(free.sum())))
        flat = index.ravel()
        keep = flat >= 0
        C[np.flatnonzero(keep), flat[keep]] = np.tile(scale, nodes)[keep]
        for s, m in slaves.items():  # w_s = w_m + (y_s - y_m) dw/dy_m; slopes equal
            dy = mesh.xy[s, 1] - mesh.xy[m, 1]
            for k in range(3):
                if index[m, k] >= 0:
                    C[3 * s + k, index[m, k]] = scale[k]
            if index[m, 2] >= 0:
                C[3 * s, index[m, 2]] += dy * scale[2]
        return C

    @cached_property
    def _model(self):
        mesh = self._mesh(self.elements)
        K, M = self._matrices(mesh)
        return mesh, K, M

    def _reduced(self, kind: str):
        """Mesh, C and the reduced stiffness and mass C^T K C, C^T M C (once per kind)."""
        if kind not in self._eigen:
            mesh, K, M = self._model
            C = self._reduction(mesh, kind)
            Cs = csr_matrix(C)  # a selection with a few joint rows: sparse products, no BLAS
            Kr = np.asarray((Cs.T @ np.asarray(Cs.T @ K).T).T)
            Mr = np.asarray((Cs.T @ np.asarray(Cs.T @ M).T).T)
            self._eigen[kind] = (mesh, C, (Kr + Kr.T) / 2, (Mr + Mr.T) / 2)
        return self._eigen[kind]

    def _compliance(self, kind: str, dof: int) -> float:
        mesh, C, Kr, _ = self._reduced(kind)
        load = C[3 * mesh.tip + dof]
        u = cho_solve(cho_factor(Kr), load)
        return float(load @ u)

    # -- statics --------------------------------------------------------------------------
    @cached_property
    def spring_constant(self) -> float:
        """Spring constant k in N/m for a normal force at the tip position.

        From the frame model (module notes); for a rectangle with the tip at x it equals
        3 E J / x^3 (J = w t^3 / 12) to rounding.
        """
        return 2.0 / self._compliance("flexural", 0)

    @cached_property
    def torsional_stiffness(self) -> float:
        """Torsional stiffness k_phi in N m/rad: torque about the axis per twist at the tip.

        For a rectangle, Saint-Venant's thin strip G w t^3 / (3 x_tip) (Timoshenko and Goodier,
        *Theory of Elasticity*; Green and Sader, J. Appl. Phys. 92, 6262 (2002)); for a V-shaped
        lever mostly the arms' opposite bending.
        """
        return 2.0 / self._compliance("torsional", 2)

    @property
    def lateral_spring_constant(self) -> float:
        """Lateral spring constant of the tip apex from twist, k_phi / (h_tip + t/2)^2, in N/m.

        The friction force F_L at the apex twists the lever by F_L (h_tip + t/2) / k_phi and
        moves the apex sideways by (h_tip + t/2) times that (Neumeister and Ducker, Rev. Sci.
        Instrum. 65, 2527 (1994)).
        """
        return self.torsional_stiffness / self.apex_lever_arm ** 2

    @cached_property
    def lateral_bending_stiffness(self) -> float:
        """In-plane (lateral bending) stiffness k_lat at the tip in N/m.

        Rectangle: E t w^3 / (4 x_tip^3) (the beam on edge); pointed: the same beam with
        E t b(x)^3 / 12, by the unit-load integral of (x_tip - x)^2 / (E t b^3 / 12); V-shaped: the two arms as bars,
        2 E t arm_width sin^2(theta) cos(theta) / L (module notes).
        """
        # E t of the section, the coating's included (its E t_c adds as a parallel layer)
        et = self.youngs_modulus * self.thickness + (
            0.0 if self.coating is None else self.coating.youngs_modulus * self.coating_thickness)
        if self.planform == "v_shaped":
            th = self.half_angle
            return 2 * et * self.arm_width * math.sin(th) ** 2 * math.cos(th) / self.length
        if self.planform == "rectangular":
            return et * self.width ** 3 / (4 * self.tip_position ** 3)
        mesh = self._mesh(self.elements)
        s = _GAUSS_S
        b = np.maximum(mesh.b0[:, None] * (1 - s) + mesh.b1[:, None] * s, self.stiff_width)
        ell = np.diff(mesh.xy[:, 0])
        # compliance by the unit-load method: delta = int (x_tip - x)^2 / (E I_z(x)) dx, x < x_tip
        x0 = mesh.xy[mesh.i, 0][:, None] + s * ell[:, None]
        arm = np.clip(self.tip_position - x0, 0.0, None)
        with np.errstate(divide="ignore", invalid="ignore"):
            integrand = np.where(arm > 0, arm ** 2 / (et * b ** 3 / 12), 0.0)
        return 1.0 / float(np.sum(integrand * _GAUSS_W * ell[:, None]))

    # -- dynamics -------------------------------------------------------------------------
    def modes(self, n: int = 3, kind: str = "flexural") -> Modes:
        """The first ``n`` flexural or torsional modes: frequencies and shapes.

        Parameters
        ----------
        n : int
            Number of modes, 1 to 20 (the frame resolves more, thin-beam theory does not).
        kind : str
            ``"flexural"`` (symmetric about the axis) or ``"torsional"`` (antisymmetric).

        Returns
        -------
        Modes

        Examples
        --------
        >>> lever = Lever.rectangular("silicon", length=125e-6, width=30e-6, thickness=4e-6)
        >>> round(lever.modes(1).frequencies[0] / 1e3)  # kHz, as Cantilever's f_1
        352
        """
        n = check_integer("n", n, 1, 20)
        kind = check_choice("kind", kind, ("flexural", "torsional"))
        mesh, C, w2, vec = self._eig(kind, n)
        n = min(n, w2.size)
        w2, vec = w2[:n], vec[:, :n]
        full = (C @ vec).reshape(mesh.xy.shape[0], 3, n)
        dof = 0 if kind == "flexural" else 2
        ref = full[mesh.tip, dof, :]
        ref = np.where(np.abs(ref) > 0, ref, 1.0)
        shapes = (full[:, dof, :] / ref).T
        return Modes(np.sqrt(np.clip(w2, 0.0, None)) / (2 * math.pi), mesh.xy[:, 0].copy(),
                     mesh.xy[:, 1].copy(), shapes, kind)

    @cached_property
    def _eigen(self) -> dict:
        return {}

    def _eig(self, kind: str, n: int):
        """At least the first ``n`` (and 3) modes of ``kind``, solved once per lever and count:
        a later call for fewer modes reuses them, so that f_n does not depend on the order of
        the calls."""
        key = ("modes", kind)
        have = self._eigen.get(key)
        if have is None or have[2].size < min(n, have[4]):
            mesh, C, Kr, Mr = self._reduced(kind)
            count = min(max(n, 3), Kr.shape[0])
            w2, vec = eigh(Kr, Mr, subset_by_index=[0, count - 1])
            self._eigen[key] = have = (mesh, C, w2, vec, Kr.shape[0])
        return have[:4]

    def frequencies(self, n: int = 3) -> tuple:
        """Frequencies f_1 ... f_n in Hz of the first ``n`` flexural modes (vacuum).

        Parameters
        ----------
        n : int
            Number of modes, 1 to 20.

        Returns
        -------
        tuple of float
        """
        return tuple(float(f) for f in self.modes(n).frequencies)

    def resonance_frequency(self, mode: int = 1) -> float:
        """Frequency of flexural mode ``mode`` (1-based) in Hz, as :class:`Cantilever`'s.

        Parameters
        ----------
        mode : int
            Mode number, 1 to 20.
        """
        mode = check_integer("mode", mode, 1, min(20, MAX_MODE))
        return self.frequencies(mode)[-1]

    def torsional_resonance_frequency(self, mode: int = 1) -> float:
        """Frequency of torsional mode ``mode`` in Hz (vacuum).

        For a rectangle it converges (as h^2) to f_n = (2 n - 1) / (4 L) sqrt(G J / (rho I_p)),
        J = w t^3 / 3, I_p = (w t^3 + w^3 t) / 12 (Green and Sader, J. Appl. Phys. 92, 6262
        (2002), in vacuum).

        Parameters
        ----------
        mode : int
            Mode number, 1 to 20.
        """
        mode = check_integer("mode", mode, 1, 20)
        return float(self.modes(mode, "torsional").frequencies[-1])

    @property
    def effective_mass(self) -> float:
        """Mass k / (2 pi f_1)^2 in kg of the point-mass oscillator of mode 1 at the tip."""
        return self.spring_constant / (2 * math.pi * self.resonance_frequency(1)) ** 2


def _coating(coating):
    return None if coating is None else lookup(coating, "coating")


def _unused(name: str, value, planform: str) -> None:
    v = check_range(name, value, 0.0, 1.0, "m")
    if v != 0.0:
        raise ValueError(f"{name} must be 0 for {'an' if planform[0] in 'aeiou' else 'a'} "
                         f"{planform} lever (it has no such part), got {v:g} m")


def _stations(marks, elements: int) -> np.ndarray:
    """Nodes from marks[0] to marks[-1] with every mark a node, about ``elements`` in all."""
    marks = np.unique(np.asarray(marks, float))
    span = marks[-1] - marks[0]
    parts = []
    for a, b in zip(marks[:-1], marks[1:]):
        if b - a <= 1e-12 * span:
            continue
        k = max(1, round(elements * (b - a) / span))
        parts.append(np.linspace(a, b, k + 1)[:-1])
    parts.append([marks[-1]])
    return np.concatenate(parts)


def sader_v_spring_constant(lever: Lever) -> float:
    """Sader's formula for the spring constant of a V-shaped lever in N/m.

    k = E t^3 b / (2 L^3) cos(theta) [1 + 4 b^3 / d^3 (3 cos(theta) - 2)]^-1, b the arm width,
    d the total width at the clamp, theta the half-angle, L the length to the apex (Sader,
    Rev. Sci. Instrum. 66, 4583 (1995), who compares it with finite-element results for
    plates).

    Parameters
    ----------
    lever : Lever
        A V-shaped lever, tip at the apex.

    Returns
    -------
    float
    """
    _v(lever)
    b, d, th = lever.arm_width, lever.width, lever.half_angle
    return (lever.youngs_modulus * lever.thickness ** 3 * b / (2 * lever.length ** 3)
            * math.cos(th) / (1 + 4 * b ** 3 / d ** 3 * (3 * math.cos(th) - 2)))


def parallel_beam_spring_constant(lever: Lever) -> float:
    """The parallel-beam approximation k = E t^3 b / (2 L^3) in N/m of a V-shaped lever.

    Two rectangular beams of the arm width b and the lever's length L side by side (Albrecht,
    Akamine, Carver and Quate, J. Vac. Sci. Technol. A 8, 3386 (1990)).

    Parameters
    ----------
    lever : Lever
        A V-shaped lever.

    Returns
    -------
    float
    """
    _v(lever)
    return lever.youngs_modulus * lever.thickness ** 3 * lever.arm_width / (2 * lever.length ** 3)


def parallel_beam_error(lever: Lever) -> float:
    """Relative error of the parallel-beam approximation, k_PBA / k - 1, for a V-shaped lever.

    k from the frame model (tip at the apex). The approximation neglects that each arm is an
    oblique beam of length L / cos(theta) twisted at the joint, and that wide arms leave a long
    solid triangle at the apex: it overestimates k by 1 % for long narrow levers (theta = 11 deg,
    arms L / 40), 4 % at theta = 22 deg, 13 % for short wide levers (theta = 32 deg) and 21 % for
    arms L / 7 wide even at theta = 11 deg (this model; Sader, Rev. Sci. Instrum. 66, 4583
    (1995), makes the same point against plate finite elements).

    Parameters
    ----------
    lever : Lever
        A V-shaped lever.

    Returns
    -------
    float
    """
    _v(lever)
    apex = lever.with_(tip_position=None) if lever.tip_position != lever.length else lever
    return parallel_beam_spring_constant(lever) / apex.spring_constant - 1.0


def _v(lever) -> None:
    check_instance("lever", lever, Lever)
    if lever.planform != "v_shaped":
        raise ValueError(f"lever must be a v_shaped Lever, got a {lever.planform} one")


from ._probes import PRESETS, preset  # noqa: E402  (the presets are Levers)
