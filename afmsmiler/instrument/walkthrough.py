"""The guided setup of an optical-beam-deflection AFM, as data: steps, narration, checks, hints.

The virtual lab manual of module (e) (the AFM SMILER paper's guided setup animation with
narration) in five steps, the order the vendors' manuals teach (e.g. Bruker's MultiMode 8
instruction manual): mount the probe, put the laser on the lever's free end for the largest
sum, centre the reflected spot on the photodiode (both differences to zero), set the
deflection setpoint, approach the sample. Each :class:`Step` holds

* ``text``: the narration the panel and the notebook show;
* ``parts``: the names of the 3D scene's parts to look at (:mod:`afmsmiler.scenes.instrument`,
  the ``"obd"`` instrument), so that a panel can highlight them and move the camera there;
* ``check``: a function of a :class:`SetupState` (the head with its knobs, the signals it
  displays, the setpoint, the coarse approach's gap) returning a :class:`StepCheck`: passed or
  not, and when not, a hint that says what to turn and which way, never the number to set.

Nothing here draws or evaluates physics of its own: the checks read the signals the head's model
computed (:meth:`~afmsmiler.instrument.OpticalHead.signals`, run once for a state) and its
closed-form optimum (:attr:`~afmsmiler.instrument.OpticalHead.best_sum`); the knob directions
the hints give follow the model's geometry (a positive turn of ``laser_x`` moves the spot
towards the lever's free end, of ``laser_y`` towards +y, of ``detector_vertical`` and
``detector_lateral`` moves the photodiode so that the spot goes down and right on it, i.e.
towards negative vertical and lateral differences); :mod:`tests.test_instrument_walkthrough`
checks each direction on the model.

The setpoint is the tip deflection the feedback will hold in contact (module (a)'s z, positive
up: the sample pushes the lever up); its force is F = k z with the lever's spring constant k.
Contact-mode imaging works at forces of the order of a nanonewton to a few tens of nanonewtons
(Meyer, Hug and Bennewitz, *Scanning Probe Microscopy* (2004), ch. 3; Butt, Cappella and Kappl,
Surf. Sci. Rep. 59, 1 (2005)); :data:`STEP_TOLERANCES` holds the range the check accepts. The
approach is done when the tip is within the scanner's z range of the surface (a few micrometres
for a tube scanner, e.g. the MultiMode's J scanner: 5 um), where the feedback takes over.

Examples
--------
>>> from afmsmiler.instrument import OpticalHead, align
>>> head = OpticalHead()
>>> state = SetupState(head, mounted=True)
>>> bool(STEPS[1].check(state))           # just mounted: the spot misses the lever
False
>>> _ = align(head)
>>> [bool(step.check(SetupState(head))) for step in STEPS[:3]]
[True, True, True]
"""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Callable

from ..parameters import Parameter, read_only, shown
from ..validation import check_choice, check_instance, check_integer
from .alignment import TOLERANCES, OpticalHead, Signals

__all__ = ["SETUP", "STEP_TOLERANCES", "SetupState", "StepCheck", "Step", "STEPS",
           "step_index", "Walkthrough"]

#: The settings of the setup besides the knobs (SI): the setpoint and the coarse approach.
SETUP = read_only({p.name: p for p in (
    Parameter(name="deflection", unit="m", display_unit="nm", default=0.0, low=-500e-9,
              high=500e-9, label="tip deflection (the deflection setpoint)"),
    Parameter(name="approach_gap", unit="m", display_unit="um", default=1e-3, low=0.0,
              high=1e-3, label="tip-sample gap (coarse approach)"),
)})

#: What the setpoint and approach steps accept (the alignment steps use :data:`TOLERANCES`).
STEP_TOLERANCES = read_only({p.name: p for p in (
    Parameter(name="min_force", unit="N", display_unit="nN", default=0.5e-9, low=0.0,
              high=1e-6, label="smallest setpoint force k z (contact kept)"),
    Parameter(name="max_force", unit="N", display_unit="nN", default=50e-9, low=0.0,
              high=1e-6, label="largest setpoint force k z (tip and sample spared)"),
    Parameter(name="approach_range", unit="m", display_unit="um", default=5e-6, low=0.0,
              high=1e-3, label="tip within the scanner's z range of the surface"),
)})


@dataclass(frozen=True)
class StepCheck:
    """A step's verdict: truthy when passed; ``message`` says why, ``hint`` what to do.

    Attributes
    ----------
    passed : bool
        Whether the step is done.
    message : str
        What was checked, in words (no numbers the student must find).
    hint : str
        What to turn and which way ("" when passed).
    """

    passed: bool
    message: str
    hint: str = ""

    def __bool__(self) -> bool:
        return self.passed

    def __str__(self) -> str:
        return ("Done: " if self.passed else "Not yet: ") + self.message + (
            f" Hint: {self.hint}" if self.hint else "")


@dataclass(frozen=True)
class SetupState:
    """What the checks look at: the head, its displayed signals, the setpoint and the gap.

    Parameters
    ----------
    head : OpticalHead
        The head with its knobs.
    signals : Signals, optional
        The head's signals at zero deflection (the free lever, what the display shows while
        aligning); computed from ``head`` when not given (one model run). A panel passes the
        ones it computed.
    deflection : float
        The deflection setpoint z in m (:data:`SETUP`).
    approach_gap : float
        The tip-sample gap in m (:data:`SETUP`; 0 is in contact).
    mounted : bool
        Whether the probe is in its holder.

    Raises
    ------
    TypeError
        For a head that is not an OpticalHead or signals that are not Signals.
    ValueError
        For a setpoint or gap out of its range.
    """

    head: OpticalHead
    signals: Signals | None = None
    deflection: float = SETUP["deflection"].default
    approach_gap: float = SETUP["approach_gap"].default
    mounted: bool = True

    def __post_init__(self):
        check_instance("head", self.head, OpticalHead)
        check_instance("mounted", self.mounted, bool)
        SETUP["deflection"].check(self.deflection)
        SETUP["approach_gap"].check(self.approach_gap)
        if self.signals is None:
            object.__setattr__(self, "signals", self.head.signals())
        check_instance("signals", self.signals, Signals)


# -- the checks ----------------------------------------------------------------------------------
def _turn(knob: str, positive: bool) -> str:
    return f"turn {knob} {'clockwise (+)' if positive else 'counter-clockwise (-)'}"


def _check_mounted(state: SetupState) -> StepCheck:
    if state.mounted:
        return StepCheck(True, "the probe chip sits in the cantilever holder, the lever over the "
                               "holder's window.")
    return StepCheck(False, "there is no probe in the holder.",
                     "put the probe chip into the holder's clip (the 'probe mounted' switch).")


def _check_laser(state: SetupState,
                 min_sum_fraction: float = TOLERANCES["min_sum_fraction"].default,
                 end_distance: float = TOLERANCES["end_distance"].default) -> StepCheck:
    if not state.mounted:
        return StepCheck(False, "there is no lever to put the laser on.",
                         "mount the probe first (step 1).")
    head, s = state.head, state.signals
    lever = head.lever
    x, y = s.spot_on_lever
    best = head.best_sum
    enough = s.sum >= min_sum_fraction * best
    gap = lever.length - x
    at_end = abs(gap) <= end_distance
    if enough and at_end:
        return StepCheck(True, "the spot is on the lever's free end and the sum is near its "
                               "largest.")
    # which way: where the model says the spot is (the student sees it in the camera's view)
    lever_lit = s.lever_fraction >= min_sum_fraction * head.best_overlap
    hints = []
    across = abs(y) > lever.width / 2 or not lever_lit and abs(y) > lever.width / 4
    if across:
        hints.append(_turn("laser_y", y < 0) + " to bring the spot onto the lever's middle line")
    if x < 0:
        hints.append(_turn("laser_x", True) + ": the spot is on the chip's body, go along the "
                                              "lever towards its free end")
    elif gap > end_distance:
        hints.append(_turn("laser_x", True) + ": the spot is on the lever but short of its "
                                              "free end")
    elif gap < -end_distance or not lever_lit and not across:
        # past the end, or at the end (centred across) with part of the spot hanging over it
        hints.append(_turn("laser_x", False) + ": the spot hangs over the free end and part "
                                               "of it misses the lever (the sum dropped); come "
                                               "back until the sum recovers")
    if not enough and lever_lit:
        hints.append("the lever reflects, but the photodiode misses part of the reflection: "
                     "centre it (step 3) and look at the sum again")
    what = ("the sum is well below its best (not all of the spot is on the lever)"
            if not lever_lit else
            "the sum is well below its best although the spot is on the lever" if not enough
            else "the sum is fine, but the spot is not at the lever's free end, where it bends "
                 "most")
    return StepCheck(False, what + ".", "; ".join(hints) + ".")


def _check_detector(state: SetupState,
                    max_difference: float = TOLERANCES["max_difference"].default,
                    min_sum_fraction: float = TOLERANCES["min_sum_fraction"].default
                    ) -> StepCheck:
    s = state.signals
    if not state.mounted or s.sum < 0.5 * min_sum_fraction * state.head.best_sum:
        return StepCheck(False, "too little light reaches the photodiode to centre it.",
                         "put the laser on the lever first (step 2).")
    hints = []
    for name, knob, label in (("vertical", "detector_vertical", "VERT"),
                              ("lateral", "detector_lateral", "HORZ")):
        value = getattr(s, f"{name}_normalised")
        if abs(value) > max_difference:
            # a positive turn moves the spot towards negative differences on the photodiode
            hints.append(f"{_turn(knob, value > 0)} until {label} reads zero ({label} is "
                         f"{'positive' if value > 0 else 'negative'})")
    if not hints:
        return StepCheck(True, "the reflected spot is centred on the four quadrants (VERT and "
                               "HORZ near zero).")
    return StepCheck(False, "the reflected spot is not centred on the photodiode.",
                     "; ".join(hints) + ".")


def _check_setpoint(state: SetupState,
                    min_force: float = STEP_TOLERANCES["min_force"].default,
                    max_force: float = STEP_TOLERANCES["max_force"].default) -> StepCheck:
    k = state.head.lever.spring_constant
    z = state.deflection
    force = k * z
    if z <= 0:
        return StepCheck(False, "a deflection setpoint at or below the free lever's pulls the "
                                "tip off (or never touches) the surface.",
                         "raise the deflection setpoint above zero: in contact the sample "
                         "pushes the lever up.")
    if force < min_force:
        return StepCheck(False, f"the setpoint force k z ({shown(force, 'nN', '.2g')}) is too "
                                "small to keep the tip in contact through noise and drift.",
                         "raise the deflection setpoint a little.")
    if force > max_force:
        return StepCheck(False, f"the setpoint force k z ({shown(force, 'nN', '.3g')}) would "
                                "wear the tip and scratch a soft sample.",
                         "lower the deflection setpoint.")
    return StepCheck(True, f"the feedback will hold the tip at k z = "
                           f"{shown(force, 'nN', '.3g')} on the sample.")


def _check_approach(state: SetupState,
                    approach_range: float = STEP_TOLERANCES["approach_range"].default,
                    min_sum_fraction: float = TOLERANCES["min_sum_fraction"].default
                    ) -> StepCheck:
    if not state.mounted or state.signals.sum < min_sum_fraction * state.head.best_sum:
        return StepCheck(False, "without the spot on the lever the feedback cannot tell when "
                                "the tip touches: it would crash into the sample.",
                         "redo the laser alignment (step 2) before approaching.")
    if state.approach_gap > approach_range:
        return StepCheck(False, "the tip is still too far above the sample for the scanner to "
                                "reach it.",
                         "lower the head with the coarse approach (the gap) while watching "
                         "the deflection signal.")
    return StepCheck(True, "the tip is within the scanner's reach: the feedback takes over and "
                           "holds the setpoint.")


@dataclass(frozen=True)
class Step:
    """One step of the guided setup.

    Attributes
    ----------
    key : str
        Short name (``"mount"``, ``"laser"``, ``"photodiode"``, ``"setpoint"``, ``"approach"``).
    title : str
        The step's heading.
    text : str
        The narration (the virtual lab manual).
    parts : tuple of str
        Parts of the ``"obd"`` scene to look at (the first is where the camera goes).
    controls : tuple of str
        The panel controls the step uses.
    check : callable
        ``check(state) -> StepCheck``.
    """

    key: str
    title: str
    text: str
    parts: tuple
    controls: tuple
    check: Callable[[SetupState], StepCheck] = field(repr=False)


#: The five steps, in order.
STEPS = (
    Step("mount", "1. Mount the probe",
         "Take the probe chip by its sides with tweezers and slide it under the cantilever "
         "holder's clip, lever first, so that the lever sticks out over the holder's window. "
         "The holder tilts the chip by about 12 degrees, so that only the tip touches the "
         "sample.",
         ("probe_chip", "cantilever_holder"), ("mounted",), _check_mounted),
    Step("laser", "2. Put the laser on the lever's free end",
         "Turn the two laser knobs (they tilt the steering mirror: laser_x moves the spot along "
         "the lever, laser_y across it). Find the lever first: where the spot falls on the "
         "lever, SUM rises. Then walk the spot along the lever to its free end: SUM stays high "
         "along the lever and halves when the spot runs off its end; come back until it "
         "recovers. The end bends most, so there the signal per nanometre is largest.",
         ("laser_x", "laser_y", "probe_chip", "steering_mirror"), ("laser_x", "laser_y"),
         _check_laser),
    Step("photodiode", "3. Centre the spot on the photodiode",
         "The reflected beam falls on the four-quadrant photodiode. Turn its two knobs until "
         "VERT (top minus bottom) and HORZ (left minus right) read zero: the spot then sits on "
         "the centre, where a deflection of the lever gives the largest, most linear signal.",
         ("photodiode", "detector_vertical", "detector_lateral"),
         ("detector_vertical", "detector_lateral"), _check_detector),
    Step("setpoint", "4. Set the deflection setpoint",
         "In contact mode the feedback holds the lever's deflection constant. Choose the "
         "deflection it will hold: the force on the sample is the lever's spring constant "
         "times that deflection. Too little and the tip loses contact; too much and it wears "
         "and scratches.",
         ("probe_chip", "photodiode"), ("deflection",), _check_setpoint),
    Step("approach", "5. Approach the sample",
         "Lower the head with the coarse approach (the thumb screws and the motor) until the "
         "tip is within the scanner's reach of the sample; the motor stops when the "
         "deflection signal reaches the setpoint, and the feedback takes over.",
         ("coarse_screw_rear", "approach_motor", "sample_puck", "probe_chip"),
         ("approach_gap",), _check_approach),
)


def step_index(key) -> int:
    """The index in :data:`STEPS` of the step ``key`` (a key or an index).

    Parameters
    ----------
    key : str or int
        A step's key or an index 0 to 4.

    Raises
    ------
    ValueError
        For an unknown key or an index out of range.
    """
    if isinstance(key, str):
        return [s.key for s in STEPS].index(check_choice("step", key, [s.key for s in STEPS]))
    return check_integer("step", key, 0, len(STEPS) - 1)


class Walkthrough:
    """The guided setup's position: the current step, Next/Back, and the checks done.

    Parameters
    ----------
    start : str or int
        The step to begin with (a key of :data:`STEPS` or an index).

    Attributes
    ----------
    index : int
        The current step's index.
    results : dict
        Step key -> the last :class:`StepCheck` of that step.
    """

    def __init__(self, start=0):
        self.index = step_index(start)
        self.results = {}

    @property
    def step(self) -> Step:
        """The current :class:`Step`."""
        return STEPS[self.index]

    def next(self) -> Step:
        """Go to the next step (stays at the last) and return it."""
        self.index = min(self.index + 1, len(STEPS) - 1)
        return self.step

    def back(self) -> Step:
        """Go to the previous step (stays at the first) and return it."""
        self.index = max(self.index - 1, 0)
        return self.step

    def check(self, state: SetupState) -> StepCheck:
        """Check the current step on ``state`` and remember the result.

        Parameters
        ----------
        state : SetupState
            The head, its signals, the setpoint and the gap.

        Returns
        -------
        StepCheck
        """
        check_instance("state", state, SetupState)
        result = self.step.check(state)
        self.results[self.step.key] = result
        return result

    def resume(self, state: SetupState) -> Step:
        """Check the steps in order on ``state`` and go to the first not yet done.

        What a setup changed behind the guide's back (the knobs set by
        :func:`~afmsmiler.instrument.align`, a re-run notebook) shows up here: the steps it
        completed are recorded as done and the guide goes on from the first that is not (the
        last step when every one is done).

        Parameters
        ----------
        state : SetupState
            The head, its signals, the setpoint and the gap.

        Returns
        -------
        Step
            The step the guide is now at.
        """
        check_instance("state", state, SetupState)
        for index, step in enumerate(STEPS):
            self.index = index
            result = step.check(state)
            self.results[step.key] = result
            if not result:
                break
        return self.step

    @property
    def done(self) -> bool:
        """Whether every step's last check passed."""
        return all(bool(self.results.get(s.key)) for s in STEPS)
