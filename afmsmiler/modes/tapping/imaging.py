"""Tapping-mode imaging through module (f)'s scanner: height, phase and dissipation.

With the ideal feedback every pixel sits at its setpoint state
(:func:`~afmsmiler.modes.tapping.balance.setpoint_state`); with the PI loop the amplitude lags
(:mod:`~afmsmiler.modes.tapping.feedback`).
"""
from __future__ import annotations

import math
from types import MappingProxyType

import numpy as np

from ...imaging.scan_modes import Mode, ModeLine, ScanPlan
from ...validation import check_choice, check_instance
from .balance import setpoint_state
from .feedback import (_STEPS_PER_TAU, FEEDBACK_PARAMETERS, FEEDBACKS, MAX_FEEDBACK_STEPS,
                       _approach_table, _check_gain, _run_feedback)
from .lever import PARAMETERS, TappingLever

__all__ = ["TappingMode"]


class TappingMode(Mode):
    """Amplitude-modulation imaging through module (f)'s scanner: height and phase channels.

    With ``feedback="ideal"`` (the default) an infinitely fast amplitude feedback holds the
    amplitude at the setpoint r A0: at every pixel the lever rests at the distance
    z_c(material) of :func:`setpoint_state` above the apex surface, with the phase lag and the
    dissipation of that state. The height channels are the apex surface plus
    z_c(material) - z_c(first material): the topography where the sample is the first material,
    plus the apparent step a change of material makes (a stiffer or less adhesive material lifts
    the lever). The phase channels show the materials' contrast, which dissipation in the
    sample makes (E_dis = (pi k A^2 / Q)[(A0 / A) sin(phi) - W]).

    With ``feedback="pi"`` the loop of :func:`amplitude_feedback` runs along the scan in time
    (trace, retrace, the step to the next line, each line continuing from the state the
    previous one left): the amplitude lags height changes with tau = 2 Q / w0 and a PI
    controller moves the positioner. Scanning faster than the loop can follow gives the known
    artefacts: the height lags at edges, the tip parachutes off a down step (the amplitude
    rises towards A0 and the error saturates), and the error channels (A - A_sp) show the
    edges. The height channel is the positioner's height minus the first material's setpoint
    distance; phase and dissipation are those of the lagging amplitude and phase.

    Parameters
    ----------
    levers : TappingLever or sequence of TappingLever
        The lever on each material (same lever, a different sample: modulus, viscosity, ...);
        at most 16 (with ``feedback="pi"``, one lever: module (f)'s levers differ only in the
        sample, and the loop's time constant is the lever's).
    setpoint_ratio : float
        Setpoint r = A_sp / A0, in (0, 1).
    material : callable, optional
        ``material(x, y)`` -> integer array (index into ``levers``) of the material at positions
        x, y in m on the sample (arrays of one shape); default: the first everywhere.
    feedback : str
        ``"ideal"`` or ``"pi"`` (:data:`FEEDBACKS`).
    amplitude_kp, amplitude_ki : float
        The PI gains (``feedback="pi"`` only; :data:`FEEDBACK_PARAMETERS`).

    Raises
    ------
    ValueError
        On a setpoint outside (0, 1), no lever, an unknown feedback or gains out of range,
        before any scan; with ``feedback="pi"``, a scan needing more than
        :data:`MAX_FEEDBACK_STEPS` steps (when the scan starts).
    TypeError
        If a lever is not a :class:`TappingLever` or ``material`` is not callable.
    """

    channels = ("height trace", "height retrace", "phase trace", "phase retrace",
                "dissipation trace")
    units = MappingProxyType({"phase trace": "rad", "phase retrace": "rad",
                              "dissipation trace": "J"})

    def __init__(self, levers, setpoint_ratio: float = PARAMETERS["setpoint_ratio"].default,
                 material=None, *, feedback: str = "ideal",
                 amplitude_kp: float = FEEDBACK_PARAMETERS["amplitude_kp"].default,
                 amplitude_ki: float = FEEDBACK_PARAMETERS["amplitude_ki"].default):
        if not isinstance(levers, TappingLever) and (isinstance(levers, (str, bytes))
                                                     or not hasattr(levers, "__iter__")):
            raise TypeError(f"levers must be a TappingLever or a sequence of them, got "
                            f"{type(levers).__name__}")
        levers = (levers,) if isinstance(levers, TappingLever) else tuple(levers)
        if not 1 <= len(levers) <= 16:
            raise ValueError(f"levers must hold 1 to 16 levers, got {len(levers)}")
        self.levers = tuple(check_instance("levers", lever, TappingLever) for lever in levers)
        self.setpoint_ratio = PARAMETERS["setpoint_ratio"].check(setpoint_ratio)
        if material is not None and not callable(material):
            raise TypeError(f"material must be a callable material(x, y), got "
                            f"{type(material).__name__}")
        self.material = material
        self.feedback = check_choice("feedback", feedback, FEEDBACKS)
        self.amplitude_kp = FEEDBACK_PARAMETERS["amplitude_kp"].check(amplitude_kp)
        self.amplitude_ki = FEEDBACK_PARAMETERS["amplitude_ki"].check(amplitude_ki)
        if self.feedback == "pi":
            taus = {lever.time_constant for lever in self.levers}
            if len(taus) != 1:
                raise ValueError(f"levers must share one quality factor and resonance "
                                 f"frequency with feedback='pi' (one lever, one time "
                                 f"constant), got time constants {sorted(taus)}")
            _check_gain(self.amplitude_ki, self.levers[0].time_constant)
            self.channels = TappingMode.channels + ("error trace", "error retrace")
        states = [setpoint_state(self.setpoint_ratio, lever) for lever in self.levers]
        #: Per material: rest distance z_c in m, phase lag in rad, E_dis in J.
        self.distance = np.array([s[0] for s in states])
        self.phase = np.array([s[1] for s in states])
        self.dissipation = np.array([s[2] for s in states])
        self._tables = None

    def _which(self, x, y):
        if self.material is None:
            return np.zeros(np.shape(x), dtype=int)
        m = np.asarray(self.material(x, y))
        if m.shape != np.shape(x) or m.dtype.kind not in "iu" or m.size and \
                (m.min() < 0 or m.max() >= len(self.levers)):
            raise ValueError(f"material(x, y) must give integers in [0, {len(self.levers) - 1}] "
                             f"shaped like x, got {m.dtype} {m.shape}")
        return m

    def start(self, plan: ScanPlan):
        """Check the scan's length for the PI loop and tabulate the approach (``"pi"`` only).

        Parameters
        ----------
        plan : afmsmiler.imaging.scan_modes.ScanPlan
            The scan.

        Returns
        -------
        None

        Raises
        ------
        TypeError
            If ``plan`` is not a ScanPlan.
        ValueError
            With ``feedback="pi"``, if the scan needs more than :data:`MAX_FEEDBACK_STEPS`
            steps of the loop.
        """
        super().start(plan)
        if self.feedback == "pi":
            tau = self.levers[0].time_constant
            lines, n = plan.shape
            span = plan.t_retrace[-1, 0] - plan.t_trace[0, 0]
            steps = lines * (2 * n - 1) + int(math.ceil(span / (tau / _STEPS_PER_TAU)))
            if steps > MAX_FEEDBACK_STEPS:
                raise ValueError(f"scan_speed: this scan needs about {steps} steps of the "
                                 f"amplitude loop (tau / {_STEPS_PER_TAU} = "
                                 f"{tau / _STEPS_PER_TAU:g} s over {span:g} s), more than "
                                 f"{MAX_FEEDBACK_STEPS}: scan faster, fewer pixels, or use "
                                 f"feedback='ideal'")
            if self._tables is None:
                self._tables = [_approach_table(lever) for lever in self.levers]
        return None

    def line(self, plan: ScanPlan, row: int, state=None) -> ModeLine:
        """One line: height, phase and dissipation at each pixel of trace and retrace.

        Parameters
        ----------
        plan : afmsmiler.imaging.scan_modes.ScanPlan
            The scan.
        row : int
            Line index.
        state : object
            ``"ideal"``: unused (nothing carries over). ``"pi"``: the loop's state at the end
            of the previous line (None before the first: settled at the setpoint).

        Returns
        -------
        afmsmiler.imaging.scan_modes.ModeLine
        """
        row = self._row(plan, row)
        if self.feedback == "pi":
            return self._line_pi(plan, row, state)
        out = {}
        ref = self.distance[0]
        for name, heights, x, y in (("trace", plan.trace, plan.x_trace, plan.y_trace),
                                    ("retrace", plan.retrace, plan.x_retrace, plan.y_retrace)):
            m = self._which(x[row], y[row])
            out[f"height {name}"] = heights[row] + self.distance[m] - ref
            out[f"phase {name}"] = self.phase[m]
            if name == "trace":
                out["dissipation trace"] = self.dissipation[m]
        return ModeLine(out, None)

    def _line_pi(self, plan, row, state):
        if self._tables is None:
            self.start(plan)
        n = plan.shape[1]
        m_t = self._which(plan.x_trace[row], plan.y_trace[row])
        m_r = self._which(plan.x_retrace[row], plan.y_retrace[row])
        # the path in time: the trace, then the retrace from its second pixel (the first is the
        # trace's last, at the same time)
        r = np.concatenate((plan.trace[row], plan.retrace[row][::-1][1:]))
        t = np.concatenate((plan.t_trace[row], plan.t_retrace[row][::-1][1:]))
        m = np.concatenate((m_t, m_r[::-1][1:]))
        lever = self.levers[0]
        a_sp = self.setpoint_ratio * lever.free_amplitude
        big_z, amp, phi, new = _run_feedback(self._tables, r.tolist(), t.tolist(), m.tolist(),
                                             a_sp, self.amplitude_kp, self.amplitude_ki,
                                             lever, self.distance.tolist(), state)
        height = big_z - self.distance[0]
        e_dis = np.empty(n)
        for k in np.unique(m[:n]):  # at most 16 materials
            sel = m[:n] == k
            e_dis[sel] = self.levers[k].dissipated_energy(amp[:n][sel], phi[:n][sel])
        back = slice(n - 1, None)  # the retrace in increasing x: pixel n - 1 is the turn-around
        out = {"height trace": height[:n], "height retrace": height[back][::-1].copy(),
               "phase trace": phi[:n], "phase retrace": phi[back][::-1].copy(),
               "dissipation trace": e_dis,
               "error trace": amp[:n] - a_sp, "error retrace": (amp[back] - a_sp)[::-1].copy()}
        return ModeLine(out, new)
