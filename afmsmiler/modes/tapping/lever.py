"""The tapping lever and its sample: the driven point mass and the tip-sample force.

The cantilever is a point mass m = k / w0^2 on a spring k with quality factor Q (module (a)'s
first flexural mode), its rest position a distance z_c above the sample, driven at the angular
frequency w = 2 pi f by the force F0 cos(w t) that gives the free amplitude A0::

    m z'' + (m w0 / Q) z' + k z = F0 cos(w t) + F_ts(z_c + z, z'),
    F0 = k A0 sqrt((1 - W^2)^2 + (W / Q)^2),     W = w / w0

with the tip-sample force F_ts of :mod:`afmsmiler.modes._forces` (van der Waals, DMT contact,
optional sample damping; Garcia and Perez, Surf. Sci. Rep. 47, 197 (2002)).

This module holds the quantities (:data:`PARAMETERS`), the validated lever and sample
(:class:`TappingLever`) and the free lever's response; the solvers live beside it
(:mod:`~afmsmiler.modes.tapping.balance`, :mod:`~afmsmiler.modes.tapping.integration`).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ...contact.tips import reduced_modulus
from ...parameters import (QUALITY_FACTOR, RESONANCE_FREQUENCY, SPRING_CONSTANT, Parameter,
                           read_only)
from ...validation import check_array
from .._forces import FORCE_PARAMETERS, _force
from ..oscillator import PointMassLever

__all__ = ["PARAMETERS", "TappingLever", "free_response"]

#: The user-settable quantities of the tapping model (SI), with :data:`FORCE_PARAMETERS`: a
#: tapping lever (k = 40 N/m, f0 = 300 kHz, Q = 400 in air) at A0 = 10 nm, driven at resonance.
PARAMETERS = read_only({**{p.name: p for p in (
    SPRING_CONSTANT.with_(default=40.0, slider_low=0.5, slider_high=100.0),
    RESONANCE_FREQUENCY,
    QUALITY_FACTOR.with_(default=400.0, slider_low=1.0, slider_high=2000.0),
    Parameter(name="frequency_ratio", unit="", default=1.0, low=0.5, high=1.5,
              slider_low=0.98, slider_high=1.02, label="drive frequency / f0"),
    Parameter(name="free_amplitude", unit="m", display_unit="nm", default=10e-9, low=0.0,
              high=1e-6, low_inclusive=False, slider_low=1e-9, slider_high=100e-9,
              label="free amplitude A0"),
    Parameter(name="distance", unit="m", display_unit="nm", default=8e-9, low=0.0, high=1e-5,
              low_inclusive=False, slider_low=0.2e-9, slider_high=30e-9,
              label="rest tip-sample distance z_c"),
    Parameter(name="setpoint_ratio", unit="", default=0.8, low=0.0, high=1.0,
              low_inclusive=False, high_inclusive=False, slider_low=0.05, slider_high=0.99,
              label="setpoint A_sp / A0"),
)}, **FORCE_PARAMETERS})


@dataclass(frozen=True)
class TappingLever(PointMassLever):
    """A driven lever and a sample: every quantity of the tapping model, validated (SI units).

    Parameters
    ----------
    spring_constant : float
        Spring constant k in N/m.
    resonance_frequency : float
        Free resonance frequency f0 in Hz.
    quality_factor : float
        Quality factor Q, > 0.
    frequency_ratio : float
        Drive frequency over f0, W = w / w0, in [0.5, 1.5] (a drive near resonance).
    free_amplitude : float
        Free amplitude A0 in m (the drive force F0 is the one that gives it far from the sample).
    radius : float
        Tip radius R in m.
    hamaker_constant : float
        Hamaker constant H in J.
    youngs_modulus : float
        Young's modulus E of the sample in Pa (rigid tip).
    poisson_ratio : float
        Poisson's ratio nu of the sample.
    intermolecular_distance : float
        Intermolecular distance a0 in m.
    sample_viscosity : float
        Sample viscosity eta in Pa s (0: no dissipation in the sample).

    Raises
    ------
    ValueError
        Naming the first parameter outside its range (:data:`PARAMETERS`), before any work.

    Examples
    --------
    >>> lever = TappingLever()
    >>> round(lever.drive_force * 1e9, 3)  # F0 = k A0 / Q at resonance, in nN
    1.0
    """

    PARAMETERS = PARAMETERS  # checked field by field in PointMassLever.__post_init__

    spring_constant: float = PARAMETERS["spring_constant"].default
    resonance_frequency: float = PARAMETERS["resonance_frequency"].default
    quality_factor: float = PARAMETERS["quality_factor"].default
    frequency_ratio: float = PARAMETERS["frequency_ratio"].default
    free_amplitude: float = PARAMETERS["free_amplitude"].default
    radius: float = PARAMETERS["radius"].default
    hamaker_constant: float = PARAMETERS["hamaker_constant"].default
    youngs_modulus: float = PARAMETERS["youngs_modulus"].default
    poisson_ratio: float = PARAMETERS["poisson_ratio"].default
    intermolecular_distance: float = PARAMETERS["intermolecular_distance"].default
    sample_viscosity: float = PARAMETERS["sample_viscosity"].default

    @property
    def reduced_modulus(self) -> float:
        """E* = E / (1 - nu^2) in Pa (module (d), rigid tip)."""
        return reduced_modulus(self.youngs_modulus, self.poisson_ratio)

    @property
    def drive_force(self) -> float:
        """Drive amplitude F0 = k A0 sqrt((1 - W^2)^2 + (W / Q)^2) in N."""
        w, q = self.frequency_ratio, self.quality_factor
        return self.spring_constant * self.free_amplitude * math.hypot(1.0 - w * w, w / q)

    @property
    def free_phase(self) -> float:
        """Phase lag of the free lever, atan2(W / Q, 1 - W^2), in rad (pi / 2 at resonance)."""
        w = self.frequency_ratio
        return math.atan2(w / self.quality_factor, 1.0 - w * w)

    @property
    def time_constant(self) -> float:
        """Amplitude time constant tau = 2 Q / w0 in s (the slow flow's decay, module notes)."""
        return self.oscillator.time_constant

    @property
    def max_amplitude(self) -> float:
        """Bound F0 Q / (k W) in m on every steady amplitude (the sample only takes energy)."""
        return self.drive_force * self.quality_factor / (self.spring_constant *
                                                         self.frequency_ratio)

    def force(self, distance, velocity=0.0):
        """Tip-sample force F_ts(d, v) in N (see :func:`~afmsmiler.modes.tip_sample_force`).

        Parameters
        ----------
        distance : float or array_like
            Tip-sample distance d in m.
        velocity : float or array_like
            Tip velocity in m/s, positive away from the sample.

        Returns
        -------
        float or ndarray
        """
        d = check_array("distance", distance, "m", low=-1e-6)
        v = check_array("velocity", velocity, "m/s")
        out = _force(d, v, self.radius, self.hamaker_constant, self.reduced_modulus,
                     self.intermolecular_distance, self.sample_viscosity)
        return out if out.ndim else float(out)

    def indentation(self, distance, amplitude):
        """Deepest indentation a0 - (z_c - A) in m of the motion z_c + A cos(theta).

        The tip touches the sample where the tip-sample distance d = z_c + z falls below a0
        (the force law's contact, :mod:`afmsmiler.modes._forces`); the first harmonic's closest
        distance is z_c - A, so the tip touches once per cycle exactly when this is > 0, and it
        is then how far it presses into the sample. A negative value is the gap (a0 less the
        closest distance) by which it stays clear. The static deflection and the higher
        harmonics the first-harmonic balance leaves out shift the closest distance by far less
        than a0 for the stiff lever of the defaults (the tests compare it with the time
        integration, where the sample's damping takes energy only in contact).

        Parameters
        ----------
        distance : float or array_like
            Rest tip-sample distance z_c in m, in (0, 1e-5].
        amplitude : float or array_like
            Amplitude A of the first harmonic in m, in [0, 1e-6].

        Returns
        -------
        float or ndarray
            a0 - (z_c - A) in m (> 0: the tip touches the sample, this deep).

        Raises
        ------
        ValueError
            Naming ``distance`` or ``amplitude`` out of range, or both when their shapes do not
            broadcast together.

        Examples
        --------
        >>> lever = TappingLever()
        >>> round(lever.indentation(8e-9, 9e-9) * 1e9, 3)  # z_c - A = -1 nm: 1.165 nm deep
        1.165
        """
        zp, ap = PARAMETERS["distance"], PARAMETERS["free_amplitude"]
        z = check_array("distance", distance, "m", low=zp.low, high=zp.high,
                        low_inclusive=False)
        a = check_array("amplitude", amplitude, "m", low=0.0, high=ap.high)
        try:
            np.broadcast_shapes(z.shape, a.shape)
        except ValueError:
            raise ValueError(f"distance and amplitude must broadcast together, got shapes "
                             f"{z.shape} and {a.shape}") from None
        out = self.intermolecular_distance - (z - a)
        return out if out.ndim else float(out)

    def dissipated_energy(self, amplitude, phase):
        """E_dis = pi F0 A sin(phi) - pi k W A^2 / Q in J from amplitude and phase lag.

        Parameters
        ----------
        amplitude : float or array_like
            Amplitude A of the first harmonic in m, in [0, 1e-6] (the free amplitude's range).
        phase : float or array_like
            Phase lag phi of the tip behind the drive in rad (pi / 2: free, at resonance).

        Returns
        -------
        float or ndarray
            Energy in J the sample takes per cycle ((pi k A^2 / Q)[(A0 / A) sin(phi) - W]).
        """
        a = check_array("amplitude", amplitude, "m", low=0.0,
                        high=PARAMETERS["free_amplitude"].high)
        phi = check_array("phase", phase, "rad", low=-2 * math.pi, high=2 * math.pi)
        out = math.pi * a * (self.drive_force * np.sin(phi) - self.spring_constant *
                             self.frequency_ratio * a / self.quality_factor)
        return out if out.ndim else float(out)


def free_response(lever: TappingLever | None = None) -> tuple[float, float]:
    """Amplitude and phase lag of the driven harmonic oscillator far from the sample.

    Parameters
    ----------
    lever : TappingLever, optional
        The lever (default: :class:`TappingLever` ()).

    Returns
    -------
    (float, float)
        A = F0 / (k sqrt((1 - W^2)^2 + (W / Q)^2)) in m (= A0 by construction) and
        phi = atan2(W / Q, 1 - W^2) in rad.
    """
    lever = TappingLever() if lever is None else _check_lever(lever)
    w, q = lever.frequency_ratio, lever.quality_factor
    return (lever.drive_force / (lever.spring_constant * math.hypot(1.0 - w * w, w / q)),
            lever.free_phase)


def _check_lever(lever):
    if not isinstance(lever, TappingLever):
        raise TypeError(f"lever must be a TappingLever, got {type(lever).__name__}")
    return lever
