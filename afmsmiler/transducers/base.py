"""The base of every transducer model: parameter metadata, the lever, its dynamics and noise floor.

A transducer model turns a physical input into an output signal through the cantilever of module
(a) (:class:`afmsmiler.cantilever.Cantilever`). Every model is described by data, in the spirit of
nanite's model registry: class attributes say what it is (``key``, ``name``, ``function``,
``signal``, ``size``: the columns of the paper's Table I) and a table of :class:`Parameter`
entries (name, SI unit, default, valid range, practical display unit and scale) from which the
widgets, the docs and Table I are generated instead of being typed twice.

The common mechanics (all models)
---------------------------------
The lever is a silicon :class:`~afmsmiler.cantilever.Cantilever` of the given ``length``,
``width`` and ``thickness``. Its first flexural mode, seen at the tip, is a damped harmonic
oscillator of stiffness k (the end-load spring constant), resonance f1 and quality factor Q::

    H_mech(f) = 1 / (1 - (f/f1)^2 + j f / (Q f1))          (= 1 at DC, ~ -j Q at f1)

(e.g. Sarid, *Scanning Force Microscopy*, OUP 1994, ch. 1; Garcia, *Amplitude Modulation AFM*,
Wiley 2010, ch. 2). Its thermal (Brownian) motion has the one-sided power spectral density
S_z(f) = S_0 |H_mech(f)|^2 with S_0 = 4 k_B T / (k omega1 Q) (fluctuation-dissipation theorem
applied to that oscillator; Butt and Jaschke, Nanotechnology 6, 1 (1995)), which integrates to
k_B T / k over all frequencies (equipartition). The deflection noise in a band [f_a, f_b] is
sqrt(S_0 f1 (F(f_b / f1) - F(f_a / f1))) with the closed-form antiderivative of |H_mech|^2 in
r = f / f1, b = sqrt(4 - 1/Q^2) (partial fractions of 1 / (r^2 - b r + 1)(r^2 + b r + 1))::

    F(r) = r / (2 (1 + r^2)) atanh(x) / x + (Q / 2) atan2(r, Q (1 - r^2)),   x = b r / (1 + r^2)

(F(inf) = pi Q / 2); well below resonance it is sqrt(S_0 B), the white floor under every
detector's resolution. The first mode alone holds 97 % of the end-load lever's k_B T / k
(Butt and Jaschke); the model gives the whole of it to the first mode.

Conventions
-----------
Public methods take and return SI units. Deflections z are positive when the tip moves up
(away from the sample), as in module (a). A model may have two modes (``"sensing"`` and
``"actuation"``, the piezoelectric film is both); a sensing chain starts from the tip deflection
z, an actuation chain from the drive quantity (voltage, current, power) and ends at z.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import ClassVar

import numpy as np
import scipy.constants

from ..cantilever import Cantilever
from ..validation import check_array, check_choice, check_positive, check_range

__all__ = ["Quantity", "Parameter", "Stage", "SignalChain", "FrequencyResponse", "Resolution",
           "Harmonics", "Transducer", "BOLTZMANN", "ELEMENTARY_CHARGE", "EPSILON_0",
           "LEVER_PARAMETERS",
           "mechanical_response", "thermal_deflection_noise"]

#: Boltzmann constant k_B in J/K, elementary charge q in C, vacuum permittivity epsilon_0 in
#: F/m: scipy's CODATA values (2022 in scipy >= 1.15), kept under these names for the models.
BOLTZMANN = scipy.constants.k
ELEMENTARY_CHARGE = scipy.constants.e
EPSILON_0 = scipy.constants.epsilon_0

FUNCTIONS = ("sensing", "actuation", "both")
SIGNALS = ("DC&AC", "AC only", "AC mostly")
SIZES = ("bulk", "embedded")


@dataclass(frozen=True)
class Quantity:
    """A physical quantity: its name, SI unit, and how widgets and plots show it.

    Parameters
    ----------
    name : str
        Identifier (also the keyword argument of a parameter).
    unit : str
        SI unit, e.g. ``"m"``, ``"V"``, ``"1/Pa"`` (``""`` if dimensionless).
    display_unit : str
        Practical unit for widgets and plots, e.g. ``"nm"``.
    scale : float
        Display value = SI value * ``scale`` (1e9 for m -> nm).
    label : str
        Human-readable description, e.g. ``"tip deflection"``.
    """

    name: str
    unit: str
    display_unit: str = ""
    scale: float = 1.0
    label: str = ""

    def display(self, si_value):
        """The value ``si_value`` (SI, scalar or array) in the display unit."""
        if np.ndim(si_value):
            return np.asarray(si_value) * self.scale
        return float(si_value) * self.scale

    def to_si(self, display_value):
        """``display_value`` (in the display unit) back in SI."""
        return display_value / self.scale

    @property
    def title(self) -> str:
        """``"label [display unit]"`` for an axis or a slider."""
        text = self.label or self.name.replace("_", " ")
        return f"{text} [{self.display_unit}]" if self.display_unit else text


@dataclass(frozen=True)
class Parameter(Quantity):
    """A model parameter: a :class:`Quantity` with a default and a valid range (SI).

    Parameters
    ----------
    name, unit, display_unit, scale, label
        As for :class:`Quantity`.
    default : float
        Default value in SI units.
    low, high : float
        Valid range (inclusive) in SI units.
    log : bool
        Whether a widget should use a logarithmic slider (the range spans decades; needs low > 0).
    """

    default: float = 0.0
    low: float = -math.inf
    high: float = math.inf
    log: bool = False

    def __post_init__(self):
        if not (self.low <= self.default <= self.high):
            raise ValueError(f"parameter {self.name}: default {self.default} outside "
                             f"[{self.low}, {self.high}]")
        if self.log and not self.low > 0:
            raise ValueError(f"parameter {self.name}: a log slider needs low > 0")

    def check(self, value) -> float:
        """Return ``value`` as float; raise ``ValueError`` naming the parameter unless in range."""
        return check_range(self.name, value, self.low, self.high, self.unit)


#: Parameters shared by every model: the lever's geometry (silicon), its Q and its temperature.
LEVER_PARAMETERS: tuple[Parameter, ...] = (
    Parameter("length", "m", "um", 1e6, "lever length", 225e-6, 20e-6, 1e-3),
    Parameter("width", "m", "um", 1e6, "lever width", 28e-6, 5e-6, 100e-6),
    Parameter("thickness", "m", "um", 1e6, "lever thickness", 3e-6, 0.2e-6, 10e-6),
    Parameter("quality_factor", "", "", 1.0, "quality factor Q", 150.0, 0.5, 1e5, log=True),
    Parameter("temperature", "K", "K", 1.0, "temperature", 295.0, 1.0, 600.0),
)


@dataclass(frozen=True)
class Stage:
    """One stage of a signal chain.

    Parameters
    ----------
    quantity : Quantity
        What the stage is (name, SI unit, display).
    values : ndarray
        Its values (SI) along the input sweep.
    """

    quantity: Quantity
    values: np.ndarray


@dataclass(frozen=True)
class SignalChain:
    """A signal chain from the input through the lever to the output, for an array of inputs.

    Attributes
    ----------
    mode : str
        ``"sensing"`` or ``"actuation"``.
    stages : tuple of Stage
        The input first, then the intermediate quantities (deflection, slope, ...), the output last.
    """

    mode: str
    stages: tuple

    @property
    def input(self) -> Stage:
        return self.stages[0]

    @property
    def output(self) -> Stage:
        return self.stages[-1]

    def stage(self, name: str) -> Stage:
        """The stage whose quantity is called ``name``."""
        for s in self.stages:
            if s.quantity.name == name:
                return s
        raise ValueError(f"name must be one of {list(self.names)}, got {name!r}")

    @property
    def names(self) -> tuple:
        return tuple(s.quantity.name for s in self.stages)


@dataclass(frozen=True)
class FrequencyResponse:
    """A complex frequency response: output per input at each frequency (SI units).

    Attributes
    ----------
    frequency : ndarray
        Frequencies in Hz.
    response : ndarray of complex
        Output per input (``unit``) at each frequency.
    input, output : Quantity
        What goes in (a tip force for sensors, the drive for actuators) and what comes out.
    unit : str
        SI unit of ``response`` (``output.unit`` per ``input.unit``).
    """

    frequency: np.ndarray
    response: np.ndarray
    input: Quantity
    output: Quantity
    unit: str

    @property
    def magnitude(self) -> np.ndarray:
        return np.abs(self.response)

    @property
    def phase(self) -> np.ndarray:
        """Phase in rad."""
        return np.angle(self.response)


@dataclass(frozen=True)
class Harmonics:
    """A force (N), power (W) or deflection (m) split by frequency: P(t) = dc + first cos(omega t)
    + second cos(2 omega t) (complex amplitudes carry the phase).

    Parameters
    ----------
    dc : complex
        The static part.
    first : complex
        The amplitude at the drive frequency omega.
    second : complex
        The amplitude at 2 omega.
    """

    dc: complex
    first: complex
    second: complex


@dataclass(frozen=True)
class Resolution:
    """The noise-limited resolution in a bandwidth, referred to the chain's input.

    Attributes
    ----------
    bandwidth : float
        Measurement bandwidth B in Hz.
    quantity : Quantity
        The input quantity the noise is referred to (tip deflection for sensors).
    contributions : dict
        Name -> rms noise in ``quantity.unit`` (each source alone).
    """

    bandwidth: float
    quantity: Quantity
    contributions: dict = field(default_factory=dict)

    @property
    def total(self) -> float:
        """The sources added in quadrature (they are uncorrelated)."""
        return math.sqrt(sum(v * v for v in self.contributions.values()))

    @property
    def dominant(self) -> str:
        """Name of the largest contribution."""
        return max(self.contributions, key=self.contributions.get)


def mechanical_response(f, resonance_frequency: float, quality_factor: float) -> np.ndarray:
    """First-mode tip response to a tip force, normalised to 1 at DC (a damped oscillator).

    Parameters
    ----------
    f : array_like
        Frequencies in Hz (>= 0).
    resonance_frequency : float
        f1 in Hz.
    quality_factor : float
        Q (> 0).

    Returns
    -------
    ndarray of complex
        1 / (1 - (f/f1)^2 + j f / (Q f1)).

    Raises
    ------
    ValueError
        If a frequency is negative or not finite, or f1 or Q is not finite and positive.
    """
    f = check_array("f", f, "Hz", low=0.0)
    resonance_frequency = check_positive("resonance_frequency", resonance_frequency, "Hz")
    quality_factor = check_positive("quality_factor", quality_factor)
    r = f / resonance_frequency
    return 1.0 / (1.0 - r * r + 1j * r / quality_factor)


def _response_power_integral(r, quality_factor: float):
    """int_0^r |1 / (1 - u^2 + j u / Q)|^2 du (see the module docstring), for Q >= 1/2, r >= 0."""
    r = np.asarray(r, dtype=float)
    b = math.sqrt(4.0 - 1.0 / quality_factor ** 2)
    x = b * r / (1.0 + r * r)
    safe = np.where(x > 1e-6, x, 0.5)   # a dummy where the series is used
    ratio = np.where(x > 1e-6, np.arctanh(safe) / safe, 1.0 + x * x / 3.0)
    return (r / (2.0 * (1.0 + r * r)) * ratio
            + quality_factor / 2.0 * np.arctan2(r, quality_factor * (1.0 - r * r)))


def thermal_deflection_noise(lever: Cantilever, quality_factor: float, temperature: float,
                             bandwidth: float, low_frequency: float | None = None) -> float:
    """Rms Brownian tip deflection in m within a bandwidth.

    Without ``low_frequency``: sqrt(4 k_B T B / (k omega1 Q)), the white floor S_0 B of the
    oscillator's thermal spectrum well below resonance (what a drive at any frequency competes
    with, since drive and Brownian force pass the same |H_mech|). With it: the spectrum
    S_0 |H_mech(f)|^2 integrated over [low_frequency, low_frequency + B] in closed form (see the
    module docstring), the tip's actual rms motion in that band, resonance included.

    Parameters
    ----------
    lever : Cantilever
        The lever (its k and f1).
    quality_factor : float
        Q of the first mode, >= 1/2 for the band integral (> 0 for the white floor).
    temperature : float
        T in K.
    bandwidth : float
        B in Hz.
    low_frequency : float, optional
        Lower edge of the band in Hz, >= 0.

    Raises
    ------
    ValueError
        If ``lever`` is not a Cantilever or a number is not finite and in its range.
    """
    if not isinstance(lever, Cantilever):
        raise ValueError(f"lever must be a Cantilever, got {lever!r}")
    quality_factor = check_positive("quality_factor", quality_factor)
    temperature = check_positive("temperature", temperature, "K")
    bandwidth = check_positive("bandwidth", bandwidth, "Hz")
    f1 = lever.resonance_frequency(1)
    s0 = 4 * BOLTZMANN * temperature / (lever.spring_constant * 2 * math.pi * f1 * quality_factor)
    if low_frequency is None:
        return math.sqrt(s0 * bandwidth)
    low_frequency = check_range("low_frequency", low_frequency, 0.0, math.inf, "Hz")
    quality_factor = check_range("quality_factor", quality_factor, 0.5, math.inf)
    edges = _response_power_integral([low_frequency / f1, (low_frequency + bandwidth) / f1],
                                     quality_factor)
    return math.sqrt(s0 * f1 * max(float(edges[1] - edges[0]), 0.0))


class Transducer:
    """Base class of a transducer model (see the module docstring).

    Subclasses set the class attributes ``key``, ``name``, ``function``, ``signal``, ``size``,
    ``PARAMETERS`` (their own :class:`Parameter` entries; the lever's are added), ``MODES``,
    ``INPUTS`` and ``OUTPUTS`` (mode -> :class:`Parameter` of the chain's input, mode ->
    :class:`Quantity` of its output), ``SENSITIVITY`` (mode -> :class:`Quantity` of the
    sensitivity's unit), optionally ``BIASED`` and ``BOUNDED_BY``, and implement ``_stages``
    and ``_sensitivity`` (and, where they apply, ``_dynamics``, ``_detector_noise`` and
    ``_validity``).

    Examples
    --------
    >>> from afmsmiler.transducers import OpticalBeamDeflection
    >>> obd = OpticalBeamDeflection(optical_path=30e-3, length=225e-6)
    >>> round(obd.sensitivity() * 1e-6, 3)  # 1/um of tip deflection
    1.277

    Parameters
    ----------
    **params : float
        Any of :meth:`parameter_table` by name, in SI units; the others take their defaults.

    Raises
    ------
    TypeError
        For an unknown parameter name.
    ValueError
        For a value outside the parameter's valid range (the message names it and the range).
    """

    key: ClassVar[str] = ""
    name: ClassVar[str] = ""
    function: ClassVar[str] = ""
    signal: ClassVar[str] = ""
    size: ClassVar[str] = ""
    summary: ClassVar[str] = ""
    PARAMETERS: ClassVar[tuple] = ()
    MODES: ClassVar[tuple] = ("sensing",)
    INPUTS: ClassVar[dict] = {}
    OUTPUTS: ClassVar[dict] = {}
    #: Unit and display of the small-signal sensitivity, per mode.
    SENSITIVITY: ClassVar[dict] = {}
    #: True when the small-signal gain is taken at the input's default (a DC bias), not at 0.
    BIASED: ClassVar[bool] = False
    #: Parameters bounded by another: name -> (other, factor), meaning 0 < value <= factor * other
    #: (an electrode cannot be longer than the lever); widgets use it to bound their sliders.
    BOUNDED_BY: ClassVar[dict] = {}

    def __init__(self, **params):
        table = self.parameter_table()
        unknown = set(params) - set(table)
        if unknown:
            raise TypeError(f"{type(self).__name__} got unknown parameter(s) {sorted(unknown)}; "
                            f"valid: {sorted(table)}")
        values = {}
        for pname, meta in table.items():
            values[pname] = meta.check(params.get(pname, meta.default))
        self._values = values
        self._validate(values)
        self.lever = Cantilever.from_material("silicon", values["length"], values["width"],
                                              values["thickness"])

    def __init_subclass__(cls, **kwargs):
        super().__init_subclass__(**kwargs)
        if cls.key:
            check_choice(f"{cls.__name__}.function", cls.function, FUNCTIONS)
            check_choice(f"{cls.__name__}.signal", cls.signal, SIGNALS)
            check_choice(f"{cls.__name__}.size", cls.size, SIZES)

    def _validate(self, values: dict) -> None:
        """Checks involving several parameters (:attr:`BOUNDED_BY`); raise ValueError naming one."""
        table = self.parameter_table()
        for name, (other, factor) in self.BOUNDED_BY.items():
            check_range(name, values[name], 0.0, factor * values[other], table[name].unit,
                        low_inclusive=False)

    def upper_bound(self, name: str) -> float:
        """The largest valid value (SI) of parameter ``name`` given the other parameters."""
        meta = self.parameter_table()[check_choice("name", name, self.parameter_table())]
        if name in self.BOUNDED_BY:
            other, factor = self.BOUNDED_BY[name]
            return min(meta.high, factor * self._values[other])
        return meta.high

    def __getattr__(self, item):
        values = self.__dict__.get("_values")
        if values is not None and item in values:
            return values[item]
        raise AttributeError(f"{type(self).__name__!s} has no attribute {item!r}")

    def __repr__(self) -> str:
        args = ", ".join(f"{k}={v:g}" for k, v in self._values.items())
        return f"{type(self).__name__}({args})"

    def __eq__(self, other) -> bool:
        return type(self) is type(other) and self._values == other._values

    __hash__ = None

    # -- metadata ---------------------------------------------------------------------------
    @classmethod
    def parameter_table(cls) -> dict:
        """Name -> :class:`Parameter` of every parameter (the model's own, then the lever's)."""
        return {p.name: p for p in cls.PARAMETERS + LEVER_PARAMETERS}

    @classmethod
    def defaults(cls) -> dict:
        """Name -> default value (SI) of every parameter."""
        return {n: p.default for n, p in cls.parameter_table().items()}

    @property
    def values(self) -> dict:
        """Name -> value (SI) of every parameter of this instance."""
        return dict(self._values)

    def replace(self, **changes) -> "Transducer":
        """A copy with some parameters changed (validated like the constructor)."""
        return type(self)(**{**self._values, **changes})

    def _mode(self, mode) -> str:
        return self.MODES[0] if mode is None else check_choice("mode", mode, self.MODES)

    def input_quantity(self, mode=None) -> Parameter:
        """The input of the chain of ``mode`` (a :class:`Parameter`: its range bounds the sweep)."""
        return self.INPUTS[self._mode(mode)]

    def output_quantity(self, mode=None) -> Quantity:
        """The output of the chain of ``mode`` (default: the first mode)."""
        return self.OUTPUTS[self._mode(mode)]

    def sensitivity_quantity(self, mode=None) -> Quantity:
        """Unit and display of :meth:`sensitivity` for ``mode``."""
        return self.SENSITIVITY[self._mode(mode)]

    # -- the lever --------------------------------------------------------------------------
    @property
    def spring_constant(self) -> float:
        """k of the lever in N/m."""
        return self.lever.spring_constant

    @property
    def resonance_frequency(self) -> float:
        """f1 of the lever in Hz."""
        return self.lever.resonance_frequency(1)

    def thermal_noise(self, bandwidth: float, low_frequency: float | None = None) -> float:
        """Rms Brownian tip deflection in m within ``bandwidth`` Hz (see the module docstring).

        Parameters
        ----------
        bandwidth : float
            B in Hz, > 0.
        low_frequency : float, optional
            Lower edge of the band in Hz: the spectrum, resonance included, is integrated over
            [low_frequency, low_frequency + B]; without it, the white floor below resonance.
        """
        return thermal_deflection_noise(self.lever, self.quality_factor, self.temperature,
                                        bandwidth, low_frequency)

    def thermal_noise_density(self, f) -> np.ndarray:
        """One-sided power spectral density of the Brownian tip deflection in m^2/Hz.

        S_z(f) = 4 k_B T / (k omega1 Q) |H_mech(f)|^2 (see the module docstring).

        Parameters
        ----------
        f : array_like
            Frequencies in Hz, >= 0.
        """
        s0 = self.thermal_noise(1.0) ** 2
        response = mechanical_response(f, self.resonance_frequency, self.quality_factor)
        return s0 * np.abs(response) ** 2

    # -- the public interface -----------------------------------------------------------------
    def chain(self, value, mode=None) -> SignalChain:
        """The signal chain for input ``value`` (scalar or array, SI, see :meth:`input_quantity`).

        Parameters
        ----------
        value : float or array_like
            The input: tip deflection z in m for a sensing chain, the drive for an actuation chain.
        mode : {"sensing", "actuation"}, optional
            For a model that does both; default: its first mode.

        Returns
        -------
        SignalChain
            Input, intermediate stages (always including ``deflection`` in m and ``slope`` in rad
            of the free end) and output, each the shape of ``value``.

        Raises
        ------
        ValueError
            If ``value`` is outside the input's valid range or ``mode`` is not offered.
        """
        mode = self._mode(mode)
        q = self.INPUTS[mode]
        x = check_array(q.name, value, q.unit, low=q.low, high=q.high)
        stages = [Stage(q, x)] + [Stage(sq, np.asarray(v, dtype=float))
                                  for sq, v in self._stages(x, mode)]
        return SignalChain(mode, tuple(stages))

    def respond(self, value, mode=None):
        """The output for input ``value`` in the chain of ``mode`` (last stage of :meth:`chain`)."""
        return self.chain(value, mode).output.values

    def operating_point(self, mode=None) -> float:
        """The input (SI) of the chain of ``mode`` where :meth:`sensitivity` is taken by default.

        Zero (the nulled detector, the undriven actuator) except for drives whose force goes as
        the square of a voltage (electrostatic, electrothermal), where it is the input's default
        DC voltage: their small-signal gain vanishes at zero bias.
        """
        mode = self._mode(mode)
        return self.INPUTS[mode].default if self.BIASED else 0.0

    def sensitivity(self, mode=None, at=None) -> float:
        """Small-signal sensitivity d(output)/d(input) in SI units.

        For a sensing chain, output per metre of tip deflection (1/m, V/m, W/m, C/m); for an
        actuation chain, tip deflection per unit drive (m/V, m/A, m/W). Its unit is
        ``sensitivity_quantity(mode).unit``.

        Parameters
        ----------
        mode : str, optional
            As for :meth:`chain`.
        at : float, optional
            The input (SI) at which to take the slope; default :meth:`operating_point`.

        Raises
        ------
        ValueError
            If ``at`` is outside the input's valid range.
        """
        mode = self._mode(mode)
        at = self.operating_point(mode) if at is None else self.INPUTS[mode].check(at)
        return float(self._sensitivity(mode, at))

    def frequency_response(self, f, mode=None) -> FrequencyResponse:
        """The complex response at frequencies ``f`` (Hz).

        A sensing chain's response is the detector output per unit tip force, through the
        lever's first mode and the detector's own bandwidth; an actuation chain's is the tip
        deflection per unit drive, through thermal lags where there are any and the first mode.
        At f -> 0 it tends to ``sensitivity() / k`` (sensing) or ``sensitivity()`` (actuation),
        except for AC-only and AC-mostly paths, which vanish at DC.

        Parameters
        ----------
        f : array_like
            Frequencies in Hz, >= 0.
        mode : str, optional
            As for :meth:`chain`.
        """
        mode = self._mode(mode)
        f = check_array("f", f, "Hz", low=0.0)
        mech = mechanical_response(f, self.resonance_frequency, self.quality_factor)
        out = self.OUTPUTS[mode]
        at = self.operating_point(mode)
        if mode == "sensing":
            gain = self._sensitivity(mode, at) / self.spring_constant
            inp = Quantity("force", "N", "nN", 1e9, "tip force")
        else:
            gain = self._sensitivity(mode, at)
            q = self.INPUTS[mode]
            # around a bias, the response is to a small AC drive added to it
            inp = (Quantity(q.name, q.unit, q.display_unit, q.scale,
                            f"small AC drive on {q.label}") if self.BIASED else q)
        response = gain * mech * self._dynamics(f, mode)
        return FrequencyResponse(f, response, inp, out, f"{out.unit or '1'}/{inp.unit}")

    def resolution(self, bandwidth: float, low_frequency: float = 1.0, mode=None) -> Resolution:
        """Noise-limited resolution in a bandwidth, referred to the chain's input.

        Parameters
        ----------
        bandwidth : float
            Measurement bandwidth B in Hz, > 0 (the band is [low_frequency, low_frequency + B]).
        low_frequency : float
            Lower edge of the band in Hz, > 0 (matters for 1/f noise, leakage, and the Brownian
            motion of a sensing chain when the band reaches the resonance).
        mode : str, optional
            As for :meth:`chain`.

        Returns
        -------
        Resolution
            Rms contributions: the detector's own noise (where known) and the lever's Brownian
            motion (``"thermal"``), in the input's units. For a sensor, the Brownian motion is
            the tip's rms deflection in the band (its spectrum integrated, resonance included);
            for an actuator, the drive whose deflection equals it: the Brownian force is white
            and passes the same |H_mech| as the drive's, so it is the white floor sqrt(S_0 B)
            over the drive's static gain at any drive frequency.
        """
        bandwidth = check_positive("bandwidth", bandwidth, "Hz")
        low_frequency = check_positive("low_frequency", low_frequency, "Hz")
        mode = self._mode(mode)
        sens = abs(self._sensitivity(mode, self.operating_point(mode)))
        z_th = self.thermal_noise(bandwidth)    # the white floor (for drives)
        contributions = {}
        for source, rms_output in self._detector_noise(bandwidth, low_frequency, mode).items():
            contributions[source] = rms_output / sens if sens > 0 else math.inf
        if mode == "sensing":
            # the tip really moves this much in the band, its resonance included
            contributions["thermal"] = self.thermal_noise(bandwidth, low_frequency)
        else:
            # the smallest drive whose static deflection equals the Brownian motion
            static = abs(self._static_gain(mode, self.operating_point(mode)))
            contributions["thermal"] = z_th / static if static > 0 else math.inf
        return Resolution(bandwidth, self.INPUTS[mode], contributions)

    def validity(self, value, mode=None) -> tuple:
        """Where the model's assumptions fail at input ``value`` (SI): a tuple of messages.

        Empty when the model holds (the default); e.g. the electrostatic model past pull-in, or a
        bimorph heated by hundreds of kelvin.

        Parameters
        ----------
        value : float
            The input in SI units.
        mode : str, optional
            As for :meth:`chain`.
        """
        mode = self._mode(mode)
        return tuple(self._validity(self.INPUTS[mode].check(value), mode))

    # -- to implement -----------------------------------------------------------------------
    def _validity(self, value: float, mode: str):
        return ()

    def _stages(self, x: np.ndarray, mode: str):  # pragma: no cover - abstract
        raise NotImplementedError

    def _sensitivity(self, mode: str, at: float) -> float:  # pragma: no cover - abstract
        raise NotImplementedError

    def _dynamics(self, f: np.ndarray, mode: str):
        """Frequency dependence beyond the first mode, normalised (detector, thermal lag)."""
        return np.ones_like(f)

    def _static_gain(self, mode: str, at: float) -> float:
        """Tip deflection per unit drive at DC, for the thermal floor of an actuation chain."""
        return self._sensitivity(mode, at)

    def _detector_noise(self, bandwidth: float, low_frequency: float, mode: str) -> dict:
        """Name -> rms output noise (output units) in the band; none by default."""
        return {}

    # -- helpers for subclasses ------------------------------------------------------------
    def _lever_stages(self, z):
        """The free-end slope stage for tip deflections ``z`` (end load: theta = 3 z / (2 L)).

        A sensing chain's input stage is the tip deflection itself.
        """
        return [(SLOPE, 1.5 * z / self.lever.length)]


DEFLECTION = Quantity("deflection", "m", "nm", 1e9, "tip deflection")
SLOPE = Quantity("slope", "rad", "mrad", 1e3, "free-end slope")
FORCE = Quantity("force", "N", "nN", 1e9, "force on the lever")
TIP_DEFLECTION_INPUT = Parameter("deflection", "m", "nm", 1e9, "tip deflection", 20e-9,
                                 -2e-6, 2e-6)

