"""The AD2 set-up through pydwf, checked call by call against a simulated device.

The simulated library records every pydwf call and answers the scope with the AD630 levels of the
simulated chain; the host's reading is compared with the chain's closed-form 2-omega phasor. The
real device is tried once: without Digilent's runtime the test skips, showing why.
"""
import math

import numpy as np
import pytest

pydwf = pytest.importorskip("pydwf", reason="pydwf (the hardware extra) is not installed")

from afmsmiler.hardware import HardwareError  # noqa: E402
from afmsmiler.hardware.ad2 import (AD2Config, AD2Unavailable, AnalogDiscovery2,  # noqa: E402
                                    SimulatedDwfLibrary, open_library, pattern_timing)
from afmsmiler.signals import ActiveProbe  # noqa: E402

CARRIER = pydwf.DwfAnalogOutNode.Carrier
WAVE_START = pydwf.DwfTriggerSource.AnalogOut1


@pytest.fixture
def session():
    lib = SimulatedDwfLibrary(seed=4)
    f = lib.probe.resonance_frequency / 2
    ad2 = AnalogDiscovery2(lib, config=AD2Config(drive_frequency=f, ac_voltage=0.5))
    ad2.open()
    yield lib, ad2
    ad2.close()


def test_pattern_timing_from_scratch():
    t = pattern_timing(100e6, 81.5e3, 0.0)
    assert t.divider == 1
    assert t.period == 1227                              # 100e6 / 81.5e3 = 1226.99
    assert (t.low_count, t.high_count) == (613, 614)
    assert t.frequency == pytest.approx(100e6 / 1227)
    assert (t.start_high, t.start_count) == (True, 614)  # rising edge at the trigger
    q = pattern_timing(100e6, 81.5e3, math.pi / 2)
    assert (q.start_high, q.start_count) == (True, 614 - 307)  # high for the first quarter: cos
    assert q.phase == pytest.approx(math.pi / 2, abs=2 * math.pi / 1227 / 2)
    late = pattern_timing(100e6, 81.5e3, math.pi)
    assert (late.start_high, late.start_count) == (False, 1227 - 614)
    slow = pattern_timing(100e6, 10.0, 0.0, max_count=32768)
    assert slow.divider == math.ceil(100e6 / (2 * 10.0 * 32768))
    assert slow.frequency == pytest.approx(10.0, rel=1e-4)
    # one count of the period: the frequency grid at 81 kHz steps by 1 / 1227 = 0.08 %
    step = pattern_timing(100e6, 100e6 / 1226).frequency / t.frequency - 1
    assert step == pytest.approx(1 / 1226, rel=1e-9)
    with pytest.raises(ValueError, match="frequency must be at most"):
        pattern_timing(100e6, 40e6)


def test_configure_makes_the_calls_the_paper_scheme_needs(session):
    lib, ad2 = session
    plan = ad2.configure()
    dev = lib.devices[0]
    ref_i, ref_q = plan["reference"]
    # the squares at 2 w, the sine at exactly half their frequency
    assert ref_i.frequency == ref_q.frequency
    assert dev.last("analogOut", "nodeFrequencySet") == (0, CARRIER, ref_i.frequency / 2)
    assert dev.last("analogOut", "nodeFunctionSet") == (0, CARRIER, pydwf.DwfAnalogOutFunction.Sine)
    assert dev.last("analogOut", "nodeAmplitudeSet") == (0, CARRIER, 0.5)
    assert dev.last("analogOut", "nodeOffsetSet") == (0, CARRIER, 0.0)
    assert dev.last("analogOut", "nodePhaseSet") == (0, CARRIER, 0.0)
    # DIO 0 in phase, DIO 1 a quarter period later, both 50 % squares on the same divider
    calls = [(n, a) for i, n, a in dev.calls if i == "digitalOut"]
    quarter = round(ref_i.period / 4)
    for pin, start in ((0, ref_i.high_count), (1, ref_i.high_count - quarter)):
        assert ("enableSet", (pin, True)) in calls
        assert ("typeSet", (pin, pydwf.DwfDigitalOutType.Pulse)) in calls
        assert ("dividerSet", (pin, ref_i.divider)) in calls
        assert ("counterSet", (pin, ref_i.low_count, ref_i.high_count)) in calls
        assert ("counterInitSet", (pin, True, start)) in calls
    # the pattern and the scope start with WaveGen 1
    assert dev.last("digitalOut", "triggerSourceSet") == (WAVE_START,)
    assert dev.last("analogIn", "triggerSourceSet") == (WAVE_START,)
    assert dev.last("analogIn", "frequencySet") == (100e3,)
    assert dev.last("analogIn", "bufferSizeSet") == (8192,)
    assert dev.last("analogIn", "triggerPositionSet") == (8192 / 100e3 / 2,)


def test_acquire_arms_before_the_trigger_and_reads_the_chain(session):
    lib, ad2 = session
    ad2.configure()
    acq = ad2.acquire()
    dev = lib.devices[0]
    starts = [(i, a) for i, n, a in dev.calls if n == "configure"]
    assert starts[-3:] == [("analogIn", (False, True)), ("digitalOut", (True,)),
                           ("analogOut", (0, True))]
    # the reading: A = (pi / 2G) hypot(V_x, V_y) and its phase, against the closed form
    x, y = acq.settled()
    truth = dev.run.second
    assert math.pi / 2 * math.hypot(x, y) == pytest.approx(abs(truth), rel=0.01)
    assert abs(math.degrees(math.atan2(y, x) - np.angle(truth))) < 1.0
    assert acq.reference_frequency == pytest.approx(2 * acq.drive_frequency)


def test_the_simulated_board_drives_the_librarys_lever_in_its_medium():
    # the board rebuilt the probe from its lever's numbers and lost its medium: a lever in water
    # rang at its vacuum f1 with water's Q (and an overdamped one raised)
    from afmsmiler.hydrodynamics import fluid_mode
    probe = ActiveProbe.build(fluid="water")
    lib = SimulatedDwfLibrary(seed=4, probe=probe)
    f_water = fluid_mode(probe.sensor.lever, "water", 1).resonance_frequency
    ad2 = AnalogDiscovery2(lib, config=AD2Config(drive_frequency=f_water / 2, ac_voltage=0.5))
    ad2.open()
    try:
        ad2.configure()
        ad2.acquire()
        run = lib.devices[0].run
        assert run.probe.sensor.fluid == run.probe.actuator.fluid == "water"
        assert run.probe.resonance_frequency == f_water
        assert run.probe.actuator.ac_voltage == pytest.approx(0.5)
    finally:
        ad2.close()


def test_untriggered_pattern_loses_the_phase():
    lib = SimulatedDwfLibrary(seed=1)
    f = lib.probe.resonance_frequency / 2

    class Untriggered(AnalogDiscovery2):
        def configure(self):
            plan = super().configure()
            self.device.digitalOut.triggerSourceSet(pydwf.DwfTriggerSource.None_)
            return plan

    ad2 = Untriggered(lib, config=AD2Config(drive_frequency=f))
    ad2.open()
    x, y = ad2.acquire().settled()
    ad2.close()
    truth = lib.devices[0].run.second
    assert abs(math.degrees(math.atan2(y, x) - np.angle(truth))) > 5.0


def test_close_stops_the_heater_and_closes(session):
    lib, ad2 = session
    ad2.configure()
    ad2.close()
    dev = lib.devices[0]
    assert ("analogOut", "configure", (0, False)) in dev.calls
    assert dev.closed and ad2.device is None
    ad2.close()                                       # twice is fine


def test_missing_runtime_becomes_ad2_unavailable():
    def no_runtime():
        raise pydwf.PyDwfError("Unable to open DWF library using ctypes.")
    with pytest.raises(AD2Unavailable, match="WaveForms runtime") as info:
        open_library(no_runtime)
    assert "Unable to open DWF library" in info.value.reason


def test_real_device_or_a_visible_skip():
    try:
        lib = open_library()
    except AD2Unavailable as exc:
        pytest.skip(exc.reason)
    ad2 = AnalogDiscovery2(lib, config=AD2Config(drive_frequency=40e3))
    try:
        ad2.open()
    except AD2Unavailable as exc:
        pytest.skip(exc.reason)
    try:
        plan = ad2.configure()
        assert plan["reference"][0].frequency == pytest.approx(80e3, rel=1e-3)
    finally:
        ad2.close()


def test_errors():
    with pytest.raises(ValueError, match="ac_voltage"):
        AD2Config(ac_voltage=7.0)
    with pytest.raises(ValueError, match="samples"):
        AD2Config(samples=100000)
    with pytest.raises(TypeError, match="config"):
        AnalogDiscovery2(SimulatedDwfLibrary(), config={"drive_frequency": 1e3})
    with pytest.raises(HardwareError, match="not open"):
        AnalogDiscovery2(SimulatedDwfLibrary()).configure()


def test_a_scope_that_never_finishes_times_out(hang_guard):
    lib = SimulatedDwfLibrary(probe=ActiveProbe(), noise=False)
    ad2 = AnalogDiscovery2(lib, config=AD2Config(drive_frequency=40e3, samples=64,
                                                 sample_rate=1e6, timeout=0.05))
    ad2.open()
    ad2.configure()
    lib.devices[0]._run = lambda: None               # the trigger never fires
    with hang_guard(5, expected=0.05), pytest.raises(HardwareError, match="did not complete"):
        ad2.acquire()  # its 0.05 s timeout


def test_library_or_simulation_falls_back_with_the_reason():
    """Notebook 08's choice of a real AD2 or its simulation, one call (it was a try/except in the
    notebook)."""
    from afmsmiler.hardware.ad2 import SimulatedDwfLibrary, library_or_simulation

    def missing():
        import pydwf
        raise pydwf.PyDwfError("no libdwf here")
    dwf, why = library_or_simulation(missing)
    assert isinstance(dwf, SimulatedDwfLibrary) and "no libdwf here" in why
    real = object()
    assert library_or_simulation(lambda: real) == (real, None)
