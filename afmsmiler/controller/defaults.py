"""The paper's four Fig. 4 scenarios as named presets, in SI units.

The paper works in scaled units: mass in ng, time in us, length in um. Conversions to SI:

=================  ==========================  ==============================
quantity           scaled unit                 SI
=================  ==========================  ==============================
mass               ng                          1e-12 kg
damping b          ng/us                       1e-12 kg / 1e-6 s = 1e-6 kg/s
stiffness k        ng/us^2                     1e-12 kg / 1e-12 s^2 = 1 N/m
K_P                (dimensionless)             (dimensionless)
K_I                1/us                        1e6 1/s
K_D                us                          1e-6 s
speed              um/us                       1 m/s  (10 um/s = 1e-5 m/s)
=================  ==========================  ==============================

All four scenarios share the lever and sample masses m_c = m_s = 1 ng, the damping
b_c = b_s = 0.015 ng/us = 1.5e-8 kg/s (the values the paper gives for (d)), the lever k_c = 1 N/m,
the deflection setpoint R = 10 nm and a 512-pixel grating line of 50 nm steps with 4 nm pixels:

(a) ``a_good_tracking``: stiff sample k_s = 100 N/m, stable gains K_P = 0.5,
    K_I = 0.01 /us = 1e4 /s, K_D = 0, slow scan 10 um/s = 1e-5 m/s: the estimate follows the
    topography within a few per cent of the step height.
(b) ``b_soft_sample``: as (a) with k_s = k_c = 1 N/m: the sample gives way under the lever, the
    estimate Z_c - Z_np is off by the whole indentation k_c R / k_s = 10 nm and by the
    deflection transients (error Z_c k_c / k_s at low frequency).
(c) ``c_fast_scan``: as (a) at 1000 um/s = 1e-3 m/s: the loop lags, so trace and retrace differ.
(d) ``d_unstable``: K_P = 100, K_I = 100 /us = 1e8 /s, K_D = 0 at 1000 um/s: the Hurwitz
    condition B C > A D fails and the oscillation grows (the loop is flagged unstable).
"""
from __future__ import annotations

from dataclasses import dataclass

from .. import samples
from ..parameters import read_only
from ..validation import check_instance
from .loop import LOOP_PARAMETERS, PARAMETERS, ContactLoop

__all__ = ["Preset", "PRESETS", "BASE", "SETPOINT", "LINE", "line_profile"]

#: Shared loop parameters in SI: the defaults of :data:`~afmsmiler.controller.PARAMETERS`.
BASE = read_only({name: PARAMETERS[name].default for name in LOOP_PARAMETERS})
#: Deflection setpoint R in m.
SETPOINT = PARAMETERS["setpoint"].default
#: The scanned line: pixels, pixel size (m), feature height (m), profile name.
LINE = read_only(dict(pixels=512, pixel_size=4e-9, height=PARAMETERS["height"].default,
                      name="grating"))


@dataclass(frozen=True)
class Preset:
    """One scenario: a loop, a scan speed and a setpoint, with its description.

    Parameters
    ----------
    name : str
        Key in :data:`PRESETS`.
    description : str
        What the scenario shows.
    loop : ContactLoop
        Loop parameters in SI.
    speed : float
        Scan speed in m/s.
    setpoint : float
        Deflection setpoint in m.
    """

    name: str
    description: str
    loop: ContactLoop
    speed: float
    setpoint: float = SETPOINT

    def scan(self, sample=None):
        """Trace and retrace of the preset's line (or of ``sample``, a 1-D Sample).

        Parameters
        ----------
        sample : afmsmiler.samples.Sample, optional
            The line to scan; default :func:`line_profile`.

        Returns
        -------
        afmsmiler.controller.ScanLine

        Raises
        ------
        TypeError
            If ``sample`` is not a Sample.
        ValueError
            If ``sample`` is not 1-D (a line: take a row with ``Sample.line``).
        """
        if sample is None:
            sample = line_profile()
        check_instance("sample", sample, samples.Sample)
        if sample.heights.ndim != 1:
            raise ValueError(f"sample must be a 1-D Sample (a line; take one row of an image "
                             f"with sample.line(row)), got heights of shape "
                             f"{sample.heights.shape}")
        return self.loop.scan_line(sample.x, sample.heights, speed=self.speed,
                                   setpoint=self.setpoint)


def line_profile(name: str = LINE["name"]):
    """The line the presets scan (512 pixels of 4 nm, 50 nm features).

    Parameters
    ----------
    name : str
        ``"grating"`` (default), ``"step"`` or ``"real line"``.

    Returns
    -------
    afmsmiler.samples.Sample
    """
    return samples.profile(name, LINE["pixels"], LINE["pixel_size"], LINE["height"])


def _loop(**changes):
    return ContactLoop(**{**BASE, **changes})


PRESETS = read_only({p.name: p for p in (
    Preset("a_good_tracking", "(a) stiff sample, stable gains, slow scan: good tracking",
           _loop(), PARAMETERS["speed"].default),
    Preset("b_soft_sample", "(b) sample as soft as the lever (k_s = k_c): large error",
           _loop(k_s=1.0), PARAMETERS["speed"].default),
    Preset("c_fast_scan", "(c) fast scan (1000 um/s): trace and retrace differ",
           _loop(), 1e-3),  # 1000 um/s
    Preset("d_unstable", "(d) K_P = K_I = 100 (scaled): growing oscillation, unstable",
           _loop(kp=100.0, ki=1e8), 1e-3),  # K_I = 100 /us, 1000 um/s
)})
