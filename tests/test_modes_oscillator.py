"""The point-mass oscillator every lever of module (g) describes itself by, and the one valid
range of k, f0 and Q that a lever carries from mode to mode.

References: python-control's frequency response and poles of the plant
1 / (m s^2 + (m w0 / Q) s + k) (an independent implementation of the transfer function), and the
textbook envelope of the underdamped free oscillation, exp(-w0 t / (2 Q)) (e.g. Cleland,
*Foundations of Nanomechanics* (2003), ch. 3).
"""
import math

import numpy as np
import pytest

from afmsmiler import brownian, parameters
from afmsmiler.contact.quantities import PARAMETERS as CONTACT
from afmsmiler.modes import BimodalLever, Oscillator, QControl, TappingLever
from afmsmiler.modes import fm, qcontrol, tapping

control = pytest.importorskip("control")

CASES = [(40.0, 300e3, 400.0), (0.1, 10e3, 2.0), (1800.0, 32768.0, 5e4), (1e-3, 10.0, 0.5)]


@pytest.mark.parametrize("k, f0, q", CASES)
def test_compliance_is_the_plant_of_python_control(k, f0, q):
    osc = Oscillator(k, f0, q)
    w0 = 2 * math.pi * f0
    m = k / w0 ** 2
    plant = control.tf([1.0], [m, m * w0 / q, k])
    w = w0 * np.array([0.1, 0.5, 0.99, 1.0, 1.01, 2.0, 10.0])
    expected = plant(1j * w)
    got = np.array([osc.compliance(x) for x in w])
    # both evaluate the same rational function in double precision: a few ulp of |H|
    assert got == pytest.approx(expected, rel=1e-12)


@pytest.mark.parametrize("k, f0, q", CASES)
def test_time_constant_is_the_poles_decay(k, f0, q):
    osc = Oscillator(k, f0, q)
    w0 = 2 * math.pi * f0
    poles = control.tf([1.0], [osc.mass, osc.mass * w0 / q, k]).poles()
    assert osc.mass == pytest.approx(k / w0 ** 2, rel=1e-15)
    assert osc.angular_frequency == pytest.approx(w0, rel=1e-15)
    if q > 0.5:  # underdamped: the envelope exp(-t / tau) is the poles' real part
        assert -1.0 / poles.real.max() == pytest.approx(osc.time_constant, rel=1e-9)
        # and the poles' modulus is w0 (m s^2 + c s + k has |s|^2 = k / m)
        assert np.abs(poles) == pytest.approx(w0, rel=1e-9)


def test_levers_give_their_oscillator():
    lever = TappingLever(spring_constant=2.0, resonance_frequency=70e3, quality_factor=150.0)
    assert lever.oscillator == Oscillator(2.0, 70e3, 150.0)
    assert lever.time_constant == lever.oscillator.time_constant
    qc = QControl(spring_constant=2.0, resonance_frequency=70e3, quality_factor=150.0)
    assert qc.oscillator == lever.oscillator
    assert qc.mass == lever.oscillator.mass
    b = BimodalLever(lever, quality_factor_2=450.0)
    one, two = b.oscillators
    assert one == lever.oscillator
    assert (two.spring_constant, two.quality_factor) == (b.stiffnesses[1], 450.0)
    assert two.angular_frequency == pytest.approx(b.angular_frequencies[1], rel=1e-15)


@pytest.mark.parametrize("name, bad", [("spring_constant", 0.0), ("spring_constant", 2e6),
                                       ("resonance_frequency", 0.0),
                                       ("resonance_frequency", 2e9),
                                       ("quality_factor", 0.0), ("quality_factor", 2e5)])
def test_a_bad_value_is_named(name, bad):
    args = dict(spring_constant=40.0, resonance_frequency=300e3, quality_factor=400.0)
    with pytest.raises(ValueError, match=f"^{name} must be in"):
        Oscillator(**{**args, name: bad})
    with pytest.raises(ValueError, match=f"^{name} must be in"):
        TappingLever(**{**args, name: bad})
    with pytest.raises(ValueError, match=f"^{name} must be in"):
        QControl(**{**args, name: bad})


# The edges of the shared ranges: a value one mode takes, every mode takes (before, Q = 0.005
# was a valid tapping lever and an invalid Q-control one, k = 1e-4 N/m a valid contact lever and
# an invalid FM one, f0 = 50 Hz a valid Q-control lever and an invalid tapping one).
EDGES = [("spring_constant", 1e-6), ("spring_constant", 1e6), ("resonance_frequency", 0.1),
         ("resonance_frequency", 1e9), ("quality_factor", 0.005), ("quality_factor", 1e5)]


@pytest.mark.parametrize("name, value", EDGES)
def test_one_range_in_every_mode(name, value):
    descriptions = [parameters.PARAMETERS[name], tapping.PARAMETERS[name],
                    qcontrol.PARAMETERS[name]]
    others = {"spring_constant": (CONTACT, fm.PARAMETERS),
              "resonance_frequency": (fm.PARAMETERS,),
              "quality_factor": ()}[name]
    descriptions += [table[name] for table in others]
    for p in descriptions:
        assert p.check(value) == value
    args = {name: value}
    assert getattr(Oscillator(**{**dict(spring_constant=40.0, resonance_frequency=300e3,
                                        quality_factor=400.0), **args}), name) == value
    assert getattr(TappingLever(**args), name) == value
    assert getattr(QControl(**args), name) == value


def test_the_brownian_closed_form_takes_any_damping():
    # the thermal spectrum's band integral holds overdamped too (a lever in water can be:
    # tests/test_brownian_model.py checks it against sympy and quadrature), so the Brownian
    # motion takes the vocabulary's Q, any Q > 0; the transducers' Q typed in vacuum keeps the
    # named narrowing (from critical damping up), their fluids compute any Q
    from afmsmiler.cantilever import Cantilever
    from afmsmiler.transducers.base import LEVER_PARAMETERS
    lever = Cantilever(450e-6, 50e-6, 2e-6, 169e9, 2330.0)
    assert brownian.PARAMETERS["quality_factor"] is parameters.QUALITY_FACTOR
    assert parameters.UNDERDAMPED_QUALITY_FACTOR in LEVER_PARAMETERS
    with pytest.raises(ValueError, match=r"^quality_factor must be in \(0, 100000"):
        brownian.thermal_deflection_noise(lever, quality_factor=0.0, bandwidth=1e3,
                                         low_frequency=0.0)
    assert brownian.thermal_deflection_noise(lever, quality_factor=0.3, bandwidth=1e3,
                                            low_frequency=0.0) > 0
