"""Module (b)'s scale models against geometry and closed forms: the drawn lever is the exaggerated
end-load shape, the reflected beam obeys the law of reflection, the astigmatic spot has the beam
radii's ratio, the meter shows the output; a real viewer is updated in place and closed."""
import math

import numpy as np
import pytest

from afmsmiler.scenes.transducers import DEFAULTS, SCENE_UNIT, TransducerScene, lever_pose
from afmsmiler.transducers import (PRINCIPLES, AstigmaticDetection, OpticalBeamDeflection,
                                   PiezoAcoustic)
from tests.recording import Recorder



def _scene(model, value, mode=None):
    rec = Recorder()
    return TransducerScene(model.operate(value, mode), vis=rec, path="t", camera=False), rec


def test_drawn_lever_is_the_exaggerated_end_load_shape():
    model = OpticalBeamDeflection()
    pose = lever_pose(model.operate(500e-9))
    L = model.length / SCENE_UNIT
    u = pose.x / L
    # the tip at the largest input (2 um) is drawn at max_tip L; 500 nm is a quarter of it
    amplitude = DEFAULTS["max_tip"] * L * 0.25
    np.testing.assert_allclose(pose.z, amplitude * (3 * u ** 2 - u ** 3) / 2, rtol=1e-12, atol=1e-15)
    np.testing.assert_allclose(pose.slope, amplitude * 3 * (u - u ** 2 / 2) / L, rtol=1e-12,
                               atol=1e-15)
    # signal meter: erf(sqrt2 s / w) as a fraction of its value at the end of the range
    s = model.optical_path * math.tan(2 * 1.5 * 500e-9 / model.length)   # D tan(2 theta)
    s_max = model.optical_path * math.tan(2 * 1.5 * 2e-6 / model.length)
    w = model.spot_radius
    assert pose.output_fraction == pytest.approx(math.erf(math.sqrt(2) * s / w)
                                                 / math.erf(math.sqrt(2) * s_max / w), rel=1e-9)


def test_reflected_beam_obeys_the_law_of_reflection():
    model = OpticalBeamDeflection()
    scene, rec = _scene(model, 0.0)
    source = rec.log["/t/element/laser"]["transform"][:3, 3]
    h = model.thickness / SCENE_UNIT
    previous = None
    for z in (0.0, 1.5e-6, -0.7e-6):
        scene.update(model.operate(z))
        top = np.array([scene.pose.x[-1], 0.0, scene.pose.z[-1] + h / 2])
        n = np.array([-scene.pose.slope[-1], 0.0, 1.0])
        n /= np.linalg.norm(n)
        incoming = (source - top) / np.linalg.norm(source - top)
        outgoing = (scene.parts["spot"] - top) / np.linalg.norm(scene.parts["spot"] - top)
        # equal angles to the normal, on opposite sides of it, in one plane
        assert np.dot(incoming, n) == pytest.approx(np.dot(outgoing, n), rel=1e-12)
        assert np.cross(n, incoming)[1] * np.cross(n, outgoing)[1] < 0
        # the spot sits on the detector plane, and moves when the lever tilts
        centre, normal, _ = scene.parts["detector"]
        assert np.dot(scene.parts["spot"] - centre, normal) == pytest.approx(0.0, abs=1e-12)
        if previous is not None:
            assert np.linalg.norm(scene.parts["spot"] - previous) > 0.05
        previous = scene.parts["spot"].copy()
    bar = rec.log["/t/meter/bar"]["transform"]
    assert bar[2, 2] == pytest.approx(abs(scene.pose.output_fraction), rel=1e-12)


def test_astigmatic_spot_has_the_beam_radii_ratio():
    model = AstigmaticDetection()
    scene, rec = _scene(model, 0.8e-6)
    a, zr = model.astigmatic_distance / 2, math.pi * model.waist ** 2 / model.wavelength
    wx = math.sqrt(1 + ((2 * 0.8e-6 - a) / zr) ** 2)
    wy = math.sqrt(1 + ((2 * 0.8e-6 + a) / zr) ** 2)
    sx, sy = scene.parts["spot"]
    assert sy / sx == pytest.approx(wy / wx, rel=1e-12)
    t = rec.log["/t/element/spot"]["transform"]
    assert t[1, 1] / t[0, 0] == pytest.approx(wy / wx, rel=1e-12)


def test_base_barely_moves_at_resonance():
    model = PiezoAcoustic(quality_factor=50.0)
    scene, _ = _scene(model, 0.05)
    # at resonance the tip moves gamma Q = 1.566 * 50 times the base
    assert scene.parts["base_offset"] == pytest.approx(scene.pose.z[-1] / (1.566 * 50), rel=1e-3)


def test_principles_swap_their_elements_in_place():
    scene, rec = _scene(OpticalBeamDeflection(), 0.0)
    assert "/t/element/detector/q0" in rec.log and "/t/element/spot" in rec.log
    seen = set()
    for key, cls in PRINCIPLES.items():
        model = cls()
        for mode in model.MODES:
            scene.update(model.operate(model.input_quantity(mode).default, mode))
            assert scene.key == key
            elements = {k for k in rec.log if k.startswith("/t/element/")}
            seen |= elements | {k.rsplit("/", 1)[0] for k in elements}  # wires: one path each
            if key != "optical_beam_deflection":
                assert "/t/element/detector/q0" not in elements or key == "astigmatic"
    assert rec.log["/t/beam"]["n_objects"] == 1 + sum(len(c.MODES) for c in PRINCIPLES.values())
    assert {"/t/element/loop", "/t/element/resistor", "/t/element/heater", "/t/element/film",
            "/t/element/electrode", "/t/element/disk", "/t/element/shaker",
            "/t/element/heating_beam", "/t/element/fibre"} <= seen


def test_bad_input():
    scene, _ = _scene(OpticalBeamDeflection(), 0.0)
    with pytest.raises(TypeError, match="^operation must be"):
        scene.update(OpticalBeamDeflection())
    with pytest.raises(ValueError, match=r"^deflection must be in \[-2e-06, 2e-06\] m"):
        scene.update(OpticalBeamDeflection().operate(1.0))
    with pytest.raises(ValueError, match="^fraction must be in"):
        lever_pose(OpticalBeamDeflection().operate(0.0), fraction=2.0)
    with pytest.raises(ValueError, match="^n_length must be"):
        lever_pose(OpticalBeamDeflection().operate(0.0), 10**9)


def test_real_view_is_updated_in_place():
    scene = TransducerScene(OpticalBeamDeflection().operate(20e-9))
    view = scene.view
    scene.update(OpticalBeamDeflection().operate(-300e-9))
    scene.update(PiezoAcoustic().operate(0.1))
    assert scene.view is view and "<html" in view.static_html().lower()


def test_photodiode_spot_travels_as_many_spot_radii_as_the_model_says():
    """The drawing exaggerates the lever's tilt and shortens the optical path, so the spot is
    drawn to the same scale as its travel: travel / radius = s / w of the model (on average over
    the two ends of the range; the drawn tip's up-down motion adds +-12 %), and it never leaves
    the photodiode."""
    model = OpticalBeamDeflection()
    scene, rec = _scene(model, 0.0)
    centre, normal, rot = scene.parts["detector"]
    half = rec.log["/t/element/detector/q0"]["object"][0].lengths[0] / 0.96  # one quadrant
    ends = []
    for z in np.linspace(-2e-6, 2e-6, 9):
        scene.update(model.operate(z))
        a = scene.parts["spot_radius"]
        offset = scene.parts["spot"] - centre
        s = float(model.chain(np.array([z])).stage("spot_displacement").values[0])
        assert np.linalg.norm(offset) / a == pytest.approx(abs(s) / model.spot_radius, rel=0.15,
                                                           abs=1e-12)
        ends.append(np.linalg.norm(offset) / a * model.spot_radius / abs(s) if abs(z) == 2e-6
                    else None)
        assert np.all(np.abs((rot[:3, :3].T @ offset)[:2]) + a <= 2 * half)  # on the diode
    ends = [r for r in ends if r is not None]
    assert np.mean(ends) == pytest.approx(1.0, rel=1e-9)


@pytest.mark.parametrize("key", list(PRINCIPLES))
def test_camera_sees_every_part_of_every_principle(key):
    """The centre of every drawn object (lever, chip, meter and its label, lasers, detectors,
    magnets, ...) projects inside a 1200 x 800 view of the default camera, at both ends of the
    input range; meshcat's axes, which would pierce the lever, are hidden."""
    from afmsmiler.scenes.camera import camera_ndc
    model = PRINCIPLES[key]()
    q = model.input_quantity(None)
    rec = Recorder()
    scene = TransducerScene(model.operate(q.low), vis=rec, path="t")
    for value in (q.low, q.high):
        scene.update(model.operate(value))
        shift = rec.log["/t"]["transform"]  # the whole drawing, centred on the lever

        def world(key):  # compose the transforms from /t down to the node
            parts = key.split("/")[1:]
            t = np.eye(4)
            for i in range(1, len(parts) + 1):
                t = t @ np.asarray(rec.log.get("/" + "/".join(parts[:i]), {}).get(
                    "transform", np.eye(4)))
            return t[:3, 3]

        centres = [world(k) for k, v in rec.log.items()
                   if k.startswith("/t/") and "object" in v and v.get("visible", True)]
        centres.append(shift[:3, 3] + [scene.pose.x[-1], 0.0, scene.pose.z[-1]])  # the free end
        ndc = camera_ndc(np.array(centres), DEFAULTS["camera"], aspect=1.5)
        assert np.all(np.abs(ndc) <= 1.0), ndc
    assert rec.log["/Axes"]["visible"] is False


def test_scene_computes_no_physics(monkeypatch):
    # the scene drew from its own runs of the chain (two per update, two more per new optical
    # lever) and branched on "piezo_acoustic" for the mode shape: it now only draws an Operation
    from afmsmiler.transducers.base import Transducer
    ops = {key: cls().operate(cls().input_quantity().default) for key, cls in PRINCIPLES.items()}
    rec = Recorder()
    scene = TransducerScene(ops["optical_beam_deflection"], vis=rec, path="t", camera=False)

    def forbidden(*args, **kwargs):
        raise AssertionError("the scene ran the model")

    for name in ("chain", "respond", "sensitivity", "frequency_response", "operate"):
        monkeypatch.setattr(Transducer, name, forbidden)
    monkeypatch.setattr(PiezoAcoustic, "base_transfer", forbidden)
    monkeypatch.setattr(AstigmaticDetection, "spot_radii", forbidden)
    for op in ops.values():
        scene.update(op)
        assert scene.key == op.model.key
    import inspect

    import afmsmiler.scenes.transducers as module
    assert "piezo_acoustic" not in inspect.getsource(module.lever_pose)


def test_optical_lever_is_a_reusable_piece():
    # module (e)'s laser alignment draws the same laser, detector, beams and spot under its path
    from afmsmiler.scenes.transducers import OpticalLever
    rec = Recorder()
    lever = OpticalLever(rec["alignment"], source=[-1.0, 0.0, 2.0], target=[1.0, 0.0, 0.0],
                         detector_distance=2.0)
    lever.draw_detector(0.6)
    # a flat lever: the beam leaves at the mirror angle and hits the detector's centre
    hit = lever.move([1.0, 0.0, 0.0], 0.0, 0.05)
    np.testing.assert_allclose(hit, lever.detector, atol=1e-12)
    np.testing.assert_allclose(lever.detector, [1.0 + 2.0 / math.sqrt(2), 0.0,
                                                2.0 / math.sqrt(2)], rtol=1e-12)
    # tilting the mirror by a turns the beam by 2 a: the spot moves by ~ 2 a d on the detector
    a = 1e-3
    moved = lever.hit([1.0, 0.0, 0.0], math.tan(a))
    assert np.linalg.norm(moved - lever.detector) == pytest.approx(2 * a * 2.0, rel=1e-2)
    assert {"/alignment/laser", "/alignment/detector/q0", "/alignment/spot"} <= set(rec.log)
    with pytest.raises(ValueError, match="^target must differ"):
        OpticalLever(rec["x"], source=[0, 0, 1], target=[0, 0, 1])
    with pytest.raises(ValueError, match="^spot_radius must be"):
        lever.move([1.0, 0.0, 0.0], 0.0, -1.0)
    with pytest.raises(ValueError, match="^slope .* away from the detector"):
        lever.hit([1.0, 0.0, 0.0], 1e6)      # a mirror turned on its side
