"""Module (g): imaging modalities computed, not animated.

- :mod:`afmsmiler.modes.tapping`: amplitude-modulation (tapping) AFM, a driven lever with van der
  Waals and DMT forces (:mod:`afmsmiler.modes._forces`), its time integration and the fast
  first-harmonic steady states with both branches; :class:`TappingMode` images through module
  (f)'s scanner;
- :mod:`afmsmiler.modes.fm`: frequency modulation, Giessibl's frequency shift of a force law and
  the Sader-Jarvis inversion back to the force;
- :mod:`afmsmiler.modes.lateral`: lateral force microscopy, the lever's torsion, friction loops
  and maps, and :class:`LateralForceMode` for module (f)'s scanner.
"""
from ._forces import FORCE_PARAMETERS, tip_sample_force, work_of_adhesion
from .fm import PARAMETERS as FM_PARAMETERS
from .fm import (FrequencyShiftCurve, force_gradient_shift, frequency_shift,
                 frequency_shift_curve, sader_jarvis)
from .lateral import PARAMETERS as LATERAL_PARAMETERS
from .lateral import (FrictionImages, FrictionLoop, LateralForceMode, LateralLever,
                      friction_loop, friction_sample, friction_scan, lateral_force, shear_modulus)
from .tapping import PARAMETERS as TAPPING_PARAMETERS
from .tapping import (AmplitudeCurve, SteadyState, TappingLever, TappingMode, amplitude_curve,
                      free_response, integrate, setpoint_state)

__all__ = ["FORCE_PARAMETERS", "tip_sample_force", "work_of_adhesion", "TAPPING_PARAMETERS",
           "AmplitudeCurve", "SteadyState", "TappingLever", "amplitude_curve", "free_response",
           "integrate", "setpoint_state", "TappingMode", "FM_PARAMETERS", "frequency_shift",
           "sader_jarvis", "force_gradient_shift", "frequency_shift_curve",
           "FrequencyShiftCurve", "LATERAL_PARAMETERS", "LateralLever", "LateralForceMode",
           "lateral_force", "friction_loop", "friction_scan", "friction_sample", "shear_modulus",
           "FrictionLoop", "FrictionImages"]
