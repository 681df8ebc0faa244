"""The files that make the repository run on JupyterHub and Binder (issue 22).

``binder/requirements.txt`` is the lock repo2docker installs: every line an exact pin (``==``),
each the version installed in this environment (the one the tests pass with; ``make lock``
writes it again after an upgrade), covering every requirement of the course's own extras.
``binder/runtime.txt`` names this Python's version. ``deploy/z2jh/config.yaml`` (Zero to
JupyterHub) gives each student the memory a module needs (measured by ``benchmarks/bench_hub.py``,
recorded below), culls idle servers, and pulls the course into each home with nbgitpuller.
"""
import re
import sys
from importlib import metadata
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
LOCK = ROOT / "binder" / "requirements.txt"
Z2JH = ROOT / "deploy" / "z2jh" / "config.yaml"
#: The extras a class needs (the notebooks, files, devices, the hub's pieces).
CLASS_EXTRAS = ("lab", "files", "hardware", "hub")
#: One student's processes (JupyterLab and one module's kernel), resident memory in MiB, as
#: benchmarks/bench_hub.py measured it (module (d), 1 student, 2026-12-02); the guarantee must
#: hold it and the limit two of them (a second module open).
MEASURED_STUDENT_MIB = 338


def _name(req: str) -> str:
    return re.split(r"[<>=!~;\[ ]", req.strip(), maxsplit=1)[0].lower().replace("_", "-")


def _lock() -> dict:
    pins = {}
    for line in LOCK.read_text().splitlines():
        line = line.strip()
        if not line or line.startswith("#"):
            continue
        assert re.fullmatch(r"[A-Za-z0-9._-]+==[A-Za-z0-9.+!-]+", line), \
            f"binder/requirements.txt: {line!r} is not an exact pin"
        name, version = line.split("==")
        pins[name.lower().replace("_", "-")] = version
    return pins


def test_the_lock_pins_what_is_installed_here():
    pins = _lock()
    stale = {}
    for name, version in pins.items():
        try:
            installed = metadata.version(name)
        except metadata.PackageNotFoundError:
            installed = None
        if installed != version:
            stale[name] = (version, installed)
    assert not stale, (f"binder/requirements.txt differs from this environment "
                       f"(locked, installed): {stale}; run `make lock`")


def test_the_lock_covers_the_course_and_its_class_extras():
    pins = _lock()
    requires = metadata.requires("afmsmiler") or []
    needed = set()
    for req in requires:
        marker = re.search(r"extra\s*==\s*['\"]([^'\"]+)['\"]", req)
        if marker is None or marker.group(1) in CLASS_EXTRAS:
            needed.add(_name(req))
    missing = sorted(n for n in needed if n not in pins)
    assert not missing, f"binder/requirements.txt lacks {missing}; run `make lock`"
    assert "afmsmiler" not in pins, "the lock pins the course itself (postBuild installs it)"


def test_the_runtime_is_this_python():
    text = (ROOT / "binder" / "runtime.txt").read_text().strip()
    assert text == f"python-{sys.version_info[0]}.{sys.version_info[1]}", text


def _mib(quantity: str) -> float:
    """A Kubernetes memory quantity (512M, 1G, 1.5Gi) in MiB."""
    m = re.fullmatch(r"([0-9.]+)([KMGT]i?)?", str(quantity))
    assert m, f"not a memory quantity: {quantity!r}"
    scale = {"K": 1e3, "M": 1e6, "G": 1e9, "T": 1e12, "Ki": 2**10, "Mi": 2**20, "Gi": 2**30,
             "Ti": 2**40, None: 1}[m.group(2)]
    return float(m.group(1)) * scale / 2**20


def test_the_z2jh_config_limits_culls_and_pulls_the_course():
    yaml = pytest.importorskip("yaml")
    config = yaml.safe_load(Z2JH.read_text())
    single = config["singleuser"]
    guarantee, limit = _mib(single["memory"]["guarantee"]), _mib(single["memory"]["limit"])
    assert guarantee >= MEASURED_STUDENT_MIB, (guarantee, MEASURED_STUDENT_MIB)
    assert limit >= 2 * MEASURED_STUDENT_MIB, "a student can keep two modules' kernels"
    assert 0 < single["cpu"]["guarantee"] <= single["cpu"]["limit"]
    command = single["lifecycleHooks"]["postStart"]["exec"]["command"]
    assert "gitpuller" in " ".join(command), command
    cull = config["cull"]
    assert cull["enabled"] is True and 0 < cull["timeout"] <= 4 * 3600 and cull["every"] > 0
