"""Module (g): imaging modalities computed, not animated.

- :mod:`afmsmiler.modes.tapping`: amplitude-modulation (tapping) AFM, a driven lever with van der
  Waals and DMT forces (:mod:`afmsmiler.modes._forces`), its time integration and the fast
  first-harmonic steady states with both branches.
"""
from ._forces import FORCE_PARAMETERS, tip_sample_force, work_of_adhesion
from .tapping import (PARAMETERS as TAPPING_PARAMETERS, AmplitudeCurve, SteadyState,
                      TappingLever, amplitude_curve, free_response, integrate,
                      setpoint_state, TappingMode)
# frequency modulation and lateral force (h-fmlfm): the lead adds their exports here

__all__ = ["FORCE_PARAMETERS", "tip_sample_force", "work_of_adhesion", "TAPPING_PARAMETERS",
           "AmplitudeCurve", "SteadyState", "TappingLever", "amplitude_curve", "free_response",
           "integrate", "setpoint_state", "TappingMode"]
