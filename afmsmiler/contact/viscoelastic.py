"""A viscoelastic sample: the standard linear solid, Lee and Radok on loading, Ting on unloading.

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

On retract the contact shrinks, where Lee and Radok's integral no longer holds (it would pull the
sample with tensile forces although nothing sticks). Ting's solution (Ting, J. Appl. Mech. 33, 845
(1966); in the form used for AFM curves by Efremov et al., Sci. Rep. 7, 1541 (2017)) applies: the
contact radius at time t equals the one at an earlier time t1 of the loading, found from::

    integral_t1^t E(t - s) dZ_s(s) = 0,     F(t) = 1/(1 - nu^2) * integral_0^t1 E(t - s) d psi(s)

With the exponential kernel both integrals are again carried by memories (of psi and of Z_s) at
the loading's samples, so each retract step is a scalar root in t1, monotone, bracketed between two
samples and found by Brent's method; with the lever, Z_s(t) is linear in the memories and
k (Z_np - Z_s) = F closes the system. When no t1 > 0 remains, the surface has receded from the tip:
F = 0 and the apex recovers freely (integral_0^t E(t - s) dZ_s = 0). A contact that grows again
after it began to shrink (a fast-creeping sample under a slow retract) is continued by Lee and
Radok's integral, an approximation outside the single-maximum case Ting solved.

Limits (tested): tau -> 0 gives the elastic curve with E_inf, tau -> inf the elastic curve with E_0,
on approach and retract; the prescribed-indentation force is checked against Ting's integrals by
quadrature.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.optimize import brentq

from ..validation import check_array, check_instance, check_positive, check_range
from .indent import IndentationCurve, _check_common, _check_depth
from .quantities import PARAMETERS
from .tips import Tip

__all__ = ["StandardLinearSolid", "hereditary_force", "viscoelastic_approach_retract",
           "ViscoelasticCycle"]


#: Positioner speeds in m/s that :func:`viscoelastic_approach_retract` accepts.
SPEED_RANGE = (1e-12, 1e3)


@dataclass(frozen=True)
class StandardLinearSolid:
    """Relaxation modulus E(t) = E_inf + (E_0 - E_inf) exp(-t / tau) of a standard linear solid.

    Parameters
    ----------
    relaxed_modulus : float
        Long-time modulus E_inf in Pa, in the range of ``PARAMETERS["youngs_modulus"]``
        ([1, 1e13] Pa: a gel to diamond and beyond).
    instantaneous_modulus : float
        Short-time modulus E_0 in Pa, in the same range and >= E_inf.
    relaxation_time : float
        tau in s, > 0.

    Raises
    ------
    ValueError
        If a modulus is outside its range, E_0 < E_inf, or tau is not positive.
    """

    relaxed_modulus: float
    instantaneous_modulus: float
    relaxation_time: float

    def __post_init__(self):
        e_range = PARAMETERS["youngs_modulus"]
        e_inf = check_range("relaxed_modulus", self.relaxed_modulus, e_range.low, e_range.high,
                            "Pa")
        e_0 = check_range("instantaneous_modulus", self.instantaneous_modulus, e_range.low,
                          e_range.high, "Pa")
        if e_0 < e_inf:
            raise ValueError(f"instantaneous_modulus must be >= relaxed_modulus ({e_inf:g} Pa), "
                             f"got {e_0:g} Pa")
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


class _Loading:
    """The loading history (contact growing) for Ting's unloading: one node per step.

    Node j holds t_j, Z_j, psi_j, h_j = int_0^t_j e^(-(t_j - s)/tau) d psi and
    H_j = int_0^t_j e^(-(t_j - s)/tau) dZ_s; between nodes psi and Z_s are linear in time, as in
    the hereditary integral's recursion. Node 0 is the onset of contact (all zero).
    """

    def __init__(self, tau, t0, capacity):
        self.tau = tau
        self.rows = np.zeros((5, capacity + 1))  # t, Z, psi, h, H
        self.rows[0, 0] = t0
        self.size = 1

    def append(self, t, z, psi, h, hz):
        self.rows[:, self.size] = t, z, psi, h, hz
        self.size += 1

    def nodes(self, t_now):
        """Arrays Z, psi, h, H at the nodes and their decay exp(-(t_now - t_j) / tau)."""
        t, z, psi, h, hz = self.rows[:, :self.size]
        with np.errstate(under="ignore"):
            return z, psi, h, hz, np.exp(-(t_now - t) / self.tau)

    def at(self, j, theta, t_now):
        """Z, psi, h, H and the decay at t1 = t_j + theta (t_(j+1) - t_j), 0 <= theta <= 1."""
        t0, z0, p0, h0, hz0 = self.rows[:, j].tolist()
        t1, z1, p1, _, _ = self.rows[:, j + 1].tolist()
        s = theta * (t1 - t0)
        decay, phi = _kernel(s, self.tau)
        w = theta * float(phi)  # int_tj^t1 e^(-(t1 - s)/tau) ds / (t_(j+1) - t_j)
        with np.errstate(under="ignore"):
            to_now = math.exp(-(t_now - t0 - s) / self.tau)
        return (z0 + theta * (z1 - z0), p0 + theta * (p1 - p0), float(decay) * h0 + w * (p1 - p0),
                float(decay) * hz0 + w * (z1 - z0), to_now)

    def solve(self, t_now, residual):
        """Ting's t1: the root of ``residual(Z, psi, h, H, decay)``, a decreasing function of t1.

        Returns None if the residual is <= 0 already at the onset (the contact has ended),
        "grow" if it is > 0 at the last node (the contact grows: Lee and Radok apply), else the
        state at t1 (see :meth:`at`).
        """
        r = residual(*self.nodes(t_now))
        if r[0] <= 0:
            return None
        if r[-1] > 0:
            return "grow"
        j = int(np.flatnonzero(r > 0)[-1])

        def g(theta):
            return residual(*self.at(j, theta, t_now))

        # the nodes' values and the interpolation's ends agree to round-off; a sign lost to it
        # puts the root on the node
        if g(1.0) >= 0:
            return self.at(j, 1.0, t_now)
        if g(0.0) <= 0:
            return self.at(j, 0.0, t_now)
        # theta to 1e-13 of a step: far below the scheme's second-order error, and brentq needs
        # no more than a few dozen steps for it (at 1e-15 round-off in g could stall it)
        return self.at(j, brentq(g, 0.0, 1.0, xtol=1e-13, maxiter=400), t_now)


def hereditary_force(time, indentation, tip, material, poisson_ratio):
    """Force in N under a prescribed indentation history (an infinitely stiff lever).

    Parameters
    ----------
    time : array_like
        Sample times in s, strictly increasing.
    indentation : array_like
        Z_s(t) in m, >= 0, same length; taken linear in time between samples (and psi(Z_s) too).
    tip : Tip
        The tip shape.
    material : StandardLinearSolid
        The sample's relaxation modulus.
    poisson_ratio : float
        nu of the sample, in [0, 0.5).

    Returns
    -------
    ndarray
        While the contact grows, F(t) = 1/(1 - nu^2) integral_0^t E(t - s) d psi(Z_s(s)) (Lee and
        Radok); once it shrinks, Ting's F(t) = 1/(1 - nu^2) integral_0^t1 E(t - s) d psi, with t1
        the root of integral_t1^t E(t - s) dZ_s = 0, and F = 0 once no such t1 exists (the
        surface has receded from the tip).

    Raises
    ------
    ValueError
        On bad parameters (see :func:`viscoelastic_approach_retract`).
    """
    t = check_array("time", time, "s", ndim=1, min_size=2, increasing=True)
    z = check_array("indentation", indentation, "m", ndim=1, low=0.0)
    if z.size != t.size:
        raise ValueError(f"indentation and time must have the same length, got {z.size} "
                         f"indentations for {t.size} times")
    check_instance("tip", tip, Tip)
    check_instance("material", material, StandardLinearSolid)
    nu = check_range("poisson_ratio", poisson_ratio, 0.0, 0.5, high_inclusive=False)
    psi = tip.force(z, 1.0)
    e_inf = material.relaxed_modulus
    d_e = material.instantaneous_modulus - material.relaxed_modulus
    tau = material.relaxation_time
    decay, phi = _kernel(np.diff(t), tau)
    out = np.zeros_like(psi)
    loading = _Loading(tau, t[0], t.size)
    # step 0: an instantaneous indentation to z[0] at t[0]
    h = hz = 0.0
    z_prev = psi_prev = 0.0
    for n in range(t.size):
        a, p = (decay[n - 1], phi[n - 1]) if n else (1.0, 1.0)
        hz_n = a * hz + p * (z[n] - z_prev)
        if z[n] == 0.0 and z_prev == 0.0 and loading.size == 1:
            loading.rows[0, 0] = t[n]  # not touched yet: the onset is later
            continue
        state = loading.solve(t[n], lambda z1, p1, h1, H1, d: e_inf * (z[n] - z1) + d_e * (
            hz_n - d * H1)) if loading.size > 1 else "grow"
        h = a * h + p * (psi[n] - psi_prev)
        hz, z_prev, psi_prev = hz_n, z[n], psi[n]
        if state == "grow":
            loading.append(t[n], z[n], psi[n], h, hz)
            out[n] = e_inf * psi[n] + d_e * h
        elif state is not None:
            _, p1, h1, _, d = state
            out[n] = e_inf * p1 + d_e * d * h1
    return out / (1.0 - nu * nu)


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
        Positioner speed |dZ_np/dt| in m/s, in [1e-12, 1e3] (:data:`SPEED_RANGE`: from a ramp of
        a picometre a second to beyond any positioner; a slower one would make the times
        overflow).

    Returns
    -------
    ViscoelasticCycle

    Raises
    ------
    ValueError
        On bad parameters, or a sphere that would be indented past its radius.

    Notes
    -----
    See the module docstring: while the contact grows, Lee and Radok's hereditary integral,
    advanced exactly for a piecewise-linear psi(Z_s(t)), each step an elastic solve with an
    effective modulus; while it shrinks, Ting's solution; the retract's force is never tensile and
    the tip leaves the surface where the force reaches zero. The retract's contact radius is
    Ting's a(t) = a(t1), not r(Z_s(t)).
    """
    z = check_array("z_np", z_np, "m", ndim=1, min_size=2, increasing=True)
    check_instance("material", material, StandardLinearSolid)
    z, k, e0 = _check_common(z, spring_constant, tip, material.instantaneous_modulus, poisson_ratio)
    v = check_range("speed", speed, *SPEED_RANGE, "m/s")
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
    radius = np.zeros(n)
    contact = np.zeros(n, dtype=bool)
    h = hz = 0.0  # memories of psi and of Z_s: int e^(-(t - s)/tau) d psi (and dZ_s)
    psi_prev = zs_prev = 0.0
    loading = None  # Ting's loading history, from the onset of contact
    for i in range(n):
        a, p = (decay[i - 1], phi[i - 1]) if i else (0.0, 1.0)
        def ting_depth(z1, hz1, d, a=a, p=p):
            # Z_s(t) from Ting's condition int_t1^t E dZ_s = 0: linear in this step's increment
            return (e_inf * z1 - d_e * (a * hz - p * zs_prev - d * hz1)) / (e_inf + p * d_e)

        def ting(z1, p1, h1, hz1, d, i=i):  # the lever's residual at t1, decreasing in t1
            return k * (path[i] - ting_depth(z1, hz1, d)) - (e_inf * p1 + d_e * d * h1)

        state = "grow" if loading is None else loading.solve(time[i], ting)
        if state == "grow":  # Lee and Radok: the step is elastic with an effective modulus
            e_eff = e_inf + p * d_e
            z_eff = path[i] - d_e * (a * h - p * psi_prev) / k
            if z_eff > 0:
                zs = float(tip._solve(np.array([z_eff]), k, e_eff)[0])
                if loading is None:
                    loading = _Loading(material.relaxation_time, time[i - 1] if i else 0.0, n)
            else:
                state, zs = None, 0.0
        elif state is not None:  # Ting: the contact shrinks, its radius is that at t1
            z1, p1, h1, hz1, d = state
            zs = ting_depth(z1, hz1, d)
            force[i] = e_inf * p1 + d_e * d * h1
            radius[i] = float(tip._radius(np.array(z1)))
        else:  # the surface has receded from the tip: its free recovery, int_0^t E dZ_s = 0
            zs = ting_depth(0.0, 0.0, 0.0) if loading is not None else 0.0
        psi = float(tip._force_unit(np.array(max(zs, 0.0))))
        h = a * h + p * (psi - psi_prev)
        hz = a * hz + p * (zs - zs_prev)
        psi_prev, zs_prev = psi, zs
        if state == "grow":
            loading.append(time[i], zs, psi, h, hz)
            force[i] = e_inf * psi + d_e * h
            radius[i] = float(tip._radius(np.array(zs)))
        if state is not None:
            z_s[i] = zs
            contact[i] = True
    z_c = force / k
    m = z.size
    app = IndentationCurve(path[:m], z_s[:m], z_c[:m], force[:m], radius[:m], contact[:m])
    # the retract starts at the turning point (shared with the approach's last sample)
    sl = slice(m - 1, n)
    ret = IndentationCurve(path[sl], z_s[sl], z_c[sl], force[sl], radius[sl], contact[sl])
    return ViscoelasticCycle(app, ret, time)
