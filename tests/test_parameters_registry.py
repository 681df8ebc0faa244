"""A name means one SI unit everywhere in the package.

Imports every module of afmsmiler, collects every :class:`afmsmiler.parameters.Parameter` it holds
(module attributes, class attributes, and the mappings, tuples, lists and sets of them, nested),
plus any other instance still alive (``gc``), and asserts that each parameter name has one SI
unit: ``length`` is in m wherever it is described, never in um in one module and m in another.
Passes today and keeps passing as the modules migrate their descriptions to ``Parameter``.
"""
import gc
import importlib
import inspect
import json
import pkgutil
import subprocess
import sys
from collections import defaultdict
from collections.abc import Mapping
from pathlib import Path
from types import SimpleNamespace

import pytest

import afmsmiler
from afmsmiler.parameters import Parameter

# Modules that a bare import must not run: none today (the meshcat server has a __main__ guard).
SKIP = ()


def _modules():
    for info in pkgutil.walk_packages(afmsmiler.__path__, "afmsmiler."):
        if info.name.startswith(SKIP):
            continue
        yield importlib.import_module(info.name)


def _walk(obj, where, found, depth=0):
    if isinstance(obj, Parameter):
        found.append((obj, where))
    elif depth < 4 and isinstance(obj, Mapping):
        for k, v in list(obj.items()):
            _walk(v, f"{where}[{k!r}]", found, depth + 1)
    elif depth < 4 and isinstance(obj, (tuple, list, set, frozenset)):
        for i, v in enumerate(obj):
            _walk(v, f"{where}[{i}]", found, depth + 1)


def collect():
    """Every Parameter in the package, with where it was found."""
    found = []
    for module in _modules():
        for name, obj in list(vars(module).items()):
            where = f"{module.__name__}.{name}"
            _walk(obj, where, found)
            if inspect.isclass(obj) and obj.__module__ == module.__name__:
                for cname, cobj in list(vars(obj).items()):
                    _walk(cobj, f"{where}.{cname}", found)
    seen = {id(p) for p, _ in found}
    for obj in gc.get_objects():  # built inside functions or registries the walk did not reach
        if isinstance(obj, Parameter) and id(obj) not in seen:
            found.append((obj, "(found by gc)"))
            seen.add(id(obj))
    return found


def clashes(found):
    """name -> {SI unit: [where, ...]} for every name described with more than one SI unit."""
    units = defaultdict(lambda: defaultdict(list))
    for p, where in found:
        units[p.name][p.unit].append(where)
    return {name: dict(by_unit) for name, by_unit in units.items() if len(by_unit) > 1}


def _collect_in_a_fresh_interpreter():
    """collect() in a new process: Parameters that other tests built are not the package's."""
    code = ("import json, sys; sys.path.insert(0, sys.argv[1]); "
            "from tests.test_parameters_registry import collect; "
            "print(json.dumps([(p.name, p.unit, where) for p, where in collect()]))")
    out = subprocess.run([sys.executable, "-c", code, str(Path(__file__).parents[1])],
                         capture_output=True, text=True, timeout=300, check=True)
    return [(SimpleNamespace(name=n, unit=u), where)
            for n, u, where in json.loads(out.stdout.strip().splitlines()[-1])]


@pytest.mark.slow  # imports the whole package in a new interpreter (seconds)
def test_a_name_means_one_si_unit_everywhere():
    found = _collect_in_a_fresh_interpreter()
    bad = clashes(found)
    assert not bad, "names with more than one SI unit: " + "; ".join(
        f"{name}: " + ", ".join(f"{unit or '(none)'} in {wheres[:3]}" for unit, wheres in u.items())
        for name, u in bad.items())


def test_the_check_finds_a_clash():
    a = Parameter(name="length", unit="m", display_unit="um", default=1e-4)
    b = Parameter(name="length", unit="", default=100.0)
    assert set(clashes([(a, "x"), (b, "y")])) == {"length"}
    assert not clashes([(a, "x"), (a.with_(default=2e-4), "y")])


def test_the_walk_reaches_mappings_tuples_and_classes():
    import types
    m = types.ModuleType("fake")
    p = Parameter(name="width", unit="m", default=1e-5)

    class Lever:
        PARAMETERS = {"width": p, "more": (p,)}
    m.Lever, m.TABLE = Lever, [p]
    found = []
    _walk(m.TABLE, "fake.TABLE", found)
    _walk(vars(Lever)["PARAMETERS"], "fake.Lever.PARAMETERS", found)
    assert [w for _, w in found] == ["fake.TABLE[0]", "fake.Lever.PARAMETERS['width']",
                                     "fake.Lever.PARAMETERS['more'][0]"]


def _range(p):
    return (p.low, p.high, p.low_inclusive, p.high_inclusive)


@pytest.mark.slow  # imports the whole package in a new interpreter (seconds)
def test_a_lever_quantity_has_one_valid_range_everywhere():
    # k, f0 and Q (and mode 2's Q_2) are described once in afmsmiler.parameters; a module may
    # change the default and the slider, never the valid range: a lever valid in one mode is
    # valid in the next (the one exception, named there: Q >= 1/2 for the models of an
    # underdamped mode: the contact loop and the transducers' Q typed in vacuum)
    from afmsmiler.parameters import PARAMETERS as SHARED
    from afmsmiler.parameters import UNDERDAMPED_QUALITY_FACTOR
    code = ("import json, sys; sys.path.insert(0, sys.argv[1]); "
            "from test_parameters_registry import collect; "
            "print(json.dumps([(p.name, p.low, p.high, p.low_inclusive, p.high_inclusive, where) "
            "for p, where in collect()]))")
    out = subprocess.run([sys.executable, "-c", code, str(Path(__file__).parent)],
                         capture_output=True, text=True, timeout=300, check=True)
    found = json.loads(out.stdout.strip().splitlines()[-1])
    shared = {name: _range(p) for name, p in SHARED.items()}
    shared["quality_factor_2"] = shared["quality_factor"]
    narrowed = {("quality_factor", _range(UNDERDAMPED_QUALITY_FACTOR))}
    bad = [(name, (low, high, li, hi), where) for name, low, high, li, hi, where in found
           if name in shared and (low, high, li, hi) != shared[name]
           and (name, (low, high, li, hi)) not in narrowed]
    assert not bad, f"lever quantities with another valid range than afmsmiler.parameters: {bad}"
