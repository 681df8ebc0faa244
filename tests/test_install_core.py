"""The core install: ``pip install afmsmiler`` brings the models only (numpy, scipy, sympy,
python-control). Every model module imports with the UI stack (widgets, figures, 3D views,
Jupyter), the file readers and the device libraries all absent, and the core dependencies
name none of them; the extras (``lab``, ``files``, ``hardware``) bring them.
"""
import subprocess
import sys
import tomllib
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
#: What only the extras bring: the notebooks' UI stack (lab), the file readers (files), the
#: device libraries (hardware), and what Jupyter brings with them.
EXTRAS_ONLY = {"ipywidgets": "lab", "matplotlib": "lab", "meshcat": "lab", "anywidget": "lab",
               "PIL": "lab", "IPython": "lab", "ipykernel": "lab", "AFMReader": "files",
               "gwyfile": "files", "afmformats": "files", "serial": "hardware",
               "trimesh": "hardware", "pydwf": "hardware"}
#: The layers that draw and wire widgets, and the web apps that serve them (voila): they need
#: the lab extra.
UI_LAYERS = ("ui", "plots", "scenes", "apps")

BLOCKED_IMPORT = f"""
import importlib, pkgutil, sys
for name in {sorted(EXTRAS_ONLY)!r}:
    sys.modules[name] = None  # "import name" now raises ImportError
import afmsmiler
failed, imported = [], 0
for info in pkgutil.walk_packages(afmsmiler.__path__, "afmsmiler."):
    if info.name.split(".")[1] in {UI_LAYERS!r}:
        continue
    try:
        importlib.import_module(info.name)
        imported += 1
    except Exception as exc:
        failed.append(f"{{info.name}}: {{type(exc).__name__}}: {{exc}}")
print(imported)
print("\\n".join(failed))
"""


@pytest.mark.slow  # over a second: make test runs it, make unit does not
def test_every_model_module_imports_without_the_extras():
    out = subprocess.run([sys.executable, "-c", BLOCKED_IMPORT], capture_output=True, text=True,
                         timeout=300, cwd=ROOT, check=True).stdout.splitlines()
    imported, failed = int(out[0]), [line for line in out[1:] if line]
    assert not failed, "model modules that need an extra to import:\n" + "\n".join(failed)
    assert imported > 50  # the walk found the models (about 90 modules)


def test_the_core_dependencies_name_no_extra():
    project = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]
    core = {d.split(">")[0].split("=")[0].split("<")[0].strip().lower()
            for d in project["dependencies"]}
    assert core == {"numpy", "scipy", "sympy", "control"}
    assert "tqdm" not in str(project)  # nothing uses it
    extras = project["optional-dependencies"]
    for pypi, extra in (("ipywidgets", "lab"), ("matplotlib", "lab"), ("meshcat", "lab"),
                        ("anywidget", "lab"), ("pillow", "lab"), ("AFMReader", "files"),
                        ("gwyfile", "files"), ("afmformats", "files"), ("pyserial", "hardware"),
                        ("trimesh", "hardware"), ("pydwf", "hardware")):
        assert any(d.startswith(pypi) for d in extras[extra]), (pypi, extra)
