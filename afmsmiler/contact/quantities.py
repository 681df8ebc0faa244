"""The user-settable quantities of module (d), described once (SI; display units through UNITS).

The valid ranges are physical ones, wide enough for every AFM experiment (a 1 uN/m to 1 MN/m lever,
a 1 Pa gel to 10 TPa, works of adhesion up to 10 J/m^2; positioner displacements within +-100 m,
far beyond any positioner, since a soft lever on a stiff sample needs metres of travel before a
micrometre sphere would be buried, a limit the tests probe) and narrow enough that every model
computes finite numbers in floating point: inside them no model returns an overflow, and outside
them the models raise a ``ValueError`` naming the quantity. The tip parameters, and the 100 m
bound on indentations and contact radii that the positioner's travel implies, are described with
the tips (:mod:`afmsmiler.contact.tips`); the reduced modulus E* that the JKR functions take
ranges over what E and nu give (:data:`afmsmiler.contact.indent.E_STAR_RANGE`).
"""
from __future__ import annotations

from ..parameters import SPRING_CONSTANT, Parameter, read_only

__all__ = ["PARAMETERS"]

#: The quantities of a contact system: name -> Parameter (what the panel's sliders show).
PARAMETERS = read_only({p.name: p for p in (
    SPRING_CONSTANT,
    Parameter(name="youngs_modulus", unit="Pa", display_unit="MPa", default=1e6, low=1.0,
              high=1e13, slider_low=1e3, slider_high=1e11, log=True,
              label="Young's modulus E"),
    Parameter(name="poisson_ratio", unit="", default=0.3, low=0.0, high=0.5,
              high_inclusive=False, slider_low=0.0, slider_high=0.49, label="Poisson's ratio nu"),
    Parameter(name="z_np", unit="m", display_unit="nm", default=60e-9, low=-100.0, high=100.0,
              slider_low=-50e-9, slider_high=200e-9, label="positioner displacement Z_np"),
    Parameter(name="work_of_adhesion", unit="J/m^2", display_unit="mJ/m^2", default=20e-3,
              low=1e-6, high=10.0, slider_low=1e-3, slider_high=0.2,
              label="work of adhesion w"),
)})
