"""Laser alignment of an optical-beam-deflection AFM head, as physics (module (e)).

The head (the optical path of a commercial AFM such as the Bruker MultiMode; the dimensions are
typical values, not a vendor's drawing, and each is a parameter of :data:`HEAD`):

1. A laser diode (670 nm, 1 mW, collimated to a 1/e^2 radius w_in = 0.25 mm) sends its beam
   horizontally onto a **steering mirror** at 45 degrees that folds it down. The two
   **laser-position knobs** (``laser_x``, ``laser_y``) are fine screws (pitch 0.254 mm, 100
   threads per inch) pushing the mirror's kinematic mount at 25 mm from its pivot: a knob turned
   by n turns tilts the mirror by atan(n p / a) and the beam by twice that in the plane of
   incidence, 2 cos(45 deg) times that out of it (:func:`~.optics.mirror_deviation`).
2. The mirror sits in the front focal plane of a **focusing lens** (f = 20 mm), so the spot moves
   across the chip at x = f slope without tilting (:func:`~.optics.focal_plane_ray`), and the
   lens focuses the beam to a waist w0 = w_in f / sqrt(f^2 + z_in^2) ~ 17 um
   (:func:`~.optics.focused_waist`) in the plane of the **lever**, which the holder tilts by
   alpha = 12 deg (holders tilt levers by 10 to 15 deg): on the lever the spot is an ellipse of
   radii w0 / cos(alpha) along it and w0 across. The lever (module (a),
   :class:`~afmsmiler.cantilever.Cantilever`, 450 x 50 um by default) sticks out of a standard
   **chip** (3.4 x 1.6 x 0.3 mm, the support chip of the probe vendors' datasheets, e.g.
   BudgetSensors and NanoWorld). Its defocus along the tilted lever (L sin alpha ~ 0.1 mm) is
   far inside the Rayleigh range (1.4 mm) and is neglected.
3. The reflected beam reaches a **four-quadrant photodiode** (3 x 3 mm, e.g. Hamamatsu S4349,
   the gaps between quadrants neglected) at the optical path D = 30 mm (module (b)'s default), as
   a Gaussian spot of radius w(D) = w0 sqrt(1 + (D / z_R)^2) ~ 0.38 mm
   (:func:`~.optics.beam_radius_at`). The two **photodiode knobs** (``detector_vertical``,
   ``detector_lateral``) translate it with screws of 0.5 mm pitch.

What the model computes (:meth:`OpticalHead.signals`):

* **Reflected power.** The share of the spot on the lever's rectangle [0, L] x [-w/2, w/2] is the
  closed-form overlap of the elliptical Gaussian with it, a product of two erf differences
  (:func:`~.optics.rectangle_fraction`), times the coating's reflectance. The chip's body
  (x < 0) returns ``chip_reflectance`` times as much light into the detector per unit of spot
  power; the default is 0, a chip whose body sends nothing into the detector (so that the sum
  tells the lever from the body; with ``chip_reflectance=1`` the sum on the body is as large as
  on the lever, the real pitfall that makes students look at the spot and walk it to the lever's
  free end). Light that misses both is lost. Diffraction at the lever's edges (fringes around a
  clipped spot) is neglected: the reflected beam stays a Gaussian carrying the overlap's power.
* **Reflected direction.** Under a tip deflection z the lever's slope is module (a)'s
  theta(x) = theta(L) (2 u - u^2), u = x / L, with theta(L) = 3 z / (2 L) for the end load; a
  spot reflects at its intensity-weighted mean slope over the lit part of the lever
  (:func:`~.optics.interval_moments`). A static ``tilt_error`` of the lever in its holder (a chip
  not seated flat) adds to it. The spot on the detector moves by module (b)'s
  :meth:`~afmsmiler.transducers.OpticalBeamDeflection.spot_displacement`, D tan(2 (tilt_error +
  mean slope)) (the reflection doubles the angle), and by the spot's own shift across the chip
  (a translation X of the incident beam moves the reflected beam by X on the detector, the other
  way: v = -X + D tan(2 theta); exact for a lever at the holder's tilt, whatever that tilt, and
  to first order in the tilt error, as exact ray tracing with r = d - 2 (d . n) n shows).
* **Signals.** Each quadrant (A top-left, B top-right, C bottom-left, D bottom-right, top
  towards positive tip deflection, left towards +y) gets the spot's power on it (erf products
  again); photodiodes of responsivity R (module (b)'s, 0.4 A/W at 670 nm) feed transimpedance
  amplifiers of gain G (10 kOhm), and the instrument displays, in V::

      sum = G R (A + B + C + D),  vertical = G R ((A + B) - (C + D)),
      lateral = G R ((A + C) - (B + D))

  and the normalised differences vertical / sum and lateral / sum.

Where the optimum is (:attr:`OpticalHead.best_sum`): the sum is the spot's overlap with the
lever, which is flat (a plateau) all along the lever once the spot is a couple of radii inside
its edges and largest, strictly, with the spot at the lever's centre (the overlap of a Gaussian
with a symmetric box is log-concave and symmetric). The lever bends most at its end, so the
signal per nm of deflection, d vertical / dz in V/m, is largest in the *end region*: with the
spot's centre about 1.6 spot radii (along the lever) inside the free end, 28 um for the default
lever and spot, where the sum is still 99.9 % of its plateau (further in, the lever's slope
there is smaller; further out, less light returns). :func:`align` does what the manuals tell
students to do (walk the spot off the free end, where the sum halves, then back until it
recovers to 98 % of its plateau): it stops about one radius inside the end (18 um), within 2 %
of the largest signal per nm.

The instrument's knobs are described by :data:`KNOBS` (travel in rad, shown in turns), the head
by :data:`HEAD`, the alignment checks by :data:`TOLERANCES`; every one a
:class:`~afmsmiler.parameters.Parameter`.

References: Meyer and Amer, Appl. Phys. Lett. 53, 1045 (1988) (the optical lever); Siegman,
*Lasers* (1986), ch. 15 (ray matrices) and ch. 16-17 (Gaussian beams); Saleh and Teich,
*Fundamentals of Photonics* (2007), ch. 1 and 3; Beaulieu et al., Appl. Phys. Lett. 88, 083108
(2006) (a fuller model of the photodetector's response to the lever's deflection); the alignment
procedure as vendors' manuals teach it (e.g. Bruker's MultiMode 8 instruction manual: the laser
on the lever for the largest sum, then the photodetector centred); the AFM SMILER paper ("AFM
SMILER: A Scale Model Interactive Learning Extended Reality Toolkit for Atomic Force Microscopy
Created with Digital Twin Technology"), whose module (e) this re-creates.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from types import MappingProxyType

import numpy as np
from scipy.optimize import brentq, minimize_scalar

from ..cantilever import Cantilever
from ..parameters import Parameter, read_only, shown
from ..transducers import OpticalBeamDeflection
from ..validation import check_choice, check_instance, check_range
from .optics import (_mirror_slopes, beam_radius_at, focused_waist, interval_fraction,
                     interval_moments, rayleigh_range, rectangle_fraction)

__all__ = ["HEAD", "KNOBS", "TOLERANCES", "DEFAULT_LEVER", "OpticalHead", "Signals",
           "Alignment", "AlignmentRun", "align", "MAX_SEARCH_POINTS"]

_OBD = OpticalBeamDeflection.parameter_table()
_MM = dict(unit="m", display_unit="mm")
_TURN = 2 * math.pi

#: The head's parameters (SI), typical values of a commercial OBD head; see the module docstring.
HEAD = read_only({p.name: p for p in (
    Parameter(name="wavelength", unit="m", display_unit="nm", default=670e-9, low=400e-9,
              high=1.6e-6, label="laser wavelength (red laser diode)"),
    Parameter(name="laser_power", unit="W", display_unit="mW", default=1e-3, low=1e-6,
              high=5e-3, log=True, label="laser power (class 2: below 1 mW)"),
    Parameter(name="beam_radius", **_MM, default=0.25e-3, low=0.05e-3, high=2e-3,
              label="collimated beam radius w_in (1/e^2)"),
    Parameter(name="focal_length", **_MM, default=20e-3, low=5e-3, high=100e-3,
              label="focusing lens f"),
    Parameter(name="mirror_arm", **_MM, default=25e-3, low=20e-3, high=50e-3,
              label="mirror mount: screw to pivot"),
    Parameter(name="mirror_screw_pitch", **_MM, default=0.254e-3, low=0.1e-3, high=0.5e-3,
              label="laser knob screw advance per turn (100 TPI)"),
    _OBD["optical_path"].with_(label="optical path D (lever to photodiode)"),
    Parameter(name="detector_size", **_MM, default=3e-3, low=0.5e-3, high=20e-3,
              label="four-quadrant photodiode side"),
    Parameter(name="detector_screw_pitch", **_MM, default=0.5e-3, low=0.1e-3, high=1e-3,
              label="photodiode knob screw advance per turn"),
    _OBD["responsivity"],
    Parameter(name="transimpedance_gain", unit="ohm", display_unit="kohm", default=10e3,
              low=100.0, high=10e6, log=True, label="transimpedance gain G per quadrant"),
    Parameter(name="reflectance", unit="", default=0.9, low=0.0, high=1.0,
              label="lever coating reflectance (Al at 670 nm)"),
    Parameter(name="chip_reflectance", unit="", default=0.0, low=0.0, high=1.0,
              label="chip body's light into the detector, relative to the lever's"),
    Parameter(name="holder_tilt", unit="rad", display_unit="deg", default=math.radians(12),
              low=0.0, high=math.radians(30), label="lever tilt in the holder alpha"),
    Parameter(name="tilt_error", unit="rad", display_unit="deg", default=math.radians(1),
              low=math.radians(-5), high=math.radians(5),
              label="chip's static tilt error in the holder"),
    Parameter(name="mount_offset_x", **_MM, default=0.9e-3, low=-2e-3, high=2e-3,
              label="lever end from the optical axis, along the lever"),
    Parameter(name="mount_offset_y", **_MM, default=0.35e-3, low=-1.2e-3, high=1.2e-3,
              label="lever end from the optical axis, across the lever"),
    Parameter(name="chip_length", **_MM, default=3.4e-3, low=0.5e-3, high=10e-3,
              label="probe chip length"),
    Parameter(name="chip_width", **_MM, default=1.6e-3, low=0.2e-3, high=5e-3,
              label="probe chip width"),
)})

#: The four knobs: rotation in rad (SI), shown in turns, positive clockwise seen from the knob's
#: end; the range is the knob's travel. The laser knobs reach +-2 mm along the lever and +-1.4 mm
#: across it in the focal plane, the mount offsets of :data:`HEAD`. The photodiode knobs' travel,
#: +-16 turns of 0.5 mm (+-8 mm), reaches the reflection of every lever mounted within
#: :data:`HEAD`'s ranges on the default head: it falls at most 2 mm (the mount offset along the
#: lever) + D tan(2 x 5 deg) = 7.3 mm from the photodiode's centre (D = 30 mm).
KNOBS = read_only({p.name: p for p in (
    Parameter(name="laser_x", unit="rad", display_unit="turn", default=0.0, low=-5 * _TURN,
              high=5 * _TURN, label="laser knob along the lever (+ clockwise)"),
    Parameter(name="laser_y", unit="rad", display_unit="turn", default=0.0, low=-5 * _TURN,
              high=5 * _TURN, label="laser knob across the lever (+ clockwise)"),
    Parameter(name="detector_vertical", unit="rad", display_unit="turn", default=0.0,
              low=-16 * _TURN, high=16 * _TURN,
              label="photodiode knob, vertical (+ clockwise)"),
    Parameter(name="detector_lateral", unit="rad", display_unit="turn", default=0.0,
              low=-16 * _TURN, high=16 * _TURN,
              label="photodiode knob, lateral (+ clockwise)"),
)})

#: What :meth:`OpticalHead.aligned` checks, with its default tolerances.
TOLERANCES = read_only({p.name: p for p in (
    Parameter(name="min_sum_fraction", unit="", default=0.9, low=0.0, high=1.0,
              label="sum at least this share of its best"),
    Parameter(name="max_difference", unit="", default=0.02, low=0.0, high=1.0,
              label="largest |difference / sum|"),
    Parameter(name="end_distance", unit="m", display_unit="um", default=40e-6, low=0.0,
              high=1e-3, label="largest distance of the spot from the lever's free end"),
)})

#: Module (a)'s default lever (a contact lever of silicon, 450 x 50 x 2 um).
DEFAULT_LEVER = Cantilever.from_material("silicon")

#: Largest number of knob settings :func:`align`'s search may try (a few tenths of a second).
MAX_SEARCH_POINTS = 20_000


def _knob_message(name: str, value: float, meta: Parameter) -> str:
    return (f"{name} must be within its travel [{meta.low / _TURN:g}, {meta.high / _TURN:g}] turn "
            f"([{meta.low:.4g}, {meta.high:.4g}] rad), got {value:.4g} rad "
            f"({value / _TURN:.4g} turn)")


def _check_knob(name, value) -> float:
    check_instance("knob", name, str)
    check_choice("knob", name, KNOBS)
    meta = KNOBS[name]
    x = check_range(name, value, -math.inf, math.inf, "rad")
    if not meta.low <= x <= meta.high:
        raise ValueError(_knob_message(name, x, meta))
    return x


@dataclass(frozen=True)
class Signals:
    """What the head's display shows for one setting of the knobs (SI units).

    Attributes
    ----------
    sum : float
        G R (A + B + C + D) in V.
    vertical : float
        G R ((A + B) - (C + D)) in V (positive: spot towards the top quadrants).
    lateral : float
        G R ((A + C) - (B + D)) in V (positive: spot towards the left quadrants).
    vertical_normalised, lateral_normalised : float
        vertical / sum and lateral / sum, in [-1, 1] (0 when no light arrives).
    reflected_fraction : float
        Share of the laser's power reflected towards the detector (lever and chip).
    lever_fraction : float
        Share of the spot's power on the lever (the Gaussian overlap with its rectangle).
    spot_on_lever : tuple of float
        The spot's centre (x from the clamp towards the free end, y from the lever's centre line)
        in m, in the lever's plane.
    spot_on_detector : tuple of float
        The lever's reflected spot (vertical, lateral) from the photodiode's centre in m.
    quadrants : tuple of float
        Optical power on A, B, C, D in W.
    deflection : float
        The tip deflection z in m the lever had.
    knobs : mapping
        Knob name -> rotation in rad.
    """

    sum: float
    vertical: float
    lateral: float
    vertical_normalised: float
    lateral_normalised: float
    reflected_fraction: float
    lever_fraction: float
    spot_on_lever: tuple
    spot_on_detector: tuple
    quadrants: tuple
    deflection: float
    knobs: MappingProxyType

    def readout(self) -> str:
        """The display's line, e.g. ``"SUM 3.52 V  VERT 0.000 V  HORZ 0.000 V"``."""
        def volts(value, digits):  # rounded first, so that no "-0.000 V" shows
            return shown(round(value, digits) + 0.0, "V", f".{digits}f")
        return (f"SUM {volts(self.sum, 2)}  VERT {volts(self.vertical, 3)}  "
                f"HORZ {volts(self.lateral, 3)}")


@dataclass(frozen=True)
class Alignment:
    """The verdict of :meth:`OpticalHead.aligned`: true when every check passed.

    Attributes
    ----------
    ok : bool
        Whether the head is aligned.
    reasons : tuple of str
        What failed, each with what to do (empty when aligned).
    signals : Signals
        The signals the verdict was made on.
    """

    ok: bool
    reasons: tuple
    signals: Signals

    def __bool__(self) -> bool:
        return self.ok

    @property
    def reason(self) -> str:
        """One line: ``"aligned"`` or the failed checks joined by ``"; "``."""
        return "aligned" if self.ok else "; ".join(self.reasons)


@dataclass(frozen=True)
class AlignmentRun:
    """What :func:`align` did: its steps, the model evaluations it needed and the verdict.

    Attributes
    ----------
    steps : tuple of (str, Signals)
        Each step's name and the signals after it.
    evaluations : int
        Knob settings evaluated.
    alignment : Alignment
        :meth:`OpticalHead.aligned` at the end.
    """

    steps: tuple
    evaluations: int
    alignment: Alignment = field(repr=False)


class OpticalHead:
    """An OBD head with its four knobs: turn them and read the display (see the module).

    Parameters
    ----------
    lever : Cantilever
        The lever (module (a)); default :data:`DEFAULT_LEVER`, 450 x 50 x 2 um of silicon. Its
        dimensions must lie in module (b)'s optical lever's ranges (length 20 um to 1 mm, width
        5 to 100 um, thickness 0.2 to 10 um).
    **parameters : float
        Any of :data:`HEAD` by name, in SI units; the others take their defaults.

    Raises
    ------
    TypeError
        For an unknown parameter or a lever that is not a Cantilever.
    ValueError
        For a value outside its valid range (naming it and the range).

    Examples
    --------
    >>> head = OpticalHead()
    >>> head.signals().sum < 0.01  # just mounted: the spot misses the lever
    True
    >>> run = align(head)
    >>> bool(head.aligned())
    True
    """

    def __init__(self, lever: Cantilever = DEFAULT_LEVER, **parameters):
        check_instance("lever", lever, Cantilever)
        unknown = sorted(set(parameters) - set(HEAD))
        if unknown:
            raise TypeError(f"OpticalHead got unknown parameter(s) {unknown}; "
                            f"valid: {sorted(HEAD)}")
        values = {n: p.check(parameters.get(n, p.default)) for n, p in HEAD.items()}
        self.lever = lever
        self._values = values
        self._knobs = {n: p.default for n, p in KNOBS.items()}
        self.waist = focused_waist(values["beam_radius"], values["focal_length"],
                                   values["wavelength"])
        self.rayleigh_range = rayleigh_range(self.waist, values["wavelength"])
        self.detector_spot_radius = beam_radius_at(values["optical_path"], self.waist,
                                                   values["wavelength"])
        # module (b)'s optical lever on this lever and detector: it moves the spot
        self.obd = OpticalBeamDeflection(
            optical_path=values["optical_path"], spot_radius=self.detector_spot_radius,
            power=min(values["laser_power"] * values["reflectance"], 20e-3) or 1e-6,
            responsivity=values["responsivity"], length=lever.length, width=lever.width,
            thickness=lever.thickness)

    def __getattr__(self, item):
        values = self.__dict__.get("_values")
        if values is not None and item in values:
            return values[item]
        raise AttributeError(f"OpticalHead has no attribute {item!r}")

    def __repr__(self) -> str:
        knobs = ", ".join(f"{k}={v / _TURN:.3g} turn" for k, v in self._knobs.items())
        return f"OpticalHead({knobs})"

    # -- the knobs ------------------------------------------------------------------------
    @property
    def knobs(self) -> MappingProxyType:
        """Knob name -> rotation in rad (read-only; change them with :meth:`turn`, :meth:`set`)."""
        return MappingProxyType(dict(self._knobs))

    @property
    def parameters(self) -> dict:
        """Name -> value (SI) of every head parameter."""
        return dict(self._values)

    def turn(self, knob: str, angle: float) -> Signals:
        """Turn ``knob`` by ``angle`` (relative, as a hand does) and return the new signals.

        Parameters
        ----------
        knob : str
            One of :data:`KNOBS`.
        angle : float
            Rotation in rad (one turn is 2 pi; ``KNOBS[knob].to_si(0.5)`` is half a turn),
            positive clockwise seen from the knob's end.

        Returns
        -------
        Signals

        Raises
        ------
        ValueError
            For an unknown knob, or a rotation taking it beyond its travel (naming the knob, the
            value it would reach and the travel); the knob is then left where it was.
        """
        check_instance("knob", knob, str)
        check_choice("knob", knob, KNOBS)
        angle = check_range("angle", angle, -math.inf, math.inf, "rad")
        target = self._knobs[knob] + angle
        try:
            self._knobs[knob] = _check_knob(knob, target)
        except ValueError as err:
            raise ValueError(f"turning {knob} by angle = {angle:.4g} rad "
                             f"({angle / _TURN:.4g} turn): {err}") from None
        return self.signals()

    def set(self, *, deflection: float = 0.0, **knobs) -> Signals:
        """Set knobs to absolute rotations (rad) and return the new signals.

        Parameters
        ----------
        deflection : float
            Deflection of the lever's free end in m at which the signals are evaluated (as in
            :meth:`signals`); the knobs are set and the model runs once.
        **knobs : float
            Knob name (of :data:`KNOBS`) -> rotation in rad within its travel.

        Returns
        -------
        Signals

        Raises
        ------
        ValueError
            For an unknown knob name or a value beyond its travel (naming it, the value and the
            travel), or a deflection out of range, before any knob moves.
        """
        checked = {name: _check_knob(name, value) for name, value in knobs.items()}
        self._check_deflection(deflection)  # before any knob moves
        self._knobs.update(checked)
        return self.signals(deflection)

    # -- the optics -----------------------------------------------------------------------
    def _focal(self, laser_x, laser_y):
        """Spot position (X, Y) in m in the focal plane for the laser knobs (rad)."""
        p, a = self.mirror_screw_pitch, self.mirror_arm
        tilt_x = np.arctan(p * np.asarray(laser_x) / _TURN / a)
        tilt_y = np.arctan(p * np.asarray(laser_y) / _TURN / a)
        u, w = _mirror_slopes(tilt_x, tilt_y, math.pi / 4)
        return self.focal_length * u, self.focal_length * w

    def _evaluate(self, laser_x, laser_y, detector_vertical, detector_lateral, deflection):
        """Quadrant powers (W), lever and chip shares, spot positions: arrays (broadcast)."""
        lever = self.lever
        length, width = lever.length, lever.width
        cos_a = math.cos(self.holder_tilt)
        wx, wy = self.waist / cos_a, self.waist
        big_x, big_y = self._focal(laser_x, laser_y)
        mx = length + (big_x - self.mount_offset_x) / cos_a   # along the lever from the clamp
        my = big_y - self.mount_offset_y                      # across, from its centre line
        fx, mean_x, mean_x2 = interval_moments(mx, wx, 0.0, length)
        lever_share = fx * interval_fraction(my, wy, -width / 2, width / 2)
        # module (a)'s slope theta(x) = theta(L) (2u - u^2), averaged over the lit lever
        shape = 2 * mean_x / length - mean_x2 / length ** 2
        theta_end = lever.slope(length, lever.force_for_deflection(deflection))
        chip_share = rectangle_fraction(mx, my, wx, wy, (-self.chip_length, 0.0),
                                        (-self.chip_width / 2, self.chip_width / 2))
        power = self.laser_power * self.reflectance
        dv = self.detector_screw_pitch * np.asarray(detector_vertical) / _TURN
        dl = self.detector_screw_pitch * np.asarray(detector_lateral) / _TURN
        # module (b)'s optical lever: the spot moves by D tan(2 theta) on the detector
        v_lever = -big_x + self.obd.spot_displacement(self.tilt_error + theta_end * shape) - dv
        v_chip = -big_x + self.obd.spot_displacement(self.tilt_error) - dv
        lat = big_y - dl
        a, w_d = self.detector_size / 2, self.detector_spot_radius
        left, right = interval_fraction(lat, w_d, 0.0, a), interval_fraction(lat, w_d, -a, 0.0)
        quads = np.zeros((4,) + np.shape(v_lever * lat * mx))
        for share, v in ((lever_share, v_lever), (self.chip_reflectance * chip_share, v_chip)):
            top, bottom = interval_fraction(v, w_d, 0.0, a), interval_fraction(v, w_d, -a, 0.0)
            for k, part in enumerate((top * left, top * right, bottom * left, bottom * right)):
                quads[k] = quads[k] + power * share * part
        return quads, lever_share, chip_share, (mx, my), (v_lever, lat)

    def _volts(self, quads):
        g = self.transimpedance_gain * self.responsivity
        a, b, c, d = quads
        total = g * (a + b + c + d)
        return total, g * ((a + b) - (c + d)), g * ((a + c) - (b + d))

    def _sum(self, **knobs) -> float:
        k = {**self._knobs, **knobs}
        quads = self._evaluate(k["laser_x"], k["laser_y"], k["detector_vertical"],
                               k["detector_lateral"], 0.0)[0]
        return self._volts(quads)[0]

    def _check_deflection(self, deflection) -> float:
        return check_range("deflection", deflection, -self.lever.length / 10,
                           self.lever.length / 10, "m")

    def signals(self, deflection: float = 0.0) -> Signals:
        """The display for the current knobs with the tip deflected by ``deflection``.

        Parameters
        ----------
        deflection : float
            Tip deflection z in m (positive up, module (a)'s convention), at most a tenth of the
            lever's length either way (the small-slope optics of this model).

        Returns
        -------
        Signals
        """
        z = self._check_deflection(deflection)
        k = self._knobs
        quads, lever_share, chip_share, (mx, my), (v, lat) = self._evaluate(
            k["laser_x"], k["laser_y"], k["detector_vertical"], k["detector_lateral"], z)
        total, vertical, lateral = (float(s) for s in self._volts(quads))
        reflected = float(lever_share + self.chip_reflectance * chip_share) * self.reflectance
        return Signals(
            sum=total, vertical=vertical, lateral=lateral,
            vertical_normalised=vertical / total if total > 0 else 0.0,
            lateral_normalised=lateral / total if total > 0 else 0.0,
            reflected_fraction=reflected, lever_fraction=float(lever_share),
            spot_on_lever=(float(mx), float(my)), spot_on_detector=(float(v), float(lat)),
            quadrants=tuple(float(q) for q in quads), deflection=z, knobs=self.knobs)

    def sensitivity(self, deflection: float = 0.0, *, normalised: bool = True) -> float:
        """Slope of the vertical signal against the tip deflection at ``deflection``.

        A central difference over +-1 nm (the signals are smooth on that scale: the spot moves
        by ~ 3 D z / L, a fraction 1e-4 of its radius).

        Parameters
        ----------
        deflection : float
            Tip deflection z in m at which to take it (as :meth:`signals`, less 1 nm).
        normalised : bool
            True: d(vertical / sum)/dz in 1/m (module (b)'s sensitivity); False: d vertical/dz
            in V/m.

        Returns
        -------
        float
        """
        h = 1e-9
        limit = self.lever.length / 10 - h
        deflection = check_range("deflection", deflection, -limit, limit, "m")
        check_instance("normalised", normalised, bool)
        lo, hi = self.signals(deflection - h), self.signals(deflection + h)
        name = "vertical_normalised" if normalised else "vertical"
        return (getattr(hi, name) - getattr(lo, name)) / (2 * h)

    @property
    def best_overlap(self) -> float:
        """The largest share of the spot on the lever: the spot at the lever's centre."""
        cos_a = math.cos(self.holder_tilt)
        lever = self.lever
        return float(rectangle_fraction(lever.length / 2, 0.0, self.waist / cos_a, self.waist,
                                        (0.0, lever.length), (-lever.width / 2, lever.width / 2)))

    @property
    def best_sum(self) -> float:
        """The largest sum in V: the spot at the lever's centre, the photodiode centred on it.

        G R P reflectance x (overlap at the centre) x (erf(sqrt(2) a / w(D)))^2, a the
        photodiode's half side: the overlap of the symmetric Gaussian with the symmetric
        rectangle is largest at its centre.
        """
        overlap = self.best_overlap
        capture = interval_fraction(0.0, self.detector_spot_radius, -self.detector_size / 2,
                                    self.detector_size / 2) ** 2
        return float(self.transimpedance_gain * self.responsivity * self.laser_power
                     * self.reflectance * overlap * capture)

    def _reflection_on_detector(self, signals: Signals) -> tuple:
        """Where the lever's reflection falls (vertical, lateral) in m from the photodiode's
        centre with both photodiode knobs at 0 (the spot on the detector plus the detector's
        own shift)."""
        pitch = self.detector_screw_pitch
        v, lat = signals.spot_on_detector
        return (v + pitch * signals.knobs["detector_vertical"] / _TURN,
                lat + pitch * signals.knobs["detector_lateral"] / _TURN)

    def _photodiode_advice(self, signals: Signals) -> str:
        """What to do when the lever reflects but the photodiode misses the reflection."""
        pitch = self.detector_screw_pitch
        for value, knob in zip(self._reflection_on_detector(signals),
                               ("detector_vertical", "detector_lateral")):
            reach = pitch * KNOBS[knob].high / _TURN
            if abs(value) > reach:
                return (f"the reflection falls {shown(abs(value), 'mm', '.3g')} from the "
                        f"photodiode's centre, beyond the {shown(reach, 'mm', '.3g')} that "
                        f"{knob}'s travel reaches: the chip sits tilted or off its place in the "
                        f"holder (tilt_error {math.degrees(self.tilt_error):.3g} deg, "
                        f"mount_offset_x {shown(self.mount_offset_x, 'mm', '.3g')}); seat it "
                        f"again")
        return ("the photodiode misses the reflection: centre it under the reflection "
                "(detector_vertical, detector_lateral)")

    def aligned(self, min_sum_fraction: float = TOLERANCES["min_sum_fraction"].default,
                max_difference: float = TOLERANCES["max_difference"].default,
                end_distance: float = TOLERANCES["end_distance"].default) -> Alignment:
        """Whether the head is aligned, and if not, why and what to turn.

        Aligned means: the sum is at least ``min_sum_fraction`` of :attr:`best_sum` (the spot
        is on the lever), the spot's centre is within ``end_distance`` of the lever's free end
        (where the lever bends most: the largest signal per nm), and both normalised
        differences are within ``max_difference`` of 0 (the spot centred on the photodiode).

        Parameters
        ----------
        min_sum_fraction : float
            Share of the best sum required, in [0, 1].
        max_difference : float
            Largest |vertical / sum| and |lateral / sum|, in [0, 1].
        end_distance : float
            Largest distance in m of the spot's centre from the free end, in [0, 1 mm].

        Returns
        -------
        Alignment
            True-valued when aligned; its ``reasons`` say what failed.
        """
        min_sum_fraction = TOLERANCES["min_sum_fraction"].check(min_sum_fraction)
        max_difference = TOLERANCES["max_difference"].check(max_difference)
        end_distance = TOLERANCES["end_distance"].check(end_distance)
        s = self.signals()
        reasons = []
        best = self.best_sum
        if s.sum < min_sum_fraction * best:
            low = f"the sum is {s.sum:.3g} V, below {min_sum_fraction:.0%} of its best {best:.3g} V"
            if s.lever_fraction < min_sum_fraction * self.best_overlap:
                reasons.append(f"{low}: put the spot on the lever (laser_x, laser_y)")
            else:
                reasons.append(f"{low}, though the lever reflects "
                               f"{s.lever_fraction / self.best_overlap:.0%} of the most it can: "
                               + self._photodiode_advice(s))
        gap = self.lever.length - s.spot_on_lever[0]
        if abs(gap) > end_distance:
            where = "short of" if gap > 0 else "beyond"
            reasons.append(f"the spot is {shown(abs(gap), 'um', '.3g')} {where} the lever's free "
                           f"end (at most {shown(end_distance, 'um', '.3g')}): turn laser_x")
        dark = s.sum < min_sum_fraction * best   # then the differences are the dark's noise
        for name, knob in (("vertical", "detector_vertical"), ("lateral", "detector_lateral")):
            value = getattr(s, f"{name}_normalised")
            if dark:
                break
            if abs(value) > max_difference:
                reasons.append(f"{name} / sum is {value:.3g} (at most {max_difference:g} either "
                               f"way): centre the photodiode with {knob}")
        return Alignment(ok=not reasons, reasons=tuple(reasons), signals=s)


# -- the optimiser: a student's procedure, with scipy.optimize doing the fine turning ------------
def _search_grid(head: OpticalHead):
    """Knob values (rad) for lines across the lever, spaced so no line can miss it."""
    p, a, f = head.mirror_screw_pitch, head.mirror_arm, head.focal_length
    gain_x = 2 * f * p / (_TURN * a)                        # focal m per rad of laser_x
    gain_y = gain_x * math.cos(math.pi / 4)
    step_x = head.lever.length * math.cos(head.holder_tilt) / 3 / gain_x
    step_y = (head.lever.width / 2 + head.waist / 2) / gain_y
    kx, ky = KNOBS["laser_x"], KNOBS["laser_y"]
    nx = int((kx.high - kx.low) / step_x) + 2
    ny = int((ky.high - ky.low) / step_y) + 2
    if nx * ny > MAX_SEARCH_POINTS:
        raise ValueError(f"the lever ({shown(head.lever.width, 'um', '.3g')} wide) is too small "
                         f"for the search: {nx * ny} knob settings, at most {MAX_SEARCH_POINTS}")
    return np.linspace(kx.low, kx.high, nx), np.linspace(ky.low, ky.high, ny), gain_x


def align(head: OpticalHead, *, end_margin: float = 0.02) -> AlignmentRun:
    """Align ``head`` as a student does, turning its knobs: search, centre, walk to the end.

    1. *Search*: sweep laser_y across its travel on lines of laser_x (spaced a third of the
       lever's length apart, points half a lever width apart) and go to the setting nearest the
       start where the lever reflects at least a quarter of :attr:`OpticalHead.best_overlap`
       (from a misaligned start the sum is near zero, so there is no gradient to follow; the
       student watches the spot on the lever, or the reflection on a card held in its path,
       since the photodiode may not catch it yet).
    2. *Photodiode*: find the reflection with the photodiode (a coarse raster of both knobs over
       their travel, a step of half the photodiode's side) and zero vertical / sum and
       lateral / sum with its knobs (``scipy.optimize.brentq``, each difference monotonic in
       its knob where light arrives; twice, since each knob changes the light the other sees).
       If the photodiode cannot be centred on the reflection (it falls beyond the knobs' reach:
       the chip sits tilted in its holder) the procedure stops here, its last step named so,
       and the verdict says what to do: the SUM the next steps follow would be the photodiode's
       edge, not the lever's.
    3. *Across*: maximise the sum over laser_y (``scipy.optimize.minimize_scalar``, bounded).
    4. *Along*: step laser_x towards the free end. Turning laser_x also moves the spot across
       a little (the mirror's two tilts couple in the exact reflection, more the further
       laser_y is turned), so when the sum falls below half the largest seen, centre across
       again first: only a fall that re-centring does not undo is the free end. Then walk back
       while the sum still rises (the search may have landed past the plateau) and go to where
       the sum is (1 - ``end_margin``) of the largest (``brentq``): about one spot radius inside
       the end, in the end region where the signal per nm of deflection is largest.
    5. *Across* again and the *photodiode* again (the spot moved on the detector as it moved on
       the lever).

    Parameters
    ----------
    head : OpticalHead
        The head; its knobs are turned (within their travel).
    end_margin : float
        Share of the sum given up at the end, in (0, 0.5).

    Returns
    -------
    AlignmentRun
        The steps, the evaluations and :meth:`OpticalHead.aligned` with default tolerances.
    """
    check_instance("head", head, OpticalHead)
    end_margin = check_range("end_margin", end_margin, 0.0, 0.5, low_inclusive=False,
                             high_inclusive=False)
    steps, count = [], [0]

    def total(**knobs):
        count[0] += 1
        return head._sum(**knobs)

    # 1. search, by the light the lever reflects (a card held in the reflected beam shows it)
    xs, ys, gain_x = _search_grid(head)
    gx, gy = np.meshgrid(xs, ys, indexing="ij")
    k = head.knobs
    _, lever_share, chip_share, _, _ = head._evaluate(gx, gy, k["detector_vertical"],
                                                      k["detector_lateral"], 0.0)
    reflected = lever_share + head.chip_reflectance * chip_share
    count[0] += reflected.size
    hits = np.argwhere(reflected > 0.25 * head.best_overlap)
    if not len(hits):
        steps.append(("search: no reflection found", head.signals()))
        return AlignmentRun(tuple(steps), count[0], head.aligned())
    distance = np.hypot(xs[hits[:, 0]] - k["laser_x"], ys[hits[:, 1]] - k["laser_y"])
    i, j = hits[np.argmin(distance)]
    steps.append(("search", head.set(laser_x=float(xs[i]), laser_y=float(ys[j]))))
    # 2. photodiode under the reflection
    s = _centre_detector(head, count)
    if not _detector_centred(head, s):
        steps.append(("photodiode: cannot centre it on the reflection", s))
        return AlignmentRun(tuple(steps), count[0], head.aligned())
    steps.append(("photodiode", s))
    # 3. across the lever
    dy = ys[1] - ys[0]

    def across(span=2 * dy):
        y = head.knobs["laser_y"]
        lo, hi = max(y - span, ys[0]), min(y + span, ys[-1])
        best = minimize_scalar(lambda u: -total(laser_y=u), bounds=(lo, hi), method="bounded",
                               options={"xatol": 1e-4 * dy, "maxiter": 100})
        return head.set(laser_y=float(best.x))
    steps.append(("across", across()))
    # 4. along, to the free end
    step = head.waist / 2 / gain_x
    low, high = KNOBS["laser_x"].low, KNOBS["laser_x"].high
    x, largest = head.knobs["laser_x"], total()
    previous = x
    for _ in range(int((high - x) / step) + 2):   # bounded by the knob's travel
        previous, x = x, min(x + step, high)
        s = total(laser_x=x)
        if s < 0.5 * largest:                     # the side or the end? centre across first
            head.set(laser_x=x)
            s = across(dy / 2).sum
            if s < 0.5 * largest:
                head.set(laser_x=previous)
                break
        largest = max(largest, s)
        if x >= high:
            break
    # back while the sum still rises (centred across at each step: the coupling again): the
    # plateau, then the last setting above the target
    back = previous
    head.set(laser_x=back)
    here = across(dy / 4).sum
    while back > low:
        candidate = max(back - step, low)
        y = head.knobs["laser_y"]
        head.set(laser_x=candidate)
        there = across(dy / 4).sum
        if there <= here * (1 + 1e-3):
            head.set(laser_x=back, laser_y=y)
            break
        back, here = candidate, there
    largest = max(largest, here)
    target = (1 - end_margin) * largest
    if here >= target > total(laser_x=x):
        x = brentq(lambda u: total(laser_x=u) - target, back, x, xtol=1e-6 * step)
    else:
        x = back
    steps.append(("along", head.set(laser_x=float(x))))
    # the mirror's two tilts couple a little (exact reflection): centre across once more
    steps.append(("across", across(dy / 2)))
    # 5. photodiode again (the spot moved on the detector as it moved on the lever)
    steps.append(("photodiode", _centre_detector(head, count)))
    return AlignmentRun(tuple(steps), count[0], head.aligned())


def _detector_centred(head: OpticalHead, s: Signals) -> bool:
    """Whether both differences are zeroed and the photodiode catches the lever's reflection."""
    capture = interval_fraction(0.0, head.detector_spot_radius, -head.detector_size / 2,
                                head.detector_size / 2) ** 2
    caught = (head.transimpedance_gain * head.responsivity * head.laser_power * head.reflectance
              * s.lever_fraction * capture)
    small = TOLERANCES["max_difference"].default / 10
    return (abs(s.vertical_normalised) < small and abs(s.lateral_normalised) < small
            and s.sum >= 0.9 * caught)


def _centre_detector(head: OpticalHead, count) -> Signals:
    """Find the reflection with the photodiode, then zero each difference with its knob."""
    kv, kl = KNOBS["detector_vertical"], KNOBS["detector_lateral"]
    # a raster of both knobs, a step of half the photodiode's side: one setting catches the
    # reflection wherever it falls within reach
    spacing = head.detector_size / 2 / head.detector_screw_pitch * _TURN
    gv = np.linspace(kv.low, kv.high, int((kv.high - kv.low) / spacing) + 2)
    gl = np.linspace(kl.low, kl.high, int((kl.high - kl.low) / spacing) + 2)
    k = head.knobs
    quads = head._evaluate(k["laser_x"], k["laser_y"], gv[:, None], gl[None, :], 0.0)[0]
    sums = head._volts(quads)[0]
    count[0] += sums.size
    if sums.max() > 0:
        i, j = np.unravel_index(np.argmax(sums), sums.shape)
        head.set(detector_vertical=float(gv[i]), detector_lateral=float(gl[j]))
    for _ in range(2):
        for knob, name in (("detector_vertical", "vertical_normalised"),
                           ("detector_lateral", "lateral_normalised")):
            meta = KNOBS[knob]

            def difference(value, knob=knob, name=name):
                count[0] += 1
                old = head.knobs[knob]
                s = head.set(**{knob: value})
                head.set(**{knob: old})
                return getattr(s, name)

            # outwards from where the knob is, in steps a quarter of the photodiode's side:
            # the nearest zero of the difference (the far ends of the travel see no light)
            centre = head.knobs[knob]
            grid = np.unique(np.clip(np.concatenate([
                centre + np.arange(-8, 9) * spacing / 2, [meta.low, meta.high]]),
                meta.low, meta.high))
            values = [difference(g) for g in grid]
            brackets = [(g0, g1) for g0, g1, v0, v1 in zip(grid[:-1], grid[1:], values[:-1],
                                                         values[1:]) if v0 * v1 < 0]
            if brackets:
                g0, g1 = min(brackets, key=lambda b: abs(b[0] + b[1] - 2 * centre))
                head.set(**{knob: brentq(difference, g0, g1, xtol=1e-9)})
    return head.signals()
