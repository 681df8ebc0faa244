"""Every public function and method documents each of its parameters (python-control's rule).

Walks the pure model and helper modules of afmsmiler; a parameter counts as documented when its
name appears in the docstring of the function (or, for a constructor, of its class).
"""
import importlib
import inspect
import pkgutil
import re

import pytest

import afmsmiler

# UI panels take widget values by keyword through Panel.update(**values); they are documented
# by their class docstring and tested through the panel tests instead.
SKIP_PACKAGES = ("afmsmiler.ui",)


def _public_modules():
    for info in pkgutil.walk_packages(afmsmiler.__path__, "afmsmiler."):
        name = info.name
        if any(part.startswith("_") for part in name.split(".")) or name.startswith(SKIP_PACKAGES):
            continue
        yield name


def _callables(module):
    for name, obj in vars(module).items():
        if name.startswith("_") or getattr(obj, "__module__", None) != module.__name__:
            continue
        if inspect.isfunction(obj):
            yield f"{module.__name__}.{name}", obj, obj.__doc__
        elif inspect.isclass(obj):
            yield f"{module.__name__}.{name}", obj, obj.__doc__
            for mname, meth in vars(obj).items():
                if mname.startswith("_") or not inspect.isfunction(meth):
                    continue
                yield f"{module.__name__}.{name}.{mname}", meth, meth.__doc__


def _parameters(obj):
    try:
        sig = inspect.signature(obj)
    except (TypeError, ValueError):
        return []
    return [p.name for p in sig.parameters.values()
            if p.name not in ("self", "cls") and not p.name.startswith("_")
            and p.kind not in (p.VAR_POSITIONAL, p.VAR_KEYWORD)]


CASES = [(qual, obj, doc) for m in _public_modules()
         for qual, obj, doc in _callables(importlib.import_module(m))]


@pytest.mark.parametrize("qual, obj, doc", CASES, ids=[c[0] for c in CASES])
def test_documented(qual, obj, doc):
    assert doc and doc.strip(), f"{qual} has no docstring"
    missing = [p for p in _parameters(obj) if not re.search(rf"\b{re.escape(p)}\b", doc)]
    assert not missing, f"{qual}: parameters not documented: {missing}"
