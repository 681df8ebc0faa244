"""Tip-sample force of the dynamic modes: van der Waals attraction, DMT contact, sample damping.

A sphere of radius R above a flat sample at distance d (m; d < a0 means contact, indentation
delta = a0 - d) feels, in the model that Garcia and Perez use for amplitude-modulation AFM
(R. Garcia and R. Perez, "Dynamic atomic force microscopy methods", Surf. Sci. Rep. 47, 197
(2002))::

    F(d) = -H R / (6 d^2)                                         d >  a0  (van der Waals)
    F(d) = -H R / (6 a0^2) + (4/3) E* sqrt(R) (a0 - d)^(3/2)       d <= a0  (DMT contact)
           - eta sqrt(R (a0 - d)) v                                (viscous sample damping)

with the Hamaker constant H, the intermolecular distance a0 (which caps the van der Waals force at
its contact value: the two branches meet at d = a0), the reduced modulus E* of module (d)
(:func:`afmsmiler.contact.reduced_modulus`, a rigid tip) and the sample viscosity eta; v is the
tip's velocity (positive away from the sample), so the damping force opposes the motion. F > 0
pushes the tip away from the sample. The adhesion force H R / (6 a0^2) is DMT's pull-off force
2 pi R w with the work of adhesion w = H / (12 pi a0^2) (Israelachvili, *Intermolecular and
Surface Forces*, 3rd ed., Sec. 13.6), so the contact branch is module (d)'s DMT force of a
paraboloid (Derjaguin, Muller and Toporov, J. Colloid Interface Sci. 53, 314 (1975)).
"""
from __future__ import annotations

import math

import numpy as np

from ..contact.quantities import PARAMETERS as CONTACT
from ..contact.tips import RADIUS, reduced_modulus
from ..parameters import Parameter, read_only
from ..validation import check_array

__all__ = ["FORCE_PARAMETERS", "tip_sample_force", "work_of_adhesion"]

#: The force law's quantities (SI): a 10 nm silicon tip on a 1 GPa polymer in air, Garcia and
#: Perez's (2002) typical values (H = 6.4e-20 J, a0 = 0.165 nm).
FORCE_PARAMETERS = read_only({p.name: p for p in (
    RADIUS.with_(default=10e-9, slider_low=1e-9, slider_high=100e-9),
    Parameter(name="hamaker_constant", unit="J", display_unit="zJ", default=6.4e-20, low=0.0,
              high=1e-18, slider_low=1e-21, slider_high=5e-19, log=True,
              label="Hamaker constant H"),
    CONTACT["youngs_modulus"].with_(default=1e9, slider_low=1e6, slider_high=200e9),
    CONTACT["poisson_ratio"],
    Parameter(name="intermolecular_distance", unit="m", display_unit="nm", default=0.165e-9,
              low=1e-11, high=1e-9, slider_low=0.1e-9, slider_high=0.5e-9,
              label="intermolecular distance a0"),
    Parameter(name="sample_viscosity", unit="Pa s", display_unit="Pa s", default=0.0, low=0.0,
              high=1e5, slider_low=0.0, slider_high=2000.0, label="sample viscosity eta"),
)})


def work_of_adhesion(hamaker_constant: float, intermolecular_distance: float) -> float:
    """Work of adhesion w = H / (12 pi a0^2) in J/m^2 that gives the same pull-off force.

    Parameters
    ----------
    hamaker_constant : float
        Hamaker constant H in J.
    intermolecular_distance : float
        Intermolecular distance a0 in m.

    Returns
    -------
    float
        w in J/m^2 (DMT's pull-off force 2 pi R w equals H R / (6 a0^2)).
    """
    h = FORCE_PARAMETERS["hamaker_constant"].check(hamaker_constant)
    a0 = FORCE_PARAMETERS["intermolecular_distance"].check(intermolecular_distance)
    return h / (12.0 * math.pi * a0 * a0)


def _force(d, v, radius, hamaker, e_star, a0, eta):
    """F(d, v) in N for arrays already checked (no validation: the solvers' inner loop)."""
    d = np.asarray(d, dtype=float)
    delta = np.maximum(a0 - d, 0.0)
    far = d > a0
    vdw = -hamaker * radius / (6.0 * np.where(far, d, a0) ** 2)
    sq = np.sqrt(radius * delta)
    contact = 4.0 / 3.0 * e_star * sq * delta - eta * sq * np.asarray(v, dtype=float)
    return vdw + np.where(far, 0.0, contact)


def tip_sample_force(distance, velocity=0.0, *,
                     radius: float = FORCE_PARAMETERS["radius"].default,
                     hamaker_constant: float = FORCE_PARAMETERS["hamaker_constant"].default,
                     youngs_modulus: float = FORCE_PARAMETERS["youngs_modulus"].default,
                     poisson_ratio: float = FORCE_PARAMETERS["poisson_ratio"].default,
                     intermolecular_distance: float =
                     FORCE_PARAMETERS["intermolecular_distance"].default,
                     sample_viscosity: float = FORCE_PARAMETERS["sample_viscosity"].default):
    """Tip-sample force F(d, v) in N: van der Waals above a0, DMT contact (and damping) below.

    Parameters
    ----------
    distance : float or array_like
        Tip-sample distance d in m (d < a0: in contact, indentation a0 - d); > -1e-6 m.
    velocity : float or array_like
        Tip velocity v in m/s (positive away from the sample); only the damping term uses it.
    radius : float
        Tip radius R in m.
    hamaker_constant : float
        Hamaker constant H in J.
    youngs_modulus : float
        Young's modulus E of the sample in Pa.
    poisson_ratio : float
        Poisson's ratio nu of the sample.
    intermolecular_distance : float
        Intermolecular distance a0 in m.
    sample_viscosity : float
        Sample viscosity eta in Pa s (0: no damping).

    Returns
    -------
    float or ndarray
        F in N (positive pushes the tip away from the sample), broadcast over d and v.

    Raises
    ------
    ValueError
        Naming the parameter that is out of its range (see :data:`FORCE_PARAMETERS`).
    """
    p = FORCE_PARAMETERS
    r = p["radius"].check(radius)
    h = p["hamaker_constant"].check(hamaker_constant)
    e_star = reduced_modulus(p["youngs_modulus"].check(youngs_modulus),
                             p["poisson_ratio"].check(poisson_ratio))
    a0 = p["intermolecular_distance"].check(intermolecular_distance)
    eta = p["sample_viscosity"].check(sample_viscosity)
    d = check_array("distance", distance, "m", low=-1e-6)
    v = check_array("velocity", velocity, "m/s")
    out = _force(d, v, r, h, e_star, a0, eta)
    return out if out.ndim else float(out)
