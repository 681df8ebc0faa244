"""Amplitude-modulation (tapping) AFM: a driven cantilever tapping a sample, two solvers.

The cantilever is a point mass m = k / w0^2 on a spring k with quality factor Q (module (a)'s
first flexural mode), its rest position a distance z_c above the sample, driven at the angular
frequency w = 2 pi f by the force F0 cos(w t) that gives the free amplitude A0::

    m z'' + (m w0 / Q) z' + k z = F0 cos(w t) + F_ts(z_c + z, z'),
    F0 = k A0 sqrt((1 - W^2)^2 + (W / Q)^2),     W = w / w0

with the tip-sample force F_ts of :mod:`afmsmiler.modes._forces` (van der Waals, DMT contact,
optional sample damping; Garcia and Perez, Surf. Sci. Rep. 47, 197 (2002)).

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
                      SETPOINT_GRID, SWEEPS, AmplitudeCurve, amplitude_curve, operating_point,
                      setpoint_state)
from .balance import _balance, _integrals  # noqa: F401  (checked by the tests)
from .integration import (BLOCK_PERIODS, LOCKIN_PERIODS, MAX_PERIODS, SteadyState, integrate)
from .feedback import (FEEDBACK_PARAMETERS, FEEDBACKS, MAX_FEEDBACK_STEPS, FeedbackLine,
                       amplitude_feedback)
from .imaging import TappingMode
from . import balance, feedback, imaging, integration, lever  # noqa: F401

__all__ = ["PARAMETERS", "TappingLever", "AmplitudeCurve", "SteadyState", "amplitude_curve",
           "integrate", "free_response", "setpoint_state", "TappingMode", "BRANCHES",
           "AMPLITUDE_GRID", "MAX_DISTANCES", "MAX_PERIODS", "BLOCK_PERIODS", "LOCKIN_PERIODS",
           "SETPOINT_GRID", "SWEEPS", "FEEDBACKS", "FEEDBACK_PARAMETERS", "FeedbackLine",
           "amplitude_feedback", "MAX_FEEDBACK_STEPS", "DISSIPATION_ROUNDINGS"]
