"""The lever's point-mass oscillator: spring constant, resonance frequency and quality factor.

Every point-mass lever of module (g) is a mass m = k / w0^2 on a spring k, damped so that its
resonance has the quality factor Q::

    m z'' + (m w0 / Q) z' + k z = F(t),      w0 = 2 pi f0

:class:`Oscillator` is that description, validated once against the package's one vocabulary
(:data:`afmsmiler.parameters.PARAMETERS`: the same valid range of k, f0 and Q in every mode, so a
lever valid in one mode is valid in the next). The tapping lever
(:class:`~afmsmiler.modes.tapping.TappingLever`), the Q-controlled lever
(:class:`~afmsmiler.modes.qcontrol.QControl`) and the two modes of the bimodal lever
(:class:`~afmsmiler.modes.bimodal.BimodalLever`) each give theirs as ``.oscillator`` (or
``.oscillators``) and read their mass and time constant from it.
"""
from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, fields

from ..parameters import PARAMETERS
from ..validation import check_range

__all__ = ["Oscillator", "PointMassLever"]


@dataclass(frozen=True)
class Oscillator:
    """A damped point-mass oscillator (one flexural mode of a lever), SI units.

    Parameters
    ----------
    spring_constant : float
        Spring constant k in N/m (:data:`afmsmiler.parameters.SPRING_CONSTANT`'s range).
    resonance_frequency : float
        Resonance frequency f0 in Hz (:data:`afmsmiler.parameters.RESONANCE_FREQUENCY`).
    quality_factor : float
        Quality factor Q (:data:`afmsmiler.parameters.QUALITY_FACTOR`).

    Raises
    ------
    ValueError
        Naming the first quantity outside its range, before any work.

    Examples
    --------
    >>> osc = Oscillator(40.0, 300e3, 400.0)
    >>> round(osc.mass * 1e12, 3)  # ng: k / (2 pi f0)^2
    11.258
    >>> round(osc.time_constant * 1e3, 4)  # ms: 2 Q / w0
    0.4244
    """

    spring_constant: float
    resonance_frequency: float
    quality_factor: float

    def __post_init__(self):
        for name in ("spring_constant", "resonance_frequency", "quality_factor"):
            object.__setattr__(self, name, PARAMETERS[name].check(getattr(self, name)))

    @property
    def angular_frequency(self) -> float:
        """w0 = 2 pi f0 in rad/s."""
        return 2.0 * math.pi * self.resonance_frequency

    @property
    def mass(self) -> float:
        """Effective mass m = k / w0^2 in kg."""
        return self.spring_constant / (2.0 * math.pi * self.resonance_frequency) ** 2

    @property
    def time_constant(self) -> float:
        """Amplitude time constant tau = 2 Q / w0 in s (an underdamped ring-down's amplitude
        decays as exp(-t / tau))."""
        return 2.0 * self.quality_factor / (2.0 * math.pi * self.resonance_frequency)

    def compliance(self, angular_frequency: float) -> complex:
        """Steady response z / F = 1 / (k (1 - r^2 + i r / Q)), r = w / w0, to F cos(w t).

        Parameters
        ----------
        angular_frequency : float
            Drive angular frequency w in rad/s, in (0, 1e12].

        Returns
        -------
        complex
            In m/N: its modulus is the amplitude per newton, minus its argument the phase lag.
        """
        w = check_range("angular_frequency", angular_frequency, 0.0, 1e12, "rad/s",
                        low_inclusive=False)
        r = w / self.angular_frequency
        return 1.0 / (self.spring_constant * complex(1.0 - r * r, r / self.quality_factor))


class PointMassLever:
    """What a lever with ``spring_constant``, ``resonance_frequency`` and ``quality_factor``
    fields shares: every field checked against its description in :attr:`PARAMETERS` when the
    (frozen) dataclass is built, and its :class:`Oscillator` (a base with no fields)."""

    #: Field name -> Parameter: the subclass's descriptions of its fields.
    PARAMETERS: Mapping = {}

    def __post_init__(self):
        for f in fields(self):
            object.__setattr__(self, f.name, self.PARAMETERS[f.name].check(getattr(self, f.name)))

    @property
    def oscillator(self) -> Oscillator:
        """The lever's point-mass oscillator (k, f0, Q)."""
        return Oscillator(self.spring_constant, self.resonance_frequency, self.quality_factor)
