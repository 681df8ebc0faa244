"""The macroscopic AFM's mechanics: the steel ruler, its strain gauge, and their calibration.

The probe is a flexible steel ruler clamped at one end (first resonance about 6 Hz) with a needle
at its free end and a resistive foil strain gauge glued near the clamp, read by an HX711
load-cell amplifier. Module (a)'s Euler-Bernoulli beam (:class:`~afmsmiler.cantilever.Cantilever`)
gives the ruler's stiffness k = 3 E J / L^3 and the strain at the gauge per newton at the needle;
the gauge and amplifier turn strain into counts:

    counts = gain * 2^22 * GF * strain

(quarter bridge, output V = V_ex GF strain / 4; the HX711 maps +-0.5 V_ex / gain to +-2^23
counts: HX711 datasheet, Avia Semiconductor, "Output data format"). So the counts per newton of
tip force are ``gain * 2^22 * GF * strain_per_newton``, and per metre of deflection ``k`` times
that. :class:`GaugeCalibration` holds the counts per newton; the build instructions
(``hardware/macro_afm/BUILD.md``) measure it by hanging a known mass on the needle
(:meth:`GaugeCalibration.from_weights`).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

from ...cantilever import Cantilever
from ...parameters import Parameter, read_only
from ...validation import check_finite, check_instance, check_positive, check_range

__all__ = ["STEEL", "RULER", "GAUGE_POSITION", "GAUGE_FACTOR", "AMPLIFIER_GAIN",
           "GaugeCalibration", "ruler", "STANDARD_GRAVITY", "PARAMETERS"]

#: Spring steel (E 200 GPa, rho 7850 kg/m^3; AISI 1095, ASM Handbook vol. 1).
STEEL = {"youngs_modulus": 200e9, "density": 7850.0}
#: A steel ruler clamped with 260 mm free: 25 mm wide, 0.5 mm thick, first resonance 6.0 Hz
#: (the paper's "about 6 Hz"), k = 8.9 N/m.
RULER = {"length": 0.26, "width": 25e-3, "thickness": 0.5e-3}
#: The gauge's centre, from the clamp (m), on the ruler's lower face.
GAUGE_POSITION = 5e-3
#: A metal foil gauge's gauge factor.
GAUGE_FACTOR = 2.0
#: HX711 channel A gain.
AMPLIFIER_GAIN = 128
#: Standard gravity in m/s^2 (CGPM 1901), for calibration weights.
STANDARD_GRAVITY = 9.80665

#: The user-settable quantities of the macro AFM's calibration (SI).
PARAMETERS = read_only({
    "counts_per_newton": Parameter(name="counts_per_newton", unit="1/N", display_unit="1/N",
                                   default=1.0e6, low=1.0, high=1e12, log=True,
                                   slider_low=1e4, slider_high=1e8,
                                   label="gauge counts per newton"),
})


def ruler(length: float = RULER["length"], width: float = RULER["width"],
          thickness: float = RULER["thickness"]) -> Cantilever:
    """The steel ruler as module (a)'s cantilever.

    Parameters
    ----------
    length : float
        Free length from the clamp to the needle in m.
    width : float
        Width in m.
    thickness : float
        Thickness in m.

    Returns
    -------
    afmsmiler.cantilever.Cantilever

    Examples
    --------
    >>> lever = ruler()
    >>> round(lever.spring_constant, 2), round(lever.resonance_frequency(1), 1)
    (8.89, 6.0)
    """
    return Cantilever(length, width, thickness, STEEL["youngs_modulus"], STEEL["density"])


@dataclass(frozen=True)
class GaugeCalibration:
    """Gauge counts per newton of force at the needle (and the ruler's stiffness).

    Parameters
    ----------
    counts_per_newton : float
        Counts above the free reading per newton at the needle (1/N).
    spring_constant : float
        The ruler's stiffness at the needle in N/m.

    Examples
    --------
    >>> cal = GaugeCalibration.from_ruler()
    >>> round(cal.counts(0.01))  # 10 mN at the needle
    13143
    """

    counts_per_newton: float
    spring_constant: float

    def __post_init__(self):
        object.__setattr__(self, "counts_per_newton", PARAMETERS["counts_per_newton"].check(
            self.counts_per_newton))
        object.__setattr__(self, "spring_constant",
                           check_positive("spring_constant", self.spring_constant, "N/m"))

    @classmethod
    def from_ruler(cls, lever: Cantilever | None = None, *,
                   gauge_position: float = GAUGE_POSITION, gauge_factor: float = GAUGE_FACTOR,
                   gain: int = AMPLIFIER_GAIN) -> "GaugeCalibration":
        """The calibration a build predicts from its ruler, gauge and amplifier.

        Parameters
        ----------
        lever : Cantilever, optional
            The ruler (default :func:`ruler`).
        gauge_position : float
            The gauge's centre from the clamp in m (the strain falls linearly to 0 at the
            needle).
        gauge_factor : float
            The gauge's gauge factor (about 2 for metal foil).
        gain : int
            The amplifier's gain (HX711: 32, 64 or 128).

        Returns
        -------
        GaugeCalibration
        """
        lever = ruler() if lever is None else check_instance("lever", lever, Cantilever)
        x = check_range("gauge_position", gauge_position, 0.0, lever.length, "m",
                        high_inclusive=False)
        gf = check_range("gauge_factor", gauge_factor, 0.1, 200.0)
        g = check_range("gain", gain, 1, 1024)
        # module (a): strain on the lower face (z_b = -h/2) under a unit force at the needle
        strain = float(lever.strain(x, -lever.thickness / 2, 1.0))
        return cls(g * 2.0 ** 22 * gf * strain, lever.spring_constant)

    @classmethod
    def from_weights(cls, free_counts: float, loaded_counts: float, mass: float, *,
                     spring_constant: float) -> "GaugeCalibration":
        """The calibration measured by hanging a known mass on the needle (BUILD.md).

        Parameters
        ----------
        free_counts : float
            The gauge's reading with nothing on the needle.
        loaded_counts : float
            The reading with ``mass`` hanging on it.
        mass : float
            The calibration mass in kg (its weight pulls the needle down: the reading's change
            is taken in magnitude).
        spring_constant : float
            The ruler's stiffness in N/m (measured from the needle's drop under the mass, or
            from module (a)).

        Returns
        -------
        GaugeCalibration
        """
        mass = check_positive("mass", mass, "kg")
        delta = abs(check_finite("loaded_counts", loaded_counts)
                    - check_finite("free_counts", free_counts))
        if not math.isfinite(delta) or delta == 0:
            raise ValueError(f"loaded_counts must differ from free_counts, got {loaded_counts!r} "
                             f"and {free_counts!r}")
        per_newton = PARAMETERS["counts_per_newton"]
        value = delta / (mass * STANDARD_GRAVITY)
        if not per_newton.low <= value <= per_newton.high:
            raise ValueError(f"|loaded_counts - free_counts| / (mass g) is the counts per newton, "
                             f"which must be in [{per_newton.low:g}, {per_newton.high:g}] 1/N, "
                             f"got {value:g} (loaded_counts {loaded_counts!r}, free_counts "
                             f"{free_counts!r}, mass {mass!r} kg)"[:300])
        return cls(value, spring_constant)

    @property
    def counts_per_metre(self) -> float:
        """Counts per metre of needle deflection, k times the counts per newton (1/m)."""
        return self.counts_per_newton * self.spring_constant

    def counts(self, force: float) -> float:
        """Counts above the free reading for a force at the needle.

        Parameters
        ----------
        force : float
            Force in N (positive pushes the needle up, as the sample does).

        Returns
        -------
        float
        """
        return check_finite("force", force, "N") * self.counts_per_newton

    def force(self, counts: float) -> float:
        """Force at the needle in N for a reading in counts above the free reading.

        Parameters
        ----------
        counts : float
            Counts above the free reading.

        Returns
        -------
        float
        """
        return check_finite("counts", counts) / self.counts_per_newton
