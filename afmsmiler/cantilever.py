"""Module (a): cantilever mechanics of a rectangular Euler-Bernoulli beam.

A rectangular cantilever of length L, width w, thickness h, Young's modulus E and density rho is
clamped at x = 0 and loaded by a point force F at its free end x = L. Solving E J z'''' = 0 with
z(0) = z'(0) = 0 (clamp), z''(L) = 0 (no moment) and E J z'''(L) = -F (end shear), in the sign
convention where F > 0 lifts the tip (z > 0), gives (see ``notebooks/01_cantilever_mechanics.ipynb`` and
``tests/test_cantilever_model.py`` for the sympy derivation)::

    z(x)     = F L^3 / (6 E J) [3 (x/L)^2 - (x/L)^3]
    theta(x) = F L^2 / (2 E J) [2 (x/L) - (x/L)^2]
    z''(x)   = F (L - x) / (E J)
    sigma(x, z_b) = -E z_b z''(x),     J = w h^3 / 12

with z_b the distance from the neutral (mid) plane, in [-h/2, h/2] (positive towards +z). The
spring constant is k = 3 E J / L^3. Free flexural vibrations have mode shapes
cosh(b x) - cos(b x) - s (sinh(b x) - sin(b x)) with b_n L the roots of cos(bL) cosh(bL) = -1,
found here numerically, and frequencies f_n = (b_n L)^2 / (2 pi L^2) sqrt(E J / (rho w h)).
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from functools import lru_cache

import numpy as np
from scipy.optimize import brentq

from .materials import Material, get_material
from .validation import check_array, check_integer, check_positive, check_range

__all__ = ["Cantilever", "eigenvalue", "MAX_MODE"]

#: Highest flexural mode the model offers (beyond it, thin-beam theory is meaningless anyway).
MAX_MODE = 50


@lru_cache(maxsize=None)
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
    check_integer("mode", mode, 1, MAX_MODE)
    centre = (mode - 0.5) * math.pi
    return brentq(lambda x: math.cos(x) + 1.0 / math.cosh(x), centre - 0.5, centre + 0.5,
                  xtol=1e-15, rtol=4 * np.finfo(float).eps, maxiter=200)


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
        If a parameter is not finite and positive.

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
        for name, unit in (("length", "m"), ("width", "m"), ("thickness", "m"),
                           ("youngs_modulus", "Pa"), ("density", "kg/m^3")):
            object.__setattr__(self, name, check_positive(name, getattr(self, name), unit))

    # -- construction ---------------------------------------------------------------------
    @classmethod
    def from_material(cls, material: str | Material, length: float, width: float,
                      thickness: float) -> "Cantilever":
        """Build a cantilever from a vendor-style description: nominal L, w, h and a material.

        Parameters
        ----------
        material : str or Material
            A key of :data:`afmsmiler.materials.MATERIALS` (``"silicon"``,
            ``"silicon_nitride"``, ...) or a :class:`~afmsmiler.materials.Material`.
        length, width, thickness : float
            Nominal dimensions in m, as printed on the datasheet.
        """
        m = get_material(material)
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
        return check_range("force", force, -math.inf, math.inf, "N")

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
        return -z_b * self.curvature(x, force)

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
        """End force in N that deflects the tip by ``tip_deflection`` (m): F = k z."""
        return self.spring_constant * check_range("tip_deflection", tip_deflection,
                                                  -math.inf, math.inf, "m")

    # -- dynamics -------------------------------------------------------------------------
    def resonance_frequency(self, mode: int = 1) -> float:
        """Frequency of flexural mode ``mode`` (1-based) in Hz (undamped, in vacuum).

        f_n = (b_n L)^2 / (2 pi L^2) sqrt(E J / (rho w h)), with b_n L from :func:`eigenvalue`.
        """
        beta_l = eigenvalue(mode)
        return beta_l ** 2 / (2 * math.pi * self.length ** 2) * math.sqrt(
            self.flexural_rigidity / (self.density * self.width * self.thickness))

    def mode_shape(self, x, mode: int = 1):
        """Shape of flexural mode ``mode`` at ``x`` (m), normalised to +1 at the free end."""
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
