"""The instruments' assembly as a pure model: data and geometry, no meshcat.

The optics are checked against the law of reflection written out as angles (incidence equals
reflection about the lever's normal, both rays in one plane with it), not through the
``reflect`` helper the model uses; the placements against the stated distances of the module's
docstring (laser exit 38 mm and lens 22 mm from the lever end along the incident beam, mirror
35 mm along the reflected one, photodiode 8 mm past the mirror).
"""
import math
import subprocess
import sys

import numpy as np
import pytest

from afmsmiler.instrument import INSTRUMENTS as EXPORTED
from afmsmiler.instrument.assembly import INSTRUMENTS, SHAPE_KINDS, Part, Shape


def test_the_model_imports_no_meshcat():
    code = ("import sys; import afmsmiler.instrument.assembly; "
            "print(sorted(m for m in sys.modules if m.split('.')[0] == 'meshcat'))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         timeout=120, check=True)
    assert out.stdout.strip() == "[]"


def test_the_scene_draws_the_model():
    from afmsmiler.scenes import instrument as scene
    assert scene.INSTRUMENTS is INSTRUMENTS is EXPORTED
    assert scene.Part is Part and scene.Shape is Shape


def _angle(u, v):
    return math.degrees(math.acos(np.dot(u, v) / (np.linalg.norm(u) * np.linalg.norm(v))))


def test_the_obd_beam_obeys_the_law_of_reflection_at_the_tilted_lever():
    obd = INSTRUMENTS["obd"]
    a = {k: np.asarray(v, float) for k, v in obd.anchors_mm.items()}
    normal = np.array([math.sin(math.radians(12.0)), 0.0, math.cos(math.radians(12.0))])
    # the model folds the beam at the origin (the tip), 17 um below the lever end's top face:
    # the 0.7 mm thick drawn beam cannot tell them apart
    assert np.linalg.norm(a["lever_end"]) < 0.02
    to_laser, to_mirror = a["laser"], a["mirror"]
    # incidence = reflection about the normal, and the three in one plane
    assert _angle(to_laser, normal) == pytest.approx(_angle(to_mirror, normal), abs=1e-9)
    assert np.dot(np.cross(to_laser, normal), to_mirror) == pytest.approx(0.0, abs=1e-9)
    # the stated distances along the beam
    assert np.linalg.norm(a["laser"]) == pytest.approx(38.0, rel=1e-12)
    assert np.linalg.norm(a["lens"]) == pytest.approx(22.0, rel=1e-12)
    assert np.linalg.norm(a["mirror"]) == pytest.approx(35.0, rel=1e-12)
    assert a["photodiode"] - a["mirror"] == pytest.approx([8.0, 0.0, 0.0])
    # the lens on the incident beam, between laser and lever
    assert np.cross(a["lens"], a["laser"]) == pytest.approx([0.0, 0.0, 0.0], abs=1e-12)
    assert obd.beam == ("laser", "lens", "lever_end", "mirror", "photodiode")


@pytest.mark.parametrize("key", list(INSTRUMENTS))
def test_every_part_comes_apart_and_is_named_once(key):
    inst = INSTRUMENTS[key]
    names = [p.name for p in inst.parts]
    assert len(set(names)) == len(names)
    assert set(inst.approach_parts) <= set(names)
    assert inst.lever[0] in names
    for p in inst.parts:
        assert p.explode_distance > 0.0
        assert np.linalg.norm(p.explode_direction) == pytest.approx(1.0, rel=1e-12)
        assert p.explode_direction * p.explode_distance == pytest.approx(
            np.asarray(p.explode_mm) * 1e-3, rel=1e-12)
        r = p.rotation
        assert r @ r.T == pytest.approx(np.eye(3), abs=1e-12)  # a rotation
        assert r @ [0.0, 0.0, 1.0] == pytest.approx(np.asarray(p.axis) /
                                                    np.linalg.norm(p.axis), abs=1e-12)
        assert all(s.kind in SHAPE_KINDS for s in p.shapes)
    # the tip touches the sample at the origin: the lever's part holds a cone pointing down
    carrier = next(p for p in inst.parts if p.name == inst.lever[0])
    tip = next(s for s in carrier.shapes if s.kind == "cone")
    apex = np.asarray(tip.at) + np.asarray(tip.axis) * tip.size[1] / 2
    assert carrier.rotation @ apex + carrier.position * 1e3 == pytest.approx([0, 0, 0],
                                                                            abs=1e-3)


def test_a_shape_of_an_unknown_kind_is_refused():
    with pytest.raises(ValueError, match="kind"):
        Shape("x", "torus", (1.0,), 0xffffff)
