"""The one registry of panels lists every panel, and every panel keeps the panel contract.

As python-control's ``kwargs_test.py`` forces a test for every new keyword, a panel class added to
``afmsmiler.ui`` without an entry in :data:`afmsmiler.ui.registry.PANELS` fails here, and so does an
entry whose notebook does not show the panel under its name, or whose slider is not a slider.
"""
import importlib
import inspect
import json
import math
import pkgutil
from pathlib import Path

import pytest

import afmsmiler.ui
from afmsmiler.ui.panel import Panel
from afmsmiler.ui.registry import MODULES, PANELS, panel_entry, panels

NOTEBOOKS = Path(__file__).resolve().parents[1] / "notebooks"


def _panel_classes():
    found = {}
    for info in pkgutil.iter_modules(afmsmiler.ui.__path__):
        module = importlib.import_module(f"afmsmiler.ui.{info.name}")
        for name, obj in vars(module).items():
            if inspect.isclass(obj) and issubclass(obj, Panel) and obj is not Panel \
                    and obj.__module__ == module.__name__ and not name.startswith("_"):
                found[name] = info.name
    return found


def test_every_panel_class_is_in_the_registry_once():
    classes = _panel_classes()
    listed = {(e.ui, e.cls) for e in PANELS}
    assert len(listed) == len(PANELS), "a panel is listed twice"
    assert {(ui, cls) for cls, ui in classes.items()} == listed
    assert len({e.key for e in PANELS}) == len(PANELS)
    assert {e.module for e in PANELS} == set(MODULES)  # every module shows a panel


def _code(notebook: str) -> str:
    cells = json.loads((NOTEBOOKS / notebook).read_text(encoding="utf-8"))["cells"]
    return "\n".join("".join(c["source"]) for c in cells if c["cell_type"] == "code")


@pytest.mark.parametrize("entry", PANELS, ids=lambda e: e.key)
def test_the_notebook_shows_the_panel_under_its_name(entry):
    code = _code(entry.notebook)
    made = [line for line in code.splitlines()
            if line.replace(" ", "").startswith(f"{entry.variable}={entry.cls}(")]
    assert made, f"{entry.notebook} makes no {entry.variable} = {entry.cls}(...)"
    assert ("scene=True" in made[0]) == entry.scene, made[0]
    assert f"{entry.variable}.show()" in code


@pytest.mark.parametrize("entry", PANELS, ids=lambda e: e.key)
def test_the_registry_slider_moves_the_model_once_with_si_values(entry):
    panel = entry.make()
    control = panel.controls[entry.slider]
    p = control.parameter  # a slider made from a Parameter
    calls = []
    update = panel.update
    panel.update = lambda **v: (calls.append(v), update(**v))
    span = control.max - control.min
    if hasattr(control, "base"):  # a log slider: its grid is in the exponent
        target = control.base ** (control.min + round(0.75 * span / control.step) * control.step)
    else:
        target = control.min + round(0.75 * span / control.step) * control.step
    panel.set(**{entry.slider: target})
    assert len(calls) == 1 and set(calls[0]) == set(panel.controls)
    # the value reached update in SI: the display value converted by the parameter's own scale
    assert calls[0][entry.slider] == pytest.approx(p.to_si(target), rel=1e-9)
    assert panel.error is None


@pytest.mark.parametrize("entry", PANELS, ids=lambda e: e.key)
def test_the_contract_refuses_before_any_work(entry):
    panel = entry.make()
    last = panel.last
    si = panel.to_si(panel.values())
    with pytest.raises(TypeError, match="unknown"):
        panel.update(**si, colour=1.0)
    with pytest.raises(TypeError, match="missing"):
        panel.update(**{k: v for k, v in si.items() if k != entry.slider})
    with pytest.raises(TypeError, match="by name"):
        panel.update(*si.values())
    named = f"^({entry.slider}|{panel.controls[entry.slider].parameter.name}) must"
    for bad in ("lots", None, math.nan, -math.inf):
        with pytest.raises((TypeError, ValueError), match=named):
            panel.update(**{**si, entry.slider: bad})
    assert panel.last is last
    with pytest.raises(TypeError, match="unknown control|unexpected keyword"):
        entry.make(colour=1.0)
    takes_values = any(p.kind is p.VAR_KEYWORD
                       for p in inspect.signature(entry.load()).parameters.values())
    if takes_values:  # initial values: refused off the slider, never clamped
        control = panel.controls[entry.slider]
        top = control.base ** control.max if hasattr(control, "base") else control.max
        with pytest.raises(ValueError, match=f"^{entry.slider} must be"):
            entry.make(**{entry.slider: 10 * abs(top) + 1.0})


def test_lookups_name_the_valid_keys():
    assert panel_entry("tapping").cls == "TappingPanel"
    assert [e.key for e in panels("h")] == ["macro_afm", "bridge", "q_control", "lockin"]
    with pytest.raises(ValueError, match="key must be one of"):
        panel_entry("afm")
    with pytest.raises(ValueError, match="module must be one of"):
        panels("z")


def test_the_readme_table_is_the_registry():
    readme = (Path(__file__).resolve().parents[1] / "README.md").read_text(encoding="utf-8")
    from afmsmiler.ui.registry import markdown_table
    assert markdown_table() in readme, "README's panel table differs: python -m afmsmiler.ui.registry"
