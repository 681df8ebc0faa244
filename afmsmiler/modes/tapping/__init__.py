"""Amplitude-modulation (tapping) AFM: a driven cantilever tapping a sample, two solvers.

A driven point-mass lever tapping a sample through van der Waals and DMT forces; its equation of
motion is stated in :mod:`~afmsmiler.modes.tapping.lever`, each solver's method in its module.

One module per concern; every name is importable from here as before:

- :mod:`~afmsmiler.modes.tapping.lever`: the quantities (:data:`PARAMETERS`), the lever and its
  sample (:class:`TappingLever`, the tip-sample force) and the free response;
- :mod:`~afmsmiler.modes.tapping.balance`: the fast steady states by first-harmonic balance
  (:func:`amplitude_curve`, both branches, the slow approach and where feedback holds the lever);
- :mod:`~afmsmiler.modes.tapping.integration`: the reference solver, time integration
  (:func:`integrate`);
- :mod:`~afmsmiler.modes.tapping.feedback`: amplitude feedback with a finite bandwidth
  (:func:`amplitude_feedback`);
- :mod:`~afmsmiler.modes.tapping.imaging`: :class:`TappingMode`, imaging through module (f)'s
  scanner.
"""
from .lever import PARAMETERS, TappingLever, free_response
from .balance import (AMPLITUDE_GRID, BRANCHES, DISSIPATION_ROUNDINGS, MAX_DISTANCES,
                      SETPOINT_GRID, SWEEPS, AmplitudeCurve, amplitude_curve,
                      amplitude_curve_steps, setpoint_state)
from .balance import operating_point  # noqa: F401  (modes.tapping.operating_point: ui.modes)
from .balance import _balance, _integrals  # noqa: F401  (checked by the tests)
from .integration import (BLOCK_PERIODS, LOCKIN_PERIODS, MAX_PERIODS, SteadyState, integrate)
from .feedback import (FEEDBACK_PARAMETERS, FEEDBACKS, MAX_FEEDBACK_STEPS, FeedbackLine,
                       amplitude_feedback)
from .imaging import TappingMode
from . import balance, feedback, imaging, integration, lever  # noqa: F401

__all__ = ["PARAMETERS", "TappingLever", "AmplitudeCurve", "SteadyState", "amplitude_curve",
           "amplitude_curve_steps", "integrate", "free_response", "setpoint_state",
           "TappingMode", "BRANCHES",
           "AMPLITUDE_GRID", "MAX_DISTANCES", "MAX_PERIODS", "BLOCK_PERIODS", "LOCKIN_PERIODS",
           "SETPOINT_GRID", "SWEEPS", "FEEDBACKS", "FEEDBACK_PARAMETERS", "FeedbackLine",
           "amplitude_feedback", "MAX_FEEDBACK_STEPS", "DISSIPATION_ROUNDINGS"]
