"""Lateral force microscopy: torsion, lateral signal, friction loops and maps, the scanner mode.

Independent sources: the closed-form ratio k_t / k = 2 (L / h)^2 / (3 (1 + nu)) of a thin
rectangular lever (Saint-Venant torsion over Euler-Bernoulli bending, k from module (a)) and
numbers worked by hand, a force balance on a tilted contact solved with
numpy.linalg (Ogletree, Carpick and Salmeron, Rev. Sci. Instrum. 67, 3298 (1996)), the
parallelogram friction loop of a flat sample, and the friction coefficients put into the
synthetic sample.
"""
import math

import numpy as np
import pytest

from afmsmiler.cantilever import Cantilever
from afmsmiler.imaging.scanner import ScanSettings, scan
from afmsmiler.materials import MATERIALS
from afmsmiler.modes import lateral
from afmsmiler.modes.lateral import (FrictionLoop, LateralForceMode, LateralLever,
                                     friction_loop, friction_sample, friction_scan,
                                     lateral_force)
from afmsmiler.samples import Sample
from afmsmiler.transducers.optical import OpticalBeamDeflection

LEVER = Cantilever.from_material("silicon", length=450e-6, width=50e-6, thickness=2e-6)
F_N = 20e-9


# -- torsion and the photodiode --------------------------------------------------------------
def test_shear_modulus_of_isotropic_silicon():
    si = MATERIALS["silicon"]
    assert lateral.shear_modulus("silicon") == pytest.approx(
        si.youngs_modulus / (2 * (1 + si.poisson_ratio)))
    assert lateral.SHEAR_MODULUS.default == pytest.approx(lateral.shear_modulus("silicon"))


@pytest.mark.parametrize("tip_height", [5e-6, 15e-6])
def test_torsional_spring_constant_against_bending(tip_height):
    """k_t / k = 4 G L^2 / (3 E h^2) = 2 (L / h)^2 / (3 (1 + nu)) with k = E w t^3 / (4 L^3)."""
    nu = MATERIALS["silicon"].poisson_ratio
    lat = LateralLever(LEVER, tip_height, lateral.shear_modulus("silicon"))
    ratio = 2 * (LEVER.length / tip_height) ** 2 / (3 * (1 + nu))
    assert lat.spring_constant / LEVER.spring_constant == pytest.approx(ratio, rel=1e-12)
    # numbers by hand: G w t^3 / (3 L) = 79.42e9 * 50e-6 * 8e-18 / 1.35e-3
    assert lat.torsional_stiffness == pytest.approx(2.3531e-8, rel=1e-4)


def test_twist_and_apex_displacement():
    lat = LateralLever(LEVER, 15e-6)
    f = 5e-9
    # the apex moves sideways by h phi = F / k_t
    assert lat.twist(f) * lat.tip_height == pytest.approx(f / lat.spring_constant, rel=1e-12)
    assert np.allclose(lat.twist([f, -f]), [lat.twist(f), -lat.twist(f)])


def test_a_lever_of_the_same_g_is_twisted_as_it_is_and_another_g_gives_a_copy():
    # a Lever whose G is the one asked for carries the torsion itself, so its frame model is
    # solved once per lever however many LateralLevers a panel makes of it
    from afmsmiler.planform import Lever
    body = Lever.rectangular("silicon", 450e-6, 50e-6, 2e-6)
    first = LateralLever(body)
    assert first.body is body and LateralLever(body).body is body
    assert first.torsional_stiffness == body.torsional_stiffness
    # another G: a copy with it, whose k_phi scales as G (Saint-Venant: G w t^3 / (3 L))
    other = LateralLever(body, shear_modulus=body.shear_modulus / 2)
    assert other.body is not body and other.body.shear_modulus == body.shear_modulus / 2
    assert other.torsional_stiffness == pytest.approx(body.torsional_stiffness / 2, rel=1e-9)


def test_lateral_signal_is_the_optical_lever_turned():
    optics = OpticalBeamDeflection(optical_path=30e-3, spot_radius=0.5e-3)
    lat = LateralLever(LEVER, 15e-6, optics=optics)
    f = np.linspace(-50e-9, 50e-9, 11)
    phi = f * lat.tip_height / lat.torsional_stiffness
    from scipy.special import erf
    expected = erf(math.sqrt(2) * 30e-3 * np.tan(2 * phi) / 0.5e-3)
    assert np.allclose(lat.signal(f), expected, rtol=1e-12, atol=0)
    # small-signal slope sqrt(8 / pi) / w * 2 D * h / k_phi, odd in F
    slope = math.sqrt(8 / math.pi) / 0.5e-3 * 2 * 30e-3 * lat.tip_height / lat.torsional_stiffness
    assert lat.signal(1e-12) / 1e-12 == pytest.approx(slope, rel=1e-6)
    assert lat.signal(-3e-9) == pytest.approx(-lat.signal(3e-9))


# -- the lateral force law -------------------------------------------------------------------
def wedge_by_force_balance(theta, mu, s, load):
    """Solve for the contact normal force N and the lever's lateral force T on a tilted
    contact: lever (T, -load), normal N (-sin, cos), friction mu N opposing the motion s."""
    n = np.array([-math.sin(theta), math.cos(theta)])
    along = np.array([math.cos(theta), math.sin(theta)])
    # T e_x + N n - s mu N along = (0, load)
    a = np.array([[1.0, n[0] - s * mu * along[0]], [0.0, n[1] - s * mu * along[1]]])
    t, _ = np.linalg.solve(a, [0.0, load])
    return t


@pytest.mark.parametrize("theta", [-0.3, 0.0, 0.1, 0.4])
@pytest.mark.parametrize("mu", [0.0, 0.2, 0.8])
@pytest.mark.parametrize("s", [1, -1])
def test_wedge_model_is_the_force_balance(theta, mu, s):
    got = lateral_force(theta, mu, s, normal_force=F_N, model="wedge")
    assert got == pytest.approx(wedge_by_force_balance(theta, mu, s, F_N), rel=1e-12, abs=1e-24)


def test_linear_model_and_its_symmetry():
    theta, mu = np.radians([-10.0, 0.0, 5.0]), np.array([0.1, 0.3, 0.5])
    t = lateral_force(theta, mu, 1, normal_force=F_N)
    r = lateral_force(theta, mu, -1, normal_force=F_N)
    assert np.allclose((t - r) / 2, mu * F_N, rtol=1e-12)  # friction flips sign
    assert np.allclose((t + r) / 2, F_N * np.tan(theta), rtol=1e-12, atol=1e-30)  # slope does not
    # the wedge reduces to it for small angles and friction
    small = lateral_force(1e-3, 1e-3, 1, normal_force=F_N, model="wedge")
    assert small == pytest.approx(lateral_force(1e-3, 1e-3, 1, normal_force=F_N), rel=1e-5)


def test_wedge_friction_map_leaks_at_second_order():
    theta, mu = 0.2, 0.3
    t = lateral_force(theta, mu, 1, normal_force=F_N, model="wedge")
    r = lateral_force(theta, mu, -1, normal_force=F_N, model="wedge")
    tan2 = math.tan(theta) ** 2
    assert (t - r) / 2 == pytest.approx(mu * F_N * (1 + tan2) / (1 - mu ** 2 * tan2), rel=1e-12)


# -- friction loops --------------------------------------------------------------------------
def test_flat_loop_is_the_parallelogram():
    mu, k, px, n = 0.25, 0.5, 1e-9, 201
    loop = friction_loop(np.zeros(n), mu, px, normal_force=F_N, lateral_stiffness=k)
    f = mu * F_N
    stick = 2 * f / k  # 20 nm: 20 pixels
    x = loop.x
    assert np.allclose(loop.trace, np.minimum(-f + k * x, f), rtol=0, atol=1e-22)
    assert np.allclose(loop.retrace, np.maximum(f - k * (x[-1] - x), -f), rtol=0, atol=1e-22)
    inside = (x > stick) & (x < x[-1] - stick)
    assert np.allclose(loop.friction_coefficient[inside], mu, rtol=1e-12)
    assert np.allclose(loop.slope_term[inside], 0.0, atol=1e-22)
    # area: base (W - 2 f / k) x height 2 f
    assert loop.dissipated_energy == pytest.approx((x[-1] - stick) * 2 * f, rel=1e-12)


@pytest.mark.parametrize("tilt_deg", [-8.0, 3.0, 15.0])
def test_tilted_loop_separates_friction_and_slope(tilt_deg):
    mu, px, n = 0.3, 2e-9, 100
    t = math.tan(math.radians(tilt_deg))
    loop = friction_loop(t * np.arange(n) * px, mu, px, normal_force=F_N,
                         lateral_stiffness=100.0)
    body = slice(1, -1)  # the stuck first pixel of each pass
    assert np.allclose(loop.trace[body], F_N * (mu + t), rtol=1e-12)
    assert np.allclose(loop.retrace[body], F_N * (-mu + t), rtol=1e-12)
    assert np.allclose(loop.slope_term[body], F_N * t, rtol=1e-12)
    assert np.allclose(loop.friction_coefficient[body], mu, rtol=1e-12)


def test_loop_accepts_a_friction_profile():
    mu = np.where(np.arange(50) < 25, 0.1, 0.5)
    loop = friction_loop(np.zeros(50), mu, 1e-9, normal_force=F_N, lateral_stiffness=100.0)
    assert isinstance(loop, FrictionLoop)
    assert np.allclose(loop.friction_coefficient[1:-1], mu[1:-1])


# -- maps ------------------------------------------------------------------------------------
def _regions(mu_map):
    core = np.zeros(mu_map.shape, bool)
    core[:, 1:-1] = True  # the stuck first/last column of each pass carries no friction
    return core


@pytest.mark.parametrize("model", ["linear", "wedge"])
def test_friction_map_recovers_the_coefficients_within_the_noise(model):
    noise = 0.5e-9
    topo, mu = friction_sample((64, 64), 10e-9, coefficients=(0.1, 0.4))
    images = friction_scan(topo, mu, normal_force=F_N, lateral_noise=noise, model=model, seed=1)
    got = images.friction_coefficient.heights
    core = _regions(mu.heights)
    residual = (got - mu.heights)[core]
    sigma = noise / math.sqrt(2) / F_N  # the half difference of two independent noises
    assert residual.std() == pytest.approx(sigma, rel=0.05)
    for value in (0.1, 0.4):
        region = core & (mu.heights == value)
        mean = got[region].mean()
        assert abs(mean - value) < 4 * sigma / math.sqrt(region.sum())


def test_tilt_and_topography_do_not_leak_into_the_friction_map():
    flat_topo, mu = friction_sample((48, 48), 10e-9)
    hilly_topo, mu2 = friction_sample((48, 48), 10e-9, tilt=math.radians(12), bump_height=40e-9)
    assert np.array_equal(mu.heights, mu2.heights)
    flat = friction_scan(flat_topo, mu, lateral_noise=0.3e-9, seed=5)
    hilly = friction_scan(hilly_topo, mu, lateral_noise=0.3e-9, seed=5)
    core = _regions(mu.heights)
    assert np.allclose(hilly.friction.heights[core], flat.friction.heights[core], rtol=0,
                       atol=1e-22)
    # the slope shows in the half sum: F_N tan(theta) of the local slope
    slope = np.arctan(np.gradient(hilly_topo.heights, 10e-9, axis=1))
    clean = friction_scan(hilly_topo, mu)
    assert np.allclose(clean.slope_term.heights[core], (F_N * np.tan(slope))[core], rtol=1e-9,
                       atol=1e-22)
    # and the raw trace alone would have mistaken it for friction
    assert np.abs(hilly.trace.heights / F_N - mu.heights)[core].max() > 0.2


def test_friction_scan_of_a_line():
    topo, mu = friction_sample(40, 5e-9, tilt=0.1)
    images = friction_scan(topo, mu)
    assert images.trace.heights.shape == (40,)
    assert np.allclose(images.friction_coefficient.heights[1:-1], mu.heights[1:-1])


# -- the scanner mode ------------------------------------------------------------------------
def test_lateral_force_mode_through_the_scanner():
    topo, mu = friction_sample((24, 24), 10e-9, tilt=math.radians(5), bump_height=20e-9)
    mode = LateralForceMode(mu, normal_force=F_N)
    result = scan(topo, None, mode, ScanSettings(24 * 10e-9, pixels=24, scan_speed=1e-6))
    assert result.units["height trace"] == "m" and result.units["lateral trace"] == "N"
    assert result.channels["lateral retrace"].unit == "N"
    assert np.allclose(result.images["height trace"], topo.heights, rtol=0, atol=1e-18)
    expected = friction_scan(topo, mu, normal_force=F_N)
    for name, image in (("lateral trace", expected.trace), ("lateral retrace", expected.retrace)):
        assert np.allclose(result.images[name], image.heights, rtol=1e-9, atol=1e-22)
    half = result.images["lateral trace"] - result.images["lateral retrace"]
    assert np.allclose((half / (2 * F_N))[:, 1:-1], mu.heights[:, 1:-1])


def test_lateral_force_mode_reads_friction_where_the_scan_is():
    """An offset scan of a friction gradient along x sees the coefficients under it."""
    px = 10e-9
    topo = Sample(np.zeros((40, 40)), px)
    columns = np.arange(40)
    mu = Sample(np.tile(0.1 + 0.005 * columns, (40, 1)), px, unit="")
    mode = LateralForceMode(mu, normal_force=F_N)
    settings = ScanSettings(20 * px, pixels=20, scan_speed=1e-6, offset=(60e-9, 0.0))
    result = scan(topo, None, mode, settings)
    got = ((result.images["lateral trace"] - result.images["lateral retrace"])
           / (2 * F_N))[:, 1:-1]
    # the scan's centre is 60 nm (6 columns) right of the sample's centre, column 19.5
    centre = 0.1 + 0.005 * (19.5 + 6)
    assert got.mean() == pytest.approx(centre, abs=0.005)
    assert np.all(np.diff(got, axis=1) >= 0) and np.allclose(np.diff(got, axis=0), 0)
    assert set(np.round(got.ravel(), 12)) <= set(np.round(0.1 + 0.005 * columns, 12))


# -- bad input -------------------------------------------------------------------------------
@pytest.mark.parametrize("call, name", [
    (lambda: LateralLever(LEVER, 0.0), "tip_height"),
    (lambda: LateralLever(LEVER, 15e-6, -1.0), "shear_modulus"),
    (lambda: LateralLever("lever"), "lever"),
    (lambda: LateralLever(LEVER).signal([0.0, 1e-2]), "lateral_force"),
    (lambda: lateral_force(0.1, 0.2, 0), "direction"),
    (lambda: lateral_force(0.1, 0.2, True), "direction"),
    (lambda: lateral_force(0.1, 0.2, 1.0), "direction"),
    (lambda: lateral_force(0.1, -0.2, 1), "friction_coefficient"),
    (lambda: lateral_force(2.0, 0.2, 1), "slope"),
    (lambda: lateral_force(0.1, 0.2, 1, normal_force=0.0), "normal_force"),
    (lambda: lateral_force(0.1, 0.2, 1, model="cubic"), "model"),
    (lambda: lateral_force(1.2, 0.5, 1, model="wedge"), "lock"),
    (lambda: friction_loop(np.zeros(10), np.zeros(9), 1e-9), "friction_coefficient"),
    (lambda: friction_loop(np.zeros(10), 0.1, 0.0), "pixel_size"),
    (lambda: friction_loop(np.zeros(10), 0.1, 1e-9, lateral_stiffness=0.0), "lateral_stiffness"),
    (lambda: friction_scan(Sample(np.zeros((4, 4)), 1e-9), Sample(np.zeros((4, 5)), 1e-9,
                                                                  unit="")), "grid"),
    (lambda: friction_scan(Sample(np.zeros((4, 4)), 1e-9), Sample(np.zeros((4, 4)), 1e-9)),
     "friction"),
    (lambda: friction_scan(*friction_sample((4, 4), 1e-9), lateral_noise=-1.0), "lateral_noise"),
    (lambda: friction_sample((4, 4), 1e-9, coefficients=(0.1,)), "coefficients"),
    (lambda: friction_sample((4, 4), 1e-9, tilt=2.0), "tilt"),
    (lambda: LateralForceMode(Sample(np.zeros((4, 4)), 1e-9)), "friction"),
])
def test_bad_input_is_named(call, name):
    with pytest.raises((ValueError, TypeError), match=name):
        call()


def test_parameters_are_consistent():
    for p in lateral.PARAMETERS.values():
        assert p.check(p.default) == p.default


def test_a_vertical_wall_is_refused_naming_the_topography():
    """A slope that rounds to 90 degrees (heights of 1e300 m) named the internal ``slope`` before;
    the user's parameter is the topography."""
    from afmsmiler.modes import friction_scan
    from afmsmiler.samples import Sample
    topo = Sample(np.where(np.arange(16) < 8, 0.0, 1e300) * np.ones((4, 1)), 10e-9, "wall")
    friction = Sample(np.full((4, 16), 0.2), 10e-9, "friction", unit="")
    with pytest.raises(ValueError, match="topography must have slopes below 90 degrees"):
        friction_scan(topo, friction)


def test_lateral_mode_line_refuses_a_plan_that_is_not_one():
    from afmsmiler.modes import LateralForceMode
    from afmsmiler.samples import Sample
    mode = LateralForceMode(Sample(np.full((4, 4), 0.2), 10e-9, "friction", unit=""))
    with pytest.raises(TypeError, match="plan"):
        mode.line(1.0, 0)
