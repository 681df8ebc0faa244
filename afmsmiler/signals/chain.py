"""The educational AFM's chain: heater drive at omega, lever motion at 2 omega, bridge, noise.

The low-cost educational AFM (Xia et al., Mechatronics 76, 102550 (2021)) uses an active probe: a
heater on the lever bends it through an aluminium/silicon bimorph (electrothermal actuation) and a
piezoresistive bridge at the clamp reads the bending. Its chain, each stage a model of module (a)
or (b), reused, not rewritten:

1. The heater voltage V(t) = V_dc + V_ac sin(w t) across R dissipates P = V^2 / R::

       P = [V_dc^2 + V_ac^2 / 2 + 2 V_dc V_ac sin(w t) - (V_ac^2 / 2) cos(2 w t)] / R

   so with V_dc = 0 the heat, and the lever, move at 2 w only: drive at half the resonance and
   demodulate at 2 w (the drive's own frequency w never reaches the lever). The simulation
   squares the sampled voltage itself; the expansion is the closed form it is tested against.
2. Heat to tip deflection: module (b)'s :class:`~afmsmiler.transducers.Electrothermal`, the
   static bimorph gain (m/W) times its thermal low-pass (the fin's H_uniform, tau = 4 L^2 /
   (pi^2 D)), times module (a)'s first mode 1 / (1 - (f/f1)^2 + j f / (Q f1))
   (:func:`afmsmiler.brownian.mechanical_response`).
3. Tip deflection to voltage: module (b)'s :class:`~afmsmiler.transducers.Piezoresistive` quarter
   bridge (its end-load stress at the clamp; the resonant motion is the first mode, whose clamp
   curvature per tip deflection the end load approximates), then an amplifier of gain G.
4. Noise, seeded: the lever's Brownian motion (module (a)'s thermal spectrum
   :func:`afmsmiler.brownian.thermal_noise_density`, resonance included), the bridge's Johnson
   noise 4 k_B T R and Hooge 1/f noise V_b^2 alpha_H / (4 N f) (module (b)'s formulas, Harley
   and Kenny 2000), and the amplifier's input noise e_n^2, all referred to its input.
   Optionally an interfering tone at three times the reference (a switching supply, say) to show
   what a square reference picks up.

The heater power is periodic in the drive period, so the steady state is computed exactly in the
frequency domain over a whole number of drive periods: FFT of the sampled P(t), times the
transfer function at every bin, inverse FFT (a linear chain's periodic steady state; the lever
has rung for a long time before the record starts, as in the lab). Being linear, it is done once
per lever and record for the sampled sin^2(w t), and an unbiased run scales that by V_ac^2 / R.
Noise is drawn in the same domain from its one-sided density S(f): bin k gets
sqrt(S f_s N / 4) (a + j b), a, b standard normal, whose inverse FFT has the variance int S df.

Sample rate: ``samples_per_period`` samples per drive period (default 128: f_s = 5.2 MHz for the
default lever's f1 / 2 = 40.8 kHz; the AD2's scope samples at up to 100 MHz). That places the
Nyquist frequency at 64 w, far above the 2 w signal and the 6 w, 10 w ... that a square reference
at 2 w also demodulates, and gives the square reference 64 samples per period: its 3rd-harmonic
weight is then within 0.4 % of 1/3 (see :mod:`afmsmiler.signals.lockin`).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ..brownian import mechanical_response
from ..parameters import Parameter, read_only
from ..transducers import Electrothermal, Piezoresistive
from ..transducers.base import BOLTZMANN
from ..validation import check_flag, check_instance, check_integer, check_positive
from .lockin import LIMITS

__all__ = ["ActiveProbe", "ChainRun", "simulate", "DC_VOLTAGE", "AC_VOLTAGE",
           "HALF_RESONANCE_RATIO", "AMPLIFIER_NOISE", "AMPLIFIER_GAIN", "INTERFERENCE",
           "SAMPLES_PER_PERIOD", "RECORD_DURATION", "PARAMETERS", "power_harmonics",
           "brownian_density"]

#: The heater's AC amplitude and DC bias: module (b)'s own descriptions (no bias by default:
#: the pure 2-omega drive).
AC_VOLTAGE = Electrothermal.parameter_table()["ac_voltage"]
DC_VOLTAGE = Electrothermal.INPUTS["actuation"].with_(default=0.0)
HALF_RESONANCE_RATIO = Parameter(name="half_resonance_ratio", unit="", default=1.0, low=0.1,
                                 high=2.0, slider_low=0.98, slider_high=1.02,
                                 label="drive frequency / (f1 / 2)")
AMPLIFIER_NOISE = Parameter(name="amplifier_noise", unit="V^2/Hz", display_unit="nV^2/Hz",
                            default=100e-18, low=0.0, high=1e-6, slider_low=1e-18,
                            slider_high=1e-8, log=True,
                            label="amplifier noise e_n^2 (100 nV^2/Hz = (10 nV)^2/Hz)")
AMPLIFIER_GAIN = Parameter(name="amplifier_gain", unit="", default=100.0, low=1.0, high=1e4,
                           log=True, label="amplifier gain G")
INTERFERENCE = Parameter(name="interference", unit="V", display_unit="uV", default=0.0, low=0.0,
                         high=1e-2, slider_low=0.0, slider_high=200e-6,
                         label="interfering tone at 3 x the reference (amplifier input)")
SAMPLES_PER_PERIOD = Parameter(name="samples_per_period", unit="", default=128, low=16,
                               high=1024, label="samples per drive period")
RECORD_DURATION = Parameter(name="record_duration", unit="s", display_unit="ms", default=20e-3,
                            low=1e-6, high=1.0, log=True, slider_low=1e-3, slider_high=0.2,
                            label="record length")
PARAMETERS = read_only({p.name: p for p in (
    AC_VOLTAGE, DC_VOLTAGE, HALF_RESONANCE_RATIO, AMPLIFIER_NOISE, AMPLIFIER_GAIN, INTERFERENCE,
    SAMPLES_PER_PERIOD, RECORD_DURATION)})

_SHARED = ("length", "width", "thickness", "quality_factor", "temperature")


def power_harmonics(dc_voltage: float, ac_voltage: float, resistance: float) -> tuple:
    """Heater power P = (V_dc + V_ac sin w t)^2 / R as phasors against sin(n w t), in W.

    Parameters
    ----------
    dc_voltage : float
        V_dc in V.
    ac_voltage : float
        V_ac in V.
    resistance : float
        R in ohm.

    Returns
    -------
    tuple of complex
        (DC, 1 w, 2 w): ((V_dc^2 + V_ac^2 / 2) / R, 2 V_dc V_ac / R, -j V_ac^2 / (2 R)); the
        2-w term is -(V_ac^2 / 2R) cos(2 w t) = (V_ac^2 / 2R) sin(2 w t - pi / 2).
    """
    v = DC_VOLTAGE.check(dc_voltage)
    va = AC_VOLTAGE.check(ac_voltage)
    r = check_positive("resistance", resistance, "ohm")
    return (complex((v * v + va * va / 2) / r), complex(2 * v * va / r), -0.5j * va * va / r)


@dataclass(frozen=True)
class ActiveProbe:
    """An active lever: module (b)'s electrothermal heater and piezoresistive bridge on one lever.

    Parameters
    ----------
    actuator : Electrothermal
        The heater (its resistance, film, and ``ac_voltage``: the drive amplitude V_ac).
    sensor : Piezoresistive
        The bridge (bias, resistance, coefficient).

    Raises
    ------
    TypeError
        If either is not of its model class.
    ValueError
        If the two describe different levers (length, width, thickness, Q, temperature,
        medium).
    """

    actuator: Electrothermal = field(default_factory=Electrothermal)
    sensor: Piezoresistive = field(default_factory=Piezoresistive)

    def __post_init__(self):
        check_instance("actuator", self.actuator, Electrothermal)
        check_instance("sensor", self.sensor, Piezoresistive)
        if self.actuator.fluid != self.sensor.fluid:
            raise ValueError(f"actuator and sensor must share the lever: its medium is "
                             f"{self.actuator.fluid!r} for the actuator, {self.sensor.fluid!r} "
                             "for the sensor")
        for name in _SHARED:
            a, s = getattr(self.actuator, name), getattr(self.sensor, name)
            if a != s:
                raise ValueError(f"actuator and sensor must share the lever: {name} is {a:g} "
                                 f"for the actuator, {s:g} for the sensor")

    @classmethod
    def build(cls, *, ac_voltage: float = AC_VOLTAGE.default, fluid: str | None = None,
              **lever) -> "ActiveProbe":
        """A probe with drive amplitude ``ac_voltage`` (V) and the shared ``lever`` parameters.

        Parameters
        ----------
        ac_voltage : float
            V_ac in V.
        fluid : str, optional
            The lever's medium (``"air"`` or ``"water"``: its f1 and Q there, Sader 1998);
            default None, in vacuum with the typed Q (:class:`~afmsmiler.transducers.base.
            Transducer`).
        **lever : float
            Any of length, width, thickness (m), quality_factor, temperature (K).
        """
        unknown = set(lever) - set(_SHARED)
        if unknown:
            raise TypeError(f"build got unknown parameter(s) {sorted(unknown)}; valid: "
                            f"ac_voltage, fluid and {list(_SHARED)}")
        return cls(Electrothermal(ac_voltage=ac_voltage, fluid=fluid, **lever),
                   Piezoresistive(fluid=fluid, **lever))

    @property
    def resonance_frequency(self) -> float:
        """f1 of the lever in Hz (module (a)), in its medium."""
        return self.actuator.resonance_frequency

    def deflection_per_power(self, f) -> np.ndarray:
        """Tip deflection per watt of heater power at frequencies ``f`` (Hz), complex, m/W.

        Module (b)'s static bimorph gain times its thermal low-pass times module (a)'s mode.

        Parameters
        ----------
        f : array_like
            Frequencies in Hz, >= 0.
        """
        a = self.actuator
        return (a.deflection_per_watt() * a.thermal_lag(f)
                * mechanical_response(f, resonance_frequency=a.resonance_frequency,
                                      quality_factor=a.quality_factor))


@dataclass(frozen=True)
class ChainRun:
    """One simulated record of the chain (all arrays sampled at t_k = k / f_s).

    Parameters
    ----------
    probe : ActiveProbe
        The probe simulated.
    drive_frequency : float
        f = w / 2 pi in Hz.
    sample_rate : float
        f_s in Hz.
    time : ndarray
        t in s.
    heater_voltage : ndarray
        V(t) in V.
    power : ndarray
        P(t) in W.
    deflection : ndarray
        The driven tip deflection in m (no noise).
    brownian : ndarray
        The lever's Brownian deflection in m.
    bridge : ndarray
        The bridge output in V for the noisy deflection (no electrical noise).
    output : ndarray
        The amplifier's output in V: G x (bridge + electrical noise + interference).
    first, second : complex
        The closed-form phasors of the output at w and 2 w in V (A e^{j theta}: the component
        A sin(n w t + theta)), from the power's expansion and the small-signal bridge gain.
    second_deflection : complex
        The closed-form 2-w deflection phasor in m.
    noise_density : float
        The one-sided density of the output's noise at 2 w in V^2/Hz (all sources).
    """

    probe: ActiveProbe
    drive_frequency: float
    sample_rate: float
    time: np.ndarray
    heater_voltage: np.ndarray
    power: np.ndarray
    deflection: np.ndarray
    brownian: np.ndarray
    bridge: np.ndarray
    output: np.ndarray
    first: complex
    second: complex
    second_deflection: complex
    noise_density: float

    @property
    def snr(self) -> float:
        """Output 2-w amplitude over the noise's rms in a 1 Hz band (sqrt(2 S)), in sqrt(Hz)."""
        return abs(self.second) / math.sqrt(2 * self.noise_density) if self.noise_density \
            else math.inf


def _electrical_density(sensor, amplifier_noise, f):
    """Johnson + Hooge (at ``f``) + amplifier (``amplifier_noise``, V^2/Hz) density, V^2/Hz."""
    return (4 * BOLTZMANN * sensor.temperature * sensor.resistance
            + amplifier_noise
            + sensor.bias_voltage ** 2 * sensor.hooge / (4 * sensor.carrier_number) / f)


def _noise(rng, psd, n: int, fs: float) -> np.ndarray:
    """A real record of ``n`` samples with one-sided density ``psd`` at the rfft bins."""
    scale = np.sqrt(psd * fs * n / 4.0)
    spectrum = scale * (rng.standard_normal(psd.size) + 1j * rng.standard_normal(psd.size))
    spectrum[0] = 0.0
    if n % 2 == 0:
        spectrum[-1] = spectrum[-1].real * math.sqrt(2.0)
    return np.fft.irfft(spectrum, n)


class _Memo:
    """The last few results of a function of keys compared with ``==`` (the transducers are
    unhashable), newest last, at most ``size`` of them and ``max_bytes`` of arrays in all (a
    longer record is computed each time); the arrays kept are read-only."""

    def __init__(self, size: int = 4, max_bytes: int = 1 << 26):
        self.size, self.max_bytes, self.entries = size, max_bytes, []

    def get(self, key, compute):
        for k, value in self.entries:
            if k == key:
                return value
        value = compute()
        if sum(a.nbytes for a in value) > self.max_bytes:
            return value
        for a in value:
            a.setflags(write=False)
        self.entries.append((key, value))
        while len(self.entries) > self.size or \
                sum(a.nbytes for _, v in self.entries for a in v) > self.max_bytes:
            self.entries.pop(0)
        return value

    def clear(self) -> None:
        self.entries = []


#: What :func:`simulate` reuses from one run to the next (issue 24: a move of the drive
#: amplitude, the lock-in panel's slider, changes none of it): the drive's waveforms, the transfer
#: function and the deflection of a unit sin^2 power (:func:`_drive`), which depend on the lever
#: (and its medium),
#: the frequency and the record but not on V_ac or V_dc, and the noise records, which depend on
#: the sensor, e_n^2, the record and the seed, not on the drive.
_DRIVES, _NOISES = _Memo(), _Memo()


def _drive(probe: ActiveProbe, f: float, n: int, fs: float) -> tuple:
    """The record's times, bins, sampled drive waveforms, transfer function and one deflection.

    Returns ``(t, freqs, s, tone, h, d_ss)``: t = k / fs, the rfft bin frequencies, s = sin(w t),
    the interference's sin(6 w t), H = :meth:`ActiveProbe.deflection_per_power` at the bins, and
    d_ss = ``irfft(rfft(s^2) H)``, the periodic steady-state deflection (m) of a heater power
    s^2 W. Without a bias P = V_ac^2 s^2 / R, and heat -> deflection is linear (the FFT too), so
    the deflection of P is (V_ac^2 / R) d_ss, equal to the FFT of the sampled P through H to
    rounding (tested): the same sampled square, without an FFT pair and a sine a move of V_ac.
    A new frequency or record (the other sliders) costs what one run did before.
    """
    values = dict(probe.actuator.values)
    values.pop("ac_voltage")

    def compute():
        t = np.arange(n) / fs
        freqs = np.fft.rfftfreq(n, 1.0 / fs)
        h = probe.deflection_per_power(freqs)
        s = np.sin(2 * math.pi * f * t)
        return (t, freqs, s, np.sin(2 * math.pi * 6 * f * t), h,
                np.fft.irfft(np.fft.rfft(s * s) * h, n))
    return _DRIVES.get((probe.actuator.fluid, values, f, n, fs), compute)


def _noises(probe, e_n2, freqs, n, fs, seed):
    """The Brownian and the electrical noise records (m, V) of seed ``seed``."""
    def compute():
        s = probe.sensor
        rng = np.random.default_rng(seed)
        electrical = _electrical_density(s, e_n2, np.maximum(freqs, freqs[1]))
        return (_noise(rng, brownian_density(probe, freqs), n, fs),
                _noise(rng, electrical, n, fs))
    return _NOISES.get((probe.sensor.fluid, dict(probe.sensor.values), e_n2, n, fs, seed), compute)


def simulate(probe: ActiveProbe | None = None, *, dc_voltage: float = DC_VOLTAGE.default,
             half_resonance_ratio: float = HALF_RESONANCE_RATIO.default,
             amplifier_noise: float = AMPLIFIER_NOISE.default,
             amplifier_gain: float = AMPLIFIER_GAIN.default,
             interference: float = INTERFERENCE.default,
             samples_per_period: int = int(SAMPLES_PER_PERIOD.default),
             record_duration: float = RECORD_DURATION.default, noise: bool = True,
             seed: int = 0) -> ChainRun:
    """Simulate the chain over a whole number of drive periods (see the module docstring).

    Parameters
    ----------
    probe : ActiveProbe, optional
        The probe (default: module (b)'s default heater and bridge, V_ac = 0.5 V).
    dc_voltage : float
        Heater bias V_dc in V (0: a pure 2-w drive).
    half_resonance_ratio : float
        Drive frequency over f1 / 2.
    amplifier_noise : float
        Amplifier input noise density e_n^2 in V^2/Hz (one-sided; e_n = 10 nV/sqrt(Hz) is
        1e-16 V^2/Hz).
    amplifier_gain : float
        Amplifier gain G.
    interference : float
        Peak amplitude in V (at the amplifier input) of a tone at 3 x 2 w.
    samples_per_period : int
        Samples per drive period, 16 to 1024.
    record_duration : float
        Minimum record length in s (rounded up to whole drive periods).
    noise : bool
        Add the noise sources (False: the deterministic chain).
    seed : int
        Seed of the noise generator.

    Returns
    -------
    ChainRun

    Raises
    ------
    ValueError
        If an argument is out of range or the record exceeds ``LIMITS["samples"]`` samples.

    Notes
    -----
    What does not depend on the drive amplitude V_ac is remembered for the next runs (bounded;
    read-only arrays): the drive's sampled waveforms and their deflections, and the noise records
    (see ``_drive``, ``_NOISES``); a run is the same with or without them (tested). The chain
    itself is not linear in V_ac (P = V^2 / R, and the bridge reads the deflection about its
    operating point), so a run is never scaled from another.
    """
    probe = ActiveProbe() if probe is None else check_instance("probe", probe, ActiveProbe)
    dc_voltage = DC_VOLTAGE.check(dc_voltage)
    ratio = HALF_RESONANCE_RATIO.check(half_resonance_ratio)
    e_n2 = AMPLIFIER_NOISE.check(amplifier_noise)
    gain = AMPLIFIER_GAIN.check(amplifier_gain)
    interference = INTERFERENCE.check(interference)
    spp = check_integer("samples_per_period", samples_per_period, int(SAMPLES_PER_PERIOD.low),
                        int(SAMPLES_PER_PERIOD.high))
    duration = RECORD_DURATION.check(record_duration)
    noise = check_flag("noise", noise)
    seed = check_integer("seed", seed, 0, 2 ** 63 - 1)
    a, s = probe.actuator, probe.sensor
    f = ratio * probe.resonance_frequency / 2
    fs = spp * f
    periods = max(1, math.ceil(duration * f - 1e-9))
    n = periods * spp
    if n > LIMITS["samples"]:
        raise ValueError(f"record_duration {duration:g} s needs {n} samples at "
                         f"{spp} per period; at most {LIMITS['samples']}: shorten it or lower "
                         f"samples_per_period")
    t, freqs, wave, tone, h, d_ss = _drive(probe, f, n, fs)
    voltage = dc_voltage + a.ac_voltage * wave
    power = voltage * voltage / a.resistance
    if dc_voltage:  # the FFT of the sampled power through H
        deflection = np.fft.irfft(np.fft.rfft(power) * h, n)
    else:  # the same, P being V_ac^2 / R times the sampled s^2 (see _drive)
        deflection = (a.ac_voltage ** 2 / a.resistance) * d_ss

    if noise:  # the same records for every drive (remembered: see _NOISES)
        brownian, v_noise = _noises(probe, e_n2, freqs, n, fs, seed)
    else:
        brownian, v_noise = np.zeros(n), np.zeros(n)
    bridge = s.respond(deflection + brownian)
    output = bridge + v_noise  # gain (bridge + noise + interference tone), in place
    if interference:
        output += interference * tone
    output *= gain

    p_dc, p_1, p_2 = power_harmonics(dc_voltage, a.ac_voltage, a.resistance)
    h_0, h_1, h_2 = probe.deflection_per_power(np.array([0.0, f, 2 * f]))
    volts_per_metre = s.sensitivity(at=float((p_dc * h_0).real))
    z2 = complex(p_2 * h_2)
    density = (float(brownian_density(probe, 2 * f)) * volts_per_metre ** 2
               + float(_electrical_density(s, e_n2, 2 * f)))
    return ChainRun(probe=probe, drive_frequency=f, sample_rate=fs, time=t,
                    heater_voltage=voltage, power=power, deflection=deflection,
                    brownian=brownian, bridge=bridge, output=output,
                    first=complex(gain * volts_per_metre * p_1 * h_1),
                    second=complex(gain * volts_per_metre * z2), second_deflection=z2,
                    noise_density=(density * gain * gain) if noise else 0.0)


def brownian_density(probe: ActiveProbe, f) -> np.ndarray:
    """The lever's Brownian deflection density in m^2/Hz at ``f`` (Hz), module (a)'s spectrum.

    Parameters
    ----------
    probe : ActiveProbe
        The probe.
    f : array_like
        Frequencies in Hz.
    """
    return check_instance("probe", probe, ActiveProbe).sensor.thermal_noise_density(f)
