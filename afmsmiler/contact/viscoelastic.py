"""A viscoelastic sample: the standard linear solid, with the hereditary integral of Lee and Radok.

The standard linear solid (a spring in parallel with a spring-dashpot arm) relaxes as::

    E(t) = E_inf + (E_0 - E_inf) exp(-t / tau)

For a rigid tip whose elastic law is F = E* psi(Z_s) (psi = F at E* = 1 Pa), the force under an
indentation history Z_s(t) whose contact grows is the hereditary integral (Lee and Radok,
J. Appl. Mech. 27, 438 (1960); Ting, J. Appl. Mech. 33, 845 (1966))::

    F(t) = 1/(1 - nu^2) * integral_0^t E(t - s) d psi(Z_s(s))/ds ds

With the exponential kernel, the integral is carried forward by one number per step: with
h(t) = integral exp(-(t - s)/tau) d psi and psi taken linear within a step of length dt,

    h_n = exp(-dt/tau) h_(n-1) + phi (psi_n - psi_(n-1)),   phi = (tau/dt)(1 - exp(-dt/tau)),

which is exact for a piecewise-linear psi(t). Coupled to the cantilever (F = k (Z_np - Z_s)), each
step is the elastic problem with the effective modulus E*_inf + phi (E*_0 - E*_inf) and a force
offset, solved by the same exact solver as :func:`~afmsmiler.contact.indent`.

Limits (tested): tau -> 0 gives the elastic curve with E_inf, tau -> inf the elastic curve with E_0.
On retract the model keeps Lee and Radok's integral while the force is compressive and lets the
tip leave the surface when it would turn tensile (the surface then recovers more slowly than the
tip retracts; re-contact within the same cycle is not modelled). Ting's correction for a
shrinking contact area is not applied: retract curves are qualitative beyond the turning point.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..validation import check_array, check_positive, check_range
from .indent import IndentationCurve, _check_common, _check_depth
from .tips import Tip

__all__ = ["StandardLinearSolid", "hereditary_force", "viscoelastic_approach_retract",
           "ViscoelasticCycle"]


@dataclass(frozen=True)
class StandardLinearSolid:
    """Relaxation modulus E(t) = E_inf + (E_0 - E_inf) exp(-t / tau) of a standard linear solid.

    Parameters
    ----------
    relaxed_modulus : float
        Long-time modulus E_inf in Pa, > 0.
    instantaneous_modulus : float
        Short-time modulus E_0 in Pa, >= E_inf.
    relaxation_time : float
        tau in s, > 0.

    Raises
    ------
    ValueError
        If a modulus is not positive, E_0 < E_inf, or tau is not positive.
    """

    relaxed_modulus: float
    instantaneous_modulus: float
    relaxation_time: float

    def __post_init__(self):
        e_inf = check_positive("relaxed_modulus", self.relaxed_modulus, "Pa")
        e_0 = check_range("instantaneous_modulus", self.instantaneous_modulus, e_inf, math.inf,
                          "Pa", high_inclusive=False)
        tau = check_positive("relaxation_time", self.relaxation_time, "s")
        object.__setattr__(self, "relaxed_modulus", e_inf)
        object.__setattr__(self, "instantaneous_modulus", e_0)
        object.__setattr__(self, "relaxation_time", tau)

    def modulus(self, time):
        """Relaxation modulus E(t) in Pa.

        Parameters
        ----------
        time : float or array_like
            Time since a step strain in s, >= 0.
        """
        t = check_array("time", time, "s", low=0.0)
        return self.relaxed_modulus + (self.instantaneous_modulus - self.relaxed_modulus) * np.exp(
            -t / self.relaxation_time)


def _kernel(dt, tau):
    with np.errstate(over="ignore", under="ignore"):
        x = dt / tau
        decay = np.exp(-x)
        # phi = (1 - e^-x) / x, with expm1 for small x and the x -> 0 limit 1
        phi = np.where(x > 0, -np.expm1(-x) / np.where(x > 0, x, 1.0), 1.0)
    return decay, phi


def hereditary_force(time, indentation, tip, material, poisson_ratio):
    """Force in N under a prescribed indentation history (an infinitely stiff lever).

    Parameters
    ----------
    time : array_like
        Sample times in s, strictly increasing.
    indentation : array_like
        Z_s(t) in m, >= 0, same length; taken linear in psi between samples.
    tip : Tip
        The tip shape.
    material : StandardLinearSolid
        The sample's relaxation modulus.
    poisson_ratio : float
        nu of the sample, in [0, 0.5).

    Returns
    -------
    ndarray
        F(t) = 1/(1 - nu^2) integral E(t - s) d psi(Z_s(s)).
    """
    t = check_array("time", time, "s", ndim=1, min_size=2, increasing=True)
    z = check_array("indentation", indentation, "m", ndim=1, size=t.size, low=0.0)
    if not isinstance(tip, Tip):
        raise ValueError(f"tip must be a Tip, got {tip!r}")
    if not isinstance(material, StandardLinearSolid):
        raise ValueError(f"material must be a StandardLinearSolid, got {material!r}")
    nu = check_range("poisson_ratio", poisson_ratio, 0.0, 0.5, high_inclusive=False)
    psi = tip.force(z, 1.0)
    scale = 1.0 / (1.0 - nu * nu)
    decay, phi = _kernel(np.diff(t), material.relaxation_time)
    d_psi = np.diff(psi)
    h = np.empty_like(psi)
    h[0] = psi[0]
    for n in range(1, psi.size):
        h[n] = decay[n - 1] * h[n - 1] + phi[n - 1] * d_psi[n - 1]
    delta = material.instantaneous_modulus - material.relaxed_modulus
    return scale * (material.relaxed_modulus * psi + delta * h)


@dataclass(frozen=True)
class ViscoelasticCycle:
    """An approach-retract cycle on a standard linear solid.

    Parameters
    ----------
    approach, retract : IndentationCurve
        The two branches (the retract runs the ramp backwards).
    time : ndarray
        Times in s of the approach samples followed by the retract samples.
    """

    approach: IndentationCurve
    retract: IndentationCurve
    time: np.ndarray


def viscoelastic_approach_retract(z_np, spring_constant, tip, material, poisson_ratio, speed):
    """Approach and retract at constant positioner speed on a standard linear solid.

    Parameters
    ----------
    z_np : array_like
        Approach ramp of Z_np in m, strictly increasing (the retract runs it backwards).
    spring_constant : float
        k in N/m, > 0.
    tip : Tip
        The tip shape.
    material : StandardLinearSolid
        E_inf, E_0 and tau of the sample.
    poisson_ratio : float
        nu of the sample, in [0, 0.5).
    speed : float
        Positioner speed |dZ_np/dt| in m/s, > 0.

    Returns
    -------
    ViscoelasticCycle

    Raises
    ------
    ValueError
        On bad parameters, or a sphere that would be indented past its radius.

    Notes
    -----
    See the module docstring: Lee and Radok's hereditary integral, advanced exactly for a
    piecewise-linear psi(Z_s(t)), each step an elastic solve with an effective modulus.
    """
    z = check_array("z_np", z_np, "m", ndim=1, min_size=2, increasing=True)
    if not isinstance(material, StandardLinearSolid):
        raise ValueError(f"material must be a StandardLinearSolid, got {material!r}")
    z, k, e0 = _check_common(z, spring_constant, tip, material.instantaneous_modulus, poisson_ratio)
    v = check_positive("speed", speed, "m/s")
    _check_depth(tip, z, k, e0)  # E_0 bounds the indentation from below; E_inf from above
    scale = e0 / material.instantaneous_modulus  # 1 / (1 - nu^2)
    _check_depth(tip, z, k, material.relaxed_modulus * scale)
    path = np.concatenate([z, z[::-1][1:]])
    time = np.concatenate([[0.0], np.cumsum(np.abs(np.diff(path)) / v)])
    decay, phi = _kernel(np.diff(time), material.relaxation_time)
    e_inf = material.relaxed_modulus * scale
    d_e = (material.instantaneous_modulus - material.relaxed_modulus) * scale
    n = path.size
    z_s = np.zeros(n)
    force = np.zeros(n)
    contact = np.zeros(n, dtype=bool)
    h = 0.0
    psi_prev = 0.0
    lifted = False
    for i in range(n):
        a, p = (decay[i - 1], phi[i - 1]) if i else (0.0, 1.0)
        e_eff = e_inf + p * d_e
        offset = d_e * (a * h - p * psi_prev)  # force not carried by this step's increment
        z_eff = path[i] - offset / k
        if lifted or z_eff <= 0:
            # out of contact; on retract, the tip has left the surface for good
            lifted = lifted or (i >= z.size and contact[i - 1])
            continue
        zs = float(tip._solve(np.array([z_eff]), k, e_eff)[0])
        psi = float(tip._force_unit(np.array(zs)))
        h = a * h + p * (psi - psi_prev)
        psi_prev = psi
        z_s[i] = zs
        force[i] = e_inf * psi + d_e * h
        contact[i] = True
    z_c = force / k
    radius = np.where(contact, tip._radius(z_s), 0.0)
    m = z.size
    app = IndentationCurve(path[:m], z_s[:m], z_c[:m], force[:m], radius[:m], contact[:m])
    # the retract starts at the turning point (shared with the approach's last sample)
    sl = slice(m - 1, n)
    ret = IndentationCurve(path[sl], z_s[sl], z_c[sl], force[sl], radius[sl], contact[sl])
    return ViscoelasticCycle(app, ret, time)
