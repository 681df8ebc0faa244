"""The contact system of module (d): a tip on a lever pressed into a sample, with its parameters.

:class:`ContactSystem` holds what the indentation models need (the tip, the lever's spring
constant, the sample's Young's modulus and Poisson's ratio, the adhesion model and its work of
adhesion), validates it once, and answers every question the course asks of it with keyword-free
calls: the indentation curve (:meth:`ContactSystem.indent`), the approach-retract cycle
(:meth:`ContactSystem.approach_retract`), the state at one Z_np on a branch
(:meth:`ContactSystem.at`), the snap-off and pull-off forces, and the largest Z_np the models
accept (:attr:`ContactSystem.z_np_limit`). It plays the part module (c)'s
:class:`~afmsmiler.controller.ContactLoop` plays there, and it can be built from a module (a)
:class:`~afmsmiler.cantilever.Cantilever` (:meth:`ContactSystem.from_cantilever`), so that the
course's modules join up.

The quantities always come in one order, the free functions' (:func:`indent`,
:func:`approach_retract`, :func:`z_np_limit`, :func:`adhesion_extrema`): spring_constant, tip,
youngs_modulus, poisson_ratio, adhesion, work_of_adhesion; the system takes them as keywords.
:data:`PARAMETERS` describes the user-settable ones (SI units, display units, defaults, valid and
slider ranges) for the panel and the docs.

Examples
--------
>>> from afmsmiler.contact import ContactSystem, Parabolic
>>> system = ContactSystem(spring_constant=0.1, tip=Parabolic(radius=50e-9),
...                        youngs_modulus=20e6, poisson_ratio=0.3, adhesion="jkr",
...                        work_of_adhesion=0.03)
>>> round(system.pull_off_force / (1.5 * 3.141592653589793 * 50e-9 * 0.03), 6)  # JKR: 3/2 pi R w
1.0
"""
from __future__ import annotations

from dataclasses import dataclass, field, replace
from functools import cached_property

import numpy as np

from ..validation import check_array, check_choice, check_instance
from .indent import (ADHESION_MODELS, ApproachRetract, IndentationCurve, _approach_retract,
                     _check_ramp, adhesion_extrema, indent, z_np_limit)
from .quantities import PARAMETERS
from .tips import Parabolic, Tip, reduced_modulus

__all__ = ["PARAMETERS", "ContactSystem", "BRANCHES", "RAMP_MARGIN", "RAMP_MIN_RANGE",
           "SNAP_OFF_MARGIN", "RAMP_FLOOR"]

#: The branches of a cycle on which :meth:`ContactSystem.at` gives the state.
BRANCHES = ("approach", "retract")
#: A ramp stops at this fraction of :attr:`ContactSystem.z_np_limit` (a sphere buried at 1).
RAMP_MARGIN = 0.9
#: Room in m below which a sphere's ramp has no use for adhesion: adhesion would pull it in past
#: its radius before Z_np = RAMP_MIN_RANGE / RAMP_MARGIN (:meth:`ContactSystem.for_ramp`).
RAMP_MIN_RANGE = 1e-9
#: A ramp with adhesion reaches this multiple of the snap-off Z_np, so the retract is complete.
SNAP_OFF_MARGIN = 1.25
#: The lowest Z_np in m a ramp reaches (a very soft lever's snap-off lies lower).
RAMP_FLOOR = -2000e-9


def _point(curve: IndentationCurve, i: int) -> IndentationCurve:
    return IndentationCurve(*(getattr(curve, f)[i:i + 1] for f in
                              ("z_np", "z_s", "z_c", "force", "contact_radius", "in_contact")))


@dataclass(frozen=True, kw_only=True)
class ContactSystem:
    """A rigid tip on a lever of spring constant k, pressed into an elastic (adhesive) sample.

    Parameters
    ----------
    spring_constant : float
        Lever spring constant k in N/m (see :data:`PARAMETERS` for the valid ranges).
    tip : Tip
        The tip shape (default: a paraboloid of radius 20 nm).
    youngs_modulus : float
        Young's modulus E of the sample in Pa, > 0.
    poisson_ratio : float
        Poisson's ratio nu of the sample, in [0, 0.5).
    adhesion : {None, "dmt", "jkr"}
        Adhesion model (DMT or JKR need a tip whose :attr:`~Tip.adhesive` is True).
    work_of_adhesion : float
        w in J/m^2, > 0 (used only with adhesion).

    Raises
    ------
    TypeError
        If ``tip`` is not a :class:`Tip`.
    ValueError
        If a value is outside its valid range (:data:`PARAMETERS`), the adhesion model is unknown
        or adhesion is asked of a cone or pyramid.

    Notes
    -----
    The models and their sources are those of :mod:`afmsmiler.contact.indent` (Hertz, Sneddon,
    Rico/Bilodeau, DMT, JKR).
    """

    spring_constant: float = PARAMETERS["spring_constant"].default
    tip: Tip = field(default_factory=Parabolic)
    youngs_modulus: float = PARAMETERS["youngs_modulus"].default
    poisson_ratio: float = PARAMETERS["poisson_ratio"].default
    adhesion: str | None = None
    work_of_adhesion: float = PARAMETERS["work_of_adhesion"].default

    def __post_init__(self):
        check_instance("tip", self.tip, Tip)
        for name in ("spring_constant", "youngs_modulus", "poisson_ratio", "work_of_adhesion"):
            object.__setattr__(self, name, PARAMETERS[name].check(getattr(self, name)))
        check_choice("adhesion", self.adhesion, ADHESION_MODELS)
        if self.adhesion is not None and not self.tip.adhesive:
            raise ValueError(f"adhesion {self.adhesion!r} needs a tip with a smooth apex "
                             f"(parabolic or spherical), got {type(self.tip).__name__}")

    @classmethod
    def from_cantilever(cls, cantilever, **parameters) -> "ContactSystem":
        """A contact system whose lever is a module (a) cantilever (k from its geometry).

        Parameters
        ----------
        cantilever : afmsmiler.cantilever.Cantilever
            The lever; its ``spring_constant`` (N/m) is used.
        **parameters
            The other fields: ``tip``, ``youngs_modulus``, ``poisson_ratio``, ``adhesion``,
            ``work_of_adhesion`` (SI).

        Returns
        -------
        ContactSystem

        Raises
        ------
        TypeError
            If ``cantilever`` is not a Cantilever or ``spring_constant`` is passed too.
        """
        from ..cantilever import Cantilever
        check_instance("cantilever", cantilever, Cantilever)
        if "spring_constant" in parameters:
            raise TypeError("spring_constant comes from the cantilever; do not pass it too")
        return cls(spring_constant=cantilever.spring_constant, **parameters)

    def replace(self, **changes) -> "ContactSystem":
        """A copy with some fields changed (validated again).

        Parameters
        ----------
        **changes
            New values of any of the fields.

        Returns
        -------
        ContactSystem
        """
        return replace(self, **changes)

    # -- derived quantities ------------------------------------------------------------------
    @property
    def reduced_modulus(self) -> float:
        """E* = E / (1 - nu^2) in Pa (rigid tip)."""
        return reduced_modulus(self.youngs_modulus, self.poisson_ratio)

    @property
    def _adhesion_kwargs(self) -> dict:
        if self.adhesion is None:
            return {}
        return dict(adhesion=self.adhesion, work_of_adhesion=self.work_of_adhesion)

    @cached_property
    def z_np_limit(self) -> float:
        """Largest Z_np in m the models accept (inf but for a sphere; see :func:`z_np_limit`)."""
        return z_np_limit(self.spring_constant, self.tip, self.youngs_modulus, self.poisson_ratio,
                          **self._adhesion_kwargs)

    @cached_property
    def _snap_off(self) -> tuple[float, float, float]:
        """(snap_off_z_np, snap_off_force, pull_off_force) of the adhesive model (zeros without)."""
        if self.adhesion is None:
            return 0.0, 0.0, 0.0
        return adhesion_extrema(self.spring_constant, self.tip, self.youngs_modulus,
                                self.poisson_ratio, **self._adhesion_kwargs)

    @property
    def snap_off_z_np(self) -> float:
        """Z_np in m at which the tip leaves the surface on retract (0 without adhesion)."""
        return self._snap_off[0]

    @property
    def snap_off_force(self) -> float:
        """Force in N just before the snap-off, signed (0 without adhesion)."""
        return self._snap_off[1]

    @property
    def pull_off_force(self) -> float:
        """Magnitude of the most adhesive force on retract in N (0 without adhesion)."""
        return self._snap_off[2]

    # -- the models --------------------------------------------------------------------------
    def indent(self, z_np) -> IndentationCurve:
        """The elastic indentation curve (no adhesion) over ``z_np`` (see :func:`indent`).

        Parameters
        ----------
        z_np : float or array_like
            Positioner displacements Z_np in m.

        Returns
        -------
        IndentationCurve
        """
        return indent(z_np, self.spring_constant, self.tip, self.youngs_modulus,
                      self.poisson_ratio)

    def approach_retract(self, z_np) -> ApproachRetract:
        """The approach-retract cycle over the ramp ``z_np`` (see :func:`approach_retract`).

        Parameters
        ----------
        z_np : array_like
            The approach ramp of Z_np in m, strictly increasing, at least 2 points, below
            :attr:`z_np_limit`.

        Returns
        -------
        ApproachRetract
        """
        # the fields were checked when the system was made: only the ramp is checked here
        return _approach_retract(_check_ramp(z_np), self.spring_constant, self.tip,
                                 self.youngs_modulus, self.poisson_ratio, self.reduced_modulus,
                                 self.adhesion, self.work_of_adhesion if self.adhesion else 0.0)

    # -- the ramp that shows a whole cycle ---------------------------------------------------
    def for_ramp(self) -> "ContactSystem":
        """This system, or the same without adhesion where adhesion leaves a ramp no room.

        Adhesion can pull a sphere in past its radius before any load: its limit Z_np (times
        :data:`RAMP_MARGIN`) then lies below :data:`RAMP_MIN_RANGE`, and no approach-retract
        cycle can be shown. Such a system is shown without adhesion (compare ``adhesion``).

        Returns
        -------
        ContactSystem
        """
        if self.adhesion and RAMP_MARGIN * self.z_np_limit < RAMP_MIN_RANGE:
            return self.replace(adhesion=None)
        return self

    def ramp(self, low: float, high: float) -> tuple[float, float]:
        """The Z_np range in m of a whole approach-retract cycle, from a wished [low, high].

        With adhesion the range reaches down to :data:`SNAP_OFF_MARGIN` times the snap-off
        Z_np, so that the retract ends off the surface; never below :data:`RAMP_FLOOR`; and up
        to at most :data:`RAMP_MARGIN` of the tip's :attr:`z_np_limit` (a sphere's).

        Parameters
        ----------
        low, high : float
            The wished ends in m (a slider's), ``low < high``.

        Returns
        -------
        (float, float)
            The ends in m.

        Raises
        ------
        ValueError
            If an end is not a finite number or ``low >= high``.
        """
        low = float(check_array("low", low, "m", ndim=0))
        high = float(check_array("high", high, "m", ndim=0))
        if not low < high:
            raise ValueError(f"low must be below high, got low={low:g} m, high={high:g} m")
        if self.adhesion:  # extend the ramp below the snap-off so that the retract is complete
            low = min(low, SNAP_OFF_MARGIN * self.snap_off_z_np)
        low = max(low, RAMP_FLOOR)
        high = min(high, RAMP_MARGIN * self.z_np_limit)
        return low, high

    def at(self, z_np, branch: str = "approach") -> IndentationCurve:
        """The state at one Z_np on the approach or the retract branch (one model run).

        With adhesion the branches differ: on approach the tip touches from Z_np = 0 on, on
        retract it stays stuck down to :attr:`snap_off_z_np`.

        Parameters
        ----------
        z_np : float
            Positioner displacement in m, below :attr:`z_np_limit`.
        branch : {"approach", "retract"}
            Which branch of the cycle.

        Returns
        -------
        IndentationCurve
            One point.
        """
        z = float(check_array("z_np", z_np, "m", ndim=0))
        branch = check_choice("branch", branch, BRANCHES)
        if self.adhesion is None:
            return self.indent(np.array([z]))
        # a two-point ramp ending at z: the last point of the approach, the first of the retract
        cycle = self.approach_retract(np.array([z - max(1e-9, 1e-9 * abs(z)), z]))
        return _point(cycle.retract, 0) if branch == "retract" else _point(cycle.approach, 1)
