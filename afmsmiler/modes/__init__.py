"""Module (g): imaging modalities computed, not animated.

- :mod:`afmsmiler.modes.oscillator`: the point-mass oscillator (k, f0, Q) every lever below
  describes itself by (:class:`Oscillator`);
- :mod:`afmsmiler.modes.tapping`: amplitude-modulation (tapping) AFM, a driven lever with van der
  Waals and DMT forces (:mod:`afmsmiler.modes._forces`), its time integration and the fast
  first-harmonic steady states with both branches; :class:`TappingMode` images through module
  (f)'s scanner;
- :mod:`afmsmiler.modes.fm`: frequency modulation, Giessibl's frequency shift of a force law and
  the Sader-Jarvis inversion back to the force;
- :mod:`afmsmiler.modes.lateral`: lateral force microscopy, the lever's torsion, friction loops
  and maps, and :class:`LateralForceMode` for module (f)'s scanner;
- :mod:`afmsmiler.modes.jumping`: jumping mode, a force curve per pixel up to a trigger and
  lateral moves with the tip lifted (:class:`JumpingMode`), compared with contact mode;
- :mod:`afmsmiler.modes.force_volume`: force-volume mapping, a force curve per pixel analysed
  with module (d)'s fit into modulus, adhesion, deformation and dissipation maps;
- :mod:`afmsmiler.modes.bimodal`: the first two flexural modes driven at once, the second
  mode's phase as the compositional channel;
- :mod:`afmsmiler.modes.qcontrol`: active quality-factor control, phase-shifted deflection
  feedback that sets the lever's effective Q and resonance.
"""
from ._forces import FORCE_PARAMETERS, tip_sample_force, work_of_adhesion
from .oscillator import Oscillator
from .fm import PARAMETERS as FM_PARAMETERS
from .fm import (FrequencyShiftCurve, force_gradient_shift, frequency_shift,
                 frequency_shift_curve, sader_jarvis)
from .lateral import PARAMETERS as LATERAL_PARAMETERS
from .lateral import (FrictionImages, FrictionLoop, LateralForceMode, LateralLever,
                      friction_loop, friction_sample, friction_scan, lateral_force, shear_modulus)
from .tapping import FEEDBACK_PARAMETERS, FEEDBACKS
from .tapping import PARAMETERS as TAPPING_PARAMETERS
from .tapping import (AmplitudeCurve, FeedbackLine, SteadyState, TappingLever, TappingMode,
                      amplitude_curve, amplitude_feedback, free_response, integrate,
                      operating_point, setpoint_state)
from .jumping import PARAMETERS as JUMPING_PARAMETERS
from .jumping import (JumpCurve, JumpingMode, ModeComparison, compare_with_contact, jump_curve,
                      trigger_z_np)
from .force_volume import PARAMETERS as FORCE_VOLUME_PARAMETERS
# (the function force_volume stays in its module: the package's name force_volume is the module)
from .force_volume import (BLEND, ForceVolume, ForceVolumeMode, SampleMaterial,
                           two_material_sample)
from .qcontrol import PARAMETERS as QCONTROL_PARAMETERS
from .qcontrol import (ClosedLoopResponse, QControl, RingDown, closed_loop_response, fit_ring_down,
                       quality_factor_from_ringdown, ring_down, stable_gains)
from .bimodal import PARAMETERS as BIMODAL_PARAMETERS
from .bimodal import (FLEXURAL_RATIO, BimodalLever, BimodalState, averaged_gradient,
                      bimodal_response, modal_stiffness)

__all__ = ["FORCE_PARAMETERS", "tip_sample_force", "work_of_adhesion", "Oscillator",
           "TAPPING_PARAMETERS",
           "AmplitudeCurve", "SteadyState", "TappingLever", "amplitude_curve", "free_response",
           "integrate", "setpoint_state", "operating_point", "TappingMode", "FM_PARAMETERS",
           "frequency_shift",
           "sader_jarvis", "force_gradient_shift", "frequency_shift_curve",
           "FrequencyShiftCurve", "LATERAL_PARAMETERS", "LateralLever", "LateralForceMode",
           "lateral_force", "friction_loop", "friction_scan", "friction_sample", "shear_modulus",
           "FrictionLoop", "FrictionImages", "FEEDBACK_PARAMETERS", "FEEDBACKS", "FeedbackLine",
           "amplitude_feedback", "JUMPING_PARAMETERS", "JumpCurve", "JumpingMode",
           "ModeComparison", "compare_with_contact", "jump_curve", "trigger_z_np",
           "FORCE_VOLUME_PARAMETERS", "BLEND", "ForceVolume", "ForceVolumeMode", "SampleMaterial",
           "two_material_sample", "BIMODAL_PARAMETERS", "FLEXURAL_RATIO",
           "BimodalLever", "BimodalState", "averaged_gradient", "bimodal_response",
           "modal_stiffness", "QCONTROL_PARAMETERS", "QControl", "ClosedLoopResponse", "RingDown",
           "closed_loop_response", "ring_down", "stable_gains", "quality_factor_from_ringdown",
           "fit_ring_down"]
