"""Module (a): the spring constant of a lever, calibrated as labs do it.

Three methods, each compared with the model's true k = 3 E J / L^3 (:class:`Cantilever`):

Sader's method (Sader, Chon and Mulvaney, "Calibration of rectangular atomic force microscope
cantilevers", Rev. Sci. Instrum. 70, 3967 (1999)). From the plan view (L, b), the fundamental
resonance frequency omega_f = 2 pi f_f and quality factor Q_f in a fluid (usually air) of density
rho_f::

    k = 0.1906 rho_f b^2 L Q_f Gamma_i(omega_f) omega_f^2

with Gamma_i the imaginary part of Sader's hydrodynamic function
(:func:`afmsmiler.hydrodynamics.hydrodynamic_function`). 0.1906 = (pi / 4) x 0.2427, the
effective mass M_e = 0.2427 M of mode 1 (L / b > 5); the formula assumes Q_f >> 1 and a lever
much heavier than the fluid it carries along (air, not water).

The thermal-noise method (Hutter and Bechhoefer, Rev. Sci. Instrum. 64, 1868 (1993); Butt and
Jaschke, Nanotechnology 6, 1 (1995)). The Brownian motion of mode 1 carries k_B T / 2 of
potential energy; seen at the tip, its mean-square deflection is share_1 k_B T / k with
share_1 = 12 / (b_1 L)^4 = 0.971 (the rest sits in the higher modes). An optical lever reads the
slope at the laser spot, calibrated in volts per metre by pressing the tip on a hard surface (an
end-loaded static shape): it reports the free mode's deflection z as z* = z / chi, with
chi = 1.09 for a spot at the free end (Butt and Jaschke 1995; Proksch et al., Nanotechnology 15,
1344 (2004)). Hence::

    k = share_1 k_B T / (chi^2 <z*^2>) = 0.817 k_B T / <z*^2>    (spot at the end)

chi is computed here from the mode shape for any spot position (:func:`optical_lever_correction`).
The mean square <z*^2> is the area of mode 1's peak in the deflection spectrum, fitted with a
simple-harmonic-oscillator line on a white background (:func:`fit_thermal_spectrum`).

The added-mass method (Cleveland, Manne, Bocek and Hansma, Rev. Sci. Instrum. 64, 403 (1993)):
a mass M glued at the tip lowers the resonance from nu_0 to nu_1, and since
(2 pi nu)^2 = k / (M + m*)::

    k = (2 pi)^2 M / (1 / nu_1^2 - 1 / nu_0^2)

(:func:`added_mass_spring_constant`).

The simulated spectrum
----------------------
:func:`thermal_spectrum` draws what a lab's spectrum analyser shows. The true one-sided spectrum
of the tip deflection is, by the fluctuation-dissipation theorem, S(f) = 4 k_B T Im chi(omega) /
omega for every mode, with the lever's response in the fluid taken from Sader's hydrodynamic
function at every frequency (not an oscillator with a fixed Q; Sader 1998)::

    chi_n(omega) = (share_n / k) / (1 - (omega / omega_vac,n)^2 (1 + T Gamma(omega))),
    T = pi rho_f b / (4 rho h)

(each mode integrates to share_n k_B T / k), seen through the optical lever (z*/z of the mode at
the spot), plus the detector's white noise floor. A periodogram of a record of 2N samples at the
rate f_s has N bins of width df = f_s / (2N); each bin of the average of M periodograms of
Gaussian noise is its mean times a Gamma(M, 1/M) variable (chi-squared with 2M degrees of
freedom over 2M; e.g. Press et al., *Numerical Recipes*, 3rd ed., Sec. 13.4), independent of the
others when the line is wider than a few bins. The spectrum is drawn so, bin by bin, instead of
simulating and transforming a time series: 2^20 bins take tens of milliseconds. Leakage of the
finite record and aliasing are left out (a windowed periodogram behind an anti-aliasing filter).

The fit is the maximum-likelihood fit for such data: the negative log-likelihood
M sum(ln S_i + P_i / S_i) of the Gamma-distributed bins P_i about the model S_i, minimised by
Fisher scoring (Gauss-Newton for this likelihood), whose inverse Fisher matrix at the optimum gives
the statistical error of f0, Q and the area, hence of k, from the record length and the number of
averages. A least-squares fit on the raw bins would weight the peak wrongly (the scatter of a bin
is proportional to its mean), and one on log P is biased by E[ln P] - ln S = psi(M) - ln M
(-0.577 for M = 1).
"""
from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np

from .brownian import BOLTZMANN, TEMPERATURE, mode_share
from .cantilever import MAX_MODE, Cantilever, eigenvalue
from .hydrodynamics import (REYNOLDS_RANGE, Fluid, FluidMode, _circ, _omega, fluid_mode,
                            get_fluid, hydrodynamic_function, mass_loading, reynolds_number)
from .parameters import QUALITY_FACTOR, RESONANCE_FREQUENCY, read_only
from .validation import check_array, check_instance, check_integer, check_range, check_size

__all__ = ["SADER_FACTOR", "LIMITS", "sader_spring_constant", "SaderCalibration",
           "sader_calibration", "added_mass_spring_constant", "optical_lever_correction",
           "ThermalSpectrum", "thermal_spectrum", "SHOFit", "fit_thermal_spectrum",
           "ThermalCalibration", "thermal_calibration", "LabCalibration", "calibrate"]

#: (pi / 4) x 0.2427: Sader, Chon and Mulvaney (1999)'s constant (M_e = 0.2427 M, L / b > 5).
SADER_FACTOR = 0.1906

#: Bounds of the simulated spectrum: bins (2^22 bins take about a second), averaged spectra,
#: and the fit's iterations.
LIMITS = read_only(dict(points=2 ** 22, averages=100_000, iterations=100))


# -- Sader's method --------------------------------------------------------------------------
def sader_spring_constant(length: float, width: float, resonance_frequency: float,
                          quality_factor: float, fluid="air") -> float:
    """Sader's method: k = 0.1906 rho_f b^2 L Q_f Gamma_i(omega_f) omega_f^2 in N/m.

    Sader, Chon and Mulvaney, Rev. Sci. Instrum. 70, 3967 (1999), with Gamma_i from
    :func:`~afmsmiler.hydrodynamics.hydrodynamic_function` (Sader 1998) at
    Re = rho_f omega_f b^2 / (4 eta), omega_f = 2 pi f_f.

    Parameters
    ----------
    length : float
        Lever length L in m.
    width : float
        Lever width b in m.
    resonance_frequency : float
        Measured fundamental resonance f_f in the fluid, in Hz (not rad/s).
    quality_factor : float
        Measured Q_f in the fluid (the method assumes Q_f >> 1).
    fluid : str or Fluid
        The fluid (a key of :data:`~afmsmiler.hydrodynamics.FLUIDS` or a Fluid).

    Returns
    -------
    float

    Raises
    ------
    ValueError
        Naming the parameter outside its range, or ``re`` when the Reynolds number leaves the
        range of Sader's fit.
    """
    length = check_range("length", length, 1e-9, 1.0, "m")
    width = check_range("width", width, 1e-9, 1.0, "m")
    resonance_frequency = RESONANCE_FREQUENCY.check(resonance_frequency)
    quality_factor = QUALITY_FACTOR.check(quality_factor)
    fluid = get_fluid(fluid)
    omega = 2.0 * math.pi * resonance_frequency
    re = reynolds_number(omega, width, fluid)
    if not REYNOLDS_RANGE[0] <= re <= REYNOLDS_RANGE[1]:
        raise ValueError(f"width = {width:g} m and resonance_frequency = {resonance_frequency:g} "
                         f"Hz give Re = {re:.3g} in {fluid.name}, outside the range "
                         f"[{REYNOLDS_RANGE[0]:g}, {REYNOLDS_RANGE[1]:g}] of Sader's "
                         f"hydrodynamic function")
    gamma_i = hydrodynamic_function(re).imag
    return (SADER_FACTOR * fluid.density * width ** 2 * length * quality_factor * gamma_i
            * omega ** 2)


@dataclass(frozen=True)
class SaderCalibration:
    """Sader's method applied to a lever's own resonance in a fluid (:func:`sader_calibration`).

    Attributes
    ----------
    mode : FluidMode
        Mode 1 in the fluid: the f_f and Q_f the method reads.
    spring_constant : float
        Sader's k in N/m.
    true_spring_constant : float
        The model's k = 3 E J / L^3 in N/m.
    """

    mode: FluidMode
    spring_constant: float
    true_spring_constant: float

    @property
    def relative_error(self) -> float:
        """k_Sader / k_true - 1."""
        return self.spring_constant / self.true_spring_constant - 1.0


def sader_calibration(lever: Cantilever, fluid="air") -> SaderCalibration:
    """Calibrate ``lever`` by Sader's method from its own f_f and Q_f in ``fluid``.

    The resonance and Q come from :func:`~afmsmiler.hydrodynamics.fluid_mode`; the method then
    sees only L, b, f_f, Q_f and the fluid, as in the lab.

    Parameters
    ----------
    lever : Cantilever
        The lever.
    fluid : str or Fluid
        The fluid.

    Returns
    -------
    SaderCalibration
    """
    mode = fluid_mode(lever, fluid, 1)
    k = sader_spring_constant(lever.length, lever.width, mode.resonance_frequency,
                              mode.quality_factor, mode.fluid)
    return SaderCalibration(mode=mode, spring_constant=k,
                            true_spring_constant=lever.spring_constant)


# -- the added-mass method -------------------------------------------------------------------
def added_mass_spring_constant(added_mass: float, loaded_frequency: float,
                               unloaded_frequency: float) -> float:
    """Cleveland's added-mass method: k = (2 pi)^2 M / (1 / nu_1^2 - 1 / nu_0^2) in N/m.

    Cleveland, Manne, Bocek and Hansma, Rev. Sci. Instrum. 64, 403 (1993): a mass M at the tip
    lowers the resonance from nu_0 to nu_1, (2 pi nu)^2 = k / (M + m*).

    Parameters
    ----------
    added_mass : float
        M in kg (> 0).
    loaded_frequency : float
        nu_1 in Hz, with the mass.
    unloaded_frequency : float
        nu_0 in Hz, without it (above nu_1).

    Returns
    -------
    float
    """
    added_mass = check_range("added_mass", added_mass, 0.0, 1.0, "kg", low_inclusive=False)
    loaded_frequency = check_range("loaded_frequency", loaded_frequency, RESONANCE_FREQUENCY.low,
                                   RESONANCE_FREQUENCY.high, "Hz")
    unloaded_frequency = check_range("unloaded_frequency", unloaded_frequency,
                                     RESONANCE_FREQUENCY.low, RESONANCE_FREQUENCY.high, "Hz")
    if not loaded_frequency < unloaded_frequency:
        raise ValueError(f"loaded_frequency must be below unloaded_frequency "
                         f"({unloaded_frequency:g} Hz): a mass lowers the resonance, got "
                         f"{loaded_frequency:g} Hz")
    return (2.0 * math.pi) ** 2 * added_mass / (loaded_frequency ** -2
                                                - unloaded_frequency ** -2)


# -- the optical lever -----------------------------------------------------------------------
def _slope_ratio(mode: int, spot: float) -> float:
    """z*/z of ``mode`` for a spot at x/L = ``spot``: the mode's slope there per unit end
    deflection over the end-loaded static shape's, 3 (2u - u^2) / (2 L)."""
    bl = eigenvalue(mode)
    v = bl * spot
    denom = math.sinh(bl) + math.sin(bl)
    s = (math.cosh(bl) + math.cos(bl)) / denom
    one_minus_s = (math.sin(bl) - math.cos(bl) - math.exp(-bl)) / denom   # without cancellation
    # phi(v) = cosh v - cos v - s (sinh v - sin v); cosh - s sinh = ((1-s) e^v + (1+s) e^-v) / 2
    end = (0.5 * (one_minus_s * math.exp(bl) + (2.0 - one_minus_s) * math.exp(-bl))
           - math.cos(bl) + s * math.sin(bl))
    # phi'(v) / b = sinh v + sin v - s (cosh v - cos v); sinh - s cosh = ((1-s) e^v - (1+s) e^-v) / 2
    if v < 1e-3:   # near the clamp, the Taylor series (2v - s v^2 + v^5/60 - s v^6/360), no cancellation
        slope = bl * v * (2.0 - s * v + v ** 4 / 60.0 - s * v ** 5 / 360.0)
    else:
        slope = bl * (0.5 * (one_minus_s * math.exp(v) - (2.0 - one_minus_s) * math.exp(-v))
                      + math.sin(v) + s * math.cos(v))
    return slope / end / (1.5 * spot * (2.0 - spot))


def optical_lever_correction(mode: int = 1, spot: float = 1.0) -> float:
    """chi = z / z*: the free mode's end deflection over what an end-load-calibrated optical
    lever reports for it.

    An optical lever reads the slope at the laser spot (x = spot L) and is calibrated on a hard
    surface, where the lever takes the end-loaded static shape, slope 3 z (2u - u^2) / (2 L) at
    u = x / L. Mode n's slope there per unit end deflection is phi_n'(x) / phi_n(L), so
    chi = [3 (2u - u^2) / (2 L)] / [phi_n'(x) / phi_n(L)]; computed from the mode shape. For
    mode 1 with the spot at the end chi = 1.090 (Proksch et al., Nanotechnology 15, 1344
    (2004)), and share_1 / chi^2 = 0.817 (Butt and Jaschke, Nanotechnology 6, 1 (1995)).

    Parameters
    ----------
    mode : int
        Mode number n, 1 to :data:`~afmsmiler.cantilever.MAX_MODE`.
    spot : float
        Laser spot position as a fraction x/L of the length, in (0, 1].

    Returns
    -------
    float
        chi (inf where the mode's slope vanishes at the spot, a higher mode's node of slope).
    """
    mode = check_integer("mode", mode, 1, MAX_MODE)
    spot = check_range("spot", spot, 0.0, 1.0, low_inclusive=False)
    ratio = _slope_ratio(mode, spot)
    return math.inf if ratio == 0.0 else 1.0 / ratio


# -- the thermal spectrum --------------------------------------------------------------------
@dataclass(frozen=True)
class ThermalSpectrum:
    """An averaged, one-sided thermal deflection spectrum as an optical-lever AFM records it.

    Attributes
    ----------
    lever : Cantilever
        The lever.
    fluid : Fluid
        Its medium.
    frequency : ndarray
        Bin frequencies j df, j = 1 .. N, in Hz.
    psd : ndarray
        The recorded spectrum in m^2/Hz (one-sided: it integrates over f > 0 to the variance),
        of the deflection the detector reports (z*, calibrated on a hard surface).
    expected : ndarray
        Its mean, the true spectrum, in m^2/Hz.
    averages : int
        M, the number of periodograms averaged.
    temperature : float
        T in K.
    spot : float
        Where the laser spot really sits, x/L.
    detector_noise : float
        The detector's white noise floor in m/sqrt(Hz).
    modes : int
        How many flexural modes it holds.
    """

    lever: Cantilever
    fluid: Fluid
    frequency: np.ndarray
    psd: np.ndarray
    expected: np.ndarray
    averages: int
    temperature: float
    spot: float
    detector_noise: float
    modes: int

    @property
    def resolution(self) -> float:
        """Bin width df in Hz."""
        return float(self.frequency[1] - self.frequency[0])

    @property
    def record_time(self) -> float:
        """Length 1 / df in s of each of the averaged records."""
        return 1.0 / self.resolution

    @property
    def sample_rate(self) -> float:
        """f_s = 2 N df in Hz."""
        return 2.0 * self.frequency.size * self.resolution


@functools.lru_cache(maxsize=16)
def _gamma_nodes(first: int, last: int) -> tuple:
    """log Gamma_r and log Gamma_i at the nodes 10^(j / 1000), j = first .. last + 1, kept for
    the next spectrum of the same lever (a panel's step: the Bessel functions are most of a
    2^14-bin spectrum's cost)."""
    nodes = 10.0 ** (np.arange(first, last + 2) / 1000.0)
    g = _omega(nodes) * _circ(nodes)
    log_r, log_i = np.log(g.real), np.log(g.imag)
    log_r.flags.writeable = log_i.flags.writeable = False
    return log_r, log_i


def _gamma_interpolated(re: np.ndarray) -> np.ndarray:
    """Gamma_rect(re) (Omega held at the ends of its range) for many Reynolds numbers at once:
    log Gamma_r and log Gamma_i interpolated linearly in tau = log10 Re between nodes at the
    multiples of 1/1000 (the ends of Omega's range, where it is held, are nodes), within 1e-6 of
    the direct evaluation (tested); evaluated directly when there are fewer values than nodes (a
    direct evaluation of 2^20 complex Bessel pairs takes about a second)."""
    tau = np.log10(re)
    first, last = math.floor(float(tau.min()) * 1000), math.ceil(float(tau.max()) * 1000)
    if re.size <= last - first + 2:
        return _omega(re) * _circ(re)
    log_r, log_i = _gamma_nodes(first, last)
    # uniform nodes: the cell and the weight by arithmetic, no search
    position = tau * 1000.0 - first
    cell = np.minimum(position.astype(np.intp), last - first)
    weight = position - cell
    real = np.exp(log_r[cell] + weight * (log_r[cell + 1] - log_r[cell]))
    imag = np.exp(log_i[cell] + weight * (log_i[cell + 1] - log_i[cell]))
    return real + 1j * imag


#: The most values a kept line-shape table or noise record holds (8 MB of float64; 4 of each
#: are kept): a panel's spectra (3 modes of 2^14 bins) are kept, a 2^22-bin spectrum of 50
#: modes is computed anew.
_KEPT_VALUES = 2 ** 20


@functools.lru_cache(maxsize=4)
def _mode_lines(lever: Cantilever, fluid: Fluid, sample_rate: float, points: int,
                modes: int) -> tuple:
    """The bins' frequencies f (Hz) and, for modes n = 1 .. ``modes``, the line shape
    r^2 T Gamma_i / (omega |1 - r^2 (1 + T Gamma)|^2) (r = f / f_vac,n, T the mass loading)
    that :func:`thermal_spectrum` weights by the mode's share and the spot, one row a mode,
    read-only: kept for the next spectrum of the same lever, fluid and bins (a panel's move of
    the spot, the temperature or the detector: the Bessel functions and the modes' sums are
    most of a spectrum's cost)."""
    df = sample_rate / (2.0 * points)
    f = df * np.arange(1, points + 1)
    omega = 2.0 * math.pi * f
    gamma = _gamma_interpolated(fluid.density * lever.width ** 2 / (4.0 * fluid.viscosity)
                                * omega)
    loading = mass_loading(lever, fluid)
    inertia_r, inertia_i = 1.0 + loading * gamma.real, loading * gamma.imag
    f2 = f * f
    loss = inertia_i / omega
    shapes = np.empty((modes, points))
    real, imag = np.empty(points), np.empty(points)
    for n in range(1, modes + 1):
        # with few temporaries
        r2 = shapes[n - 1]
        np.multiply(f2, lever.resonance_frequency(n) ** -2, out=r2)
        np.multiply(r2, inertia_r, out=real)
        np.subtract(1.0, real, out=real)
        np.multiply(r2, inertia_i, out=imag)
        np.multiply(real, real, out=real)
        np.multiply(imag, imag, out=imag)
        np.add(real, imag, out=real)
        np.multiply(r2, loss, out=r2)
        np.divide(r2, real, out=r2)
    f.flags.writeable = shapes.flags.writeable = False
    return f, shapes


@functools.lru_cache(maxsize=4)
def _gamma_draws(seed: int, averages: int, points: int) -> np.ndarray:
    """``numpy.random.default_rng(seed).standard_gamma(averages, points)``, read-only: kept for
    the next spectrum of the same seed and size (the same draws, bit for bit)."""
    draws = np.random.default_rng(seed).standard_gamma(averages, points)
    draws.flags.writeable = False
    return draws


def thermal_spectrum(lever: Cantilever, fluid="air", *, temperature: float = TEMPERATURE.default,
                     sample_rate: float | None = None, points: int = 2 ** 16,
                     averages: int = 16, detector_noise: float = 50e-15, spot: float = 1.0,
                     modes: int | None = None, seed=None) -> ThermalSpectrum:
    """Simulate the averaged thermal deflection spectrum of ``lever`` in ``fluid``.

    Every mode's spectrum 4 k_B T Im chi_n(omega) / omega with Sader's hydrodynamic function at
    each frequency, seen through the optical lever with its spot at ``spot``, plus the detector
    floor; each bin drawn as its mean times a Gamma(M, 1/M) variable (see the module docstring).

    Parameters
    ----------
    lever : Cantilever
        The lever.
    fluid : str or Fluid
        Its medium (a key of :data:`~afmsmiler.hydrodynamics.FLUIDS` or a Fluid).
    temperature : float
        T in K.
    sample_rate : float, optional
        f_s in Hz, 1 Hz to 1 GHz; default 10 f_vac,1 (mode 1 in the lower fifth of the span).
    points : int
        N, the spectrum's bins (a record of 2N samples), 16 to 2^22.
    averages : int
        M, the periodograms averaged, 1 to 100 000.
    detector_noise : float
        The detector's white noise floor in m/sqrt(Hz), >= 0.
    spot : float
        The laser spot's position x/L, in (0, 1].
    modes : int, optional
        Flexural modes included, 1 to 50; default those below 4 f_s / 2 (at most 50).
    seed : int or numpy.random.Generator, optional
        The noise's seed (None: fresh noise).

    Returns
    -------
    ThermalSpectrum
    """
    lever = check_instance("lever", lever, Cantilever)
    fluid = get_fluid(fluid)
    temperature = TEMPERATURE.check(temperature)
    if sample_rate is None:
        sample_rate = 10.0 * lever.resonance_frequency(1)
    sample_rate = check_range("sample_rate", sample_rate, 1.0, 1e9, "Hz")
    points = check_size("points", points, LIMITS["points"], 16)
    averages = check_size("averages", averages, LIMITS["averages"])
    detector_noise = check_range("detector_noise", detector_noise, 0.0, 1e-3, "m/sqrt(Hz)")
    spot = check_range("spot", spot, 0.0, 1.0, low_inclusive=False)
    if modes is None:
        modes = max(1, sum(1 for n in range(1, MAX_MODE + 1)
                           if lever.resonance_frequency(n) < 2.0 * sample_rate))
    modes = check_integer("modes", modes, 1, MAX_MODE)
    if not isinstance(seed, np.random.Generator) and seed is not None:
        seed = check_integer("seed", seed, 0, 2 ** 63 - 1)
    lines = _mode_lines if modes * points <= _KEPT_VALUES else _mode_lines.__wrapped__
    f, shapes = lines(lever, fluid, float(sample_rate), points, modes)
    prefactor = 4.0 * BOLTZMANN * temperature / lever.spring_constant
    expected = np.full(points, detector_noise ** 2)
    for n in range(1, modes + 1):
        expected += (_slope_ratio(n, spot) ** 2 * mode_share(n) * prefactor) * shapes[n - 1]
    if isinstance(seed, int) and points <= _KEPT_VALUES:
        draws = _gamma_draws(seed, averages, points)
    else:
        rng = seed if isinstance(seed, np.random.Generator) else np.random.default_rng(seed)
        draws = rng.standard_gamma(averages, points)
    psd = expected * draws / averages
    f = f.copy()
    for a in (f, psd, expected):
        a.flags.writeable = False
    return ThermalSpectrum(lever=lever, fluid=fluid, frequency=f, psd=psd, expected=expected,
                           averages=averages, temperature=temperature, spot=spot,
                           detector_noise=detector_noise, modes=modes)


# -- the fit ---------------------------------------------------------------------------------
def _sho(f, params):
    """ln S and d ln S / d(ln f0, ln Q, ln A, ln W) of the SHO line on a white floor."""
    f0, q, area, white = np.exp(params)
    r2 = (f / f0) ** 2
    d = (1.0 - r2) ** 2 + r2 / q ** 2
    line = area * 2.0 / (math.pi * q * f0) / d
    s = line + white
    jac = np.empty((f.size, 4))
    w = line / s
    jac[:, 0] = w * (-1.0 - (4.0 * r2 * (1.0 - r2) - 2.0 * r2 / q ** 2) / d)
    jac[:, 1] = w * (-1.0 + 2.0 * r2 / (q ** 2 * d))
    jac[:, 2] = w
    jac[:, 3] = white / s
    return s, jac


@dataclass(frozen=True)
class SHOFit:
    """The maximum-likelihood fit of a simple-harmonic-oscillator line on a white background.

    S(f) = W + A (2 / (pi Q f0)) / ((1 - (f/f0)^2)^2 + (f / (Q f0))^2), whose line integrates
    to A over f > 0.

    Attributes
    ----------
    resonance_frequency : float
        f0 in Hz.
    quality_factor : float
        Q.
    area : float
        A = <z*^2>, the mode's mean-square (reported) deflection, in m^2.
    background : float
        W in m^2/Hz.
    covariance : ndarray, shape (4, 4)
        Of (ln f0, ln Q, ln A, ln W): the inverse Fisher matrix at the optimum.
    band : tuple of float
        The fitted band (f_low, f_high) in Hz.
    bins : int
        Bins in the band.
    iterations : int
        Fisher-scoring steps taken.
    resolution : float
        The spectrum's bin width df in Hz.
    """

    resonance_frequency: float
    quality_factor: float
    area: float
    background: float
    covariance: np.ndarray
    band: tuple
    bins: int
    iterations: int
    resolution: float

    @property
    def bins_per_linewidth(self) -> float:
        """The line's full width f0 / Q in bins: below about 5 the bins are not independent
        (leakage) and the line is not resolved; record longer."""
        return self.resonance_frequency / (self.quality_factor * self.resolution)

    @property
    def relative_errors(self) -> dict:
        """1-sigma relative statistical errors of f0, Q, A and W (from :attr:`covariance`)."""
        sd = np.sqrt(np.diag(self.covariance))
        return dict(zip(("resonance_frequency", "quality_factor", "area", "background"),
                        map(float, sd)))

    def model(self, f):
        """The fitted S(f) in m^2/Hz.

        Parameters
        ----------
        f : array_like
            Frequencies in Hz (>= 0).
        """
        f = check_array("f", f, "Hz", low=0.0)
        params = np.log([self.resonance_frequency, self.quality_factor, self.area,
                         self.background])
        return _sho(f.ravel(), params)[0].reshape(f.shape)


def _smooth(y: np.ndarray, block: int) -> np.ndarray:
    n = y.size // block
    return y[:n * block].reshape(n, block).mean(axis=1)


def _start(f: np.ndarray, p: np.ndarray, averages: int):
    """A first guess (f_peak, Q, A, W) and a band from the block-averaged spectrum (blocks of
    at least 64 / M bins, so that each smoothed point averages 64 periodogram values)."""
    block = max(1, f.size // 4096, min(-(-64 // averages), f.size // 64))
    fs, ps = _smooth(f, block), _smooth(p, block)
    skip = min(3, ps.size - 1)
    i = skip + int(np.argmax(ps[skip:]))
    f_peak = float(fs[i])
    beyond = ps[(fs > 1.5 * f_peak) & (fs < 2.0 * f_peak)]
    white = 0.5 * float(beyond.min()) if beyond.size else 0.01 * float(ps[i])
    height = float(ps[i]) - white
    half = ps - white < 0.5 * height
    left = np.nonzero(half[:i])[0]
    right = np.nonzero(half[i:])[0]
    f_left = float(fs[left[-1]]) if left.size else float(fs[0])
    f_right = float(fs[i + right[0]]) if right.size else 2.0 * f_peak
    fwhm = max(f_right - f_left, fs[1] - fs[0] if fs.size > 1 else f_peak / 10)
    q = max(f_peak / fwhm, 0.6)
    area = 0.5 * math.pi * height * fwhm
    reach = min(0.9 * f_peak, max(10.0 * fwhm, 20.0 * float(f[1] - f[0])))
    return (f_peak, q, max(area, 1e-300), max(white, 1e-300)), (f_peak - reach,
                                                                f_peak + reach)


def _maximum_likelihood(fb, pb, m, params):
    """Fisher scoring of M sum(ln S + P / S) from ``params``: (params, steps taken)."""
    def nll(x):
        s = _sho(fb, x)[0]
        return m * float(np.sum(np.log(s) + pb / s))

    current = nll(params)
    iteration = 0
    for iteration in range(1, LIMITS["iterations"] + 1):
        s, jac = _sho(fb, params)
        grad = m * (jac.T @ (1.0 - pb / s))
        fisher = m * (jac.T @ jac)
        try:
            step = -np.linalg.solve(fisher, grad)
        except np.linalg.LinAlgError:
            step = -np.linalg.lstsq(fisher, grad, rcond=None)[0]
        step = np.clip(step, -2.0, 2.0)   # at most a factor e^2 per step in any parameter
        for _ in range(40):
            trial = params + step
            value = nll(trial)
            if math.isfinite(value) and value <= current:
                break
            step = step / 2.0
        else:
            break
        params, previous, current = trial, current, value
        if np.max(np.abs(step)) < 1e-9 or previous - current < 1e-12 * abs(current):
            break
    return params, iteration


def fit_thermal_spectrum(spectrum: ThermalSpectrum, *, band=None) -> SHOFit:
    """Fit mode 1's peak of ``spectrum`` with an SHO line plus a white background.

    Maximum likelihood for averaged periodogram bins (Gamma-distributed with shape M about the
    model; see the module docstring), by Fisher scoring in (ln f0, ln Q, ln A, ln W) with step
    halving, at most 100 steps.

    Parameters
    ----------
    spectrum : ThermalSpectrum
        The recorded spectrum.
    band : tuple of float, optional
        (f_low, f_high) in Hz; default the peak +- 10 full widths (at most +- 0.9 f_peak),
        found on the block-averaged spectrum and then on the fitted line (f0 +- 10 f0 / Q,
        refitted up to twice).

    Returns
    -------
    SHOFit

    Raises
    ------
    ValueError
        If the band holds fewer than 8 bins, or the fit does not converge.
    """
    spectrum = check_instance("spectrum", spectrum, ThermalSpectrum)
    f, p, m = spectrum.frequency, spectrum.psd, spectrum.averages
    guess, auto = _start(f, p, m)
    automatic = band is None
    if band is None:
        band = auto
    else:
        if not isinstance(band, (tuple, list)) or len(band) != 2:
            raise ValueError(f"band must be (f_low, f_high) in Hz, got {band!r:.60}")
        low = check_range("band[0]", band[0], 0.0, float(f[-1]), "Hz")
        high = check_range("band[1]", band[1], low, math.inf, "Hz", low_inclusive=False)
        band = (low, high)
        inside = p[(f >= low) & (f <= high)]
        if inside.size:
            k = int(np.argmax(inside))
            guess = (float(f[(f >= low) & (f <= high)][k]),) + guess[1:]
    params = np.log(np.array(guess, dtype=float))
    df = float(f[1] - f[0])
    for attempt in range(3):   # automatic band: refit once or twice on the fitted line's band
        sel = (f >= band[0]) & (f <= band[1])
        fb, pb = f[sel], p[sel]
        if fb.size < 8:
            raise ValueError(f"band must hold at least 8 bins of the spectrum, got {fb.size} "
                             f"in [{band[0]:g}, {band[1]:g}] Hz")
        params, iteration = _maximum_likelihood(fb, pb, m, params)
        f0, q = math.exp(params[0]), math.exp(params[1])
        if not automatic or not (math.isfinite(f0) and math.isfinite(q)):
            break
        reach = min(0.9 * f0, max(10.0 * f0 / q, 20.0 * df))
        new = (f0 - reach, f0 + reach)
        if attempt == 2 or (abs(new[1] - new[0] - (band[1] - band[0]))
                            < 0.2 * (band[1] - band[0]) and band[0] <= f0 <= band[1]):
            break
        band = new
    s, jac = _sho(fb, params)
    covariance = np.linalg.pinv(m * (jac.T @ jac))
    f0, q, area, white = map(float, np.exp(params))
    if not all(map(math.isfinite, (f0, q, area, white))) or not band[0] <= f0 <= band[1]:
        raise ValueError(f"the fit did not converge to a peak inside the band [{band[0]:g}, "
                         f"{band[1]:g}] Hz (got f0 = {f0:g} Hz): give a band around mode 1")
    return SHOFit(resonance_frequency=f0, quality_factor=q, area=area, background=white,
                  covariance=covariance, band=(float(band[0]), float(band[1])),
                  bins=int(fb.size), iterations=iteration, resolution=df)


@dataclass(frozen=True)
class ThermalCalibration:
    """The thermal-noise calibration of a spectrum (:func:`thermal_calibration`).

    Attributes
    ----------
    spring_constant : float
        k = share_1 k_B T / (chi^2 A) in N/m.
    uncertainty : float
        Its 1-sigma statistical error in N/m, from the fit's Fisher matrix (record length and
        averages).
    fit : SHOFit
        The fitted peak (f0, Q, A).
    mode_share : float
        share_1 = 12 / (b_1 L)^4 = 0.971.
    correction : float
        chi for the assumed spot position.
    true_spring_constant : float
        The model's k = 3 E J / L^3 in N/m.
    """

    spring_constant: float
    uncertainty: float
    fit: SHOFit
    mode_share: float
    correction: float
    true_spring_constant: float

    @property
    def relative_error(self) -> float:
        """k / k_true - 1."""
        return self.spring_constant / self.true_spring_constant - 1.0


def thermal_calibration(spectrum: ThermalSpectrum, *, spot: float = 1.0,
                        band=None) -> ThermalCalibration:
    """Calibrate k from a thermal spectrum: k = share_1 k_B T / (chi^2 <z*^2>).

    Hutter and Bechhoefer (1993) with Butt and Jaschke (1995)'s mode share 0.971 and the
    optical-lever correction chi (:func:`optical_lever_correction`) for the spot position the
    experimenter assumes (the spectrum may have been recorded with the spot elsewhere: that is
    one of the method's biases). <z*^2> is the area of :func:`fit_thermal_spectrum`'s line.

    Parameters
    ----------
    spectrum : ThermalSpectrum
        The recorded spectrum (its temperature is the one assumed).
    spot : float
        The assumed spot position x/L, in (0, 1].
    band : tuple of float, optional
        The fitted band in Hz (default: see :func:`fit_thermal_spectrum`).

    Returns
    -------
    ThermalCalibration
    """
    spectrum = check_instance("spectrum", spectrum, ThermalSpectrum)
    chi = optical_lever_correction(1, spot)
    fit = fit_thermal_spectrum(spectrum, band=band)
    share = mode_share(1)
    k = share * BOLTZMANN * spectrum.temperature / (chi ** 2 * fit.area)
    return ThermalCalibration(spring_constant=k, uncertainty=k * fit.relative_errors["area"],
                              fit=fit, mode_share=share, correction=chi,
                              true_spring_constant=spectrum.lever.spring_constant)



# -- all the methods at once -----------------------------------------------------------------
@dataclass(frozen=True)
class LabCalibration:
    """A lever calibrated the ways a lab does it, beside its true k (:func:`calibrate`).

    Attributes
    ----------
    spectrum : ThermalSpectrum
        The recorded thermal spectrum.
    thermal : ThermalCalibration
        The thermal-noise method on it.
    sader : float
        Sader's method in N/m with f_f and Q_f read off the thermal fit (as in the lab).
    sader_model : SaderCalibration
        Sader's method with the model's own f_R and Q (Sader's weak-damping relations).
    true_spring_constant : float
        The model's k = 3 E J / L^3 in N/m.
    """

    spectrum: ThermalSpectrum
    thermal: ThermalCalibration
    sader: float
    sader_model: SaderCalibration
    true_spring_constant: float

    def rows(self) -> list:
        """(method, k in N/m, k / k_true - 1) for each method, the true k first.

        Returns
        -------
        list of tuple
        """
        k = self.true_spring_constant
        return [("model: 3 E J / L^3", k, 0.0),
                ("thermal noise (SHO fit, 0.971, chi)", self.thermal.spring_constant,
                 self.thermal.relative_error),
                ("Sader (f and Q of the fit)", self.sader, self.sader / k - 1.0),
                ("Sader (the model's f and Q)", self.sader_model.spring_constant,
                 self.sader_model.relative_error)]


def calibrate(lever: Cantilever, fluid="air", *, spot: float = 1.0,
              assumed_spot: float = 1.0, points: int = 2 ** 16, averages: int = 16,
              seed=None) -> LabCalibration:
    """Record a thermal spectrum of ``lever`` in ``fluid`` and calibrate k by every method.

    One call for the notebook: :func:`thermal_spectrum`, :func:`thermal_calibration` (with the
    spot where the experimenter believes it is), Sader's method on the fitted f and Q, and
    Sader's method on the model's own resonance.

    Parameters
    ----------
    lever : Cantilever
        The lever.
    fluid : str or Fluid
        Its medium.
    spot : float
        Where the laser spot really is, x/L in (0, 1].
    assumed_spot : float
        Where the experimenter assumes it is, x/L in (0, 1].
    points : int
        Bins of the spectrum, 16 to 2^22.
    averages : int
        Spectra averaged, 1 to 100 000.
    seed : int or numpy.random.Generator, optional
        The noise's seed.

    Returns
    -------
    LabCalibration
    """
    assumed_spot = check_range("assumed_spot", assumed_spot, 0.0, 1.0, low_inclusive=False)
    spectrum = thermal_spectrum(lever, fluid, points=points, averages=averages, spot=spot,
                                seed=seed)
    thermal = thermal_calibration(spectrum, spot=assumed_spot)
    fit = thermal.fit
    try:
        sader = sader_spring_constant(lever.length, lever.width, fit.resonance_frequency,
                                      fit.quality_factor, spectrum.fluid)
    except ValueError:   # a fitted f outside Sader's Reynolds range: the method does not apply
        sader = math.nan
    return LabCalibration(spectrum=spectrum, thermal=thermal, sader=sader,
                          sader_model=sader_calibration(lever, spectrum.fluid),
                          true_spring_constant=lever.spring_constant)
