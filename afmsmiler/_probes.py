"""Vendor presets of :mod:`afmsmiler.planform`: common AFM probes with their datasheets' numbers.

Each :class:`Probe` holds the nominal geometry its datasheet prints, the printed nominal spring
constant and resonance frequency with their ranges, and where they come from. What a datasheet
does not print (a pointed end's length, a V's total width at the clamp, sometimes the coating)
is estimated and said so in ``notes``; ``confirmed`` is False where the printed ranges could not
be checked against the datasheet when this table was written (from the vendor's product page as
remembered, not re-read): treat those as indicative.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

from .materials import MATERIALS
from .parameters import read_only
from .validation import check_instance

__all__ = ["Probe", "PRESETS", "preset"]


@dataclass(frozen=True)
class Probe:
    """A vendor's probe: nominal geometry and printed ranges (SI units).

    Attributes
    ----------
    name : str
        The vendor's product name.
    vendor : str
        The vendor.
    datasheet : str
        The product page or datasheet the numbers come from.
    planform : str
        ``"rectangular"``, ``"pointed"`` or ``"v_shaped"``.
    material : str
        A key of :data:`afmsmiler.materials.MATERIALS`.
    length, width, thickness : float
        Nominal L, w (for a V the total width at the clamp) and t in m.
    tip_height : float
        Nominal tip height in m (underside to apex).
    point_length : float
        Length of a pointed end in m (0 for the other planforms).
    arm_width : float
        Arm width of a V in m (0 for the other planforms).
    coating : str or None
        Back-side coating (key of MATERIALS), or None.
    coating_thickness : float
        Its thickness in m.
    spring_constant : tuple of float
        Printed (nominal, min, max) spring constant in N/m.
    resonance_frequency : tuple of float
        Printed (nominal, min, max) resonance frequency in Hz (in air).
    confirmed : bool
        Whether the printed ranges were checked against the datasheet.
    notes : str
        What is estimated rather than printed.
    """

    name: str
    vendor: str
    datasheet: str
    planform: str
    material: str
    length: float
    width: float
    thickness: float
    tip_height: float
    spring_constant: tuple
    resonance_frequency: tuple
    point_length: float = 0.0
    arm_width: float = 0.0
    coating: str | None = None
    coating_thickness: float = 0.0
    confirmed: bool = True
    notes: str = ""

    def lever(self):
        """The probe's :class:`~afmsmiler.planform.Lever` (tip at the free end or apex).

        Returns
        -------
        Lever
        """
        from .planform import Lever
        m = MATERIALS[self.material]
        coating = None if self.coating is None else MATERIALS[self.coating]
        return Lever(self.planform, self.length, self.width, self.thickness, m.youngs_modulus,
                     m.density, m.shear_modulus, None, self.tip_height,
                     point_length=self.point_length, arm_width=self.arm_width,
                     name=self.name, source=f"{self.vendor}, {self.datasheet}",
                     coating=coating, coating_thickness=self.coating_thickness)


_BS = "BudgetSensors"
_NS = "NanoSensors"
_OL = "Olympus (OMCL series, now sold by Oxford Instruments Asylum Research)"
_BR = "Bruker AFM Probes"
_NW = "NanoWorld"
_POINT = ("point length not printed: estimated as half the width (a right-angled point) from "
          "the vendor's drawings")
_V = ("total width at the clamp not printed: taken equal to the length (arms at 63.4 deg to the "
      "clamp line; 64.5 deg measured for SNL-10 B, Nanoscale Res. Lett. 7, 608 (2012)); Ti/Au "
      "back coating taken as 45 nm of gold")

_TABLE = (
    Probe("Tap300Al-G", _BS, "Tap300Al-G datasheet (budgetsensors.com): 125 x 30 x 4 um, "
          "40 N/m (20-75), 300 kHz +-100 kHz", "rectangular", "silicon", 125e-6, 30e-6, 4e-6,
          17e-6, (40.0, 20.0, 75.0), (300e3, 200e3, 400e3), coating="aluminium",
          coating_thickness=30e-9),
    Probe("Tap150Al-G", _BS, "Tap150Al-G datasheet: 125 x 25 x 2.1 um, 5 N/m (1.5-15), "
          "150 kHz +-75 kHz", "rectangular", "silicon", 125e-6, 25e-6, 2.1e-6, 17e-6,
          (5.0, 1.5, 15.0), (150e3, 75e3, 225e3), coating="aluminium", coating_thickness=30e-9),
    Probe("Multi75Al-G", _BS, "Multi75Al-G datasheet: 225 x 28 x 3 um, 3 N/m (1-7), "
          "75 kHz +-15 kHz", "rectangular", "silicon", 225e-6, 28e-6, 3e-6, 17e-6,
          (3.0, 1.0, 7.0), (75e3, 60e3, 90e3), coating="aluminium", coating_thickness=30e-9),
    Probe("ContAl-G", _BS, "ContAl-G datasheet: 450 x 50 x 2 um, 0.2 N/m (0.07-0.4), "
          "13 kHz +-4 kHz", "rectangular", "silicon", 450e-6, 50e-6, 2e-6, 17e-6,
          (0.2, 0.07, 0.4), (13e3, 9e3, 17e3), coating="aluminium", coating_thickness=30e-9),
    Probe("PPP-NCHR", _NS, "PointProbe Plus PPP-NCHR datasheet: 125 x 30 x 4 um, 42 N/m "
          "(10-130), 330 kHz (204-497)", "rectangular", "silicon", 125e-6, 30e-6, 4e-6, 12.5e-6,
          (42.0, 10.0, 130.0), (330e3, 204e3, 497e3), confirmed=False),
    Probe("PPP-FMR", _NS, "PointProbe Plus PPP-FMR datasheet: 225 x 28 x 3 um, 2.8 N/m "
          "(0.5-9.5), 75 kHz (45-115)", "rectangular", "silicon", 225e-6, 28e-6, 3e-6, 12.5e-6,
          (2.8, 0.5, 9.5), (75e3, 45e3, 115e3), confirmed=False),
    Probe("AC160TS", _OL, "OMCL-AC160TS-R3 product page: 160 x 40 x 3.7 um, 26 N/m "
          "(8.4-57), 300 kHz (200-400), tip height 14 um at the end", "pointed", "silicon",
          160e-6, 40e-6, 3.7e-6, 14e-6, (26.0, 8.4, 57.0), (300e3, 200e3, 400e3),
          point_length=20e-6, notes=_POINT),
    Probe("AC240TS", _OL, "OMCL-AC240TS-R3 product page: 240 x 40 x 2.3 um, 2 N/m "
          "(0.6-3.5), 70 kHz (50-90), tip height 14 um at the end", "pointed", "silicon",
          240e-6, 40e-6, 2.3e-6, 14e-6, (2.0, 0.6, 3.5), (70e3, 50e3, 90e3),
          point_length=20e-6, notes=_POINT),
    Probe("Arrow-NCR", _NW, "Arrow-NCR datasheet: 160 x 45 (mean) x 4.6 um, 42 N/m (27-80), "
          "285 kHz (240-380)", "pointed", "silicon", 160e-6, 45e-6, 4.6e-6, 12.5e-6,
          (42.0, 27.0, 80.0), (285e3, 240e3, 380e3), point_length=22.5e-6, confirmed=False,
          notes=_POINT),
    Probe("MLCT-A", _BR, "MLCT product page, lever A (triangular): 175 um long, arms 22 um, "
          "0.55 um thick, 0.07 N/m, 22 kHz", "v_shaped", "silicon_nitride", 175e-6, 175e-6,
          0.55e-6, 7e-6, (0.07, 0.035, 0.14), (22e3, 15e3, 30e3), arm_width=22e-6,
          coating="gold", coating_thickness=45e-9, confirmed=False, notes=_V),
    Probe("MLCT-E", _BR, "MLCT product page, lever E (triangular): 140 um long, arms 18 um, "
          "0.55 um thick, 0.1 N/m, 38 kHz", "v_shaped", "silicon_nitride", 140e-6, 140e-6,
          0.55e-6, 7e-6, (0.1, 0.05, 0.2), (38e3, 26e3, 50e3), arm_width=18e-6,
          coating="gold", coating_thickness=45e-9, confirmed=False, notes=_V),
    Probe("MLCT-F", _BR, "MLCT product page, lever F (triangular): 85 um long, arms 22 um, "
          "0.55 um thick, 0.6 N/m, 125 kHz", "v_shaped", "silicon_nitride", 85e-6, 85e-6,
          0.55e-6, 7e-6, (0.6, 0.3, 1.2), (125e3, 90e3, 160e3), arm_width=22e-6,
          coating="gold", coating_thickness=45e-9, confirmed=False, notes=_V),
    Probe("SNL-10-B", _BR, "SNL-10 product page, lever B (triangular): 205 um long, arms "
          "40 um, 0.6 um thick, 0.12 N/m, 23 kHz", "v_shaped", "silicon_nitride", 205e-6,
          2 * 205e-6 * math.tan(math.radians(90 - 64.5)), 0.6e-6, 7e-6, (0.12, 0.06, 0.24),
          (23e3, 15e3, 30e3), arm_width=40e-6, coating="gold", coating_thickness=45e-9,
          confirmed=False, notes=_V.replace("taken equal to the length (arms at 63.4 deg",
                                            "from the arms at 64.5 deg").replace(
                                                "; 64.5 deg measured for SNL-10 B,", ",")),
)

#: The presets by product name (read-only).
PRESETS = read_only({p.name: p for p in _TABLE})


def preset(name: str):
    """The :class:`~afmsmiler.planform.Lever` of a vendor probe, by product name.

    Parameters
    ----------
    name : str
        A key of :data:`PRESETS` (``"AC240TS"``, ``"Tap300Al-G"``, ``"MLCT-E"``, ...).

    Returns
    -------
    Lever

    Raises
    ------
    ValueError
        For an unknown name, listing the known ones.

    Examples
    --------
    >>> lever = preset("AC240TS")
    >>> 0.6 < lever.spring_constant < 3.5  # N/m, the datasheet's range
    True
    """
    check_instance("name", name, str)
    if name not in PRESETS:
        raise ValueError(f"name must be one of {sorted(PRESETS)}, got {name!r}")
    return PRESETS[name].lever()
