"""Module (a): cantilever mechanics of a rectangular Euler-Bernoulli beam.

A rectangular cantilever of length L, width w, thickness h, Young's modulus E and density rho is
clamped at x = 0 and loaded by a point force F at its free end x = L. Solving E J z'''' = 0 with
z(0) = z'(0) = 0 (clamp), z''(L) = 0 (no moment) and E J z'''(L) = -F (end shear), in the sign
convention where F > 0 lifts the tip (z > 0), gives (see
``notebooks/01_cantilever_mechanics.ipynb`` and
``tests/test_cantilever_model.py`` for the sympy derivation)::

    z(x)     = F L^3 / (6 E J) [3 (x/L)^2 - (x/L)^3]
    theta(x) = F L^2 / (2 E J) [2 (x/L) - (x/L)^2]
    z''(x)   = F (L - x) / (E J)
    sigma(x, z_b) = -E z_b z''(x),     J = w h^3 / 12

with z_b the distance from the neutral (mid) plane, in [-h/2, h/2] (positive towards +z). The
spring constant is k = 3 E J / L^3. Free flexural vibrations have mode shapes
cosh(b x) - cos(b x) - s (sinh(b x) - sin(b x)) with b_n L the roots of cos(bL) cosh(bL) = -1,
found here numerically, and frequencies f_n = (b_n L)^2 / (2 pi L^2) sqrt(E J / (rho w h)).

The formulas are those of every strength-of-materials text (e.g. Timoshenko and Gere, *Mechanics
of Materials*) as applied to AFM levers by Butt and Jaschke, Nanotechnology 6, 1 (1995), Butt,
Cappella and Kappl, Surf. Sci. Rep. 59, 1 (2005) and Sader, J. Appl. Phys. 84, 64 (1998); the
eigenvalues are those tabulated by Blevins, *Formulas for Natural Frequency and Mode Shape*
(1979), Table 8-1. Module (a) of the AFM SMILER toolkit ("AFM SMILER: A Scale Model Interactive
Learning Extended Reality Toolkit for Atomic Force Microscopy Created with Digital Twin
Technology") is the model this course re-creates.

The user-settable quantities are described once in :data:`PARAMETERS` (SI unit, display unit,
valid and slider ranges); :class:`Cantilever` validates with them and the widget panel builds its
sliders from them. One load case is computed at once by :meth:`Cantilever.bending`, whose
:class:`Bending` result the figures and the 3D view draw without computing anything again.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from functools import lru_cache

import numpy as np
from scipy.optimize import brentq

from .materials import DENSITY, YOUNGS_MODULUS, Material, lookup
from .parameters import Parameter, read_only
from .validation import check_array, check_instance, check_integer, check_range

__all__ = ["Cantilever", "Bending", "eigenvalue", "check_modes", "MAX_MODE", "PARAMETERS",
           "FORCE", "LENGTH", "WIDTH", "THICKNESS", "SECTION", "EXAGGERATION", "LIMITS"]

#: Highest flexural mode the model offers (beyond it, thin-beam theory is meaningless anyway).
MAX_MODE = 50

# -- the parameter vocabulary of module (a) ------------------------------------------------------
# Valid ranges keep every result finite in double precision (a 1 nm to 1 m beam of 1 Pa to 10 TPa
# under at most 10^6 N: z(L) <= 10^43 m, sigma <= 10^34 Pa); the slider ranges are the panel's (a contact lever like BudgetSensors
# ContAl-G, 450 x 50 x 2 um of silicon, by default; L up to 1000 um so that it can be doubled).
#: End force F (positive lifts the tip).
FORCE = Parameter(name="force", unit="N", display_unit="nN", default=100e-9, low=-1e6, high=1e6,
                  slider_low=-500e-9, slider_high=500e-9, label="end force F")
#: Lever length L (clamp to free end).
LENGTH = Parameter(name="length", unit="m", display_unit="um", default=450e-6, low=1e-9, high=1.0,
                   slider_low=20e-6, slider_high=1000e-6, label="length L")
#: Lever width w.
WIDTH = Parameter(name="width", unit="m", display_unit="um", default=50e-6, low=1e-9, high=1.0,
                  slider_low=5e-6, slider_high=100e-6, label="width w")
#: Lever thickness h.
THICKNESS = Parameter(name="thickness", unit="m", display_unit="um", default=2e-6, low=1e-9,
                      high=1.0, slider_low=0.2e-6, slider_high=10e-6, label="thickness h")
#: Position of the cross-section as a fraction x/L of the length (it can never leave the lever).
SECTION = Parameter(name="section", unit="", default=0.0, low=0.0, high=1.0,
                    label="section x/L")
#: Factor by which the 3D view exaggerates the deflection.
EXAGGERATION = Parameter(name="exaggeration", unit="", display_unit="x", default=100.0, low=1.0,
                         high=1e6, slider_low=1.0, slider_high=1e4, log=True,
                         label="exaggeration")

#: Every user-settable quantity of module (a), by keyword name (read-only).
PARAMETERS = read_only({p.name: p for p in (FORCE, LENGTH, WIDTH, THICKNESS, YOUNGS_MODULUS,
                                            DENSITY, SECTION, EXAGGERATION)})

#: Largest grids of :meth:`Cantilever.bending` (a call at these limits takes well under a second).
LIMITS = read_only(dict(n_length=10_000, n_thickness=1_000, n_section=10_000,
                        n_field=2_000_000))


def check_modes(modes, name: str = "modes") -> list:
    """Return ``modes`` as a list of mode numbers; raise naming ``name`` unless it is a sequence of
    1 to :data:`MAX_MODE` integers, each in [1, MAX_MODE].

    Parameters
    ----------
    modes : sequence of int
        Mode numbers (1-based).
    name : str
        The parameter's name, for the message.

    Returns
    -------
    list of int
    """
    check_instance("name", name, str)
    if isinstance(modes, (str, bytes)) or not isinstance(modes, (list, tuple, range, np.ndarray)):
        raise TypeError(f"{name} must be a sequence of mode numbers, got "
                        f"{type(modes).__name__} {modes!r:.60}")
    if not 1 <= len(modes) <= MAX_MODE:
        raise ValueError(f"{name} must name 1 to {MAX_MODE} modes, got {len(modes)}")
    return [check_integer(name, m, 1, MAX_MODE) for m in modes]


def eigenvalue(mode: int) -> float:
    """Dimensionless eigenvalue b_n L of flexural mode ``mode`` (1-based) of a clamped-free beam.

    The root of cos(x) cosh(x) = -1 in the n-th bracket around (n - 1/2) pi, found with Brent's
    method on the equivalent, well-scaled form cos(x) + 1 / cosh(x) = 0.

    Parameters
    ----------
    mode : int
        Mode number, 1 to :data:`MAX_MODE`.

    Returns
    -------
    float
        b_n L (1.8751..., 4.6941..., 7.8548..., ...).
    """
    return _eigenvalue(check_integer("mode", mode, 1, MAX_MODE))


@lru_cache(maxsize=None)
def _eigenvalue(mode: int) -> float:
    centre = (mode - 0.5) * math.pi
    return brentq(lambda x: math.cos(x) + 1.0 / math.cosh(x), centre - 0.5, centre + 0.5,
                  xtol=1e-15, rtol=4 * np.finfo(float).eps, maxiter=200)


@dataclass(frozen=True)
class Bending:
    """One load case of a lever, sampled for drawing (:meth:`Cantilever.bending`), in SI units.

    The figures and the 3D view of module (a) draw from it and compute nothing themselves, so that
    one slider move runs the model once.

    Attributes
    ----------
    lever : Cantilever
        The lever.
    force : float
        End force F in N.
    section : float
        Position of the cross-section as a fraction x/L.
    x : ndarray, shape (n_length,)
        Stations along the lever in m, from 0 to L.
    z_b : ndarray, shape (n_thickness,)
        Levels through the thickness in m, from -h/2 (bottom) to +h/2 (top).
    deflection : ndarray, shape (n_length,)
        z(x) in m.
    slope : ndarray, shape (n_length,)
        theta(x) in rad.
    stress : ndarray, shape (n_length, n_thickness)
        Bending stress sigma(x, z_b) in Pa.
    section_z_b : ndarray, shape (n_section,)
        Levels through the thickness at the cross-section in m, from -h/2 to +h/2.
    section_stress : ndarray, shape (n_section,)
        sigma(section x, z_b) in Pa.
    section_strain : ndarray, shape (n_section,)
        Axial strain there (dimensionless).
    frequencies : tuple of float
        f_1, f_2, ... of the first ``modes`` flexural modes in Hz.
    mode_shapes : ndarray, shape (modes, n_length)
        Their shapes at ``x``, 1 at the free end.
    """

    lever: "Cantilever"
    force: float
    section: float
    x: np.ndarray
    z_b: np.ndarray
    deflection: np.ndarray
    slope: np.ndarray
    stress: np.ndarray
    section_z_b: np.ndarray
    section_stress: np.ndarray
    section_strain: np.ndarray
    frequencies: tuple
    mode_shapes: np.ndarray

    @property
    def section_x(self) -> float:
        """Position of the cross-section in m."""
        return self.section * self.lever.length

    @property
    def spring_constant(self) -> float:
        """k of the lever in N/m."""
        return self.lever.spring_constant

    @property
    def tip_deflection(self) -> float:
        """z(L) in m."""
        return float(self.deflection[-1])

    @property
    def tip_slope(self) -> float:
        """theta(L) in rad (the largest slope)."""
        return float(self.slope[-1])

    @property
    def top_stress(self) -> np.ndarray:
        """sigma(x, +h/2) in Pa, the top surface."""
        return self.stress[:, -1]

    @property
    def max_stress(self) -> float:
        """Largest |sigma| in Pa (on a surface at the clamp: 6 |F| L / (w h^2))."""
        return float(np.abs(self.stress).max())


@dataclass(frozen=True)
class Cantilever:
    """A rectangular, clamped-free Euler-Bernoulli cantilever with an end load.

    Parameters
    ----------
    length : float
        Length L in m (clamp to free end).
    width : float
        Width w in m.
    thickness : float
        Thickness h in m.
    youngs_modulus : float
        Young's modulus E in Pa.
    density : float
        Density rho in kg/m^3.

    Raises
    ------
    ValueError
        If a parameter is outside its valid range (:data:`PARAMETERS`: dimensions 1 nm to 1 m,
        E 1 Pa to 10 TPa, rho 1 to 10^5 kg/m^3), naming it, its value and the range.

    Examples
    --------
    >>> lever = Cantilever.from_material("silicon", length=125e-6, width=30e-6, thickness=4e-6)
    >>> round(lever.spring_constant, 1)  # N/m
    41.5
    """

    length: float
    width: float
    thickness: float
    youngs_modulus: float
    density: float

    def __post_init__(self):
        for name in ("length", "width", "thickness", "youngs_modulus", "density"):
            object.__setattr__(self, name, PARAMETERS[name].check(getattr(self, name)))

    # -- construction ---------------------------------------------------------------------
    @classmethod
    def from_material(cls, material: str | Material, length: float = LENGTH.default,
                      width: float = WIDTH.default,
                      thickness: float = THICKNESS.default) -> "Cantilever":
        """Build a cantilever from a vendor-style description: nominal L, w, h and a material.

        Parameters
        ----------
        material : str or Material
            A key of :data:`afmsmiler.materials.MATERIALS` (``"silicon"``,
            ``"silicon_nitride"``, ...) or a :class:`~afmsmiler.materials.Material`.
        length : float
            Nominal length L in m, as printed on the datasheet.
        width : float
            Nominal width w in m.
        thickness : float
            Nominal thickness h in m.

        Returns
        -------
        Cantilever

        Raises
        ------
        ValueError
            For an unknown material or a dimension outside its valid range.
        TypeError
            If ``material`` is neither a string nor a Material.
        """
        m = lookup(material, "material")
        return cls(length, width, thickness, m.youngs_modulus, m.density)

    # -- statics --------------------------------------------------------------------------
    @property
    def area_moment(self) -> float:
        """Second moment of area J = w h^3 / 12 in m^4."""
        return self.width * self.thickness ** 3 / 12.0

    @property
    def flexural_rigidity(self) -> float:
        """E J in N m^2."""
        return self.youngs_modulus * self.area_moment

    @property
    def spring_constant(self) -> float:
        """End-load spring constant k = 3 E J / L^3 in N/m."""
        return 3.0 * self.flexural_rigidity / self.length ** 3

    @property
    def mass(self) -> float:
        """Mass of the beam rho L w h in kg."""
        return self.density * self.length * self.width * self.thickness

    @property
    def effective_mass(self) -> float:
        """Mass of the equivalent point-mass oscillator of mode 1, k / (2 pi f1)^2, in kg."""
        return self.spring_constant / (2 * math.pi * self.resonance_frequency(1)) ** 2

    def _x(self, x) -> np.ndarray:
        return check_array("x", x, "m", low=0.0, high=self.length)

    def _force(self, force) -> float:
        return FORCE.check(force)

    def deflection(self, x, force):
        """Deflection z(x) in m under an end force.

        Parameters
        ----------
        x : float or array_like
            Position along the lever in m, in [0, L].
        force : float
            End force F in N (positive lifts the tip).

        Returns
        -------
        float or ndarray
            z(x) = F L^3 / (6 E J) [3 (x/L)^2 - (x/L)^3], same shape as ``x``.
        """
        x = self._x(x)
        force = self._force(force)
        u = x / self.length
        return force * self.length ** 3 / (6 * self.flexural_rigidity) * (3 * u ** 2 - u ** 3)

    def slope(self, x, force):
        """Slope theta(x) = dz/dx in rad: F L^2 / (2 E J) [2 (x/L) - (x/L)^2].

        Parameters
        ----------
        x : float or array_like
            Position along the lever in m, in [0, L].
        force : float
            End force F in N (positive lifts the tip).
        """
        x = self._x(x)
        force = self._force(force)
        u = x / self.length
        return force * self.length ** 2 / (2 * self.flexural_rigidity) * (2 * u - u ** 2)

    def curvature(self, x, force):
        """Curvature d2z/dx2 = F (L - x) / (E J) in 1/m.

        Parameters
        ----------
        x : float or array_like
            Position along the lever in m, in [0, L].
        force : float
            End force F in N (positive lifts the tip).
        """
        x = self._x(x)
        force = self._force(force)
        return force * (self.length - x) / self.flexural_rigidity

    def bending_moment(self, x, force):
        """Bending moment M(x) = E J z''(x) = F (L - x) in N m.

        Parameters
        ----------
        x : float or array_like
            Position along the lever in m, in [0, L].
        force : float
            End force F in N (positive lifts the tip).
        """
        return self.flexural_rigidity * self.curvature(x, force)

    def _z_b(self, z_b) -> np.ndarray:
        h2 = self.thickness / 2
        return check_array("z_b", z_b, "m", low=-h2, high=h2)

    def strain(self, x, z_b, force):
        """Axial bending strain -z_b z''(x) (dimensionless).

        Parameters
        ----------
        x : float or array_like
            Position along the lever in m, in [0, L].
        z_b : float or array_like
            Distance from the neutral plane in m, in [-h/2, h/2]; broadcasts against ``x``.
        force : float
            End force in N.
        """
        z_b = self._z_b(z_b)
        curvature = self.curvature(x, force)
        try:
            np.broadcast_shapes(z_b.shape, curvature.shape)
        except ValueError:
            raise ValueError(f"z_b must broadcast against x: z_b has shape {z_b.shape}, "
                             f"x has shape {curvature.shape}") from None
        return -z_b * curvature

    def stress(self, x, z_b, force):
        """Axial bending stress sigma = -E z_b z''(x) in Pa (negative is compressive).

        Parameters
        ----------
        x : float or array_like
            Position along the lever in m, in [0, L].
        z_b : float or array_like
            Distance from the neutral plane in m, in [-h/2, h/2]; broadcasts against ``x``.
        force : float
            End force in N.

        Notes
        -----
        The largest magnitude is at the clamp surface, 6 F L / (w h^2).
        """
        return self.youngs_modulus * self.strain(x, z_b, force)

    def force_for_deflection(self, tip_deflection: float) -> float:
        """End force in N that deflects the tip by ``tip_deflection``: F = k z.

        Parameters
        ----------
        tip_deflection : float
            Tip deflection z(L) in m, at most L either way (far beyond small deflections).
        """
        return self.spring_constant * check_range("tip_deflection", tip_deflection,
                                                  -self.length, self.length, "m")

    def bending(self, force: float = FORCE.default, *, section: float = SECTION.default,
                n_length: int = 201, n_thickness: int = 9, n_section: int = 41,
                modes: int = 3) -> Bending:
        """The lever under an end ``force``, sampled on a grid for figures and 3D views.

        Parameters
        ----------
        force : float
            End force F in N, in [-10^6, 10^6] (positive lifts the tip).
        section : float
            Position of the cross-section as a fraction x/L, in [0, 1].
        n_length : int
            Stations along the lever, 2 to 10000.
        n_thickness : int
            Levels through the thickness of the stress field, 2 to 1000 (odd: one is the neutral
            plane); n_length x n_thickness at most 2 x 10^6.
        n_section : int
            Levels through the thickness at the cross-section, 2 to 10000.
        modes : int
            Flexural modes whose frequencies and shapes are included, 0 to :data:`MAX_MODE`.

        Returns
        -------
        Bending

        Raises
        ------
        ValueError
            Naming the argument outside its range, before any work.

        Examples
        --------
        >>> lever = Cantilever.from_material("silicon", length=450e-6, width=50e-6,
        ...                                  thickness=2e-6)
        >>> b = lever.bending(100e-9, n_length=5)
        >>> round(b.tip_deflection / 1e-9, 1)  # nm: F / k
        539.2
        """
        force = self._force(force)
        section = SECTION.check(section)
        n_length = check_integer("n_length", n_length, 2, LIMITS["n_length"])
        n_thickness = check_integer("n_thickness", n_thickness, 2, LIMITS["n_thickness"])
        if n_length * n_thickness > LIMITS["n_field"]:
            raise ValueError(f"n_length x n_thickness must be at most {LIMITS['n_field']}, got "
                             f"{n_length} x {n_thickness}")
        n_section = check_integer("n_section", n_section, 2, LIMITS["n_section"])
        modes = check_integer("modes", modes, 0, MAX_MODE)
        x = np.linspace(0.0, self.length, n_length)
        z_b = np.linspace(-0.5, 0.5, n_thickness) * self.thickness
        sz = np.linspace(-0.5, 0.5, n_section) * self.thickness
        section_strain = self.strain(section * self.length, sz, force)
        return Bending(
            lever=self, force=force, section=section, x=x, z_b=z_b,
            deflection=self.deflection(x, force), slope=self.slope(x, force),
            stress=self.stress(x[:, None], z_b[None, :], force),
            section_z_b=sz, section_stress=self.youngs_modulus * section_strain,
            section_strain=section_strain,
            frequencies=tuple(self.resonance_frequency(n) for n in range(1, modes + 1)),
            mode_shapes=np.array([self.mode_shape(x, n) for n in range(1, modes + 1)]
                                 ).reshape(modes, n_length))

    # -- dynamics -------------------------------------------------------------------------
    def resonance_frequency(self, mode: int = 1) -> float:
        """Frequency of flexural mode ``mode`` (1-based) in Hz (undamped, in vacuum).

        f_n = (b_n L)^2 / (2 pi L^2) sqrt(E J / (rho w h)), with b_n L from :func:`eigenvalue`.

        Parameters
        ----------
        mode : int
            Mode number, 1 to :data:`MAX_MODE`.
        """
        beta_l = eigenvalue(mode)
        return beta_l ** 2 / (2 * math.pi * self.length ** 2) * math.sqrt(
            self.flexural_rigidity / (self.density * self.width * self.thickness))

    def mode_shape(self, x, mode: int = 1):
        """Shape of flexural mode ``mode`` at ``x``, normalised to +1 at the free end.

        Parameters
        ----------
        x : float or array_like
            Position along the lever in m, in [0, L].
        mode : int
            Mode number, 1 to :data:`MAX_MODE`.
        """
        x = self._x(x)
        bl = eigenvalue(mode)
        u = bl * x / self.length
        denom = math.sinh(bl) + math.sin(bl)
        s = (math.cosh(bl) + math.cos(bl)) / denom
        # cosh - s sinh = ((1 - s) e^u + (1 + s) e^-u) / 2 with 1 - s computed without
        # cancellation, so that high modes (s -> 1) keep their accuracy
        one_minus_s = (math.sin(bl) - math.cos(bl) - math.exp(-bl)) / denom

        def phi(v):
            return (0.5 * (one_minus_s * np.exp(v) + (2 - one_minus_s) * np.exp(-v))
                    - np.cos(v) + s * np.sin(v))
        return phi(u) / phi(bl)
