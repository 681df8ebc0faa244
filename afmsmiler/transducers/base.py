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

(:func:`afmsmiler.brownian.mechanical_response`; Sarid, *Scanning Force Microscopy*, OUP 1994,
ch. 1; Garcia, *Amplitude Modulation AFM*, Wiley 2010, ch. 2). Its thermal (Brownian) motion is
the lever's own, from module (a)'s :mod:`afmsmiler.brownian`: the first mode's one-sided power
spectral density S_z(f) = S_0 |H_mech(f)|^2 with S_0 = 0.971 x 4 k_B T / (k omega1 Q)
(fluctuation-dissipation theorem), which integrates to 0.971 k_B T / k: for a point-loaded
rectangular lever the first mode carries the share 12 / (b_1 L)^4 = 0.971 of k_B T / k, the
higher modes the rest (Butt and Jaschke, Nanotechnology 6, 1 (1995)). The deflection noise in a
band is that spectrum integrated in closed form; well below resonance it is sqrt(S_0 B), the
white floor under every detector's resolution.

The medium
----------
Without ``fluid`` the lever rings at its vacuum f1 with the Q typed in (``quality_factor``).
With ``fluid="air"`` or ``"water"`` each mode n rings at its f_R,n in that fluid with the
fluid's Q_n, both from Sader's hydrodynamic function (:func:`afmsmiler.hydrodynamics.
fluid_mode`; Sader, J. Appl. Phys. 84, 64 (1998)): the fluid's added mass lowers the frequency,
its viscosity sets Q, and k is unchanged. The oscillator above then takes f_R,n and Q_n, so the
response, the thermal spectrum (S_0 = 0.971 x 4 k_B T / (k omega_R Q), which still integrates to
0.971 k_B T / k) and every chain built on them are the lever's in that medium. Sader's Q is a
weak-damping result (Q >> 1): below Q = 5 (:data:`afmsmiler.hydrodynamics.LOW_Q`)
:meth:`Transducer.validity` says that the one-oscillator model is rough there.

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

from ..brownian import (TEMPERATURE, mechanical_response, thermal_deflection_noise,
                        thermal_noise_density)
from ..cantilever import MAX_MODE, Cantilever
from ..hydrodynamics import FLUID_NAMES, LOW_Q, REYNOLDS_RANGE, fluid_mode
from ..parameters import UNDERDAMPED_QUALITY_FACTOR, Parameter
from ..validation import (check_array, check_choice, check_instance, check_integer,
                          check_positive)

__all__ = ["quantity", "Parameter", "Stage", "SignalChain", "FrequencyResponse", "Resolution",
           "Harmonics", "Transducer", "Operation", "BOLTZMANN", "ELEMENTARY_CHARGE", "EPSILON_0",
           "LEVER_PARAMETERS", "SWEEP_POINTS"]

#: Boltzmann constant k_B in J/K, elementary charge q in C, vacuum permittivity epsilon_0 in
#: F/m: scipy's CODATA values (2022 in scipy >= 1.15), kept under these names for the models.
BOLTZMANN = scipy.constants.k
ELEMENTARY_CHARGE = scipy.constants.e
EPSILON_0 = scipy.constants.epsilon_0

FUNCTIONS = ("sensing", "actuation", "both")
SIGNALS = ("DC&AC", "AC only", "AC mostly")
SIZES = ("bulk", "embedded")
#: Inputs sampled over the input's range by :meth:`Transducer.operate` (plots, 3D view).
SWEEP_POINTS = 201


def quantity(*, name: str, unit: str, display_unit: str | None = None,
             label: str = "") -> Parameter:
    """A quantity of a signal chain (a stage, an output, a sensitivity): a :class:`Parameter`
    without bounds, so that every quantity is described by the one class of
    :mod:`afmsmiler.parameters` (display scale from :data:`~afmsmiler.parameters.UNITS`).

    Parameters
    ----------
    name : str
        Identifier (one SI unit per name across the package).
    unit : str
        SI unit (``""`` if dimensionless).
    display_unit : str, optional
        Practical unit for plots and readouts (a key of ``UNITS``); default: ``unit``.
    label : str
        Human-readable description, e.g. ``"tip deflection"``.

    Returns
    -------
    Parameter
        Default 0, valid range unbounded.
    """
    return Parameter(name=name, unit=unit, display_unit=display_unit, default=0.0, label=label)


#: Parameters shared by every model: the lever's geometry (silicon), its typed Q (in vacuum: from
#: critical damping up, the vocabulary's named narrowing; a fluid computes its own Q, which may be
#: lower) and its temperature (module (a)'s Brownian motion, :mod:`afmsmiler.brownian`).
LEVER_PARAMETERS: tuple[Parameter, ...] = (
    Parameter(name="length", unit="m", display_unit="um", default=225e-6, low=20e-6, high=1e-3,
              label="lever length"),
    Parameter(name="width", unit="m", display_unit="um", default=28e-6, low=5e-6, high=100e-6,
              label="lever width"),
    Parameter(name="thickness", unit="m", display_unit="um", default=3e-6, low=0.2e-6,
              high=10e-6, label="lever thickness"),
    UNDERDAMPED_QUALITY_FACTOR,
    TEMPERATURE,
)


@dataclass(frozen=True)
class Stage:
    """One stage of a signal chain.

    Parameters
    ----------
    quantity : Parameter
        What the stage is (name, SI unit, display).
    values : ndarray
        Its values (SI) along the input sweep.
    """

    quantity: Parameter
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
        """The stage whose quantity is called ``name``.

        Parameters
        ----------
        name : str
            One of :attr:`names`.

        Raises
        ------
        TypeError
            If ``name`` is not a str.
        ValueError
            If no stage is called ``name``.
        """
        check_instance("name", name, str)
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
    input, output : Parameter
        What goes in (a tip force for sensors, the drive for actuators) and what comes out.
    unit : str
        SI unit of ``response`` (``output.unit`` per ``input.unit``).
    """

    frequency: np.ndarray
    response: np.ndarray
    input: Parameter
    output: Parameter
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
    quantity : Parameter
        The input quantity the noise is referred to (tip deflection for sensors).
    contributions : dict
        Name -> rms noise in ``quantity.unit`` (each source alone).
    """

    bandwidth: float
    quantity: Parameter
    contributions: dict = field(default_factory=dict)

    @property
    def total(self) -> float:
        """The sources added in quadrature (they are uncorrelated)."""
        return math.sqrt(sum(v * v for v in self.contributions.values()))

    @property
    def dominant(self) -> str:
        """Name of the largest contribution."""
        return max(self.contributions, key=self.contributions.get)


@dataclass(frozen=True)
class Operation:
    """A model run at one input: what a panel shows after one slider move (SI units).

    Made by :meth:`Transducer.operate`, which evaluates the signal chain once (over the input's
    range and at the input together); the figure and the 3D view draw from it and never run the
    model again.

    Attributes
    ----------
    model : Transducer
        The model that ran.
    mode : str
        ``"sensing"`` or ``"actuation"``.
    value : float
        The input (SI).
    sweep : SignalChain
        The chain over the input's valid range (``n_points`` inputs).
    point : SignalChain
        The chain at ``value`` (each stage an array of one value).
    sensitivity : float
        d(output)/d(input) at ``value`` (SI, ``model.sensitivity_quantity(mode).unit``).
    response : FrequencyResponse or None
        The frequency response at the frequencies asked for.
    resolution : Resolution or None
        The noise-limited resolution in the bandwidth asked for.
    validity : tuple of str
        Where the model's assumptions fail at ``value`` (see :meth:`Transducer.validity`).
    """

    model: "Transducer"
    mode: str
    value: float
    sweep: SignalChain
    point: SignalChain
    sensitivity: float
    response: FrequencyResponse | None = None
    resolution: Resolution | None = None
    validity: tuple = ()

    @property
    def deflection_fraction(self) -> float:
        """Tip deflection at ``value`` over the largest |deflection| of the sweep, in [-1, 1]."""
        z_max = float(np.abs(self.sweep.stage("deflection").values).max()) or 1.0
        return float(self.point.stage("deflection").values[0]) / z_max

    @property
    def output_fraction(self) -> float:
        """Output at ``value`` over the largest |output| of the sweep, in [-1, 1]."""
        out_max = float(np.abs(self.sweep.output.values).max()) or 1.0
        return float(self.point.output.values[0]) / out_max


class Transducer:
    """Base class of a transducer model (see the module docstring).

    Subclasses set the class attributes ``key``, ``name``, ``function``, ``signal``, ``size``,
    ``PARAMETERS`` (their own :class:`Parameter` entries; the lever's are added), ``MODES``,
    ``INPUTS`` and ``OUTPUTS`` (mode -> :class:`Parameter` of the chain's input, mode ->
    :func:`quantity` of its output), ``SENSITIVITY`` (mode -> :func:`quantity` of the
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
    fluid : str, optional
        The lever's medium, ``"air"`` or ``"water"``: each mode rings at its frequency in the
        fluid with the fluid's Q (Sader 1998; the typed ``quality_factor`` is then unused).
        Default None: in vacuum, with the typed Q (see the module docstring).
    **params : float
        Any of :meth:`parameter_table` by name, in SI units; the others take their defaults.

    Raises
    ------
    TypeError
        For an unknown parameter name.
    ValueError
        For a value outside the parameter's valid range (the message names it and the range),
        or an unknown fluid.
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

    def __init__(self, *, fluid: str | None = None, **params):
        if fluid is not None and not (isinstance(fluid, str) and fluid in FLUID_NAMES):
            raise ValueError(f"fluid must be None (vacuum, the typed Q) or one of "
                             f"{list(FLUID_NAMES)}, got {fluid!r}")
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
        self._fluid = fluid
        self._modes = {}   # mode number -> (f_n, Q_n) in the medium, computed once
        self._sader = {}   # mode number -> its FluidMode, in a fluid

    def __init_subclass__(cls, **kwargs):
        super().__init_subclass__(**kwargs)
        if cls.key:
            check_choice(f"{cls.__name__}.function", cls.function, FUNCTIONS)
            check_choice(f"{cls.__name__}.signal", cls.signal, SIGNALS)
            check_choice(f"{cls.__name__}.size", cls.size, SIZES)

    def _validate(self, values: dict) -> None:
        """Checks involving several parameters (:attr:`BOUNDED_BY`); raise ValueError naming both
        (either may be the one the user just set)."""
        table = self.parameter_table()
        for name, (other, factor) in self.BOUNDED_BY.items():
            high = factor * values[other]
            if not 0.0 < values[name] <= high:
                unit = table[name].unit
                raise ValueError(f"{name} must be in (0, {high:g}] {unit} ({factor:g} x {other} "
                                 f"= {values[other]:g} {unit}), got {values[name]:g} {unit}")

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
        medium = "" if self.fluid is None else f"fluid={self.fluid!r}, "
        return f"{type(self).__name__}({medium}{args})"

    def __eq__(self, other) -> bool:
        return (type(self) is type(other) and self.fluid == other.fluid
                and self._values == other._values)

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
        """A copy with some parameters (or ``fluid``) changed, validated like the constructor."""
        return type(self)(**{"fluid": self.fluid, **self._values, **changes})

    def _mode(self, mode) -> str:
        return self.MODES[0] if mode is None else check_choice("mode", mode, self.MODES)

    def input_quantity(self, mode=None) -> Parameter:
        """The input of the chain of ``mode`` (a :class:`Parameter`: its range bounds the sweep)."""
        return self.INPUTS[self._mode(mode)]

    def output_quantity(self, mode=None) -> Parameter:
        """The output of the chain of ``mode`` (default: the first mode)."""
        return self.OUTPUTS[self._mode(mode)]

    def sensitivity_quantity(self, mode=None) -> Parameter:
        """Unit and display of :meth:`sensitivity` for ``mode``."""
        return self.SENSITIVITY[self._mode(mode)]

    # -- the lever --------------------------------------------------------------------------
    @property
    def spring_constant(self) -> float:
        """k of the lever in N/m."""
        return self.lever.spring_constant

    @property
    def fluid(self) -> str | None:
        """The lever's medium: None (vacuum, the typed Q), ``"air"`` or ``"water"``."""
        return self._fluid

    def mode_in_medium(self, mode: int = 1) -> tuple:
        """Where flexural mode ``mode`` rings and its Q: (f_n in Hz, Q_n).

        In vacuum the lever's own f_n and the typed Q (the same for every mode); in a fluid
        f_R,n and Q_n from Sader's hydrodynamic function
        (:func:`afmsmiler.hydrodynamics.fluid_mode`).

        Parameters
        ----------
        mode : int
            Mode number n, 1 to :data:`~afmsmiler.cantilever.MAX_MODE`.

        Returns
        -------
        tuple of float
            (f_n in Hz, Q_n).
        """
        return self._medium(check_integer("mode", mode, 1, MAX_MODE))

    def _medium(self, mode: int) -> tuple:
        """:meth:`mode_in_medium` of a checked mode number (the properties ask it often)."""
        if mode not in self._modes:
            if self.fluid is None:
                self._modes[mode] = (self.lever.resonance_frequency(mode),
                                     self._values["quality_factor"])
            else:
                m = self._sader[mode] = fluid_mode(self.lever, self.fluid, mode)
                self._modes[mode] = (m.resonance_frequency, m.quality_factor)
        return self._modes[mode]

    @property
    def resonance_frequency(self) -> float:
        """f1 of the lever in Hz, in its medium."""
        return self._medium(1)[0]

    @property
    def quality_factor(self) -> float:
        """Q of the first mode: the typed one in vacuum, the fluid's in a fluid."""
        return self._medium(1)[1]

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
        return thermal_deflection_noise(self.lever, quality_factor=self.quality_factor,
                                        temperature=self.temperature, bandwidth=bandwidth,
                                        low_frequency=low_frequency, mode=1,
                                        resonance_frequency=self.resonance_frequency)

    def thermal_noise_density(self, f) -> np.ndarray:
        """One-sided power spectral density of the Brownian tip deflection in m^2/Hz.

        S_z(f) = 0.971 x 4 k_B T / (k omega1 Q) |H_mech(f)|^2, the first mode's share (see
        :func:`afmsmiler.brownian.thermal_noise_density`), at f1 and Q in the lever's medium.

        Parameters
        ----------
        f : array_like
            Frequencies in Hz, >= 0.
        """
        return thermal_noise_density(self.lever, f, quality_factor=self.quality_factor,
                                     temperature=self.temperature, mode=1,
                                     resonance_frequency=self.resonance_frequency)

    # -- the lever's shape --------------------------------------------------------------------
    def deflection_shape(self, u) -> tuple:
        """The drawn lever's shape along it, normalised to 1 at the tip, and its derivatives.

        A static chain bends the lever like an end load, (3 u^2 - u^3) / 2 (module (a)); a model
        that drives the first mode at resonance (the piezo shaker) overrides this with the mode
        shape. The 3D view draws whatever the model says here.

        Parameters
        ----------
        u : array_like
            Positions along the lever as fractions of L, in [0, 1].

        Returns
        -------
        tuple of ndarray
            (shape, d shape / du, d^2 shape / du^2).
        """
        u = check_array("u", u, low=0.0, high=1.0)
        return (3 * u ** 2 - u ** 3) / 2, 3 * (u - u ** 2 / 2), 3 * (1 - u)

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

    def operate(self, value: float, mode=None, *, frequencies=None, bandwidth: float | None = None,
                n_points: int = SWEEP_POINTS) -> Operation:
        """Everything a panel shows at input ``value``, the signal chain evaluated once.

        The chain runs once over ``n_points`` inputs spanning the input's valid range with
        ``value`` appended; the sweep, the point, the sensitivity at ``value``, and (when asked)
        the frequency response and the resolution come with it.

        Parameters
        ----------
        value : float
            The input in SI units, inside the input's valid range.
        mode : str, optional
            As for :meth:`chain`.
        frequencies : array_like, optional
            Frequencies in Hz (>= 0) of the frequency response; none when omitted.
        bandwidth : float, optional
            Measurement bandwidth in Hz of the resolution; none when omitted.
        n_points : int
            Inputs of the sweep, 2 to 100000.

        Returns
        -------
        Operation

        Raises
        ------
        ValueError
            If ``value`` is outside the input's range, ``mode`` is not offered, or a size or
            bandwidth is invalid.
        """
        mode = self._mode(mode)
        q = self.INPUTS[mode]
        value = q.check(value)
        n_points = check_integer("n_points", n_points, 2, 100_000)
        if frequencies is not None:
            frequencies = check_array("frequencies", frequencies, "Hz", low=0.0, ndim=1)
        xs = np.append(np.linspace(q.low, q.high, n_points), value)
        both = self.chain(xs, mode)
        sweep = SignalChain(mode, tuple(Stage(st.quantity, st.values[:-1]) for st in both.stages))
        point = SignalChain(mode, tuple(Stage(st.quantity, st.values[-1:]) for st in both.stages))
        return Operation(
            model=self, mode=mode, value=value, sweep=sweep, point=point,
            sensitivity=self.sensitivity(mode, at=value),
            response=None if frequencies is None else self.frequency_response(frequencies, mode),
            resolution=None if bandwidth is None else self.resolution(bandwidth, mode=mode),
            validity=(*self._medium_validity(), *self._validity(value, mode, point)))

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
        mech = mechanical_response(f, resonance_frequency=self.resonance_frequency,
                                   quality_factor=self.quality_factor)
        out = self.OUTPUTS[mode]
        at = self.operating_point(mode)
        if mode == "sensing":
            gain = self._sensitivity(mode, at) / self.spring_constant
            inp = TIP_FORCE
        else:
            gain = self._sensitivity(mode, at)
            q = self.INPUTS[mode]
            # around a bias, the response is to a small AC drive added to it
            inp = q.with_(label=f"small AC drive on {q.label}") if self.BIASED else q
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
        value = self.INPUTS[mode].check(value)
        return (*self._medium_validity(),
                *self._validity(value, mode, self.chain(np.array([value]), mode)))

    def _medium_validity(self):
        if self.fluid is None:
            return
        if self.quality_factor < LOW_Q:
            yield (f"in {self.fluid} Q = {self.quality_factor:.3g}: Sader's Q holds for Q >> 1, "
                   "so the one-oscillator lever is rough here")
        self._medium(1)
        m = self._sader[1]
        if not m.in_fit_range:
            yield (f"in {self.fluid} the lever's Reynolds number {m.reynolds_number:.3g} lies "
                   f"outside Sader's fit ({REYNOLDS_RANGE[0]:g} to {REYNOLDS_RANGE[1]:g}): its "
                   "f1 and Q there are extrapolated")

    # -- to implement -----------------------------------------------------------------------
    def _validity(self, value: float, mode: str, point: SignalChain):
        """Messages where the model fails at ``value``; ``point`` is the chain there."""
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


DEFLECTION = quantity(name="deflection", unit="m", display_unit="nm", label="tip deflection")
SLOPE = quantity(name="slope", unit="rad", display_unit="mrad", label="free-end slope")
FORCE = quantity(name="force", unit="N", display_unit="nN", label="force on the lever")
TIP_FORCE = quantity(name="force", unit="N", display_unit="nN", label="tip force")
TIP_DEFLECTION_INPUT = Parameter(name="deflection", unit="m", display_unit="nm", default=20e-9,
                                 low=-2e-6, high=2e-6, label="tip deflection")

