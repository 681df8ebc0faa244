"""The OBD head's laser alignment, against independent sources.

* The sum is the closed-form Gaussian overlap: scipy's dblquad of the spot's intensity over the
  lever's rectangle (and of the detector spot over the photodiode) gives the same.
* Where the optimum is: the sum's largest value is at the lever's centre (a plateau along the
  lever, found again by Nelder-Mead), while the signal per nm is largest in the end region,
  where the independent merit int_0^L g(x - m) theta(x) dx (module (a)'s slope, scipy's quad)
  has its maximum.
* Symmetry: both differences vanish with the spot at the photodiode's centre, and are odd in
  the photodiode's offset.
* The vertical signal's sensitivity is module (b)'s optical lever's, sqrt(8/pi) / w * 3 D / L,
  whose end slope 3 z / (2 L) sympy derives here from the beam equation.
* An optimiser drives the knobs from misaligned starts (sum near zero) to alignment: from every
  corner of the allowed mount (offsets along and across, the chip's tilt) with the knobs at the
  far ends of their travel, and (slow) from 32 starts of a scrambled Sobol sequence over the whole
  allowed mount and knob ranges; the reflection's reach is checked by the geometry
  v = -X + D tan(2 tilt_error). Where the photodiode cannot reach it, the procedure stops with the
  spot on the lever and names the distance.
* Errors: a knob beyond its travel or an unknown knob names it, its value and the travel.
"""
import math

import numpy as np
import pytest
import sympy as sp
from scipy.integrate import dblquad, quad
from scipy.optimize import minimize, minimize_scalar

from afmsmiler.cantilever import Cantilever
from afmsmiler.instrument import (HEAD, KNOBS, TOLERANCES, Alignment, OpticalHead, Signals,
                                  align)
from afmsmiler.transducers import OpticalBeamDeflection

TURN = 2 * math.pi


def _gauss(x, m, w):
    return math.exp(-2 * (x - m) ** 2 / w ** 2)


def place(head, mx, my):
    """Turn the laser knobs so the spot's centre is at (mx, my) on the lever (Newton steps)."""
    def at(k):
        s = head.set(laser_x=k[0], laser_y=k[1])
        return np.array(s.spot_on_lever) - [mx, my]
    k = np.zeros(2)
    for _ in range(20):
        miss = at(k)
        if np.abs(miss).max() < 1e-13:
            break
        jac = np.column_stack([(at(k + step) - miss) / 1e-3 for step in np.eye(2) * 1e-3])
        k = k - np.linalg.solve(jac, miss)
    assert np.abs(at(k)).max() < 1e-12
    return centre_detector(head)


def centre_detector(head):
    """Move the photodiode's centre exactly onto the lever's reflected spot (no optimiser)."""
    s = head.signals()
    pitch = head.detector_screw_pitch
    v = s.spot_on_detector[0] + pitch * s.knobs["detector_vertical"] / TURN
    lat = s.spot_on_detector[1] + pitch * s.knobs["detector_lateral"] / TURN
    return head.set(detector_vertical=v / pitch * TURN, detector_lateral=lat / pitch * TURN)


def overlap_dblquad(head, mx, my):
    """Share of the spot on the lever: dblquad of the elliptical Gaussian over the rectangle."""
    lever = head.lever
    wx, wy = head.waist / math.cos(head.holder_tilt), head.waist
    val = dblquad(lambda y, x: _gauss(x, mx, wx) * _gauss(y, my, wy), 0.0, lever.length,
                  -lever.width / 2, lever.width / 2, epsabs=1e-24, epsrel=1e-11)[0]
    return val / (math.pi / 2 * wx * wy)


def capture_dblquad(head):
    """Share of a centred detector spot on the photodiode's square (dblquad)."""
    a, w = head.detector_size / 2, head.detector_spot_radius
    val = dblquad(lambda y, x: _gauss(x, 0.0, w) * _gauss(y, 0.0, w), -a, a, -a, a,
                  epsrel=1e-12)[0]
    return val / (math.pi / 2 * w * w)


def display_gain(head):
    """Sum in V per unit overlap and capture: G R P reflectance."""
    return head.transimpedance_gain * head.responsivity * head.laser_power * head.reflectance


def slope_weight(head, mx):
    """Module (a)'s slope averaged over the lit lever, over its end slope (scipy quad)."""
    lever = head.lever
    wx = head.waist / math.cos(head.holder_tilt)
    force = lever.force_for_deflection(10e-9)
    end = lever.slope(lever.length, force)
    num = quad(lambda x: _gauss(x, mx, wx) * lever.slope(x, force) / end, 0.0, lever.length,
               points=[min(max(mx, 0.0), lever.length)], epsabs=1e-20, epsrel=1e-12)[0]
    den = quad(lambda x: _gauss(x, mx, wx), 0.0, lever.length,
               points=[min(max(mx, 0.0), lever.length)], epsabs=1e-20, epsrel=1e-12)[0]
    return num / den


@pytest.fixture
def head():
    return OpticalHead()


# -- the sum ----------------------------------------------------------------------------------
@pytest.mark.parametrize("mx, my", [(225e-6, 0.0), (430e-6, 0.0), (450e-6, 0.0), (300e-6, 25e-6),
                                    (440e-6, -30e-6), (10e-6, 5e-6), (480e-6, 0.0)])
def test_sum_is_the_closed_form_gaussian_overlap(head, mx, my):
    s = place(head, mx, my)
    expected = overlap_dblquad(head, mx, my)
    assert s.lever_fraction == pytest.approx(expected, rel=1e-7, abs=1e-13)
    assert s.reflected_fraction == pytest.approx(head.reflectance * expected, rel=1e-7,
                                                 abs=1e-13)
    assert s.sum == pytest.approx(display_gain(head) * expected * capture_dblquad(head),
                                  rel=1e-7, abs=1e-12)
    assert sum(s.quadrants) * head.transimpedance_gain * head.responsivity == \
        pytest.approx(s.sum, rel=1e-12)


def test_best_sum_is_the_largest_at_the_lever_centre(head):
    lever = head.lever
    best = display_gain(head) * overlap_dblquad(head, lever.length / 2, 0.0) \
        * capture_dblquad(head)
    assert head.best_sum == pytest.approx(best, rel=1e-7)
    # an optimiser started on the lever finds nothing larger
    place(head, 300e-6, 10e-6)

    def minus_sum(k):
        return -head.set(laser_x=k[0], laser_y=k[1]).sum
    found = minimize(minus_sum, [head.knobs["laser_x"], head.knobs["laser_y"]],
                     method="Nelder-Mead", options={"xatol": 1e-6, "fatol": 1e-12})
    assert -found.fun <= head.best_sum * (1 + 1e-9)
    assert -found.fun >= head.best_sum * (1 - 1e-6)
    # the sum is a plateau along the lever: within 1e-4 of the best from 2 spot radii inside
    # either end, and it halves with the spot's centre on the free end
    for mx in np.linspace(3 * head.waist, lever.length - 3 * head.waist, 7):
        assert place(head, mx, 0.0).sum == pytest.approx(head.best_sum, rel=1e-4)
    assert place(head, lever.length, 0.0).sum == pytest.approx(head.best_sum / 2, rel=1e-3)


def test_signal_per_deflection_is_largest_in_the_end_region(head):
    """The end region: where int_0^L g(x - m) theta(x) dx is largest (independent quad)."""
    lever = head.lever
    wx = head.waist / math.cos(head.holder_tilt)

    def merit(mx):  # reflected power x mean slope, in units of the end slope
        return -quad(lambda x: _gauss(x, mx, wx) * (2 * x / lever.length
                                                    - (x / lever.length) ** 2),
                     0.0, lever.length, points=[min(mx, lever.length)], epsrel=1e-12)[0]
    ref = minimize_scalar(merit, bounds=(lever.length - 5 * wx, lever.length), method="bounded",
                          options={"xatol": 1e-10}).x

    def minus_sensitivity(mx):
        place(head, mx, 0.0)
        return -head.sensitivity(normalised=False)
    got = minimize_scalar(minus_sensitivity, bounds=(lever.length - 5 * wx, lever.length),
                          method="bounded", options={"xatol": 1e-9}).x
    assert got == pytest.approx(ref, abs=0.5e-6)
    # 1.6 spot radii inside the free end (the docstring's 28 um), the sum 99.9 % of its best
    assert (lever.length - ref) / wx == pytest.approx(1.6, abs=0.05)
    assert place(head, ref, 0.0).sum > 0.999 * head.best_sum
    # align() stops where the sum is 98 % of its plateau: within 2 % of the best signal per nm
    fresh = OpticalHead()
    align(fresh)
    assert merit(fresh.signals().spot_on_lever[0]) / merit(ref) > 0.98


# -- the differences ---------------------------------------------------------------------------
@pytest.mark.parametrize("mx, my, z", [(430e-6, 0.0, 0.0), (300e-6, 10e-6, 0.0),
                                       (440e-6, -5e-6, 0.0)])
def test_differences_vanish_at_the_photodiode_centre(head, mx, my, z):
    s = place(head, mx, my)
    assert abs(s.vertical_normalised) < 1e-12 and abs(s.lateral_normalised) < 1e-12
    assert abs(s.vertical) < 1e-12 * s.sum and abs(s.lateral) < 1e-12 * s.sum
    a, b, c, d = s.quadrants
    assert a == pytest.approx(b) == pytest.approx(c) == pytest.approx(d)
    # odd in the photodiode's offset (mirror symmetry of the Gaussian and the quadrants)
    k = dict(head.knobs)
    for knob, name in (("detector_vertical", "vertical"), ("detector_lateral", "lateral")):
        up = head.set(**{knob: k[knob] + 0.1}).__getattribute__(name)
        down = head.set(**{knob: k[knob] - 0.1}).__getattribute__(name)
        head.set(**k)
        assert up == pytest.approx(-down, rel=1e-9) and abs(up) > 1e-3


def test_a_deflection_moves_the_spot_up_by_module_b_optical_lever(head):
    s0 = place(head, 430e-6, 0.0)
    z = 50e-9
    s1 = head.signals(deflection=z)
    lever = head.lever
    theta = lever.slope(lever.length, lever.force_for_deflection(z)) * slope_weight(head, 430e-6)
    d = head.optical_path
    expected = d * (math.tan(2 * (head.tilt_error + theta)) - math.tan(2 * head.tilt_error))
    assert s1.spot_on_detector[0] - s0.spot_on_detector[0] == pytest.approx(expected, rel=1e-7)
    assert s1.vertical > 0 and s1.vertical_normalised > 0  # tip up: towards A + B
    assert s1.spot_on_detector[1] == pytest.approx(s0.spot_on_detector[1], abs=1e-15)


def _exact_detector_coordinate(x_beam, tilt, tilt_error, distance):
    """Where the reflected ray meets the photodiode, by exact 2D ray tracing (x-z plane).

    The incident ray comes down (0, -1) at height x_beam; the lever's surface through the origin
    is tilted by ``tilt`` (its free end towards +x) plus ``tilt_error``; the photodiode is the
    plane normal to the nominal reflected direction (no error) at ``distance``. Returns the
    coordinate towards the top quadrants (where a tip-up rotation of the surface sends the ray).
    """
    def reflect(angle):
        n = np.array([-math.sin(angle), math.cos(angle)])
        d = np.array([0.0, -1.0])
        return d - 2 * (d @ n) * n
    r0 = reflect(tilt)
    r = reflect(tilt + tilt_error)
    hit = np.array([x_beam, x_beam * math.tan(tilt + tilt_error)])  # on the surface
    centre = distance * r0
    t = (centre - hit) @ r0 / (r @ r0)
    point = hit + t * r - centre
    dr = reflect(tilt + 1e-7) - r0                                   # a tip-up rotation
    top = dr / np.linalg.norm(dr)
    return float(point @ top)


@pytest.mark.parametrize("tilt_error", [0.0, math.radians(1), math.radians(-2)])
def test_spot_on_detector_matches_exact_ray_tracing(tilt_error):
    """v = -X + D tan(2 tilt_error): the spot's shift across the chip and the lever's rotation."""
    head = OpticalHead(tilt_error=tilt_error)
    alpha = head.holder_tilt
    coords = []
    for mx in (200e-6, 430e-6, 445e-6):
        s = place(head, mx, 0.0)
        dv = head.detector_screw_pitch * s.knobs["detector_vertical"] / TURN
        x_beam = (mx - head.lever.length) * math.cos(alpha) + head.mount_offset_x
        got = s.spot_on_detector[0] + dv
        # exact for a lever at its nominal tilt; otherwise within X tan(alpha) sin(2 delta)
        tol = 1e-12 + 2 * abs(x_beam) * abs(math.tan(alpha) * math.sin(2 * tilt_error))
        for sign in (-1, 1):  # the free end down towards the sample, or up: the same
            exact = _exact_detector_coordinate(x_beam, sign * alpha, tilt_error,
                                               head.optical_path)
            assert got == pytest.approx(exact, abs=tol)
        coords.append(got)
    assert coords[0] > coords[1]  # towards the free end, the spot goes down on the detector


def _sympy_end_slope_over_deflection():
    """theta(L) / z(L) of a clamped lever under an end force, from E J z'''' = 0 (sympy)."""
    x, length, force, ej = sp.symbols("x L F EJ", positive=True)
    c = sp.symbols("c0:4")
    z = sum(ci * x ** i for i, ci in enumerate(c))
    eqs = [z.subs(x, 0), sp.diff(z, x).subs(x, 0), sp.diff(z, x, 2).subs(x, length),
           (ej * sp.diff(z, x, 3)).subs(x, length) + force]
    z = z.subs(sp.solve(eqs, c))
    ratio = sp.simplify(sp.diff(z, x).subs(x, length) / z.subs(x, length))
    assert ratio == 3 / (2 * length)
    return sp.lambdify(length, ratio)


def test_vertical_sensitivity_is_module_b_optical_lever():
    """A small spot on the free end: d(vertical / sum)/dz = sqrt(8/pi) / w(D) * 2 D * 3 / (2 L)."""
    end_ratio = _sympy_end_slope_over_deflection()
    head = OpticalHead(beam_radius=2e-3, focal_length=5e-3, optical_path=5e-3,
                       detector_size=20e-3, tilt_error=0.0, mount_offset_x=0.0,
                       mount_offset_y=0.0)
    place(head, head.lever.length - 3 * head.waist, 0.0)
    d, w, length = head.optical_path, head.detector_spot_radius, head.lever.length
    expected = math.sqrt(2) * 2 / math.sqrt(math.pi) / w * 2 * d * end_ratio(length)
    assert head.sensitivity() == pytest.approx(expected, rel=1e-4)
    obd = OpticalBeamDeflection(optical_path=d, spot_radius=w, length=length)
    assert head.sensitivity() == pytest.approx(obd.sensitivity(), rel=1e-4)


def test_sensitivity_of_the_default_head_is_module_b_weighted_by_the_lit_slope(head):
    """Any spot: module (b)'s sensitivity x the lit part's mean slope x sec^2(2 tilt_error)."""
    for mx in (300e-6, 430e-6):
        place(head, mx, 0.0)
        expected = (head.obd.sensitivity() * slope_weight(head, mx)
                    / math.cos(2 * head.tilt_error) ** 2)
        assert head.sensitivity() == pytest.approx(expected, rel=1e-6)


# -- the optimiser -----------------------------------------------------------------------------
STARTS = [
    dict(params={}, knobs={}),
    dict(params=dict(mount_offset_x=-1.2e-3, mount_offset_y=-0.6e-3,
                     tilt_error=math.radians(-2)),
         knobs=dict(laser_x=3 * TURN, detector_lateral=-4 * TURN)),
    dict(params=dict(tilt_error=math.radians(2.5)),
         knobs=dict(laser_x=-4 * TURN, laser_y=3 * TURN, detector_vertical=5 * TURN)),
]


def _assert_aligned_at_the_optimum(head, run):
    """The verdict, and the optimum checked independently (dblquad overlaps, the geometry)."""
    s = head.signals()
    assert run.alignment.ok, run.alignment.reason
    assert bool(head.aligned()) and head.aligned().reason == "aligned"
    lever = head.lever
    best = display_gain(head) * overlap_dblquad(head, lever.length / 2, 0.0) \
        * capture_dblquad(head)
    assert s.sum == pytest.approx(best, rel=0.03)            # at its optimum within 3 %
    assert s.sum <= best * (1 + 1e-9)
    assert abs(s.vertical_normalised) < 1e-6 and abs(s.lateral_normalised) < 1e-6
    gap = lever.length - s.spot_on_lever[0]
    assert 0 < gap < TOLERANCES["end_distance"].default    # in the end region
    assert abs(s.spot_on_lever[1]) < 0.05 * lever.width    # centred across
    assert [name for name, _ in run.steps] == ["search", "photodiode", "across", "along",
                                               "across", "photodiode"]
    assert run.evaluations < 10_000
    for knob, value in head.knobs.items():
        assert KNOBS[knob].low <= value <= KNOBS[knob].high


@pytest.mark.parametrize("start", STARTS, ids=["as-mounted", "offset-chip", "knobs-astray"])
def test_align_drives_the_knobs_from_a_misaligned_start(start):
    head = OpticalHead(**start["params"])
    s0 = head.set(**start["knobs"])
    assert s0.sum < 1e-3 * head.best_sum          # off the lever: nothing to follow
    assert not head.aligned()
    _assert_aligned_at_the_optimum(head, align(head))


_MOUNT = ("mount_offset_x", "mount_offset_y", "tilt_error")


def _corner_starts():
    """Each corner of the allowed mount (offsets along and across, the chip's tilt), the knobs
    turned the other way to their travel's ends: the farthest starts there are."""
    starts = []
    for signs in np.ndindex(2, 2, 2):
        params = {n: (HEAD[n].high if b else HEAD[n].low) for n, b in zip(_MOUNT, signs)}
        knobs = {n: (KNOBS[n].low if params[m] > 0 else KNOBS[n].high) for n, m in (
            ("laser_x", "mount_offset_x"), ("laser_y", "mount_offset_y"),
            ("detector_vertical", "tilt_error"), ("detector_lateral", "mount_offset_y"))}
        starts.append((params, knobs))
    return starts


def _spread_starts(count, seed):
    """``count`` starts spread over the whole allowed mount and knob ranges (a scrambled Sobol
    sequence: every region of the seven-dimensional box gets its share)."""
    from scipy.stats import qmc
    names = (*_MOUNT, *KNOBS)
    table = {**HEAD, **KNOBS}
    lows, highs = [table[n].low for n in names], [table[n].high for n in names]
    points = qmc.scale(qmc.Sobol(len(names), seed=seed).random(count), lows, highs)
    return [({n: float(v) for n, v in zip(_MOUNT, row[:3])},
             {n: float(v) for n, v in zip(KNOBS, row[3:])}) for row in points]


def _reflection_reachable(params, optical_path=HEAD["optical_path"].default):
    """Independent geometry: the reflection of the lever's end region falls D tan(2 tilt_error)
    from the axis, shifted back by the spot's offset X ~ mount_offset_x (a translated incident
    beam moves the reflected one by X the other way); the photodiode knobs reach it."""
    v = -params["mount_offset_x"] + optical_path * math.tan(2 * params["tilt_error"])
    reach = HEAD["detector_screw_pitch"].default * KNOBS["detector_vertical"].high / TURN
    return abs(v) < reach


@pytest.mark.parametrize("params, knobs", _corner_starts(),
                         ids=[f"corner{i}" for i in range(8)])
def test_align_from_every_corner_of_the_allowed_mount(params, knobs):
    """Off the axis sideways at the mount's limit (the mirror's tilts couple: walking along
    moves the spot across) and tilted at the limit (the reflection far off the photodiode)."""
    assert _reflection_reachable(params)
    head = OpticalHead(**params)
    head.set(**knobs)
    _assert_aligned_at_the_optimum(head, align(head))


@pytest.mark.slow
@pytest.mark.parametrize("params, knobs", _spread_starts(32, seed=5),
                         ids=[f"start{i}" for i in range(32)])
def test_align_from_starts_spread_over_the_allowed_ranges(params, knobs):
    head = OpticalHead(**params)
    head.set(**knobs)
    _assert_aligned_at_the_optimum(head, align(head))


def test_align_says_when_the_photodiode_cannot_reach_the_reflection():
    """A long optical path and a tilted chip throw the reflection beyond the photodiode's reach:
    the procedure stops with the spot on the lever and says so, naming the reach."""
    tilt, path = math.radians(5), 0.1
    head = OpticalHead(optical_path=path, tilt_error=tilt)
    mount = dict(mount_offset_x=head.mount_offset_x, tilt_error=tilt)
    assert _reflection_reachable(mount) and not _reflection_reachable(mount, path)
    run = align(head)
    s = head.signals()
    assert run.steps[-1][0] == "photodiode: cannot centre it on the reflection"
    assert s.lever_fraction > 0.25 * head.best_overlap      # the laser stays on the lever
    assert not run.alignment
    reason = run.alignment.reason
    assert "put the spot on the lever" not in reason
    assert "beyond the 8 mm that detector_vertical's travel reaches" in reason
    assert "tilt_error 5 deg" in reason
    # the distance it names is the geometry's: D tan(2 tilt) less the spot's offset X
    x_spot = head.mount_offset_x - (head.lever.length - s.spot_on_lever[0]) * math.cos(
        head.holder_tilt)
    expected = path * math.tan(2 * tilt) - x_spot
    assert f"{expected * 1e3:.3g} mm from the photodiode's centre" in reason


def test_aligned_says_what_is_wrong(head):
    verdict = head.aligned()
    assert isinstance(verdict, Alignment) and not verdict
    assert any("sum" in r for r in verdict.reasons)
    assert any("free end" in r and "laser_x" in r for r in verdict.reasons)
    place(head, 430e-6, 0.0)
    assert head.aligned()
    head.turn("detector_vertical", 0.2)
    verdict = head.aligned()
    assert not verdict and "detector_vertical" in verdict.reason
    assert head.aligned(max_difference=1.0)


def test_a_reflecting_chip_fools_the_sum_but_not_the_check():
    head = OpticalHead(chip_reflectance=1.0)
    s = place(head, -1e-3, 0.0)             # on the chip's body, 1 mm from the lever's base
    assert s.lever_fraction == 0.0
    assert s.sum >= head.best_sum           # as bright as the lever, or brighter
    verdict = head.aligned()
    assert not verdict and "free end" in verdict.reason


# -- the API and its errors --------------------------------------------------------------------
def test_tables_describe_every_knob_with_its_travel():
    assert set(KNOBS) == {"laser_x", "laser_y", "detector_vertical", "detector_lateral"}
    for p in KNOBS.values():
        assert p.unit == "rad" and p.display_unit == "turn"
        assert math.isfinite(p.low) and math.isfinite(p.high) and p.low < p.default < p.high
    assert KNOBS["laser_x"].to_si(0.5) == pytest.approx(math.pi)
    assert KNOBS["laser_x"].to_display(KNOBS["laser_x"].high) == pytest.approx(5.0)
    for table in (KNOBS, HEAD, TOLERANCES):
        with pytest.raises(TypeError):
            table["laser_x"] = None
    assert OpticalHead().parameters == {n: p.default for n, p in HEAD.items()}


def test_turn_is_relative_and_set_absolute(head):
    head.turn("laser_x", KNOBS["laser_x"].to_si(0.5))
    s = head.turn("laser_x", KNOBS["laser_x"].to_si(0.5))
    assert head.knobs["laser_x"] == pytest.approx(TURN)
    assert isinstance(s, Signals) and s.knobs["laser_x"] == pytest.approx(TURN)
    assert head.set(laser_x=TURN) == s


def test_readout_shows_the_display(head):
    s = place(head, 430e-6, 0.0)
    text = s.readout()
    assert text.startswith(f"SUM {s.sum:.2f} V") and "VERT 0.000 V" in text
    assert "HORZ" in text


def test_knob_beyond_its_travel_names_it_its_value_and_the_travel(head):
    head.set(laser_x=4 * TURN)
    with pytest.raises(ValueError) as err:
        head.turn("laser_x", 2 * TURN)
    msg = str(err.value)
    assert "laser_x" in msg and "travel" in msg and "[-5, 5] turn" in msg and "6 turn" in msg
    assert "angle" in msg and "2 turn" in msg    # the campaign: turn() names its argument
    assert head.knobs["laser_x"] == pytest.approx(4 * TURN)   # left where it was
    with pytest.raises(ValueError, match=r"detector_vertical.*\[-16, 16\] turn.*-17 turn"):
        head.set(detector_vertical=-17 * TURN)
    with pytest.raises(ValueError, match="laser_y"):
        head.set(laser_x=0.0, laser_y=float("nan"))
    assert head.knobs["laser_x"] == pytest.approx(4 * TURN)   # nothing moved


def test_unknown_knob_names_it_and_the_knobs(head):
    with pytest.raises(ValueError, match=r"knob.*laser_x.*'focus'"):
        head.turn("focus", 1.0)
    with pytest.raises(ValueError, match=r"knob.*'focus'"):
        head.set(focus=1.0)
    with pytest.raises(TypeError, match="knob"):
        head.turn(3, 1.0)


@pytest.mark.parametrize("call, error, name", [
    (lambda: OpticalHead(focal_length=-1.0), ValueError, "focal_length"),
    (lambda: OpticalHead(tilt_error=1.0), ValueError, "tilt_error"),
    (lambda: OpticalHead(colour="red"), TypeError, "colour"),
    (lambda: OpticalHead(lever="silicon"), TypeError, "lever"),
    (lambda: OpticalHead().signals(deflection=1e-3), ValueError, "deflection"),
    (lambda: OpticalHead().aligned(min_sum_fraction=2.0), ValueError, "min_sum_fraction"),
    (lambda: OpticalHead().aligned(end_distance=-1.0), ValueError, "end_distance"),
    (lambda: OpticalHead().sensitivity(normalised=1), TypeError, "normalised"),
    (lambda: OpticalHead().turn("laser_x", float("inf")), ValueError, "angle"),
    (lambda: align("head"), TypeError, "head"),
    (lambda: align(OpticalHead(), end_margin=0.7), ValueError, "end_margin"),
])
def test_bad_inputs_name_the_parameter(call, error, name):
    with pytest.raises(error, match=name):
        call()


def test_another_lever_from_module_a():
    lever = Cantilever.from_material("silicon", length=125e-6, width=30e-6, thickness=4e-6)
    head = OpticalHead(lever, mount_offset_x=0.3e-3)
    run = align(head)
    assert run.alignment.ok, run.alignment.reason
    assert head.signals().sum == pytest.approx(head.best_sum, rel=0.03)


def test_every_knob_and_head_parameter_makes_a_slider():
    """The walkthrough builds its sliders with the one factory, from these tables."""
    from afmsmiler.ui.controls import control
    for p in (*KNOBS.values(), *HEAD.values(), *TOLERANCES.values()):
        w = control(p)
        assert w.description == p.title
        assert p.check(p.to_si(w.value)) == pytest.approx(p.default, rel=1e-12, abs=1e-15)


def test_the_search_is_bounded():
    """A tiny lever would need a finer raster than MAX_SEARCH_POINTS allows: refused, named."""
    from afmsmiler.instrument import MAX_SEARCH_POINTS
    tiny = Cantilever.from_material("silicon", length=20e-6, width=5e-6, thickness=1e-6)
    with pytest.raises(ValueError, match=rf"search.*at most {MAX_SEARCH_POINTS}"):
        align(OpticalHead(tiny))
