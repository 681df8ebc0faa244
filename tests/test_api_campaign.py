"""The bad-input campaign over the public API of the model layer.

Every public function, class and method of the physics modules (cantilever, materials,
transducers, controller, contact, samples, brownian when present) and of the house modules
(parameters, validation) is first called with valid arguments, built from its signature: the
defaults, and a small table of valid values by parameter name (``lever`` -> a Cantilever, ``tip``
-> a Parabolic tip, ``loop`` -> a ContactLoop, ...). The signatures are read at collection time, so
the campaign follows the modules as their signatures change. Then each parameter in turn gets bad
values (NaN, +-inf, a string, None, a bool, a complex, a list, a foreign object, a wrong shape,
zero, negative, huge and tiny numbers, a huge integer), the others staying valid.

A call passes when it either

* raises ``ValueError`` or ``TypeError`` whose message names the parameter, or
* returns a result whose numbers are all finite, and the bad value was a plain number (a NaN, a
  string, None, a complex or an object accepted silently is a failure);

and in any case returns within 10 s (a SIGALRM guard per call) without asking for more memory
than the guard allows (RLIMIT_AS, so a size that would swap the machine fails as MemoryError).
A valid call must return finite numbers too.

What cannot be built (no valid value known for a parameter, or the valid call itself raises) is
skipped visibly, with the reason. Known failures in modules that this file's author does not own
are strict xfails, listed with their calls in ``tests/api_campaign_known.py``; the lead fixes them
and deletes the entries (strict: a fixed entry turns the run red until it is deleted).
``python tests/api_campaign_record.py`` rewrites that file from a fresh run.

``make unit`` runs the smoke part (the first parameter of every callable and each parameter of the
house modules); ``make test`` runs every parameter (``slow``) and a hypothesis search over random
numbers for every callable (``slow``).
"""
from __future__ import annotations

import dataclasses
import importlib
import inspect
import math
import os
import resource
import signal
import time
from contextlib import contextmanager
from pathlib import Path

import numpy as np
import pytest
from hypothesis import HealthCheck, Phase, given, settings
from hypothesis import strategies as st

from afmsmiler.parameters import Parameter

from api_campaign_known import KNOWN

if os.environ.get("AFMSMILER_CAMPAIGN_RECORD"):  # tests/api_campaign_record.py: see everything
    KNOWN = {}

# Overflow and invalid-value warnings of extreme inputs are expected; the results are judged.
pytestmark = pytest.mark.filterwarnings("ignore::RuntimeWarning")

MODULES = ["afmsmiler.cantilever", "afmsmiler.materials", "afmsmiler.transducers",
           "afmsmiler.controller", "afmsmiler.contact", "afmsmiler.samples",
           "afmsmiler.brownian", "afmsmiler.parameters", "afmsmiler.validation"]
HOUSE = ("afmsmiler.parameters", "afmsmiler.validation")
TIME_LIMIT = 10.0  # s per call: the bound
MEMORY_MARGIN = 4 * 2**30  # bytes of address space a call may add (23 GB machine, shared)

# Parameters that are not inputs of the physics: the name and unit a validation helper prints.
NOT_INPUTS = {"name", "unit", "what", "label", "description", "readout_format"}
# Free text that a constructor stores as given (a curve's or a material's name, a source).
FREE_TEXT = {"name", "source", "label", "description", "channel"}
#: Parameters that name another one in an error message (any text will do; a non-str is refused).
MESSAGE_NAMES = {"cantilever.check_modes:name"}
# Returned by the models, not built by a user: their constructors are not part of the input API
# (their methods are called on a result the model returned, see INSTANCES).
RESULTS = {"Stability", "LoopResponse", "ScanLine", "ScanPass", "ScanImage", "ClosedForm",
           "IndentationCurve", "ApproachRetract", "ViscoelasticCycle", "FitResult", "TableRow",
           "SignalChain", "Stage", "FrequencyResponse", "Resolution", "Harmonics", "Preset",
           "Operation", "Bending"}
# Abstract bases: their methods are called on each concrete subclass instead.
ABSTRACT = {"Tip", "Transducer"}
# Legacy descriptions that afmsmiler.parameters.Parameter replaces (issue 8, section 1).
LEGACY = {"afmsmiler.contact.TipParameter", "afmsmiler.transducers.Quantity",
          "afmsmiler.transducers.Parameter"}
# The validation helpers check one input (value or values) that the message calls by the name
# it is given; their other arguments are the calling library's constants, not user input.
HOUSE_INPUTS = {"value", "values"}
# Conversions that carry NaN through (a gap in a plotted curve); check() validates.
NAN_PASSES = {"afmsmiler.parameters.Parameter.to_si", "afmsmiler.parameters.Parameter.to_display"}
# Callables whose documented answer for valid input may be infinite ("no limit").
INFINITE_OK = {"afmsmiler.contact.z_np_limit": "inf means no limit (documented)"}


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
    "modes": 3,
}

# Valid values for one callable (by its qualified name), where the name table does not fit.
OVERRIDES = {
    "afmsmiler.transducers.get_principle": {"key": "optical_beam_deflection"},
    "afmsmiler.contact.make_tip": {"key": "parabolic"},
    "afmsmiler.cantilever.check_modes": {"modes": (1, 2, 3)},
    "afmsmiler.contact.adhesion_extrema": {"adhesion": "jkr", "work_of_adhesion": 0.03},
    "afmsmiler.contact.ContactSystem.at": {"z_np": 10e-9},
    "afmsmiler.contact.contact_surface": {"current": lambda: _curve()},
    "afmsmiler.materials.get_material": {"name": "silicon"},
    "afmsmiler.materials.Material": {"name": "test", "youngs_modulus": 169e9},
    "afmsmiler.cantilever.Cantilever": {"youngs_modulus": 169e9},
    "afmsmiler.contact.fit_curve": {"position": lambda: _synthetic().tip_position,
                                    "force": lambda: _synthetic().force},
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
    "afmsmiler.validation.check_size": {"value": 3},
    "afmsmiler.validation.check_shape": {"value": (4, 4)},
    "afmsmiler.validation.check_instance": {"value": lambda: {"a": 1}, "kind": dict},
    "afmsmiler.validation.check_array": {"values": [1.0, 2.0]},
    "afmsmiler.validation.check_range": {"value": 1.0},
    "afmsmiler.validation.check_positive": {"value": 1.0},
    "afmsmiler.validation.check_nonnegative": {"value": 1.0},
    "afmsmiler.validation.check_finite": {"value": 1.0},
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
    "SignalChain": lambda: _obd().chain(_obd().input_quantity().default),
    "Material": lambda: __import__("afmsmiler.materials",
                                   fromlist=["get_material"]).get_material("silicon"),
}


def _obd():
    from afmsmiler.transducers import OpticalBeamDeflection
    return OpticalBeamDeflection()


def _sls():
    from afmsmiler.contact import StandardLinearSolid
    return StandardLinearSolid(1e6, 2e6, 1e-3)


def _is_lever(obj):
    return type(obj).__name__ == "Cantilever"


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
    "2d": (np.ones((3, 3)), True), "empty": (np.array([]), True),
    "nan-array": (np.array([0.0, math.nan]), False),
}


def _input_names(inst):
    """How messages name ``value``: a transducer's input (``deflection``), a Parameter's name."""
    if not hasattr(inst, "input_quantity"):
        return [inst.name] if isinstance(getattr(inst, "name", None), str) else []
    try:
        return [inst.input_quantity(m).name for m in (None, *getattr(inst, "MODES", ()))]
    except Exception:  # noqa: BLE001 - no such modes
        return [inst.input_quantity().name]


#: parameter -> other names a message may use for it (given the object whose method it is).
ALIASES = {"value": _input_names, "at": _input_names}


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


def _default_of(t: Target, name, inst):
    sig = _signature(t)
    p = sig.parameters.get(name)
    if p is not None and p.default is not p.empty:
        return p.default
    if inspect.isclass(t.func) and hasattr(t.func, "defaults"):
        return t.func.defaults().get(name)
    if t.method == "replace" and inst is not None:
        return getattr(inst, name, None)
    return None


# -- guards -------------------------------------------------------------------------------------
class CallTimeout(Exception):
    pass


def _alarm(_signum, _frame):
    raise CallTimeout(f"still running after {TIME_LIMIT:g} s")


@contextmanager
def guarded():
    """At most TIME_LIMIT seconds and MEMORY_MARGIN more bytes of address space for one call."""
    old_handler = signal.signal(signal.SIGALRM, _alarm)
    soft, hard = resource.getrlimit(resource.RLIMIT_AS)
    with open("/proc/self/statm") as fh:
        used = int(fh.read().split()[0]) * resource.getpagesize()
    limit = used + MEMORY_MARGIN
    if hard != resource.RLIM_INFINITY:
        limit = min(limit, hard)
    resource.setrlimit(resource.RLIMIT_AS, (limit, hard))
    signal.setitimer(signal.ITIMER_REAL, TIME_LIMIT)
    try:
        yield
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
        resource.setrlimit(resource.RLIMIT_AS, (soft, hard))
        signal.signal(signal.SIGALRM, old_handler)


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
        if t.method is None and inspect.isclass(t.func):
            return result, _probe(result)
        return result


def _describe(t: Target, name, label):
    return f"{t.id}({name}={label})"


def _judge(t: Target, name, label, value, can_return, kwargs, inst):
    """None if the call behaved, else what went wrong."""
    names = [name]
    if name in ALIASES and inst is not None:
        names += ALIASES[name](inst)
    if t.module == "afmsmiler.validation" and "name" in kwargs:
        names.append(kwargs["name"])
    start = time.perf_counter()
    try:
        result = _call(t, {**kwargs, name: value}, inst)
    except CallTimeout as exc:
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
        elapsed = time.perf_counter() - start
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
        return f"{_describe(t, name, label)} -> took {elapsed:.1f} s"
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
            smoke = i == 0 or t.module in HOUSE
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
    for label, (value, can_return) in BAD.items():
        if not _applicable(label, valid) or (label == "None" and signature_default is None
                                              and name in _signature(t).parameters):
            continue
        if free_text and label in ("str", "None"):
            continue  # a label stored as given; a choice (get_material's name) must reject it
        problem = _judge(t, name, label, value, can_return, kwargs, inst)
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

    @settings(max_examples=15, deadline=None, derandomize=True, database=None,
              phases=[Phase.explicit, Phase.generate],  # no shrinking: a hang costs 10 s a try
              suppress_health_check=list(HealthCheck))
    @given(st.sampled_from(names), NUMBERS)
    def search(name, value):
        problem = _judge(t, name, repr(value), value, True, kwargs, inst)
        assert problem is None, problem

    search()
