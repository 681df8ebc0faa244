"""The bad-input campaign over the public API: the models, the upper floors and the hardware.

Every public function, class and method of the physics modules (cantilever, materials,
transducers, controller, contact, samples, brownian when present), of module (f)'s imaging
modules (dilation, scanner, modes, corrections, statistics) and PNG export, of module (e)'s
optical head (instrument.optics, instrument.alignment), and of the house
modules (parameters, validation) is first called with valid arguments, built from its signature:
the defaults, and a small table of valid values by parameter name (``lever`` -> a Cantilever,
``tip`` -> a Parabolic tip, ``loop`` -> a ContactLoop, ``sample`` -> a 16 x 16 image, ...). The
signatures are read at collection time, so the campaign follows the modules as their signatures
change. Then each parameter in turn gets bad values (NaN, +-inf, a string, None, a bool, a
complex, a list, a foreign object, a wrong shape, zero, negative, huge and tiny numbers, a huge
integer, 10**400 beyond the float range), the others staying valid; a Sample parameter also gets
extreme samples (a line, 2 x 2, flat, heights near 1e308, pixels of 1e-300 m, a deflection
channel ...) and an imaging function's tip the ends of module (d)'s tip ranges. A generator is consumed under the guard.

A call passes when it either

* raises ``ValueError`` or ``TypeError`` whose message names the parameter, or
* returns a result whose numbers are all finite, and the bad value was a plain number (a NaN, a
  string, None, a complex or an object accepted silently is a failure);

and in any case returns within 10 s of CPU (a SIGPROF timer per call: CPU, so that a loaded CI
machine does not turn a slow call into a failure; a SIGALRM hang guard at 60 s catches a call
that waits instead of computing) without asking for more memory
than the guard allows (RLIMIT_AS, so a size that would swap the machine fails as MemoryError).
A valid call must return finite numbers too.

What cannot be built (no valid value known for a parameter, or the valid call itself raises) is
skipped visibly, with the reason. Known failures in modules that this file's author does not own
are strict xfails, listed with their calls in ``tests/api_campaign_known.py``; the lead fixes them
and deletes the entries (strict: a fixed entry turns the run red until it is deleted).
``python tests/api_campaign_record.py`` rewrites that file from a fresh run.

The upper floors (issue 21, section 6) are tried the same way:

* figures, scenes and exercises (:data:`UPPER_MODULES`): each object parameter (one whose
  annotation or numpydoc type is a kind of :data:`OBJECTS`: a model result, a Figure, a
  visualizer) gets a foreign object, a string, a number and None, and must name itself in a
  TypeError or ValueError; each other parameter gets the table of bad values (``slow``); an
  exercise's checker may answer with a Feedback that did not pass;
* every panel of the registry (``afmsmiler.ui.registry``): ``set()`` with what a control cannot hold, the
  constructor with an initial value ``set()`` refuses, ``update()`` with such values (``slow``),
  each named; the cases that wait for the panel contract (issue 21, section 1) are non-strict
  xfails (:data:`PANEL_CONTRACT`);
* the file readers: a real file of each format, cut short, bytes replaced, header numbers made
  huge, negative or zero, must be refused naming the file or read as finite numbers.

The hardware layer (:data:`HARDWARE_MODULES`, issue 21, section 6) is tried as the models are:
every public callable of the frame format, the parameter tables, the three devices' codecs, the
transports, the twins, the drivers (each connected to its twin, served in memory), the sessions,
the experiments, the force bridge and the AD2; and hostile devices: a driver whose far end,
after an honest start, sends garbage, an endless line, events for ever, its host's line back,
nothing, huge or negative integers, words for integers, short replies, replies to another SEQ or
echoing another command, unknown error numbers. Every operation must end in the guard with a
HardwareError or an honest result (:class:`HostileLink`).

Every call runs under the same time and memory guard. ``make unit`` runs the smoke part (the
first parameter of every callable, each parameter of the house modules, the object parameters,
the panels' ``set()``, a few damaged files); ``make test`` runs every parameter (``slow``) and a
hypothesis search over random numbers for every callable (``slow``).
"""
from __future__ import annotations

import dataclasses
import enum
import importlib
import inspect
import math
import os
import re
import resource
import signal
import threading
import time
import zlib
from contextlib import contextmanager
from pathlib import Path

import numpy as np
import pytest
from hypothesis import HealthCheck, Phase, given, seed, settings
from hypothesis import strategies as st

from afmsmiler.parameters import Parameter

from tests.api_campaign_known import KNOWN

if os.environ.get("AFMSMILER_CAMPAIGN_RECORD"):  # tests/api_campaign_record.py: see everything
    KNOWN = {}

# Overflow and invalid-value warnings of extreme inputs are expected; the results are judged.
pytestmark = pytest.mark.filterwarnings("ignore::RuntimeWarning")

MODULES = ["afmsmiler.cantilever", "afmsmiler.planform", "afmsmiler.materials", "afmsmiler.transducers",
           "afmsmiler.controller", "afmsmiler.contact", "afmsmiler.samples",
           "afmsmiler.brownian", "afmsmiler.parameters", "afmsmiler.validation",
           # module (f): each public module of the imaging package (not the package, whose
           # re-exports would give the classes twice), and the PNG export
           "afmsmiler.imaging.dilation", "afmsmiler.imaging.scanner", "afmsmiler.imaging.scan_modes",
           "afmsmiler.imaging.corrections", "afmsmiler.imaging.statistics",
           "afmsmiler.plots.export",
           # module (e): the optical head's laser alignment
           "afmsmiler.instrument.optics", "afmsmiler.instrument.alignment",
           # module (g): the imaging modalities
           "afmsmiler.modes._forces", "afmsmiler.modes.tapping", "afmsmiler.modes.fm",
           "afmsmiler.modes.jumping", "afmsmiler.modes.force_volume", "afmsmiler.modes.bimodal",
           "afmsmiler.modes.lateral", "afmsmiler.modes.qcontrol", "afmsmiler.modes.oscillator",
           # module (h): the educational AFM's signal chain and lock-in
           "afmsmiler.signals.lockin", "afmsmiler.signals.ad630", "afmsmiler.signals.chain",
           "afmsmiler.signals.demo",
           # module (h): an AFM image as a printable STL
           "afmsmiler.hardware.printing",
           # module (a): the lever in a fluid and its calibration (issue 23)
           "afmsmiler.hydrodynamics", "afmsmiler.calibration",
           # module (a): "your probe", a Lever in air and water, calibrated (issue 23)
           "afmsmiler.probe",
           # the modules as web apps (voila's command line and template)
           "afmsmiler.apps"]
HOUSE = ("afmsmiler.parameters", "afmsmiler.validation")
TIME_LIMIT = 10.0  # s of CPU per call: the issue's bound (CPU, so a loaded machine cannot fail it)
WALL_LIMIT = 60.0  # s of wall-clock time per call: a hang guard for a call that waits, not computes
MEMORY_MARGIN = 4 * 2**30  # bytes of address space a call may add (23 GB machine, shared)

# Parameters that are not inputs of the physics: the name and unit a validation helper prints.
NOT_INPUTS = {"name", "unit", "what", "label", "description", "readout_format"}
# Free text that a constructor stores as given (a curve's or a material's name, a source).
FREE_TEXT = {"name", "source", "label", "description", "channel"}
#: Parameters that name another one in an error message (any text will do; a non-str is refused).
MESSAGE_NAMES = {"cantilever.check_modes:name", "hardware.framing.as_bytes:name"}
#: Methods that take a new name for the object they return (any text will do; a non-str is
#: refused): a label, as a constructor's ``name`` is.
NEW_NAMES = {"samples.Sample.with_heights:name", "hardware.printing.mesh_to_sample:name"}
#: The bad-value labels that are not numbers (a parameter that takes anything accepts them all).
NOT_NUMBERS = ("nan", "str", "bool", "complex", "object", "nan-array")
#: "callable:parameter" -> (bad-value labels that are in fact valid there, why): documented values
#: that the table of bad values cannot know about.
ACCEPTED = {
    # valid values, each of which runs the whole trial: two real-time ring-downs on the twin,
    # timed by the host's clock (a loaded machine can starve them); test_hardware_experiments
    # runs the trial, and the campaign keeps the values its validation refuses
    "hardware.experiments.q_control_trial:gain": (
        ("zero", "negative", "tiny"), "gains in [-10, 10]: each runs the real-time trial"),
    "hardware.experiments.q_control_trial:spring": (
        ("tiny",), "a spring in (0, 2000] N/m: it runs the real-time trial"),
    "imaging.scanner.Scan:tip": (("None",), "None is the documented ideal, infinitely sharp tip"),
    "imaging.scanner.scan:tip": (("None",), "None is the documented ideal, infinitely sharp tip"),
    "imaging.scan_modes.ConstantHeight.line:state": (("bool",), "the documented state: whether the "
                                                "tip was in contact at the end of the line"),
    # any text is a file name; "1e-6" would also write a PNG into the working directory
    "plots.export.save_png:path": (("str",), "any text is a file name"),
    "modes.lateral.LateralForceMode.line:state": (
        NOT_NUMBERS,
        "unused and documented so: each line is a steady friction loop"),
    "modes.tapping.TappingMode.line:state": (
        NOT_NUMBERS,
        "unused by the ideal feedback (the default) and documented so"),
    "modes.force_volume.force_volume:adhesion": (("None",), "None is the documented "
                                                 "adhesion-free contact"),
    "modes.force_volume.force_volume:seed": (("None",), "None is the documented fresh noise"),
    "modes.force_volume.force_volume_steps:adhesion": (("None",), "None is the documented "
                                                       "adhesion-free contact"),
    "modes.force_volume.force_volume_steps:seed": (("None",), "None is the documented fresh "
                                                   "noise"),
    "modes.force_volume.force_volume_steps:block_pixels": (
        ("None",), "None is the documented: blocks as large as memory allows"),
    "modes.force_volume.two_material_sample:seed": (("None",), "None is the documented fresh "
                                                    "layout"),
    "modes.lateral.friction_scan:seed": (("None",), "None is the documented fresh noise"),
    "modes.lateral.LateralLever:tip_height": (("None",), "None is the documented: from the lever"),
    "modes.lateral.LateralLever:shear_modulus": (("None",), "None is the documented: the "
                                                 "lever's own"),
    **{f"planform.Lever{m}:{p}": (("None",), "None is documented: tip at the free end, no "
                                  "coating, the material's or the lever's G")
       for m in ("", ".rectangular", ".pointed", ".v_shaped")
       for p in ("tip_position", "coating")},
    **{f"planform.Lever.v_shaped:{p}": (("None",), "None is documented: the width from the "
                                        "half-angle, or the half-angle from the width")
       for p in ("width", "half_angle")},
    # module (h): "1e-6" is a word of the frame format ([A-Za-z0-9_.:-]+), and a word a driver
    # does not know is kept as a str (documented): a device of a newer firmware may send it
    # any text without spaces is a token ("1e-6" too)
    "apps.voila_command:token": (("str",), "any printable text without spaces is a token"),
    "hardware.framing.event_frame:word": (("str",), "any word of the frame format"),
    "hardware.framing.error_frame:word": (("str",), "any word of the frame format"),
    "hardware.twin.Twin.error:word": (("str",), "any word of the frame format"),
    **{f"hardware.{twin}.error:word": (("str",), "Twin.error's: any word of the frame format")
       for twin in ("macro.twin.MacroAFMTwin", "educational.twin.EducationalAFMTwin",
                    "haptic.twin.HapticTwin")},
    "hardware.macro.codec.ErrorReply:word": (("str",), "any word of the frame format"),
    "hardware.macro.codec.EventMsg:arg": (("str",), "any word of the frame format"),
    "hardware.protocol.ParamTable.enum:doc": (("str",), "the enum's docstring: free text"),
    "hardware.protocol.WireParam:meaning": (("str",), "what it is in a few words: free text"),
    "hardware.macro.codec.EventMsg:event": (("str",), "an event word this driver does not "
                                            "know is kept as a str (documented)"),
    "hardware.macro.codec.Status:state": (("str",), "a state word this driver does not know "
                                          "is kept as a str (documented)"),
    "hardware.protocol.WireUnit:si_unit": (("str",), "the SI unit's symbol: free text"),
    "hardware.protocol.WireParam.valid:wire": (
        NOT_NUMBERS,
        "a predicate: False is its documented answer for anything not a valid wire value"),
    "hardware.haptic.codec.force_frame:force": (("nan",), "documented: a non-finite force is "
                                                "sent as 0, the safe setpoint"),
    "hardware.haptic.device.HapticDevice.send_force:force": (("nan",), "documented (as "
                                                              "force_frame): sent as 0"),
    # any str may name a serial port: whether it is one is the machine's answer at the time
    # (TransportClosed naming it, documented), as open()'s FileNotFoundError is, not bad input
    **{f"hardware.{f}:port": (("str",), "any str may name a serial port; one that is not "
                              "there raises TransportClosed naming it (documented)")
       for f in ("haptic.device.open_haptic", "experiments.haptic_device")},
    "hardware.haptic.twin.HapticTwin:finger": (("None",), "None is the documented free handle "
                                               "(no finger on it)"),
    # the upper floors (test_upper_bad_values_are_named_or_harmless): free text, stored as given
    **{f"scenes.{scene}:path": (("str",), "any text is a path in the viewer's tree")
       for scene in ("cantilever.CantileverScene", "contact.ContactScene",
                     "imaging.ImagingScene", "modes.ModesScene", "transducers.TransducerScene",
                     "probe.ProbeScene")},
    "scenes.legends.TextPlate:text": (("str",), "any text is the plate's text"),
    "plots.controller.ScanFigure:title": (("str",), "any text is a figure's title"),
    "plots.imaging.scan_view:status": (("str",), "any text is the title's note"),
    "plots.modes.ForceVolumeFigure:status": (("str",), "any text is the maps' note"),
    "plots.modes.TappingFigure:status": (("str",), "any text is the curve's note"),
    "plots.contact.fit_figure:zoom": (("None",), "None is the documented whole curve"),
    "plots.hardware.comparison_view:z_step": (("nan",), "NaN is the documented unknown z step "
                                              "(the default)"),
}
# First cases of a callable that take seconds (each of their bad values runs a simulation): `make
# test` runs them, `make unit` does not. (The two time integrations are called with their fewest
# periods, see VALID: under a second each, so `make unit` runs them.)
SLOW_SMOKE: set[str] = {
    "hardware.experiments.q_control_trial:haptic",  # about 1.6 s
}
# Returned by the models, not built by a user: their constructors are not part of the input API
# (their methods are called on a result the model returned, see INSTANCES).
RESULTS = {"Signals", "Alignment", "AlignmentRun", "Stability", "LoopResponse", "ScanLine", "ScanPass", "ScanImage", "ClosedForm",
           "IndentationCurve", "ApproachRetract", "ViscoelasticCycle", "FitResult", "TableRow",
           "SignalChain", "Stage", "FrequencyResponse", "Resolution", "Harmonics", "Preset",
           "Operation", "Bending", "FitResults", "ApexPath", "Modes",
           # module (f): the scanner's and the corrections' results, and what a mode returns
           # (the scanner checks a ModeLine's channels when it receives one)
           "ScanResult", "LineRecord", "ScanPlan", "ModeLine", "Crash", "Plane", "Histogram",
           "Profile", "PngExport",
           # module (g): what the modalities' models return
           "AmplitudeCurve", "SteadyState", "FrequencyShiftCurve", "FrictionLoop",
           "FrictionImages", "FeedbackLine", "JumpCurve", "ModeComparison", "ForceVolume",
           "BimodalState", "LockInResult", "Spectrum", "AD630Result", "ChainRun", "LockInDemo",
           "PrintComparison", "ClosedLoopResponse", "RingDown",
           # module (a): a mode in a fluid, a thermal spectrum, its fit and the calibrations
           "FluidMode", "ThermalSpectrum", "SHOFit", "ThermalCalibration", "SaderCalibration",
           "LabCalibration", "ProbeReport"}
# Abstract bases: their methods are called on each concrete subclass instead.
ABSTRACT = {"Tip", "Transducer", "Mode", "DeviceSession"}
# Legacy descriptions that afmsmiler.parameters.Parameter replaces (issue 8, section 1).
LEGACY = {"afmsmiler.contact.TipParameter", "afmsmiler.transducers.Quantity",
          "afmsmiler.transducers.Parameter"}
# The validation helpers check one input (value or values) that the message calls by the name
# it is given; their other arguments are the calling library's constants, not user input.
HOUSE_INPUTS = {"value", "values"}
#: Reference solvers whose cost in a valid but hard case is bounded by a documented limit of
#: steps, not by the campaign's seconds: a call may run out its 10 s (every other outcome, the
#: error messages included, is judged as anywhere else).
REFERENCE_SOLVERS = {
    "afmsmiler.modes.tapping.integrate": "the tapping lever's time integration: in hard contact "
    "(a rest distance of a nanometre or less) tens of seconds, bounded by max_periods",
    "afmsmiler.modes.bimodal.bimodal_response": "the two-mode time integration, bounded by "
    "max_periods",
    "afmsmiler.hardware.haptic.bridge.TappingSource": "builds its period with the tapping "
    "lever's time integration (above), bounded by its max_periods (documented)",
}
# Conversions that carry NaN through (a gap in a plotted curve); check() validates.
NAN_PASSES = {"afmsmiler.parameters.Parameter.to_si", "afmsmiler.parameters.Parameter.to_display",
              "afmsmiler.validation.check_real"}  # documented: NaN and inf are the caller's
# Callables whose documented answer for valid input may be infinite ("no limit").
INFINITE_OK = {"afmsmiler.contact.z_np_limit": "inf means no limit (documented)",
               "afmsmiler.imaging.dilation.estimate_tip_radius":
                   "inf: an image without a strict local maximum bounds no radius (documented)",
               "afmsmiler.modes.qcontrol.stable_gains":
                   "-inf or inf: no stability limit on that side (documented)",
               "afmsmiler.hardware.haptic.twin.HapticTwin":
                   "-inf: the tick of the last force frame before the first one (its watchdog's "
                   "never)",
               "afmsmiler.hardware.haptic.device.open_haptic": "its twin's -inf, as HapticTwin"}


# -- valid values by parameter name ------------------------------------------------------------
class Ctx:
    """A valid value that depends on the object whose method is called (or the callable)."""

    def __init__(self, make):
        self.make = make


def _lever():
    from afmsmiler.cantilever import Cantilever
    return Cantilever.from_material("silicon", length=225e-6, width=28e-6, thickness=3e-6)


def _loop():
    from afmsmiler.controller import PRESETS
    return next(iter(PRESETS.values())).loop


def _curve():
    from afmsmiler.contact import Parabolic, indent
    return indent(np.linspace(-50e-9, 30e-9, 40), 0.1, Parabolic(50e-9), 20e6, 0.3)


def _synthetic():
    from afmsmiler.contact import Parabolic, synthetic_curve
    return synthetic_curve(Parabolic(50e-9), spring_constant=0.1, youngs_modulus=20e6,
                           poisson_ratio=0.3, points=200, noise=1e-11, seed=1)


def _image():
    """A small image (16 x 16 pixels of 10 nm) with a 3 nm bump and a ripple: every imaging
    function works on it in milliseconds, and a 50 nm tip fits in it."""
    from afmsmiler.samples import Sample
    y, x = np.mgrid[0:16, 0:16].astype(float)
    h = 3e-9 * np.exp(-((x - 7.0) ** 2 + (y - 8.0) ** 2) / 8.0) + 0.2e-9 * np.sin(x)
    return Sample(h, 10e-9, "campaign")


def _settings(**changes):
    """A scan that fits in :func:`_image`: 100 nm (its centre), 8 x 8 pixels."""
    from afmsmiler.imaging.scanner import ScanSettings
    return ScanSettings(**{"scan_size": 100e-9, "pixels": 8, "scan_speed": 1e-6, **changes})


def _system():
    from afmsmiler.contact import ContactSystem, Parabolic
    return ContactSystem(tip=Parabolic(50e-9))


def _constant_force():
    from afmsmiler.imaging.scan_modes import ConstantForce
    return ConstantForce(_loop())


def _constant_height():
    from afmsmiler.imaging.scan_modes import ConstantHeight
    return ConstantHeight(_system(), z_np=1e-9)


def _scan(mode=None, **settings):
    from afmsmiler.contact import Parabolic
    from afmsmiler.imaging.scanner import Scan
    mode = _constant_force() if mode is None else mode
    tip = mode.tip if mode.tip is not None else Parabolic(50e-9)
    return Scan(_image(), tip, mode, _settings(**settings))


def _plan(mode):
    return _scan(mode).plan


def _input_default(inst):
    if hasattr(inst, "input_quantity"):
        return inst.input_quantity().default
    return inst.default  # a Parameter checking a value


def _first_parameter(inst):
    return next(iter(inst.parameter_table()))


VALID = {
    "lever": _lever, "cantilever": _lever, "loop": _loop, "curve": _curve,
    "tip": lambda: __import__("afmsmiler.contact", fromlist=["Parabolic"]).Parabolic(50e-9),
    "length": 225e-6, "width": 28e-6, "thickness": 3e-6, "youngs_modulus": 20e6,
    "density": 2330.0, "poisson_ratio": 0.3, "material": "silicon",
    "x": Ctx(lambda inst: np.linspace(0.0, 200e-6, 11) if _is_lever(inst) else 1e-9),
    "force": 1e-9, "z_b": 1e-6, "tip_deflection": 10e-9, "mode": 1,
    "z_np": lambda: np.linspace(-100e-9, 30e-9, 60), "spring_constant": 0.1,
    "z_s": lambda: np.linspace(0.0, 20e-9, 10), "reduced_modulus": 20e6,
    "r": lambda: np.linspace(0.0, 20e-9, 10), "rho": lambda: np.linspace(0.0, 50e-9, 10),
    "contact_radius": lambda: np.linspace(1e-9, 15e-9, 10), "radius": 50e-9,
    "work_of_adhesion": 0.03, "time": lambda: np.linspace(0.0, 1e-2, 50),
    "indentation": lambda: np.linspace(0.0, 20e-9, 50), "speed": 1e-6,
    "relaxed_modulus": 1e6, "instantaneous_modulus": 2e6, "relaxation_time": 1e-3,
    "heights": lambda: 1e-9 * np.arange(64.0).reshape(8, 8) % 7, "pixel_size": 10e-9,
    "setpoint": 10e-9, "height": Ctx(lambda inst: (np.zeros(16) if isinstance(inst, type(_loop()))
                                                   else 5e-8)),
    "den": [1.0, 2.0, 3.0], "roots": [-1.0, -2.0], "row": 0,
    "t_knots": lambda: np.array([0.0, 1e-3, 2e-3]), "T_knots": lambda: np.array([0.0, 1e-9, 0.0]),
    "bandwidth": 1e3, "f": lambda: np.logspace(2, 6, 20), "value": Ctx(_input_default),
    "d": 10e-9, "slope": 1e-3, "spot": 1e-6, "current": 1e-3, "moment": 1e-12,
    "field_gradient": 1.0, "dc_voltage": 1.0, "frequency": 1e3, "power": 1e-3,
    "pixels": 64, "shape": (32, 32), "count": 5, "period": 100e-9,
    "path": lambda: __import__("afmsmiler.data", fromlist=["path"]).path("spot3-0192.jpk-force"),
    "position": lambda: _synthetic().tip_position, "mapping": {"a": 1.0},
    "display_unit": "nm", "values": [1.0, 2.0], "low": 0.0, "high": 10.0, "choices": ("a", "b"),
    "kind": float, "limit": 100, "ndim": 2, "span": 1.0, "steps": 10,
    "name": "q_x", "unit": "m", "si_value": 1e-4, "display_value": 100.0,
    "u": lambda: np.linspace(0.0, 1.0, 11), "resonance_frequency": 13e3, "section": 0.5,
    "quality_factor": 150.0, "angular_frequency": 8e4,
    "modes": 3,
    # module (e): the optical head (afmsmiler.instrument)
    "focal_length": 0.02, "distance": 0.01, "centre": 0.0, "waist": 17e-6,
    "tilt_in_plane": 0.01, "tilt_out_of_plane": 0.01, "incidence": 0.7, "knob": "laser_x",
    "head": lambda: __import__("afmsmiler.instrument.alignment",
                               fromlist=["OpticalHead"]).OpticalHead(),
    "centre_x": 1e-5, "centre_y": 0.0, "radius_x": 2e-5, "radius_y": 2e-5,
    "x_range": (0.0, 4.5e-4), "y_range": (-2.5e-5, 2.5e-5), "beam_radius": 0.25e-3,
    "wavelength": 670e-9, "angle": 1.0, "end_margin": 0.02, "deflection": 1e-8,
    "normalised": True, "min_sum_fraction": 0.9, "max_difference": 0.02, "end_distance": 4e-5,
    # module (f)
    "sample": _image, "image": _image, "particle_radius": 10e-9, "scan_size": 100e-9,
    "settings": _settings, "system": _system, "column": 0,
    "plan": Ctx(_plan), "state": Ctx(lambda inst: inst.start(_plan(inst))),
    "channel": Ctx(lambda inst: inst.channels[0] if hasattr(inst, "channels") else "height"),
    "start": (10e-9, 20e-9), "end": (120e-9, 100e-9), "line_rate": 1.0, "t": 1e-3,
    # module (g)
    "hamaker_constant": 6.4e-20, "intermolecular_distance": 1.65e-10, "amplitude": 10e-9,
    "phase": 1.0, "distances": lambda: np.linspace(2e-9, 12e-9, 20),
    "levers": lambda: __import__("afmsmiler.modes", fromlist=["TappingLever"]).TappingLever(),
    "z": lambda: np.linspace(0.3e-9, 10e-9, 64), "force_gradient": 0.1,
    "lateral_force": 1e-9, "friction_coefficient": 0.2, "direction": 1,
    # module (a): the lever in a fluid and its calibration
    "fluid": "air", "re": 1.0, "viscosity": 1e-3, "spectrum": lambda: _spectrum(),
    "added_mass": 1e-12,
    "topography": _image, "friction": lambda: __import__("afmsmiler.samples", fromlist=[
        "Sample"]).Sample(np.full((16, 16), 0.2), 10e-9, "friction", unit=""),
}

# Valid values for one callable (by its qualified name), where the name table does not fit.
def _campaign_dir(name: str) -> str:
    """A folder in the temporary directory, the same one every call (nothing piles up)."""
    import tempfile
    path = os.path.join(tempfile.gettempdir(), name)
    os.makedirs(path, exist_ok=True)
    return path


OVERRIDES = {
    "afmsmiler.apps.notebook_path": {"name": "f"},
    "afmsmiler.apps.write_template": {
        "directory": lambda: _campaign_dir("afm-campaign-voila")},
    "afmsmiler.apps.voila_command": {
        "target": lambda: str(__import__("afmsmiler.apps", fromlist=["NOTEBOOKS"]).NOTEBOOKS),
        "port": 8866, "open_browser": False, "token": None},
    "afmsmiler.transducers.get_principle": {"key": "optical_beam_deflection"},
    "afmsmiler.contact.make_tip": {"key": "parabolic"},
    "afmsmiler.cantilever.check_modes": {"modes": (1, 2, 3)},
    "afmsmiler.planform.Lever": {"planform": "rectangular", "youngs_modulus": 169e9},
    "afmsmiler.planform.Lever.modes": {"kind": "flexural"},
    "afmsmiler.planform.Lever.v_shaped": {"width": 160e-6, "thickness": 0.6e-6},
    "afmsmiler.planform.preset": {"name": "AC240TS"},
    **{f"afmsmiler.planform.{f}": {"lever": lambda: __import__(
        "afmsmiler.planform", fromlist=["preset"]).preset("MLCT-E")}
       for f in ("sader_v_spring_constant", "parallel_beam_spring_constant",
                 "parallel_beam_error")},
    # "your probe": a Lever (a pointed preset), not module (a)'s Cantilever
    **{f"afmsmiler.probe.{f}": {"lever": lambda: __import__(
        "afmsmiler.planform", fromlist=["preset"]).preset("AC240TS")}
       for f in ("mean_width", "equivalent_cantilever", "planform_outline", "oscillator",
                 "half_widths")},
    "afmsmiler.probe.probe_report": {"lever": lambda: __import__(
        "afmsmiler.planform", fromlist=["preset"]).preset("AC240TS"), "points": 2 ** 12,
        "averages": 4},
    "afmsmiler.contact.adhesion_extrema": {"adhesion": "jkr", "work_of_adhesion": 0.03},
    "afmsmiler.contact.ContactSystem.at": {"z_np": 10e-9},
    "afmsmiler.contact.contact_surface": {"current": lambda: _curve()},
    "afmsmiler.materials.get_material": {"name": "silicon"},
    "afmsmiler.materials.Material": {"name": "test", "youngs_modulus": 169e9},
    "afmsmiler.cantilever.Cantilever": {"youngs_modulus": 169e9},
    "afmsmiler.contact.fit_curve": {"position": lambda: _synthetic().tip_position,
                                    "force": lambda: _synthetic().force},
    "afmsmiler.contact.fit_curves": {"position": lambda: np.stack([_synthetic().tip_position] * 3),
                                     "force": lambda: np.stack([_synthetic().force] * 3)},
    "afmsmiler.contact.hereditary_force": {"material": lambda: _sls()},
    "afmsmiler.contact.viscoelastic_approach_retract": {"material": lambda: _sls()},
    "afmsmiler.contact.ForceCurve": {"z_np": lambda: _synthetic().z_np,
                                     "force": lambda: _synthetic().force},
    "afmsmiler.samples.from_file": {"path": lambda: __import__(
        "afmsmiler.data", fromlist=["path"]).path("bruker_d3100.spm")},
    "afmsmiler.samples.load": {"path": lambda: __import__(
        "afmsmiler.data", fromlist=["path"]).path("bruker_d3100.spm")},
    "afmsmiler.samples.channels": {"path": lambda: __import__(
        "afmsmiler.data", fromlist=["path"]).path("bruker_d3100.spm")},
    "afmsmiler.samples.Sample": {"heights": lambda: np.zeros((8, 8))},
    "afmsmiler.samples.Sample.resample": {"pixel_size": 5e-9},
    "afmsmiler.samples.save_gwy": {
        "sample": lambda: __import__("afmsmiler.samples", fromlist=["Sample"]).Sample(
            np.zeros((8, 8)), 1e-9),
        "path": lambda: __import__("tempfile").gettempdir() + "/afmsmiler_campaign.gwy"},
    "afmsmiler.validation.check_choice": {"value": "a"},
    "afmsmiler.validation.check_integer": {"value": 3},
    "afmsmiler.validation.check_flag": {"value": True},
    "afmsmiler.validation.check_size": {"value": 3},
    "afmsmiler.validation.check_shape": {"value": (4, 4)},
    "afmsmiler.validation.check_instance": {"value": lambda: {"a": 1}, "kind": dict},
    "afmsmiler.validation.check_array": {"values": [1.0, 2.0]},
    "afmsmiler.validation.check_range": {"value": 1.0},
    "afmsmiler.validation.check_positive": {"value": 1.0},
    "afmsmiler.validation.check_nonnegative": {"value": 1.0},
    "afmsmiler.validation.check_finite": {"value": 1.0},
    "afmsmiler.validation.check_real": {"value": 1.0},
    "afmsmiler.parameters.Parameter": {"name": "length", "unit": "m", "display_unit": "um",
                                       "default": 1e-4, "low": 0.0, "high": 1e-3},
    "afmsmiler.parameters.unit_scale": {"display_unit": "nm", "unit": "m"},
    "afmsmiler.controller.closed_form": {"b": [2.0, 0.0, 0.0], "structure": "distinct",
                                         "params": (-2.0, -1.0)},
    "afmsmiler.samples.profile": {"name": "step"},
    "afmsmiler.contact.surface_displacement": {"z_s": 10e-9},
    "afmsmiler.contact.jkr_instability": {"reduced_modulus": 20e6},
    "afmsmiler.transducers.Transducer.upper_bound": {"name": Ctx(_first_parameter)},
    "afmsmiler.transducers.SignalChain.stage": {"name": Ctx(lambda inst: inst.names[0])},
    "afmsmiler.controller.ContactLoop": {
        f.name: Ctx(lambda inst, f=f.name: getattr(_loop(), f))
        for f in dataclasses.fields(importlib.import_module("afmsmiler.controller").ContactLoop)},
    "afmsmiler.imaging.dilation.tip_radius_from_width": {"width": lambda: __import__(
        "afmsmiler.imaging.dilation", fromlist=["sphere_apparent_width"]).sphere_apparent_width(
        10e-9, __import__("afmsmiler.contact", fromlist=["Parabolic"]).Parabolic(20e-9))},
    # "mode" is a lever's mode number elsewhere
    "afmsmiler.imaging.scanner.Scan": {"mode": _constant_force},
    "afmsmiler.calibration.added_mass_spring_constant": {"loaded_frequency": 1e4,
                                                         "unloaded_frequency": 1.2e4},
    "afmsmiler.imaging.scanner.scan": {"mode": _constant_force},
    "afmsmiler.plots.export.save_png": {
        "path": lambda: __import__("tempfile").gettempdir() + "/afmsmiler_campaign.png"},
    # module (g)
    # the fewest periods it integrates (one block and the lock-in's): the campaign checks the
    # input, test_modes_tapping the physics; each bad value that passes integrates that long
    "afmsmiler.modes.tapping.integrate": {"distance": 12e-9, "max_periods": 20},
    "afmsmiler.modes.tapping.TappingLever.indentation": {"distance": lambda: np.linspace(
        2e-9, 12e-9, 20)},
    "afmsmiler.modes.fm.frequency_shift": {"force": lambda: _vdw},
    "afmsmiler.modes.fm.frequency_shift_curve": {"force": lambda: _vdw},
    "afmsmiler.modes.fm.sader_jarvis": {"df": lambda: -10.0 * (0.3e-9 / np.linspace(
        0.3e-9, 10e-9, 64)) ** 2},
    "afmsmiler.modes.lateral.friction_loop": {"heights": lambda: np.zeros(32)},
    "afmsmiler.modes.tapping.amplitude_feedback": {"heights": lambda: np.zeros(32),
                                                   "times": lambda: np.linspace(0, 1e-3, 32)},
    "afmsmiler.modes.jumping.JumpingMode": {"systems": _system},
    "afmsmiler.modes.jumping.apex_path": {
        "curve": lambda: __import__("afmsmiler.modes.jumping", fromlist=["jump_curve"])
        .jump_curve(_system()), "surface": lambda: np.zeros(4)},
    "afmsmiler.modes.tapping.AmplitudeCurve.branch": {"name": "attractive"},
    "afmsmiler.modes.tapping.AmplitudeCurve.on_branch": {
        "name": "attractive", "values": Ctx(lambda curve: curve.dissipated_energy)},
    "afmsmiler.modes.force_volume.force_volume": {
        "materials": lambda: __import__("afmsmiler.modes", fromlist=["BLEND"]).BLEND,
        "labels": lambda: (np.arange(256).reshape(16, 16) % 2)},
    "afmsmiler.modes.force_volume.force_volume_steps": {
        "materials": lambda: __import__("afmsmiler.modes", fromlist=["BLEND"]).BLEND,
        "labels": lambda: (np.arange(256).reshape(16, 16) % 2)},
    "afmsmiler.modes.force_volume.ForceVolumeMode": {
        "materials": lambda: __import__("afmsmiler.modes", fromlist=["BLEND"]).BLEND},
    "afmsmiler.modes.force_volume.SampleMaterial.system": {"adhesion": "dmt"},
    "afmsmiler.modes.bimodal.BimodalLever.compliance": {"angular_frequency": 2e6},
    "afmsmiler.modes.bimodal.bimodal_response": {"distance": 12e-9, "max_periods": 30},
    "afmsmiler.modes.bimodal.averaged_gradient": {"distance": 12e-9},
    # module (h): a 2 kHz tone sampled at 1 MHz for 40 ms
    "afmsmiler.signals.lockin.lock_in": {"signal": lambda: _tone(), "sample_rate": 1e6,
                                         "frequency": 1e3, "time_constant": 1e-3},
    "afmsmiler.signals.ad630.demodulate": {"signal": lambda: _tone(), "sample_rate": 1e6,
                                           "frequency": 1e3, "time_constant": 1e-3},
    "afmsmiler.signals.lockin.harmonic_pickup": {"harmonic": 3},
    "afmsmiler.hardware.printing.save_stl": {
        "path": lambda: __import__("tempfile").gettempdir() + "/afmsmiler_campaign.stl"},
    "afmsmiler.hardware.printing.write_stl": {
        "mesh": lambda: _print_mesh(),
        "path": lambda: __import__("tempfile").gettempdir() + "/afmsmiler_campaign.stl"},
    "afmsmiler.hardware.printing.mesh_to_sample": {"mesh_or_path": lambda: _print_mesh(),
                                                   "pitch": 5e-6},
    "afmsmiler.modes.qcontrol.QControl.feedback_force": {"velocity": 1e-3},
    "afmsmiler.hardware.printing.triangle_count": {"shape": (16, 16)},
    "afmsmiler.hardware.printing.compare_scan": {"reference": _image, "image": _image},
    "afmsmiler.modes.qcontrol.closed_loop_response": {"frequency": lambda: np.linspace(
        290e3, 310e3, 50)},
    "afmsmiler.modes.qcontrol.ring_down": {"time": lambda: np.linspace(0.0, 1e-3, 200)},
    "afmsmiler.modes.qcontrol.quality_factor_from_ringdown": {
        "time": lambda: _ring()[0], "deflection": lambda: _ring()[1]},
    "afmsmiler.modes.qcontrol.fit_ring_down": {
        "time": lambda: _ring()[0], "deflection": lambda: _ring()[1]},
    "afmsmiler.signals.lockin.amplitude_spectrum": {"signal": lambda: _tone(),
                                                    "sample_rate": 1e6},
    "afmsmiler.signals.lockin.lowpass": {"x": lambda: _tone(), "sample_rate": 1e6},
    "afmsmiler.signals.lockin.reference_waveforms": {"n_samples": 1000, "sample_rate": 1e6,
                                                     "frequency": 2e3},
    "afmsmiler.signals.lockin.square_wave": {"cycles": lambda: np.linspace(0, 3, 100)},
    "afmsmiler.signals.ad630.switch": {"signal": lambda: _tone()[:1000],
                                       "reference": lambda: np.sign(np.sin(np.arange(1000.0)))},
    "afmsmiler.signals.ad630.amplitude_from_levels": {"level_x": 0.1, "level_y": 0.1},
    "afmsmiler.signals.chain.power_harmonics": {"ac_voltage": 0.5, "resistance": 1e3},
    "afmsmiler.signals.chain.brownian_density": {
        "probe": lambda: __import__("afmsmiler.signals.chain", fromlist=["ActiveProbe"])
        .ActiveProbe(), "f": lambda: np.logspace(3, 5, 10)},
    "afmsmiler.modes.lateral.lateral_force": {"slope": 0.0},
    "afmsmiler.controller.ContactLoop.scan_line": {
        "x": lambda: np.linspace(0.0, 1.5e-6, 16), "height": lambda: np.zeros(16)},
}

# Further valid configurations of one callable, each a target of its own: the branches that the
# defaults do not reach (adhesion models, the sphere's finite depth).
def _sphere():
    from afmsmiler.contact import Spherical
    return Spherical(50e-9)


VARIANTS = {
    "afmsmiler.contact.approach_retract": {
        "jkr": {"adhesion": "jkr", "work_of_adhesion": 0.03},
        "dmt": {"adhesion": "dmt", "work_of_adhesion": 0.03},
        "sphere-jkr": {"adhesion": "jkr", "work_of_adhesion": 0.03, "tip": _sphere,
                       "z_np": lambda: np.linspace(-60e-9, 20e-9, 40)}},
    "afmsmiler.contact.z_np_limit": {
        "sphere-jkr": {"adhesion": "jkr", "work_of_adhesion": 0.03, "tip": _sphere},
        "sphere-dmt": {"adhesion": "dmt", "work_of_adhesion": 0.03, "tip": _sphere}},
    "afmsmiler.contact.indent": {"sphere": {"tip": _sphere,
                                            "z_np": lambda: np.linspace(-60e-9, 20e-9, 40)}},
}


def _tips():
    """The general dilation path: module (d)'s other three tips."""
    from afmsmiler.contact import Conical, Pyramidal
    return {"sphere": {"tip": _sphere}, "cone": {"tip": lambda: Conical()},
            "pyramid": {"tip": lambda: Pyramidal()}}


def _scans():
    """The scanner's other branches: constant height, a rotated, drifting, creeping, tilted,
    noisy scan (bilinear sampling, separate retrace), and the general dilation (a cone)."""
    from afmsmiler.contact import Conical
    moving = {"settings": lambda: _settings(angle=0.3, drift=(1e-9, -1e-9), creep=0.01,
                                            offset=(5e-9, 0.0), tilt=(0.01, -0.02), noise=1e-10,
                                            seed=1)}
    return {"height": {"mode": _constant_height, "tip": lambda: _system().tip},
            "moving": moving, "cone": {"tip": lambda: Conical()}}


for _name in ("dilate", "erode", "certainty_map", "tip_surface"):
    VARIANTS[f"afmsmiler.imaging.dilation.{_name}"] = _tips()
for _name in ("Scan", "scan"):
    VARIANTS[f"afmsmiler.imaging.scanner.{_name}"] = _scans()

# A system object is probed after it is built (its derived quantities, its main methods), so
# that a bad value the constructor lets through shows where it breaks.
PROBES = {
    "ContactLoop": lambda o: (o.poles, o.is_stable(), o.stability_margin,
                              o.steady_state(10e-9), o.closed_forms()),
    "Cantilever": lambda o: (o.spring_constant, o.effective_mass, o.resonance_frequency(1),
                             o.deflection(np.linspace(0.0, o.length, 5), 1e-9)),
    "StandardLinearSolid": lambda o: o.modulus(np.linspace(0.0, 1e-2, 5)),
    "Sample": lambda o: (o.x, o.size),
    "Parabolic": lambda o: o.force(np.linspace(0.0, 10e-9, 5), 1e6),
    "Spherical": lambda o: o.force(np.linspace(0.0, 0.5 * o.radius, 5), 1e6),
    "Conical": lambda o: o.force(np.linspace(0.0, 10e-9, 5), 1e6),
    "Pyramidal": lambda o: o.force(np.linspace(0.0, 10e-9, 5), 1e6),
    "ScanSettings": lambda o: (o.pixel_size, o.pixel_size_y, o.line_time, o.scan_time,
                               o.displacement(o.scan_time)),
    "Scan": lambda o: o.run(),
    "ConstantForce": lambda o: _scan(o).run(),
    "ConstantHeight": lambda o: _scan(o).run(),
}


def _probe(obj):
    for klass in type(obj).__mro__:
        if klass.__name__ in PROBES:
            return PROBES[klass.__name__](obj)
    if hasattr(obj, "sensitivity") and hasattr(obj, "parameter_table"):  # a transducer
        return (obj.sensitivity(), obj.resonance_frequency, obj.spring_constant)
    return None


# Objects whose methods are called: how to build one (else: its constructor from valid values).
INSTANCES = {
    "IndentationCurve": _curve,
    "ForceCurve": lambda: _synthetic(),
    "ScanImage": lambda: __import__("afmsmiler.controller", fromlist=["scan_image"]).scan_image(
        _loop(), np.zeros((4, 8)), 10e-9, speed=1e-6, setpoint=10e-9),
    "Preset": lambda: next(iter(__import__("afmsmiler.controller",
                                           fromlist=["PRESETS"]).PRESETS.values())),
    "Sample": lambda: __import__("afmsmiler.samples", fromlist=["Sample"]).Sample(
        1e-9 * np.arange(64.0).reshape(8, 8), 10e-9),
    "ContactLoop": _loop,
    "Signals": lambda: __import__("afmsmiler.instrument.alignment",
                                  fromlist=["OpticalHead"]).OpticalHead().signals(),
    "SignalChain": lambda: _obd().chain(_obd().input_quantity().default),
    "Material": lambda: __import__("afmsmiler.materials",
                                   fromlist=["get_material"]).get_material("silicon"),
    "Scan": _scan,
    "ConstantForce": _constant_force,
    "ConstantHeight": _constant_height,
    "AmplitudeCurve": lambda: __import__("afmsmiler.modes", fromlist=[
        "amplitude_curve"]).amplitude_curve(np.linspace(2e-9, 12e-9, 20)),
    "FluidMode": lambda: __import__("afmsmiler.hydrodynamics", fromlist=[
        "fluid_mode"]).fluid_mode(_lever(), "water"),
    "SHOFit": lambda: __import__("afmsmiler.calibration", fromlist=[
        "fit_thermal_spectrum"]).fit_thermal_spectrum(_spectrum()),
    "LabCalibration": lambda: __import__("afmsmiler.calibration", fromlist=[
        "calibrate"]).calibrate(_lever(), points=2 ** 12, seed=1),
    "ProbeReport": lambda: __import__("afmsmiler.probe", fromlist=["probe_report"]).probe_report(
        __import__("afmsmiler.planform", fromlist=["preset"]).preset("AC240TS"),
        points=2 ** 12, averages=4, seed=1),
    "LockInResult": lambda: __import__("afmsmiler.signals.lockin", fromlist=["lock_in"]).lock_in(
        _tone(), sample_rate=1e6, frequency=1e3, time_constant=1e-3),
    "Profile": lambda: __import__("afmsmiler.imaging.statistics",
                                  fromlist=["line_profile"]).line_profile(
        _image(), (10e-9, 20e-9), (120e-9, 100e-9)),
}


def _vdw(z):
    """A van der Waals force law (N) of the distance z (m): module (g)'s FM functions take one."""
    return -6.4e-20 * 10e-9 / (6.0 * np.asarray(z) ** 2)


def _print_mesh():
    """A printable mesh of :func:`_image` (16 x 16 pixels, 400x): module (h)'s STL export."""
    from afmsmiler.hardware.printing import sample_to_mesh
    return sample_to_mesh(_image())


def _ring():
    """A ring-down of a 1 kHz resonance with Q = 20 sampled at 100 kHz for 20 ms (t in s, m)."""
    t = np.arange(2000) / 1e5
    w = 2 * np.pi * 1e3
    return t, 1e-9 * np.exp(-w * t / 40) * np.cos(w * np.sqrt(1 - 1 / 1600) * t)


def _spectrum():
    """A thermal spectrum of the campaign's lever in air: 2^12 bins, 4 averages, seeded."""
    from afmsmiler.calibration import thermal_spectrum
    return thermal_spectrum(_lever(), "air", points=2 ** 12, averages=4, seed=1)


def _tone():
    """40 ms of a 2 kHz tone of 0.1 V sampled at 1 MHz: module (h)'s lock-in input."""
    return 0.1 * np.sin(2 * np.pi * 2e3 * np.arange(40_000) / 1e6)


def _obd():
    from afmsmiler.transducers import OpticalBeamDeflection
    return OpticalBeamDeflection()


def _sls():
    from afmsmiler.contact import StandardLinearSolid
    return StandardLinearSolid(1e6, 2e6, 1e-3)


def _is_lever(obj):
    return type(obj).__name__ == "Cantilever"


# -- module (h): the hardware layer ----------------------------------------------------------------
#: Each public module of the hardware layer: the frame format, the parameter tables, the three
#: devices' codecs, the transports, the framed-device base, the twins (the far end of a
#: transport), the drivers (each built on its own twin, served in memory), the sessions, the
#: experiments, the force bridge's sources and the Analog Discovery 2 (its simulated library).
#: Not here: SerialTransport and PtyLink (they open a port), the exceptions, and the codecs'
#: enums (Python's Enum lookup; every function that takes one is tried instead).
HARDWARE_MODULES = [
    "afmsmiler.hardware.framing", "afmsmiler.hardware.protocol",
    "afmsmiler.hardware.macro.codec", "afmsmiler.hardware.educational.codec",
    "afmsmiler.hardware.haptic.codec", "afmsmiler.hardware.transport",
    "afmsmiler.hardware.framed", "afmsmiler.hardware.twin",
    "afmsmiler.hardware.macro.twin", "afmsmiler.hardware.educational.twin",
    "afmsmiler.hardware.haptic.twin", "afmsmiler.hardware.macro.device",
    "afmsmiler.hardware.educational.device", "afmsmiler.hardware.haptic.device",
    "afmsmiler.hardware.session", "afmsmiler.hardware.macro.session",
    "afmsmiler.hardware.educational.session", "afmsmiler.hardware.macro.mechanics",
    "afmsmiler.hardware.experiments", "afmsmiler.hardware.haptic.bridge",
    "afmsmiler.hardware.ad2"]
MODULES += HARDWARE_MODULES
#: Hardware classes that are not built from values by a user (a port, a protocol, a base).
HARDWARE_SKIPPED = {"afmsmiler.hardware.transport.SerialTransport",
                    "afmsmiler.hardware.transport.MemoryTransport",  # built by pair()
                    "afmsmiler.hardware.transport.PtyLink",
                    "afmsmiler.hardware.transport.Transport"}
RESULTS |= {"DeviceInfo", "ScanProgress", "BridgeStats", "PatternTiming", "QControlTrial",
            "SecondHarmonic", "AD2Reading", "Acquisition"}
#: What a device reads or is driven with while a case runs: stopped after each case.
_HARDWARE_OPEN = []


def _opened(obj):
    """``obj`` (a device, a twin's server, a session, a transport), closed after the case."""
    _HARDWARE_OPEN.append(obj)
    return obj


def _close_hardware():
    while _HARDWARE_OPEN:
        obj = _HARDWARE_OPEN.pop()
        try:
            (obj.stop if hasattr(obj, "stop") and not hasattr(obj, "close") else obj.close)()
        except Exception:  # noqa: BLE001 - a case's leftovers: closing is best effort
            pass


@pytest.fixture(autouse=True)
def _hardware_closed():
    """No thread of a twin, a device or a session outlives its case (their CPU would count in
    the next case's guard)."""
    yield
    _close_hardware()


def _filled_link(lines=64):
    """A memory link's host end with ``lines`` valid frames waiting (a read takes one at once)."""
    from afmsmiler.hardware.transport import MemoryTransport
    host, end = MemoryTransport.pair()
    end.write(b"1 OK ID TWIN 1 0.1.0*E3\n" * lines)
    return _opened(host)


def _served(twin):
    from afmsmiler.hardware import open_twin
    host, server = open_twin(twin)
    _opened(server)
    return host


def _macro_twin():
    from afmsmiler.hardware.macro import MacroAFMTwin
    return MacroAFMTwin()


def _edu_twin():
    from afmsmiler.hardware.educational import EducationalAFMTwin
    return EducationalAFMTwin(_image())


def _haptic_twin():
    from afmsmiler.hardware.haptic import HapticTwin
    return HapticTwin()


def _connected(cls, twin, **options):
    """A driver connected to its twin (served in memory at once), closed after the case."""
    device = _opened(cls(_served(twin), timeout=0.5, retries=1, **options))
    device.connect()
    return device


def _macro():
    """A macro AFM homed on its twin, set for a scan of 4 x 2 pixels."""
    from afmsmiler.hardware.macro import MacroAFM
    device = _connected(MacroAFM, _macro_twin(), stream_timeout=2.0)
    device.home()
    device.configure(pixels=4, lines=2)
    return device


def _edu():
    """An educational AFM on its twin, set for a scan of 4 x 2 pixels that fits the image."""
    from afmsmiler.hardware.educational import EducationalAFM
    device = _connected(EducationalAFM, _edu_twin())
    device.configure(pixels=4, lines=2, pitch=10e-9)
    return device


def _haptic():
    from afmsmiler.hardware.haptic import HapticDevice
    return _connected(HapticDevice, _haptic_twin())


def _table():
    from afmsmiler.hardware.macro.codec import TABLE
    return TABLE


def _bridge_stats():
    from afmsmiler.hardware.haptic.bridge import ForceBridge, FunctionSource

    class Still:  # a device that holds still: the bridge's loop alone
        def send_force(self, force):
            pass

        def latest(self):
            return None
    return ForceBridge(FunctionSource(lambda t, x: 0.0), Still()).run(ticks=5)


def _low_q_lever():
    """A tapping lever that settles in a few dozen periods (Q = 20), for the cases that only
    need a valid one: each bad value that passes integrates it to its steady state."""
    from afmsmiler.modes.tapping import TappingLever
    return TappingLever(quality_factor=20.0)


def _hw(module, name, *args, **kwargs):
    """``afmsmiler.hardware.<module>.<name>(*args, **kwargs)``, built when a case needs it
    (an argument that is a callable is built first)."""
    def build():
        obj = importlib.import_module(f"afmsmiler.hardware.{module}")
        for part in name.split("."):
            obj = getattr(obj, part)
        return obj(*(a() if callable(a) else a for a in args), **kwargs)
    return build


def _twin_server():
    from afmsmiler.hardware.transport import MemoryTransport
    from afmsmiler.hardware.twin import Twin, TwinServer
    host, end = MemoryTransport.pair()
    _opened(host)
    return _opened(TwinServer(Twin(), end, time_scale=0.0))


def _printed():
    """What the macro AFM's twin scans: a printed grating of 16 x 16 pixels."""
    from afmsmiler.hardware.macro import printed_sample
    return printed_sample(pixels=16)


def _ad2():
    """An AD2 opened on the simulated WaveForms library."""
    from afmsmiler.hardware.ad2 import AnalogDiscovery2, SimulatedDwfLibrary
    device = _opened(AnalogDiscovery2(SimulatedDwfLibrary()))
    device.open()
    return device


def _still():
    """A force function that is zero everywhere (the bridge's sources take ``f(t, x)``)."""
    return lambda t, x: 0.0


INSTANCES.update({
    "WireParam": lambda: _table()["NX"],
    "ParamTable": _table,
    "MemoryTransport": _filled_link,
    "FaultyTransport": _hw("transport", "FaultyTransport", _filled_link),
    "TwinServer": _twin_server,
    "EducationalAFMTwin": _edu_twin,
    "MacroAFM": _macro, "EducationalAFM": _edu, "HapticDevice": _haptic,
    "MacroSession": lambda: _opened(_hw("macro.session", "MacroSession.twin", _printed)()),
    "EducationalSession": lambda: _opened(_hw("educational.session", "EducationalSession.twin",
                                              _image)()),
    "GaugeCalibration": _hw("macro.mechanics", "GaugeCalibration.from_ruler"),
    "ForceBridge": _hw("haptic.bridge", "ForceBridge", _hw("haptic.bridge", "FunctionSource",
                                                           lambda: _still()), _haptic),
    "IndentationSource": _hw("haptic.bridge", "IndentationSource", _system),
    "GaugeSource": _hw("haptic.bridge", "GaugeSource", lambda: (lambda: 0),
                       force_per_count=1e-3),
    "CantileverSource": _hw("haptic.bridge", "CantileverSource", _lever),
    "TappingSource": _hw("haptic.bridge", "TappingSource", 12e-9, lambda: _low_q_lever()),
    "FunctionSource": _hw("haptic.bridge", "FunctionSource", lambda: _still()),
    "AnalogDiscovery2": _ad2,
})


def _frame(*fields):
    from afmsmiler.hardware.framing import Frame
    return lambda: Frame(*fields)


_H = "afmsmiler.hardware."
_STATUS = ("IDLE", 0, 0, 0)
OVERRIDES.update({
    # the frame format and the tables
    _H + "framing.crc8": {"data": b"123456789"},
    _H + "framing.as_bytes": {"name": "data", "data": b"1 ID"},
    _H + "framing.Frame": {"seq": 1, "code": "ID"},
    _H + "framing.encode_frame": {"frame": _frame(1, "ID")},
    _H + "framing.decode_frame": {"line": b"1 OK ID MACROAFM 1 0.1.0*22\n"},
    _H + "framing.reply_frame": {"seq": 1, "code": "ID"},
    _H + "framing.error_frame": {"seq": 1, "code": 3},
    _H + "framing.event_frame": {"word": "DONE"},
    _H + "protocol.WireUnit": {"si_unit": "m", "scale": 1e-6},
    _H + "protocol.WireParam": {"name": "NX", "code": "NX", "unit": "count", "low": 1,
                                "high": 128, "default": 8},
    _H + "protocol.WireParam.to_si": {"wire": 8}, _H + "protocol.WireParam.to_wire": {"value": 8},
    _H + "protocol.WireParam.valid": {"wire": 8}, _H + "protocol.WireParam.check": {"wire": 8},
    _H + "protocol.WireParam.check_reply": {"wire": 8},
    _H + "protocol.ParamTable": {"device": "TWIN", "params": lambda: (_table()["NX"],)},
    _H + "protocol.ParamTable.by_si_name": {"name": "pixels"},
    _H + "protocol.ParamTable.enum": {"module": "afmsmiler.hardware.macro.codec"},
    _H + "protocol.ParamTable.check_reply": {"results": ("NX", 8), "command": "GP"},
    # the codecs
    _H + "macro.codec.Pixel": {"row": 0, "col": 1, "z": 3, "counts": 5},
    _H + "macro.codec.LineEnd": {"row": 0, "pixels": 8},
    _H + "macro.codec.EventMsg": {"event": "DONE"},
    _H + "macro.codec.Reply": {"seq": 1, "command": "ST", "results": _STATUS},
    _H + "macro.codec.ErrorReply": {"seq": 1, "code": 3},
    _H + "macro.codec.Status": {"state": "IDLE", "row": 0, "col": 0, "flags": 0},
    _H + "macro.codec.MacroAFMCodec.command": {"seq": 1, "command": "ST"},
    _H + "macro.codec.MacroAFMCodec.message": {"frame": _frame(0, "PX", (0, 1, 3, 5))},
    _H + "macro.codec.MacroAFMCodec.frame": {"message": _hw("macro.codec", "LineEnd", 0, 8)},
    _H + "macro.codec.MacroAFMCodec.encode": {"message": _hw("macro.codec", "LineEnd", 0, 8)},
    _H + "macro.codec.MacroAFMCodec.status_results": {
        "status": _hw("macro.codec", "Status", "IDLE", 0, 0, 0)},
    _H + "macro.codec.MacroAFMCodec.parse": {"line": b"0 LN 0 8*D6\n"},
    _H + "macro.codec.MacroAFMCodec.status": {"reply": _hw("macro.codec", "Reply", 1, "ST",
                                                            _STATUS)},
    _H + "educational.codec.command": {"seq": 1, "code": "ST"},
    _H + "educational.codec.pixel": {"row": 0, "col": 1, "counts": 5},
    _H + "educational.codec.line_end": {"row": 0, "n": 8},
    _H + "educational.codec.event": {"word": "DONE"},
    _H + "educational.codec.stream_error": {"code": 8},
    _H + "haptic.codec.Status": {"state": "IDLE", "flags": 0, "position": 1e-3, "force": 0.1},
    _H + "haptic.codec.PositionSample": {"position": 1e-3, "velocity": 1e-3,
                                         "device_time": 1.0},
    _H + "haptic.codec.force_frame": {"force": 0.1},
    _H + "haptic.codec.force_from_wire": {"micro": 5},
    _H + "haptic.codec.parse_position": {"frame": _frame(0, "PO", (1000, 10, 5))},
    _H + "haptic.codec.parse_status": {"frame": _frame(1, "OK", ("ST", "IDLE", 0, 10, 5))},
    _H + "haptic.codec.position_frame": {"position": 1e-3, "velocity": 1e-3,
                                         "device_time": 1.0},
    _H + "haptic.codec.status_results": {"state": "IDLE", "flags": 0, "position": 1e-3,
                                         "force": 0.1},
    _H + "haptic.codec.param_to_wire": {"param": "MF", "value": 1.0},
    _H + "haptic.codec.param_from_wire": {"param": "MF", "wire": 5},
    # transports, the framed base, the twins
    _H + "transport.MemoryTransport.pair": {},
    _H + "transport.MemoryTransport.write": {"data": b"1 ID*C1\n"},
    _H + "transport.MemoryTransport.readline": {"timeout": 0.05},
    _H + "transport.FaultyTransport": {"inner": _filled_link},
    _H + "transport.FaultyTransport.write": {"data": b"1 ID*C1\n"},
    _H + "transport.FaultyTransport.readline": {"timeout": 0.05},
    _H + "framed.FramedDevice": {"transport": _filled_link},
    _H + "twin.Twin.ok": {"frame": _frame(1, "ID")},
    _H + "twin.Twin.error": {"frame": _frame(1, "ID"), "code": 2},
    _H + "twin.Twin.handle": {"frame": _frame(1, "ST")},
    _H + "twin.Twin.execute": {"frame": _frame(1, "ST")},
    **{_H + f"{m}.{c}.{f}": {"frame": _frame(1, "ST"), **({"code": 2} if f == "error" else {})}
       for m, c in (("macro.twin", "MacroAFMTwin"), ("educational.twin", "EducationalAFMTwin"),
                    ("haptic.twin", "HapticTwin"))
       for f in ("ok", "error", "handle", "execute")},
    **{_H + f"{m}.{c}.poll": {"now": 1e-3}
       for m, c in (("twin", "Twin"), ("macro.twin", "MacroAFMTwin"),
                    ("educational.twin", "EducationalAFMTwin"), ("haptic.twin", "HapticTwin"))},
    _H + "twin.TwinServer": {"twin": _hw("twin", "Twin"), "transport": _filled_link},
    _H + "twin.open_twin": {"twin": _hw("twin", "Twin")},
    _H + "macro.twin.MacroAFMTwin.surface": {"x": 1e-3, "y": 1e-3},
    _H + "educational.twin.EducationalAFMTwin": {"sample": _image},
    _H + "haptic.twin.HapticTwin.push": {"force": 0.1},
    # the drivers (each on its twin) and their sessions
    _H + "macro.device.MacroAFM": {"transport": _filled_link},
    _H + "macro.device.MacroAFM.get": {"param": "NX"},
    _H + "macro.device.MacroAFM.set": {"param": "NX", "value": 8},
    _H + "macro.device.MacroAFM.wait_button": {"timeout": 0.05},
    _H + "macro.device.MacroAFM.save": {"path": lambda: __import__("tempfile").gettempdir()
                                        + "/afmsmiler_campaign_macro.gwy",
                                        "sample": _image},
    _H + "educational.device.EducationalAFM": {"transport": _filled_link},
    _H + "educational.device.EducationalAFM.request": {"code": "ST"},
    _H + "educational.device.EducationalAFM.get": {"par": "NX"},
    _H + "educational.device.EducationalAFM.set": {"par": "NX", "value": 16},
    _H + "educational.device.live_view": {"scene": lambda: __import__(
        "afmsmiler.scenes.imaging", fromlist=["ImagingScene"]).ImagingScene(
        _image(), vis=__import__("tests.recording", fromlist=["Recorder"]).Recorder(),
        camera=False)},  # an ImagingScene drawing into the recording fake
    _H + "haptic.device.HapticDevice": {"transport": _filled_link},
    _H + "haptic.device.HapticDevice.command": {"code": "ST"},
    _H + "haptic.device.HapticDevice.get": {"param": "MF"},
    _H + "haptic.device.HapticDevice.set": {"param": "MF", "value": 1.0},
    _H + "haptic.device.HapticDevice.send_force": {"force": 0.1},
    _H + "haptic.device.HapticDevice.ring_down": {"hold": 0.05, "duration": 0.05},
    _H + "session.DeviceSession.close": {},
    _H + "macro.session.MacroSession": {"device": _macro},
    _H + "macro.session.MacroSession.open": {"transport": lambda: _served(_macro_twin())},
    _H + "macro.session.MacroSession.twin": {"scanned": _printed},
    _H + "educational.session.EducationalSession.open": {
        "transport": lambda: _served(_edu_twin())},
    _H + "educational.session.EducationalSession.twin": {"scanned": _image},
    _H + "educational.session.EducationalSession": {"device": _edu},
    # mechanics, experiments, the bridge, the AD2
    _H + "macro.mechanics.GaugeCalibration": {"counts_per_newton": 1e4, "spring_constant": 50.0},
    _H + "macro.mechanics.GaugeCalibration.from_weights": {
        "free_counts": 10.0, "loaded_counts": 1010.0, "mass": 0.01, "spring_constant": 50.0},
    _H + "macro.mechanics.GaugeCalibration.counts": {"force": 0.1},
    _H + "macro.mechanics.GaugeCalibration.force": {"counts": 100.0},
    _H + "experiments.virtual_lever": {"haptic": _haptic},
    _H + "experiments.q_control_trial": {"haptic": _haptic},
    _H + "experiments.bridge_readout": {"stats": _bridge_stats},
    _H + "experiments.reference_error": {"demo": lambda: OBJECTS["LockInDemo"]()},
    _H + "experiments.ad2_reading": {"dwf": _hw("ad2", "SimulatedDwfLibrary"),
                                     "drive_frequency": 40e3},
    _H + "experiments.educational_twin": {"sample": _image},
    _H + "haptic.bridge.ForceBridge": {"source": _hw("haptic.bridge", "FunctionSource",
                                                     lambda: _still()), "device": _haptic},
    _H + "haptic.bridge.ForceBridge.run": {"ticks": 5},
    _H + "haptic.bridge.FunctionSource": {"func": lambda: _still()},
    _H + "haptic.bridge.IndentationSource": {"system": _system},
    _H + "haptic.bridge.TappingSource": {"distance": 12e-9, "max_periods": 20},
    _H + "haptic.bridge.GaugeSource": {"read": lambda: (lambda: 0), "force_per_count": 1e-3},
    _H + "haptic.bridge.CantileverSource": {"cantilever": _lever},
    **{_H + f"haptic.bridge.{c}.force": {"time": 0.0, "position": 1e-3}
       for c in ("FunctionSource", "IndentationSource", "TappingSource", "GaugeSource",
                 "CantileverSource")},
    _H + "ad2.pattern_timing": {"clock": 100e6, "frequency": 40e3},
    _H + "ad2.AnalogDiscovery2": {"dwf": _hw("ad2", "SimulatedDwfLibrary")},
})


# -- bad values ---------------------------------------------------------------------------------
class Foreign:
    """An object of no kind that any parameter expects."""

    def __repr__(self):
        return "Foreign()"


#: label -> (value, whether returning normally can be right). Non-numbers must be rejected.
BAD = {
    "nan": (math.nan, False), "inf": (math.inf, True), "-inf": (-math.inf, True),
    "None": (None, False), "str": ("1e-6", False), "bool": (True, False),
    "complex": (1 + 1j, False), "list": ([1.0, 2.0], True), "object": (Foreign(), False),
    "zero": (0.0, True), "negative": (-1.0, True), "huge": (1e300, True),
    "-huge": (-1e300, True), "tiny": (1e-300, True), "bigint": (10**9, True),
    "hugeint": (10**400, True),  # beyond the float range: float() raises OverflowError
    "2d": (np.ones((3, 3)), True), "empty": (np.array([]), True),
    "nan-array": (np.array([0.0, math.nan]), False),
}


def _bad_samples(valid):
    """Samples of the right type that are extreme: every imaging function must work on them
    (finite numbers) or raise naming a parameter, within the time and memory guard."""
    from afmsmiler.samples import Sample
    h = valid.heights
    image = h if h.ndim == 2 else np.tile(h, (len(h), 1))
    return {
        "sample-line": Sample(image[0], valid.pixel_size),
        "sample-2x2": Sample(image[:2, :2], valid.pixel_size),
        "sample-2-rows": Sample(image[:2], valid.pixel_size),
        "sample-flat": Sample(np.zeros_like(image), valid.pixel_size),
        "sample-huge-heights": Sample(image * 1e290, valid.pixel_size),
        "sample-extreme": Sample(np.where(image > np.median(image), 1.7e308, -1.7e308),
                                 valid.pixel_size),  # the range overflows a float
        "sample-tiny-heights": Sample(image * 1e-290, valid.pixel_size),
        "sample-tiny-pixels": Sample(image, 1e-300),
        "sample-huge-pixels": Sample(image, 1e3),
        "sample-anisotropic": Sample(image, 1e-10, pixel_size_y=1e-3),
        "sample-volts": Sample(image, valid.pixel_size, channel="deflection", unit="V"),
    }


def _bad_tips(valid):
    """Tips at the ends of module (d)'s ranges: the sharpest and bluntest paraboloid and sphere,
    a cone and a pyramid of nearly 90 degrees (far wider than any small image)."""
    from afmsmiler.contact import Conical, Parabolic, Pyramidal, Spherical
    from afmsmiler.contact.tips import RADIUS
    wide = math.pi / 2 * (1 - 1e-12)
    return {"tip-sharpest": Parabolic(RADIUS.low), "tip-bluntest": Parabolic(RADIUS.high),
            "tip-sharpest-sphere": Spherical(RADIUS.low),
            "tip-bluntest-sphere": Spherical(RADIUS.high),
            "tip-flat-cone": Conical(wide), "tip-sharp-cone": Conical(1e-12),
            "tip-flat-pyramid": Pyramidal(wide)}


def _bad_loops(valid):
    """Loops at the ends of module (c)'s gain ranges: unstable ones diverge and overflow."""
    from afmsmiler.controller import PARAMETERS as P
    return {"loop-unstable": valid.replace(ki=P["ki"].high),
            "loop-slightly-unstable": valid.replace(kp=P["kp"].low, ki=2.2e6),
            "loop-stiffest": valid.replace(kp=P["kp"].high, ki=P["ki"].high),
            "loop-no-gain": valid.replace(kp=P["kp"].low, ki=P["ki"].low)}


def _bad_systems(valid):
    """Contact systems with adhesion (the path-dependent branch of constant height) and at the
    ends of module (d)'s ranges."""
    from afmsmiler.contact import PARAMETERS as P
    from afmsmiler.contact import Spherical
    return {"system-jkr": dataclasses.replace(valid, adhesion="jkr", work_of_adhesion=0.03),
            "system-dmt-most": dataclasses.replace(valid, adhesion="dmt",
                                                   work_of_adhesion=P["work_of_adhesion"].high),
            "system-sphere-jkr": dataclasses.replace(valid, tip=Spherical(50e-9),
                                                     adhesion="jkr", work_of_adhesion=0.03),
            "system-stiffest": dataclasses.replace(valid, spring_constant=P["spring_constant"].high,
                                                   youngs_modulus=P["youngs_modulus"].high),
            "system-softest": dataclasses.replace(valid, spring_constant=P["spring_constant"].low,
                                                  youngs_modulus=P["youngs_modulus"].low)}


def _bad_settings(valid):
    """Scan settings at the ends of their ranges that still fit :func:`_image` (the scan then
    runs: a scan that is built must finish with finite numbers)."""
    from afmsmiler.imaging.scanner import PARAMETERS as P
    near = 1 - 1e-9
    return {
        "settings-fastest": _settings(scan_speed=P["scan_speed"].high),
        "settings-slowest": _settings(scan_speed=P["scan_speed"].low),
        "settings-one-long-line": _settings(pixels=2048, lines=1),
        "settings-two-pixel-lines": _settings(pixels=2, lines=2048),
        "settings-half-turn": _settings(angle=math.pi * near),
        "settings-steepest-tilt": _settings(tilt=(math.pi / 2 * near, -math.pi / 2 * near)),
        "settings-most-noise": _settings(noise=P["noise"].high, seed=0),
        "settings-most-creep": _settings(creep=P["creep"].high, creep_time=P["creep_time"].low,
                                         offset=(1e-9, -1e-9)),
        "settings-tiny-range": _settings(scan_size=P["scan_size"].low),
    }


def _input_names(inst):
    """How messages name ``value``: a transducer's input (``deflection``), a Parameter's name,
    a device parameter's names (its protocol.h name, wire code and SI name)."""
    if hasattr(inst, "si_name") and hasattr(inst, "code"):  # a WireParam
        return [n for n in (inst.name, inst.code, inst.si_name) if n]
    if not hasattr(inst, "input_quantity"):
        return [inst.name] if isinstance(getattr(inst, "name", None), str) else []
    try:
        return [inst.input_quantity(m).name for m in (None, *getattr(inst, "MODES", ()))]
    except Exception:  # noqa: BLE001 - no such modes
        return [inst.input_quantity().name]


#: parameter -> other names a message may use for it (given the object whose method it is).
ALIASES = {"value": _input_names, "at": _input_names, "wire": _input_names}


def _applicable(label, valid):
    """Whether a bad value is a bad value for a parameter whose valid value is ``valid``."""
    if valid is None and label == "None":
        return False  # None is this parameter's default
    if isinstance(valid, bool) and label == "bool":
        return False
    if isinstance(valid, type) and label in ("object",):
        return False
    return True


# -- targets ------------------------------------------------------------------------------------
@dataclasses.dataclass
class Target:
    qual: str
    owner: object  # the class whose method this is, or None
    func: object
    method: str | None
    module: str
    tag: str = ""  # a variant's name (e.g. "jkr"), its valid values in VARIANTS
    extra: dict = dataclasses.field(default_factory=dict)

    @property
    def id(self):
        tag = f"[{self.tag}]" if self.tag else ""
        return f"{self.qual.removeprefix('afmsmiler.')}{tag}"


def _in_package(module):
    """Whether ``module`` is a file of the afmsmiler package that is imported (this checkout)."""
    import afmsmiler
    root = Path(afmsmiler.__file__).resolve().parent
    return root in Path(module.__file__).resolve().parents


def _public(module):
    names = getattr(module, "__all__", None)
    if names is None:
        names = [n for n, o in vars(module).items() if not n.startswith("_")
                 and getattr(o, "__module__", "").startswith(module.__name__)]
    return names


def _methods(cls):
    seen = set()
    for klass in cls.__mro__:
        if not getattr(klass, "__module__", "").startswith("afmsmiler"):
            continue
        for name, attr in vars(klass).items():
            if name.startswith("_") or name in seen:
                continue
            seen.add(name)
            if isinstance(attr, (staticmethod, classmethod)) or inspect.isfunction(attr):
                yield name


def targets():
    out, seen = [], set()
    for modname in MODULES:
        try:
            module = importlib.import_module(modname)
        except ImportError:
            continue
        if not _in_package(module):
            continue  # an editable install of another checkout filled the gap
        for name in _public(module):
            obj = getattr(module, name, None)
            if not (inspect.isfunction(obj) or inspect.isclass(obj)):
                continue
            if not getattr(obj, "__module__", "").startswith("afmsmiler"):
                continue
            qual = f"{modname}.{name}"
            if id(obj) in seen and inspect.isfunction(obj):
                continue
            seen.add(id(obj))
            if inspect.isfunction(obj):
                out.append(Target(qual, None, obj, None, modname))
                for tag, extra in VARIANTS.get(qual, {}).items():
                    out.append(Target(qual, None, obj, None, modname, tag, extra))
                continue
            if issubclass(obj, BaseException):
                continue
            if issubclass(obj, enum.Enum) or qual in HARDWARE_SKIPPED:
                continue  # Python's Enum lookup; a port (see HARDWARE_MODULES)
            if obj.__name__ in ABSTRACT or qual in LEGACY:
                continue
            if obj.__name__ not in RESULTS:
                out.append(Target(qual, None, obj, None, modname))
            for m in _methods(obj):
                out.append(Target(f"{qual}.{m}", obj, obj, m, modname))
    return out


def _resolve(v, inst):
    if isinstance(v, Ctx):
        return v.make(inst)
    return v() if callable(v) and not isinstance(v, type) else v


def _base_qual(t: Target) -> list[str]:
    """Names under which an override may be given: the target, and its method on the base."""
    names = [t.qual]
    if t.owner is not None:
        for klass in t.owner.__mro__:
            if t.method in vars(klass):
                names.append(f"{klass.__module__.rsplit('.', 1)[0]}.{klass.__name__}.{t.method}")
                names.append(f"{t.module}.{klass.__name__}.{t.method}")
    return names


def _override(t: Target, pname):
    for q in _base_qual(t):
        if pname in OVERRIDES.get(q, {}):
            return True, OVERRIDES[q][pname]
    if t.owner is None and inspect.isclass(t.func):
        if pname in OVERRIDES.get(t.qual, {}):
            return True, OVERRIDES[t.qual][pname]
    return False, None


def _build_instance(t: Target):
    cls = t.owner
    if cls.__name__ in INSTANCES:
        return INSTANCES[cls.__name__]()
    kwargs = _valid_kwargs(Target(t.qual.rsplit(".", 1)[0], None, cls, None, t.module), None)
    return cls(**kwargs)


def _signature(t: Target):
    func = t.func if t.method is None else getattr(t.owner, t.method)
    return inspect.signature(func)


def _param_names(t: Target, inst=None):
    """The perturbable parameters: named ones, plus a transducer's table behind ``**params``."""
    sig = _signature(t)
    names = [p.name for p in sig.parameters.values()
             if p.name not in ("self", "cls") and p.kind in (p.POSITIONAL_OR_KEYWORD,
                                                             p.KEYWORD_ONLY)]
    var_kw = any(p.kind == p.VAR_KEYWORD for p in sig.parameters.values())
    if var_kw:
        table = None
        if inspect.isclass(t.func) and hasattr(t.func, "parameter_table"):
            table = t.func.parameter_table()
        elif t.method == "replace" and hasattr(t.owner, "parameter_table"):
            table = t.owner.parameter_table()
        elif t.method == "replace" and dataclasses.is_dataclass(t.owner):
            table = {f.name: None for f in dataclasses.fields(t.owner)}
        if table:
            names += [n for n in table if n not in names]
    return names


def _valid_kwargs(t: Target, inst):
    sig = _signature(t)
    kwargs = {}
    for p in sig.parameters.values():
        if p.name in ("self", "cls") or p.kind in (p.VAR_POSITIONAL, p.VAR_KEYWORD):
            continue
        found, v = _override(t, p.name)
        if p.name in t.extra:
            kwargs[p.name] = _resolve(t.extra[p.name], inst)
        elif found:
            kwargs[p.name] = _resolve(v, inst)
        elif p.default is not p.empty:
            continue  # the default
        elif p.name in VALID:
            try:
                kwargs[p.name] = _resolve(VALID[p.name], inst)
            except Exception as exc:  # noqa: BLE001 - the table's value does not fit here
                raise LookupError(f"the valid value of {p.name!r} does not fit: "
                                  f"{type(exc).__name__}: {exc}") from None
        else:
            raise LookupError(f"no valid value known for parameter {p.name!r}")
    return kwargs


def _field_default(t: Target, name):
    """The default of field ``name`` of the dataclass whose ``replace`` is called (else a
    sentinel): ``replace(lines=None)`` means the field's default, as the constructor does."""
    if t.method == "replace" and dataclasses.is_dataclass(t.owner):
        for f in dataclasses.fields(t.owner):
            if f.name == name and f.default is not dataclasses.MISSING:
                return f.default
    return dataclasses.MISSING


def _default_of(t: Target, name, inst):
    sig = _signature(t)
    p = sig.parameters.get(name)
    if p is not None and p.default is not p.empty:
        return p.default
    if inspect.isclass(t.func) and isinstance(inspect.getattr_static(t.func, "defaults", None),
                                              (classmethod, staticmethod)):
        return t.func.defaults().get(name)
    if t.method == "replace" and inst is not None:
        return getattr(inst, name, None)
    return None


# -- guards -------------------------------------------------------------------------------------
class CallTimeout(Exception):
    pass


def _alarm(signum, _frame):
    if signum == signal.SIGPROF:
        raise CallTimeout(f"still running after {TIME_LIMIT:g} s of CPU")
    raise CallTimeout(f"still running after {WALL_LIMIT:g} s")


@contextmanager
def guarded():
    """At most TIME_LIMIT seconds of CPU (WALL_LIMIT of wall-clock time) and MEMORY_MARGIN more
    bytes of address space for one call."""
    old_handler = signal.signal(signal.SIGALRM, _alarm)
    old_prof = signal.signal(signal.SIGPROF, _alarm)
    soft, hard = resource.getrlimit(resource.RLIMIT_AS)
    with open("/proc/self/statm") as fh:
        used = int(fh.read().split()[0]) * resource.getpagesize()
    limit = used + MEMORY_MARGIN
    if hard != resource.RLIM_INFINITY:
        limit = min(limit, hard)
    resource.setrlimit(resource.RLIMIT_AS, (limit, hard))
    signal.setitimer(signal.ITIMER_PROF, TIME_LIMIT)
    signal.setitimer(signal.ITIMER_REAL, WALL_LIMIT)
    try:
        yield
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.setitimer(signal.ITIMER_PROF, 0)
        resource.setrlimit(resource.RLIMIT_AS, (soft, hard))
        signal.signal(signal.SIGALRM, old_handler)
        signal.signal(signal.SIGPROF, old_prof)


def _non_finite(obj, depth=0, seen=None):
    """A path to the first non-finite number in a result, else None."""
    seen = set() if seen is None else seen
    if depth > 4 or id(obj) in seen:
        return None
    seen.add(id(obj))
    if isinstance(obj, (bool, np.bool_, str, type)) or obj is None:
        return None
    if isinstance(obj, Parameter):  # a description: an infinite bound means "no bound"
        return None
    if type(obj).__name__ == "ScanResult":  # NaN marks the lines not scanned (documented):
        return _non_finite(obj.channels, depth + 1, seen)  # the finished lines must be finite
    if type(obj).__name__ in ("LineRecord", "ModeLine") and obj.crash is not None:
        return None  # a crashed line: NaN on the pixels not reached (documented)
    if any(k.__name__ == "Acquisition" and k.__module__ == "afmsmiler.acquisition"
           for k in type(obj).__mro__) or type(obj).__name__ == "Snapshot":
        return None  # NaN marks the pixels not measured yet (documented, issue 21 section 2)
    if type(obj).__name__ == "BridgeStats" and obj.ticks < 2:
        return None  # its rate and jitter are NaN before two ticks (documented)
    if type(obj).__name__ == "ClosedLoopResponse" and not obj.steady:
        return None  # an unstable Q-control loop has no steady state: NaN (documented)
    if type(obj).__name__ == "ComparisonView":  # module (h)'s print comparison, as shown: NaN
        if math.isnan(obj.rms):  # images and rms before a comparison (documented), the z step
            return None          # while unknown (documented): the figure's empty bottom row
        return _non_finite([obj.reference, obj.image, obj.difference, obj.extent, obj.rms],
                           depth + 1, seen)
    if type(obj).__name__ == "AmplitudeCurve":  # NaN pads the roots a distance lacks
        has = ~np.isnan(obj.amplitude)  # (documented): the roots that exist must be finite
        return _non_finite([obj.amplitude[has], obj.phase[has], obj.dissipated_energy[has]],
                           depth + 1, seen)
    if isinstance(obj, (int, np.integer)):
        return None
    if isinstance(obj, (float, np.floating, complex, np.complexfloating)):
        return None if np.isfinite(obj) else repr(obj)
    if isinstance(obj, np.ndarray):
        if obj.dtype.kind in "fc" and not np.isfinite(obj).all():
            nan = int(np.isnan(obj).sum())
            return (f"array with {int((~np.isfinite(obj)).sum())} non-finite of {obj.size}"
                    f"{f', {nan} NaN' if nan else ''}")
        return None
    if isinstance(obj, dict) or type(obj).__name__ == "mappingproxy":
        items = obj.items()
    elif isinstance(obj, (tuple, list)):
        items = enumerate(obj)
    elif dataclasses.is_dataclass(obj):
        items = ((f.name, getattr(obj, f.name)) for f in dataclasses.fields(obj))
    elif type(obj).__module__.startswith("afmsmiler") and hasattr(obj, "__dict__"):
        items = vars(obj).items()
    else:
        return None
    for k, v in items:
        bad = _non_finite(v, depth + 1, seen)
        if bad is not None:
            return f"{k}: {bad}"
    return None


def _call(t: Target, kwargs, inst):
    func = t.func if t.method is None else getattr(inst, t.method)
    with guarded():
        result = func(**kwargs)
        if t.module in HARDWARE_MODULES:  # a link, a server, a session: closed after the case
            for part in (result if isinstance(result, tuple) else (result,)):
                if callable(getattr(part, "close", None)) or callable(getattr(part, "stop",
                                                                              None)):
                    _opened(part)
        if inspect.isgenerator(result):  # a generator must check its arguments when called,
            result = list(result)        # and what it yields counts
        if t.method is None and inspect.isclass(t.func):
            return result, _probe(result)
        return result


def _describe(t: Target, name, label):
    return f"{t.id}({name}={label})"


def _judge(t: Target, name, label, value, can_return, kwargs, inst, also=()):
    """None if the call behaved, else what went wrong (a message may name ``also`` too)."""
    names = [name, *also]
    if name in ALIASES and inst is not None:
        names += ALIASES[name](inst)
    if t.module == "afmsmiler.validation" and "name" in kwargs:
        names.append(kwargs["name"])
    start = time.process_time()
    try:
        result = _call(t, {**kwargs, name: value}, inst)
    except CallTimeout as exc:
        if t.qual in REFERENCE_SOLVERS:
            return None  # its cost is bounded by its documented step limit, not by seconds
        return f"{_describe(t, name, label)} -> {exc}"
    except MemoryError:
        return f"{_describe(t, name, label)} -> MemoryError (a size without a bound)"
    except (ValueError, TypeError) as exc:
        if any(n in str(exc) for n in names):
            return None
        return f"{_describe(t, name, label)} -> {type(exc).__name__} not naming {name}: " \
               f"{str(exc)[:120]!r}"
    except Exception as exc:  # noqa: BLE001 - every other exception is the finding
        return f"{_describe(t, name, label)} -> {type(exc).__name__}: {str(exc)[:120]!r}"
    finally:
        elapsed = time.process_time() - start
    if label in ("nan", "nan-array") and t.qual in NAN_PASSES:
        return None
    if not can_return:
        return f"{_describe(t, name, label)} -> accepted silently"
    bad = _non_finite(result)
    if bad is not None and label in ("inf", "-inf") and "nan" not in bad.lower():
        bad = None  # an infinite input may give an infinite answer; never a NaN
    if bad is not None and t.qual in INFINITE_OK and "nan" not in bad.lower():
        bad = None
    if bad is not None:
        return f"{_describe(t, name, label)} -> returned non-finite ({bad})"
    if elapsed > TIME_LIMIT:  # pragma: no cover - the alarm fires first
        return f"{_describe(t, name, label)} -> took {elapsed:.1f} s of CPU"
    return None


# -- the cases ----------------------------------------------------------------------------------
TARGETS = targets()


def _inputs(t: Target, names):
    """The parameters that take user input."""
    if t.module == "afmsmiler.validation":
        return [n for n in names if n in HOUSE_INPUTS]
    return [n for n in names if not (t.module in HOUSE and n in NOT_INPUTS)]


def _cases():
    cases = []
    for t in TARGETS:
        try:
            names = _param_names(t)
        except (TypeError, ValueError):
            continue
        names = _inputs(t, names)
        for i, name in enumerate(names or [None]):
            case_id = f"{t.id}:{name or '(valid call)'}"
            smoke = (i == 0 or t.module in HOUSE) and case_id not in SLOW_SMOKE
            marks = [] if smoke else [pytest.mark.slow]
            if case_id in KNOWN:
                reason, slow = KNOWN[case_id]
                marks.append(pytest.mark.xfail(reason=reason, strict=True))
                if slow and not any(m.name == "slow" for m in marks):
                    marks.append(pytest.mark.slow)  # a known hang: 10 s per run
            cases.append(pytest.param(t, name, id=case_id, marks=marks))
    return cases


def _prepare(t: Target):
    """(instance or None, valid kwargs), or skip saying why it cannot be built."""
    inst = None
    if t.owner is not None and not isinstance(inspect.getattr_static(t.owner, t.method),
                                              (staticmethod, classmethod)):
        try:
            inst = _build_instance(t)
        except Exception as exc:  # noqa: BLE001
            pytest.skip(f"cannot build a {t.owner.__name__} to call {t.method} on: "
                        f"{type(exc).__name__}: {str(exc)[:100]}")
    elif t.owner is not None:
        inst = t.owner
    try:
        kwargs = _valid_kwargs(t, inst)
    except LookupError as exc:
        pytest.skip(f"{t.qual}: {exc} (add it to VALID or OVERRIDES)")
    return inst, kwargs


def _valid_call(t, inst, kwargs):
    try:
        result = _call(t, kwargs, inst)
    except CallTimeout as exc:
        return f"{t.id}(valid arguments) -> {exc}"
    except Exception as exc:  # noqa: BLE001
        pytest.skip(f"the valid call {t.qual}({', '.join(kwargs)}) raised "
                    f"{type(exc).__name__}: {str(exc)[:100]} (fix its valid values)")
    bad = _non_finite(result)
    if bad is not None and t.qual in INFINITE_OK and "nan" not in bad.lower():
        bad = None
    return None if bad is None else f"{t.id}(valid arguments) -> returned non-finite ({bad})"


@pytest.mark.parametrize("t, name", _cases())
def test_bad_input_is_named_or_harmless(t, name):
    inst, kwargs = _prepare(t)
    failures = []
    problem = _valid_call(t, inst, kwargs)
    if problem:
        failures.append(problem)
    if name is None:  # nothing to perturb: the valid call must give finite numbers
        assert not failures, "\n".join(failures)
        return
    valid = kwargs.get(name, _default_of(t, name, inst))
    signature_default = _default_of(t, name, inst)
    free_text = name in FREE_TEXT and isinstance(valid, str) and (
        (inspect.isclass(t.func) and t.method is None) or name == "label"
        or f"{t.id}:{name}" in MESSAGE_NAMES)  # labels and names for messages: any text
    free_text = free_text or f"{t.id}:{name}" in NEW_NAMES  # a new name (default: the old)
    for label, (value, can_return) in BAD.items():
        if not _applicable(label, valid) or (label == "None" and signature_default is None
                                              and name in _signature(t).parameters):
            continue
        if label in ACCEPTED.get(f"{t.id.split('[')[0]}:{name}", ((),))[0]:
            continue  # a documented value of this parameter (see ACCEPTED)
        if label == "None" and _field_default(t, name) is None:
            continue  # replace() of a dataclass: None is this field's default (e.g. "as x")
        if free_text and label in ("str", "None"):
            continue  # a label stored as given; a choice (get_material's name) must reject it
        problem = _judge(t, name, label, value, can_return, kwargs, inst)
        if problem:
            failures.append(problem)
    extremes = {"Sample": _bad_samples, "Parabolic": _bad_tips,
                "ScanSettings": _bad_settings, "ContactLoop": _bad_loops,
                "ContactSystem": _bad_systems}.get(type(valid).__name__)
    if extremes in (_bad_loops, _bad_systems) and not t.module.startswith("afmsmiler.imaging"):
        extremes = None  # modules (c) and (d)'s own campaigns cover their loops and systems
    if extremes is _bad_tips and not t.module.startswith("afmsmiler.imaging"):
        extremes = None  # module (d)'s own functions: a 1 pm sphere cannot reach their default
        # depths and they say so naming the depth (z_s, z_np); the tips' ranges are its own
    if extremes is not None:  # well-typed samples and tips that a function may not handle
        for label, value in extremes(valid).items():
            # the misfit may be the combination (a tip wider than a 2 x 2 image): the message
            # may name any parameter of the call
            problem = _judge(t, name, label, value, True, kwargs, inst, also=list(kwargs))
            if problem:
                failures.append(problem)
    assert not failures, "\n".join(failures)


# -- hypothesis: random numbers for every parameter of every callable ------------------------
NUMBERS = st.one_of(
    st.floats(allow_nan=False, allow_infinity=False),
    st.floats(min_value=-1e-6, max_value=1e-6),
    st.integers(min_value=-10**12, max_value=10**12),
    st.builds(lambda e, s: s * 10.0 ** e, st.integers(-320, 308), st.sampled_from([1.0, -1.0])))


def _search_cases():
    cases = []
    for t in TARGETS:
        if t.module in HARDWARE_MODULES:
            continue  # a random count or timeout of the hardware is a wait in real time (a bridge
            # run of 10**12 ticks): a minute of the hang guard per example; its parameters'
            # cases try the large values, and the hostile devices what a device sends
        try:
            if not _inputs(t, _param_names(t)):
                continue
        except (TypeError, ValueError):
            continue
        marks = [pytest.mark.slow]
        if f"{t.id}:*" in KNOWN:
            reason, _ = KNOWN[f"{t.id}:*"]
            marks.append(pytest.mark.xfail(reason=reason, strict=True))
        cases.append(pytest.param(t, id=t.id, marks=marks))
    return cases


@pytest.mark.parametrize("t", _search_cases())
def test_random_numbers_are_named_or_harmless(t):
    inst, kwargs = _prepare(t)
    names = _inputs(t, _param_names(t))
    if _valid_call(t, inst, kwargs):
        pytest.skip(f"{t.qual}: its valid call already fails (see the per-parameter cases)")

    # a seed of the target's own (derandomize=True drew other numbers from one full run to the
    # next: the search must find the same examples every time, in CI as here)
    @seed(zlib.crc32(t.id.encode()))
    @settings(max_examples=15, deadline=None, database=None,
              phases=[Phase.explicit, Phase.generate],  # no shrinking: a hang costs 10 s a try
              suppress_health_check=list(HealthCheck))
    @given(st.sampled_from(names), NUMBERS)
    def search(name, value):
        problem = _judge(t, name, repr(value), value, True, kwargs, inst)
        assert problem is None, problem

    search()


# -- the upper floors: figures, scenes and exercises given a wrong object -----------------------
#: Each public module of the figure, scene and exercise layers whose callables take model results.
#: Not here: scenes.view and scenes.viewer (they open the 3D view's server), scenes.instrument
#: (its tables are the course's own constants, no user input), plots.live (the browser's figure).
UPPER_MODULES = ["afmsmiler.plots.cantilever", "afmsmiler.plots.contact",
                 "afmsmiler.plots.controller", "afmsmiler.plots.hardware",
                 "afmsmiler.plots.imaging", "afmsmiler.plots.lockin", "afmsmiler.plots.modes",
                 "afmsmiler.plots.instrument", "afmsmiler.plots.transducers",
                 "afmsmiler.plots.probe",
                 "afmsmiler.scenes.cantilever", "afmsmiler.scenes.contact",
                 "afmsmiler.scenes.imaging", "afmsmiler.scenes.legends",
                 "afmsmiler.scenes.modes", "afmsmiler.scenes.shapes",
                 "afmsmiler.scenes.transducers", "afmsmiler.scenes.camera",
                 "afmsmiler.scenes.animation", "afmsmiler.scenes.probe",
                 "afmsmiler.exercises.contact", "afmsmiler.exercises.controller",
                 "afmsmiler.exercises.imaging"]


def _recorder():
    """A stand-in for meshcat's Visualizer that records what a scene sends (tests/recording)."""
    from tests.recording import Recorder
    return Recorder()


def _op():
    """The optical lever's operation at its default input, with its frequency response."""
    return _obd().operate(_obd().input_quantity().default, frequencies=np.logspace(2, 6, 20))


def _scan_line():
    return _loop().scan_line(np.linspace(0.0, 1.5e-6, 16), np.zeros(16))


def _fit():
    from afmsmiler.contact import Parabolic, fit_curve
    c = _synthetic()
    return fit_curve(c.tip_position, c.force, Parabolic(50e-9), spring_constant=0.1,
                     poisson_ratio=0.3)


def _force_volume():
    from afmsmiler.contact import Parabolic
    from afmsmiler.modes import BLEND
    from afmsmiler.modes.force_volume import force_volume
    return force_volume(_image(), BLEND, Parabolic(50e-9),
                        labels=np.arange(256).reshape(16, 16) % 2)


def _upper(module, name, *args, **kwargs):
    """``module.name(*args, **kwargs)``, imported when a valid value is built."""
    return lambda: getattr(importlib.import_module(module), name)(
        *(a() if callable(a) else a for a in args), **kwargs)


#: The kinds of object that the upper floors take, by class name (as the callables' annotations
#: and docstrings name them) -> how to build a valid one. A parameter of one of these kinds is an
#: object parameter: a foreign object there must be named (TypeError naming the parameter).
OBJECTS = {
    "Bending": lambda: _lever().bending(),
    "CantileverCurves": _upper("afmsmiler.plots.cantilever", "cantilever_curves",
                               lambda: _lever().bending()),
    "ProbeReport": lambda: INSTANCES["ProbeReport"](),
    "ProbeCurves": _upper("afmsmiler.plots.probe", "probe_curves",
                          lambda: INSTANCES["ProbeReport"]()),
    "Tip": lambda: VALID["tip"](),
    "IndentationCurve": _curve,
    "ApproachRetract": lambda: _system().approach_retract(np.linspace(-50e-9, 30e-9, 40)),
    "ForceCurve": _synthetic,
    "FitResult": _fit,
    "ContactLoop": _loop,
    "ScanLine": _scan_line,
    "ScanImage": lambda: INSTANCES["ScanImage"](),
    "ScanResult": lambda: _scan().run(),
    "ScanView": _upper("afmsmiler.plots.imaging", "scan_view", lambda: _scan().run()),
    "MacroView": _upper("afmsmiler.plots.hardware", "macro_view", np.zeros((4, 4)),
                        np.zeros((4, 4)), 1e-3, 16),
    "LockInDemo": _upper("afmsmiler.signals.demo", "lock_in_demo"),
    "AmplitudeCurve": lambda: INSTANCES["AmplitudeCurve"](),
    "FrictionLoop": _upper("afmsmiler.exercises.modes", "friction_loop_data"),
    "FrequencyShiftCurve": lambda: importlib.import_module(
        "afmsmiler.modes.fm").frequency_shift_curve(_vdw, np.linspace(0.3e-9, 10e-9, 64)),
    "JumpCurve": _upper("afmsmiler.modes.jumping", "jump_curve", _system),
    "ForceVolume": _force_volume,
    "OpticalHead": lambda: VALID["head"](),
    "Operation": _op,
    "ChainCurves": _upper("afmsmiler.plots.transducers", "chain_curves", _op),
    "ContactCurves": lambda: importlib.import_module("afmsmiler.plots.contact").contact_curves(
        _system().approach_retract(np.linspace(-50e-9, 30e-9, 40)), _curve(), VALID["tip"](),
        60e-9),
    "ScanCurves": _upper("afmsmiler.plots.controller", "scan_curves", _scan_line, _loop),
    "Transducer": _obd,
    "ColorScale": _upper("afmsmiler.scenes.colors", "ColorScale", 0.0, 1.0),
    "Sample": _image,
    "FitExercise": _upper("afmsmiler.exercises.contact", "fitting_exercise"),
    "Visualizer": _recorder,
    "Animation": lambda: __import__("meshcat.animation", fromlist=["Animation"]).Animation(),
    "Figure": lambda: __import__("matplotlib.figure", fromlist=["Figure"]).Figure(),
}
#: Valid values of the upper floors' other parameters, by "callable:parameter" (else by name in
#: VALID, else the default).
UPPER_VALID = {
    "plots.contact.contact_curves": {"extent": 60e-9},
    "plots.contact.fit_window": {"width": 20e-9},
    "plots.controller.polygon_figure": {"x": lambda: np.linspace(0.0, 1.5e-6, 16),
                                        "height": lambda: np.zeros(16), "speed": 1e-6},
    "scenes.contact.surface_mesh": {"extent": 60e-9, "unit": 1e-9},
    "scenes.contact.tip_mesh": {"height": 50e-9, "unit": 1e-9},
    "exercises.contact.check_fitted_modulus": {"answer": 20e6},
    "exercises.contact.check_contact_point": {"answer": 0.0},
    "exercises.contact.pull_off_feedback": {"answer": 6e-9, "model": "dmt"},
    "exercises.contact.check_pull_off_forces": {"dmt": 6e-9, "jkr": 5e-9},
    "exercises.controller.height_error": {"speed": 1e-6},
    "scenes.legends.TextPlate": {"text": "campaign"},
    "scenes.shapes.polyline": {"points": lambda: np.zeros((3, 3))},
    "scenes.shapes.cone": {"height": 1.0, "radius": 0.5},
    # "your probe" draws a Lever (a pointed preset), not module (a)'s Cantilever
    **{f"scenes.probe.{f}": {"lever": lambda: __import__(
        "afmsmiler.planform", fromlist=["preset"]).preset("AC240TS"), "twist": 0.01}
       for f in ("lever_mesh", "ProbeScene")},
    "scenes.shapes.sphere": {"radius": 0.5},
    "scenes.camera.set_camera": {"position": (1.0, 1.0, 1.0)},
    "scenes.animation.set_track": {"prop": "position",
                                   "frames": lambda: np.arange(3.0),
                                   "values": lambda: np.zeros((3, 3))},
    "scenes.animation.set_translations": {"frames": lambda: np.arange(3.0),
                                          "positions": lambda: np.zeros((3, 3))},
    "scenes.animation.quaternions_about_x": {"angles": lambda: np.zeros(3)},
    "plots.controller.fig4_figure": {"sample": lambda: _image().line(0)},
    "plots.modes.branch_values": {"values": lambda: INSTANCES["AmplitudeCurve"]().amplitude,
                                  "name": "attractive"},
    "exercises.imaging.substrate_tilt": {"image": _upper("afmsmiler.exercises.imaging",
                                                         "tilted_image")},
    "exercises.imaging.check_levelled": {"image": _upper("afmsmiler.exercises.imaging",
                                                         "tilted_image")},
    "scenes.transducers.OpticalLever": {"source": (0.0, 0.0, 1.0), "target": (0.0, 0.0, 0.0)},
    "scenes.transducers.quadrant_photodiode": {"centre": (0.0, 0.0, 1.0),
                                               "normal": (0.0, 0.0, 1.0)},
}


def _kind(func, name):
    """The class name that ``func``'s parameter ``name`` takes (its annotation, else the type
    its numpydoc docstring gives), if it is one of :data:`OBJECTS`, else None."""
    target = func.__init__ if inspect.isclass(func) else func
    annotation = inspect.signature(func).parameters[name].annotation
    texts = [annotation] if isinstance(annotation, str) else []
    match = re.search(rf"^\s*{name}\s*:\s*([\w.]+)", inspect.getdoc(func) or "", re.M)
    if match is None and target is not func:
        match = re.search(rf"^\s*{name}\s*:\s*([\w.]+)", inspect.getdoc(target) or "", re.M)
    if match:
        texts.append(match.group(1))
    for text in texts:
        for part in text.split("|"):
            kind = part.strip().rsplit(".", 1)[-1]
            if kind in OBJECTS:
                return kind
    return None


def _object_cases():
    cases = []
    for t in _upper_targets():
        first = True
        for name in _param_names(t):
            kind = _kind(t.func, name)
            if kind is not None:  # the first of a callable in the smoke part, the others slow
                cases.append(pytest.param(t, name, kind, id=f"{t.id}:{name}",
                                          marks=[] if first else [pytest.mark.slow]))
                first = False
    return cases


def _upper_targets():
    global MODULES
    saved, MODULES = MODULES, UPPER_MODULES
    try:
        return [t for t in targets() if t.method is None]  # the entry points
    finally:
        MODULES = saved


def _is_checker(t):
    """Whether ``t`` answers any answer with a Feedback: an exercise's checker (``check_``) or a
    function of the exercises annotated to return one (one part's verdict, such as
    ``exercises.contact.pull_off_feedback``)."""
    if not t.module.startswith("afmsmiler.exercises."):
        return False
    returns = getattr(t.func, "__annotations__", {}).get("return") if t.method is None else None
    return t.qual.rsplit(".", 1)[1].startswith("check_") or returns == "Feedback"


def _judge_checker(t, name, label, value, can_return, kwargs, inst):
    """As :func:`_judge` for a checker: a verdict that the answer is wrong (a Feedback that did
    not pass) is the harmless outcome of a bad answer, never an exception from inside."""
    try:
        with guarded():
            verdict = t.func(**{**kwargs, name: value})
    except (TypeError, ValueError) as exc:  # a bad setting or a foreign model, named
        return None if name in str(exc) else \
            f"{_describe(t, name, label)} -> {type(exc).__name__} not naming {name}: " \
            f"{str(exc)[:120]!r}"
    except Exception as exc:  # noqa: BLE001 - every other exception is the finding
        return f"{_describe(t, name, label)} -> {type(exc).__name__}: {str(exc)[:120]!r}"
    if type(verdict).__name__ != "Feedback" or (verdict.passed and not can_return):
        return f"{_describe(t, name, label)} -> passed: {verdict}"[:200]
    return None


def _upper_kwargs(t, skip=None):
    """Valid values of every required parameter of ``t`` but ``skip`` (and of those that
    UPPER_VALID names), or a visible skip saying which cannot be built."""
    kwargs, table = {}, UPPER_VALID.get(t.id, {})
    for p in _signature(t).parameters.values():
        if p.kind in (p.VAR_POSITIONAL, p.VAR_KEYWORD) or p.name == skip:
            continue
        kind = _kind(t.func, p.name)
        try:
            if p.name in table:
                kwargs[p.name] = _resolve(table[p.name], None)
            elif p.default is not p.empty:
                continue
            elif kind is not None:
                kwargs[p.name] = OBJECTS[kind]()
            elif p.name in VALID:
                kwargs[p.name] = _resolve(VALID[p.name], None)
            else:
                pytest.skip(f"{t.qual}: no valid value known for parameter {p.name!r} (add it "
                            f"to UPPER_VALID)")
        except Exception as exc:  # noqa: BLE001
            pytest.skip(f"{t.qual}: the valid value of {p.name!r} cannot be built: "
                        f"{type(exc).__name__}: {str(exc)[:100]}")
    return kwargs


def _upper_object_kwargs(t, name, kind):
    """Valid values of ``t``'s parameters, ``name`` a valid ``kind`` (or a visible skip)."""
    kwargs = _upper_kwargs(t, skip=name)
    try:
        table = UPPER_VALID.get(t.id, {})
        kwargs[name] = _resolve(table[name], None) if name in table else OBJECTS[kind]()
    except Exception as exc:  # noqa: BLE001
        pytest.skip(f"{t.qual}: a valid {kind} cannot be built: {type(exc).__name__}: "
                    f"{str(exc)[:100]}")
    return kwargs


@pytest.mark.parametrize("t, name, kind", _object_cases())
def test_a_wrong_object_is_named(t, name, kind):
    """A figure, a scene or an exercise given a foreign object where it takes a model result
    (or a number, a string, None where the parameter is required) raises TypeError or
    ValueError naming the parameter: an AttributeError from deep inside, naming nothing, was the
    finding (353 of them in issue 21's review)."""
    kwargs = _upper_object_kwargs(t, name, kind)
    problem = _valid_call(t, None, kwargs)
    assert problem is None, problem
    failures = []
    for label in ("object", "str", "huge", "None"):
        value = BAD[label][0]
        if label == "None" and _signature(t).parameters[name].default is None:
            continue  # None is this parameter's default (a new figure, no visualizer)
        problem = (_judge_checker if _is_checker(t) else _judge)(t, name, label, value, False,
                                                                  kwargs, None)
        if problem:
            failures.append(problem)
    assert not failures, "\n".join(failures)


# -- the upper floors: panels ---------------------------------------------------------------------
def _panel_registry():
    """Every panel of the course (afmsmiler.ui.registry.PANELS): its key -> its class."""
    from afmsmiler.ui.registry import PANELS
    return {entry.key: entry.load() for entry in PANELS}


def _new_panel(cls, **initial):
    """A panel without a 3D view (no server under test), as the pages build one."""
    if "scene" in inspect.signature(cls).parameters:
        initial = {"scene": False, **initial}
    with guarded():
        return cls(**initial)


def _out_of_range(control):
    """A value past a slider's top end (display units), or None for a control without one."""
    import ipywidgets as widgets
    if isinstance(control, widgets.FloatLogSlider):
        return control.base ** control.max * 10.0
    if isinstance(control, (widgets.FloatSlider, widgets.IntSlider)):
        return control.max + (control.max - control.min) + 1
    return None


def _panel_bad_values(control):
    """label -> a value that ``control`` cannot hold: the campaign's bad values that are bad for
    it, 10**400 and a value past its end."""
    import ipywidgets as widgets
    labels = ["nan", "inf", "str", "None", "complex", "object", "hugeint", "list"]
    if not isinstance(control, widgets.Checkbox):
        labels.append("bool")
    out = {label: BAD[label][0] for label in labels}
    if isinstance(control, (widgets.Dropdown, widgets.ToggleButtons, widgets.RadioButtons)):
        del out["None"]  # None may be an option (no preset): the options are judged below
        options = [o[1] if isinstance(o, tuple) else o for o in control.options]
        out = {k: v for k, v in out.items() if v not in options}
    high = _out_of_range(control)
    if high is not None:
        out["past-the-end"] = high
    return out


def _panel_judge(what, name, call):
    """None if ``call()`` raised ValueError or TypeError naming ``name`` in time, else why."""
    try:
        with guarded():
            call()
    except CallTimeout as exc:
        return f"{what} -> {exc}"
    except (ValueError, TypeError) as exc:
        return None if name in str(exc) else f"{what} -> {type(exc).__name__} not naming " \
                                              f"{name}: {str(exc)[:120]!r}"
    except Exception as exc:  # noqa: BLE001 - every other exception is the finding
        return f"{what} -> {type(exc).__name__}: {str(exc)[:120]!r}"
    return f"{what} -> accepted"


def _panel_cases(kind, slow):
    cases = []
    for page in sorted(_panel_registry()):
        marks = [pytest.mark.slow] if slow else []
        cases.append(pytest.param(page, id=page, marks=marks))
    return cases


@pytest.mark.parametrize("page", _panel_cases("set", slow=False))
def test_a_panel_set_names_what_a_control_cannot_hold(page):
    """``panel.set(name=value)`` refuses a value its control cannot hold (NaN, a string, None,
    10**400, a value past a slider's end ...) naming the control, and changes nothing."""
    panel = _new_panel(_panel_registry()[page])
    before = panel.values()
    failures = []
    for name, control in panel.controls.items():
        if not hasattr(control, "value"):
            continue  # a button
        for label, value in _panel_bad_values(control).items():
            problem = _panel_judge(f"{page}.set({name}={label})", name,
                                   lambda: panel.set(**{name: value}))
            if problem:
                failures.append(problem)
    if panel.values() != before:
        failures.append(f"{page}: a refused set() changed the controls")
    assert not failures, "\n".join(failures)


@pytest.mark.parametrize("page", _panel_cases("constructor", slow=True))
def test_a_panel_constructor_names_what_set_refuses(page):
    """An initial value that ``set()`` refuses (past a slider's end, NaN, a string) is refused
    by the constructor too, naming the control, instead of clamped silently."""
    cls = _panel_registry()[page]
    if not any(p.kind == p.VAR_KEYWORD for p in inspect.signature(cls).parameters.values()):
        pytest.skip(f"{cls.__name__} takes no initial control values")
    panel = _new_panel(cls)
    failures = []
    for name, control in panel.controls.items():
        if _out_of_range(control) is None:
            continue  # initial values are the sliders'
        for label in ("past-the-end", "nan", "str"):
            value = _out_of_range(control) if label == "past-the-end" else BAD[label][0]
            problem = _panel_judge(f"{cls.__name__}({name}={label})", name,
                                   lambda: _new_panel(cls, **{name: value}))
            if problem:
                failures.append(problem)
    assert not failures, "\n".join(failures)


@pytest.mark.parametrize("page", _panel_cases("update", slow=True))
def test_a_panel_update_names_what_a_control_cannot_hold(page):
    """The callback ``update(**values)`` (sliders in SI) checks the values it gets (a test or
    an exercise calls it directly), naming the control, instead of taking anything."""
    panel = _new_panel(_panel_registry()[page])
    values = panel.to_si(panel.values())  # what update takes: sliders in SI
    failures = []
    for name, control in panel.controls.items():
        p = getattr(control, "parameter", None)
        if p is None:
            continue
        for label in ("past-the-end", "nan", "str", "object", "hugeint"):
            if label == "past-the-end":  # past the parameter's valid range (SI)
                if not (math.isfinite(p.high) or math.isfinite(p.low)):
                    continue
                value = 2 * p.high + 1 if math.isfinite(p.high) else 2 * p.low - 1
            else:
                value = BAD[label][0]
            problem = _panel_judge(f"{page}.update({name}={label})", name,
                                   lambda: panel.update(**{**values, name: value}))
            if problem:
                failures.append(problem)
    assert not failures, "\n".join(failures)


# -- the file readers given damaged files -------------------------------------------------------
DATA_FILES = Path(__file__).parent / "data"
#: One real file of every format load() reads (tests/data/README.md names their sources).
DAMAGED_SOURCES = {".spm": lambda: Path(__import__("afmsmiler.samples",
                                                   fromlist=["REAL_IMAGE"]).REAL_IMAGE),
                   ".top": lambda: DATA_FILES / "afmreader_sample_0.top",
                   ".stp": lambda: DATA_FILES / "afmreader_sample_0.stp",
                   ".ibw": lambda: DATA_FILES / "scifidatasets_btfo_dso.ibw",
                   ".jpk": lambda: DATA_FILES / "afmreader_sample_0.jpk",
                   ".asd": lambda: DATA_FILES / "playnano_asd_sample_0.asd",
                   ".gwy": lambda: DATA_FILES / "scifidatasets_pto_110_virgin0001.gwy",
                   ".npy": None}  # an array written here
#: damage -> (what it does to the file's bytes, whether it is in the smoke part)
DAMAGES = {"cut-10": (lambda b, r: b[:len(b) // 10], True),
           "cut-90": (lambda b, r: b[:len(b) * 9 // 10], False),
           **{f"header-bytes-{i}": (lambda b, r: _flip(b, r, 8, 4096), i == 0) for i in range(4)},
           **{f"any-bytes-{i}": (lambda b, r: _flip(b, r, 64, len(b)), False) for i in range(2)},
           "header-digits": (lambda b, r: _digits(b, r), True),
           **{f"header-number-{i}": (lambda b, r: _digits(b, r, one=True), i < 2)
              for i in range(8)}}


def _flip(raw, rng, count, within):
    """``raw`` with ``count`` bytes at random places of its first ``within`` bytes replaced."""
    out = bytearray(raw)
    for i in rng.integers(0, min(within, len(raw)), count):
        out[i] = int(rng.integers(0, 256))
    return bytes(out)


_SIZE_WORDS = re.compile(rb"(?i)offset|length|size|lines|samps|rows|columns|shape|res\b|pixels")


def _digits(raw, rng, one=False):
    """``raw`` with every decimal number of its first 64 kB (or one of them, at random) made
    10**11, negative or 0: a text header's sizes, offsets and scales gone wrong."""
    head, tail = raw[:65536], raw[65536:]
    choices = (b"-1", b"0", b"99999999999", b"-99999999999", b"-40960")
    numbers = list(re.finditer(rb"(?<=[ :=(,])\d{1,9}(?=[ \r\n,)])", head))
    if one:  # a size, an offset, a length or a shape: the numbers a reader allocates and seeks by
        sizes = [m for m in numbers if _SIZE_WORDS.search(
            head[head.rfind(b"\n", 0, m.start()) + 1:m.start()])]
        numbers = [sizes[int(rng.integers(0, len(sizes)))]] if sizes else []
    for m in reversed(numbers):
        head = head[:m.start()] + choices[int(rng.integers(0, len(choices)))] + head[m.end():]
    return head + tail


def _known(cid, marks):
    """``marks``, and a strict xfail if ``cid`` is a known failure (api_campaign_known.py)."""
    if cid in KNOWN:
        marks = [*marks, pytest.mark.xfail(reason=KNOWN[cid][0], strict=True)]
    return marks


def _damaged_cases():
    cases = []
    for suffix in DAMAGED_SOURCES:
        for damage, (_, smoke) in DAMAGES.items():
            cid = f"samples.readers.load:damaged{suffix}-{damage}"
            cases.append(pytest.param(suffix, damage, id=cid,
                                      marks=_known(cid, [] if smoke else [pytest.mark.slow])))
    return cases


@pytest.mark.parametrize("suffix, damage", _damaged_cases())
def test_a_damaged_file_is_named(tmp_path, suffix, damage):
    """A real file of each format, damaged (cut short, bytes of its header or anywhere replaced,
    its header's numbers made huge, negative or zero), read by :func:`samples.load` and
    :func:`samples.channels`: each either raises ValueError naming the file, or reads an image
    of finite numbers, within the campaign's time and memory guard. An AttributeError,
    OSError, KeyError or OverflowError from inside a reader is the finding."""
    from afmsmiler import samples
    if DAMAGED_SOURCES[suffix] is None:
        np.save(tmp_path / "source.npy", 1e-9 * np.arange(64.0).reshape(8, 8))
        raw, kwargs = (tmp_path / "source.npy").read_bytes(), {"pixel_size": 1e-9}
    else:
        raw, kwargs = DAMAGED_SOURCES[suffix]().read_bytes(), {}
    rng = np.random.default_rng(zlib.crc32(f"{suffix}-{damage}".encode()))
    path = tmp_path / f"damaged{suffix}"
    path.write_bytes(DAMAGES[damage][0](raw, rng))
    failures = []
    for read, args in ((samples.load, kwargs), (samples.channels, {})):
        what = f"{read.__name__}({path.name}, {damage})"
        try:
            with guarded():
                result = read(path, **args)
        except CallTimeout as exc:
            failures.append(f"{what} -> {exc}")
        except MemoryError:
            failures.append(f"{what} -> MemoryError (a size from the file without a bound)")
        except ValueError as exc:
            if path.name not in str(exc):
                failures.append(f"{what} -> ValueError not naming the file: {str(exc)[:120]!r}")
        except Exception as exc:  # noqa: BLE001 - every other exception is the finding
            failures.append(f"{what} -> {type(exc).__name__}: {str(exc)[:120]!r}")
        else:
            bad = _non_finite(result.heights if read is samples.load else result)
            if bad is not None:
                failures.append(f"{what} -> returned non-finite ({bad})")
    assert not failures, "\n".join(failures)


# -- the upper floors: every other parameter gets the bad values ---------------------------------
def _upper_number_cases():
    cases = []
    for t in _upper_targets():
        for name in _param_names(t):
            if _kind(t.func, name) is not None:
                continue  # an object parameter: test_a_wrong_object_is_named
            cid = f"{t.id}:{name}"
            cases.append(pytest.param(t, name, id=cid, marks=_known(cid, [pytest.mark.slow])))
    return cases


@pytest.mark.parametrize("t, name", _upper_number_cases())
def test_upper_bad_values_are_named_or_harmless(t, name):
    """Each other parameter of the figures, scenes and exercises (sizes, ranges, labels, answers)
    gets the campaign's bad values, the others staying valid, judged as in the model layer."""
    kwargs = _upper_kwargs(t)
    problem = _valid_call(t, None, kwargs)
    assert problem is None, problem
    default = _default_of(t, name, None)
    cid = f"{t.id}:{name}"
    failures = []
    for label, (value, can_return) in BAD.items():
        if label == "None" and default is None:
            continue  # None is this parameter's default
        if not _applicable(label, kwargs.get(name, default)):
            continue
        if label in ACCEPTED.get(cid, ((),))[0]:
            continue  # a documented value of this parameter (see ACCEPTED)
        problem = (_judge_checker if _is_checker(t) else _judge)(t, name, label, value,
                                                                  can_return, kwargs, None)
        if problem:
            failures.append(problem)
    assert not failures, "\n".join(failures)


# -- module (h): hostile devices -------------------------------------------------------------------
class HostileLink:
    """The far end of a transport, played in the caller's thread: the device's twin answers
    each host line (``mode = "honest"``), or a hostile device does.

    A hostile device sends garbage lines, one endless line (what a transport hands up of a run
    without a newline: :data:`~afmsmiler.hardware.transport.MAX_LINE` bytes at a time), frames
    that never answer (events for ever), the host's own line back, nothing at all, or the twin's
    frames changed: huge or negative integers, words for integers, replies cut short, replies
    to another SEQ, replies that echo another command, error numbers no device has. It answers
    as fast as the host reads (the worst case for a deadline), and never blocks longer than the
    host's timeout.
    """

    MODES = ("garbage", "endless", "flood", "echo", "silent", "huge", "negative", "words",
             "short", "wrong-seq", "wrong-code", "unknown-error")

    def __init__(self, twin):
        import collections
        self.twin = twin
        self.mode = "honest"
        self.pending = collections.deque()
        self.lock = threading.Lock()
        self.last = b""
        self.closed = False

    def _changed(self, frame):
        from afmsmiler.hardware.framing import INT_MAX, INT_MIN, Frame
        mode, args = self.mode, frame.args
        ints = {"huge": INT_MAX, "negative": INT_MIN, "words": "W"}
        if mode in ints:
            args = tuple(ints[mode] if isinstance(a, int) else a for a in args)
            if frame.code == "ER" and mode == "words":
                args = ("W",)
        elif mode == "short":
            args = args[:1]
        elif mode == "wrong-code" and frame.code == "OK":
            args = ("ZZ", *args[1:])
        elif mode == "unknown-error" and frame.seq:
            return Frame(frame.seq, "ER", (99, "W"))
        elif mode == "wrong-seq" and frame.seq:
            return Frame(frame.seq % 255 + 1, frame.code, args)
        return Frame(frame.seq, frame.code, args)

    def _queue(self, frames):
        from afmsmiler.hardware.framing import encode_frame
        if self.mode != "silent":
            self.pending.extend(encode_frame(self._changed(f))[:-1] for f in frames)

    def write(self, data):
        from afmsmiler.hardware.errors import FrameError, TransportClosed
        from afmsmiler.hardware.framing import as_bytes, decode_frame
        data = as_bytes("data", data)
        with self.lock:
            if self.closed:
                raise TransportClosed("the hostile link is closed")
            for raw in data.split(b"\n"):
                try:
                    frame = decode_frame(raw)
                except FrameError:
                    continue
                self.last = raw
                self._queue(self.twin.handle(frame))

    def readline(self, timeout):
        from afmsmiler.hardware.errors import TransportClosed, TransportTimeout
        from afmsmiler.hardware.framing import Frame, encode_frame
        from afmsmiler.hardware.transport import MAX_LINE
        with self.lock:
            if self.closed:
                raise TransportClosed("the hostile link is closed")
            mode = self.mode
            if mode == "garbage":
                return b"#$%^ \xff\x00 not a frame"
            if mode == "endless":
                return b"7" * MAX_LINE
            if mode == "flood":
                return encode_frame(Frame(0, "EV", ("BOOT",)))[:-1]
            if mode == "echo" and self.last:
                return self.last
            if not self.pending and self.twin.next_due() is not None:
                self._queue(self.twin.poll(self.twin.next_due()))
            if self.pending:
                time.sleep(5e-4)  # a stream at the pace of a fast serial link, not faster
                return self.pending.popleft()
        time.sleep(min(float(timeout), 0.01))
        raise TransportTimeout("the hostile device sent nothing")

    def close(self):
        with self.lock:
            self.closed = True


def _hostile_devices():
    """device -> (driver, its twin, honest setup, operations by name)."""
    from afmsmiler.hardware.educational import EducationalAFM
    from afmsmiler.hardware.haptic import HapticDevice
    from afmsmiler.hardware.macro import MacroAFM
    return {
        "macro": (lambda link: MacroAFM(link, timeout=0.2, retries=1, stream_timeout=0.2),
                  _macro_twin, lambda d: (d.home(), d.configure(pixels=4, lines=2)), {
                      "connect": lambda d: d.connect(), "get": lambda d: d.get("NX"),
                      "set": lambda d: d.set("NX", 4), "status": lambda d: d.status(),
                      "gauge": lambda d: d.gauge(), "force": lambda d: d.force(),
                      "home": lambda d: d.home(), "configuration": lambda d: d.configuration(),
                      "scan": lambda d: d.scan()}),
        "educational": (lambda link: EducationalAFM(link, timeout=0.2, retries=1), _edu_twin,
                        lambda d: d.configure(pixels=4, lines=2), {
                            "connect": lambda d: d.connect(), "get": lambda d: d.get("NX"),
                            "set": lambda d: d.set("NX", 4), "scan": lambda d: d.scan()}),
        "haptic": (lambda link: HapticDevice(link, timeout=0.2, retries=1), _haptic_twin,
                   lambda d: None, {
                       "connect": lambda d: d.connect(), "get": lambda d: d.get("MF"),
                       "set": lambda d: d.set("MF", 1.0), "status": lambda d: d.status(),
                       "enable": lambda d: d.enable(),
                       "position": lambda d: (d.start_stream(1e-3),
                                             d.wait_position(HOSTILE_TIMEOUT))}),
    }


#: Seconds each request waits once the device has turned hostile (the honest start waits 0.2 s):
#: the cases wait out these deadlines, so they set how long the 180 cases take.
HOSTILE_TIMEOUT = 0.05

#: Operations whose smoke cases run in ``make unit`` (the others, and every mode of them, run
#: in ``make test``): a connect meets each hostile device.
HOSTILE_SMOKE = {"connect"}


def _hostile_cases():
    cases = []
    for device, (_, _, _, ops) in _hostile_devices().items():
        for op in ops:
            for mode in HostileLink.MODES:
                cid = f"hostile:{device}.{op}[{mode}]"
                smoke = op in HOSTILE_SMOKE and mode in ("garbage", "endless", "huge", "short")
                cases.append(pytest.param(device, op, mode, id=cid, marks=_known(
                    cid, [] if smoke else [pytest.mark.slow])))
    return cases


@pytest.mark.parametrize("device, op, mode", _hostile_cases())
def test_a_hostile_device_gets_a_named_error_in_time(device, op, mode):
    """A driver whose device (the far end of its transport) turns hostile after an honest
    start: each operation ends within the campaign's guard (one deadline per request, whatever
    the device sends) with a HardwareError (DeviceNotResponding, ReplyError naming the
    parameter, DeviceError ...) or an honest result of finite numbers. An IndexError,
    KeyError, OverflowError, a MemoryError (a size taken from the device), an exception in the
    driver's reader thread, or a hang is the finding."""
    from afmsmiler.hardware.errors import HardwareError
    make, twin, setup, ops = _hostile_devices()[device]
    link = _opened(HostileLink(twin()))
    driver = _opened(make(link))
    if op != "connect":
        driver.connect()
        setup(driver)
    # the hostile part runs on short deadlines: a late answer there is a named timeout, which
    # passes as any HardwareError does (the honest start above keeps the roomier ones)
    driver.timeout = HOSTILE_TIMEOUT
    if hasattr(driver, "stream_timeout"):
        driver.stream_timeout = HOSTILE_TIMEOUT
    link.mode = mode
    thread_errors = []
    old_hook = threading.excepthook
    threading.excepthook = lambda args: thread_errors.append(
        f"{type(args.exc_value).__name__}: {str(args.exc_value)[:120]!r}")
    what = f"{device}.{op}() against a device that turned {mode}"
    problem = None
    try:
        with guarded():
            result = ops[op](driver)
    except CallTimeout as exc:
        problem = f"{what} -> {exc}"
    except MemoryError:
        problem = f"{what} -> MemoryError (a size from the device without a bound)"
    except HardwareError:
        pass
    except Exception as exc:  # noqa: BLE001 - every other exception is the finding
        problem = f"{what} -> {type(exc).__name__}: {str(exc)[:120]!r}"
    else:
        bad = _non_finite(result)
        if bad is not None:
            problem = f"{what} -> returned non-finite ({bad})"
    finally:
        _close_hardware()
        threading.excepthook = old_hook
    if thread_errors:
        problem = f"{what} -> in a thread: {thread_errors[0]}"
    assert problem is None, problem


@pytest.mark.parametrize("faulty", [False, True], ids=["memory", "faulty"])
def test_an_endless_line_is_cut_and_refused_in_time(faulty):
    """A device that writes megabytes without a newline: the transport hands them up
    :data:`MAX_LINE` bytes at a time, and a connect ends with DeviceNotResponding within the
    guard instead of the buffer or the wait growing without bound."""
    from afmsmiler.hardware.errors import DeviceNotResponding
    from afmsmiler.hardware.macro import MacroAFM
    from afmsmiler.hardware.transport import MAX_LINE, FaultyTransport, MemoryTransport
    host, end = MemoryTransport.pair()
    _opened(host)
    end.write(b"7" * (4 * 2**20))
    link = FaultyTransport(host, seed=1, corrupt=0.5, garbage=0.5) if faulty else host
    try:
        with guarded():
            assert len(link.readline(0.1)) <= MAX_LINE
            with pytest.raises(DeviceNotResponding):
                MacroAFM(link, timeout=0.2, retries=1).connect()
    finally:
        _close_hardware()
