"""Figures of module (g): the signal each imaging mode measures, drawn from the models' results.

- :class:`TappingFigure`: amplitude, phase lag and dissipated energy against the rest distance
  z_c, both branches of :func:`~afmsmiler.modes.amplitude_curve` (the attractive, low one and the
  repulsive, high one), the unstable roots between them, the region where both coexist, the
  setpoint and the state the amplitude feedback holds (:func:`~afmsmiler.modes.setpoint_state`).
- :class:`LateralFigure`: a friction loop (trace and retrace lateral force along one line) with
  its decomposition into friction, half the difference, and the slope term, half the sum (Ogletree,
  Carpick and Salmeron 1996); the friction-coefficient and slope-term maps of a scan.
- :class:`FrequencyShiftFigure`: the frequency shift df(z) by Giessibl's formula beside its
  small-amplitude limit -f0 / (2 k) dF/dz, and the force recovered by the Sader-Jarvis inversion
  over the force put in.
- :class:`JumpingFigure`: one pixel's jumping-mode force curve (approach to the trigger, retract
  by the lift, against Z_np and against time) and the height image with a line's profile.
- :class:`ForceVolumeFigure`: the modulus, adhesion, deformation and dissipation maps of a
  force-volume measurement and each material's force curve.

Each figure takes the model's result objects and only converts units (the display units of
:data:`afmsmiler.parameters.UNITS`); nothing here computes physics. The figures are pyplot-free
:class:`~matplotlib.figure.Figure` objects whose artists are updated in place, so that a panel's
:class:`~afmsmiler.plots.live.LiveFigure` sends them to the browser.
"""
from __future__ import annotations

import math
from collections.abc import Mapping

import numpy as np
from matplotlib.figure import Figure

from ..brownian import BOLTZMANN, TEMPERATURE
from ..modes.fm import FrequencyShiftCurve
from ..modes.force_volume import ForceVolume
from ..modes.jumping import JumpCurve
from ..modes.lateral import FrictionImages, FrictionLoop
from ..imaging.scanner import ScanResult
from ..modes.tapping import AmplitudeCurve
from ..parameters import read_only, unit_scale
from ..validation import check_array, check_flag, check_instance, check_integer, check_real
from .limits import data_range, hold, sticky_limits
from .live import set_clim

__all__ = ["UNITS_SHOWN", "ENERGY_FLOOR", "TappingFigure", "LateralFigure", "FrequencyShiftFigure",
           "JumpingFigure", "ForceVolumeFigure", "branch_values", "unstable_roots"]

#: The units the figures show each quantity in (keys of :data:`afmsmiler.parameters.UNITS`).
UNITS_SHOWN = read_only(dict(distance="nm", amplitude="nm", phase="deg", energy="zJ",
                             force="nN", position="nm", frequency="Hz", time="ms",
                             modulus="MPa", height="nm"))

_NM = unit_scale(UNITS_SHOWN["distance"], "m")
_DEG = unit_scale(UNITS_SHOWN["phase"], "rad")
_ZJ = unit_scale(UNITS_SHOWN["energy"], "J")
_NN = unit_scale(UNITS_SHOWN["force"], "N")
_KHZ = unit_scale("kHz", "Hz")
_MS = unit_scale(UNITS_SHOWN["time"], "s")
_MPA = unit_scale(UNITS_SHOWN["modulus"], "Pa")
#: The smallest span of the E_dis axis in zJ: k_B T at room temperature (4.1 zJ), the lever's
#: thermal energy. The model returns 0 where E_dis is zero within its accuracy
#: (:attr:`~afmsmiler.modes.AmplitudeCurve.dissipated_energy_error`); the axis then shows that
#: zero on a scale where a dissipation worth measuring would show, not a flat line magnified
#: to +-5e-4 zJ.
ENERGY_FLOOR = BOLTZMANN * TEMPERATURE.default * _ZJ
_COLORS = read_only(dict(attractive="C0", repulsive="C3", unstable="0.55", point="C2",
                         trace="C0", retrace="C3", friction="C2", slope="C1", input="k",
                         recovered="C3", giessibl="C0", gradient="C1"))


def branch_values(curve: AmplitudeCurve, values: np.ndarray, name: str) -> np.ndarray:
    """One column of ``values`` (shaped like ``curve.amplitude``) on a branch, NaN where none.

    The model's own choice, :meth:`AmplitudeCurve.on_branch
    <afmsmiler.modes.AmplitudeCurve.on_branch>` (the root :meth:`AmplitudeCurve.branch` picks:
    the stable root of the branch, the largest if two), so that e.g. the dissipated energy lines
    up with the branch's amplitude.

    Parameters
    ----------
    curve : AmplitudeCurve
        The curve.
    values : ndarray
        An array of the shape of ``curve.amplitude`` (e.g. ``curve.dissipated_energy``).
    name : str
        ``"attractive"`` or ``"repulsive"``.

    Returns
    -------
    ndarray
        Shape (n,), NaN where the branch has no stable root.
    """
    check_instance("curve", curve, AmplitudeCurve)
    return curve.on_branch(values, name)


def unstable_roots(curve: AmplitudeCurve) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The unstable roots of a curve as flat arrays: distance, amplitude and phase (SI).

    Parameters
    ----------
    curve : AmplitudeCurve
        The curve.

    Returns
    -------
    (ndarray, ndarray, ndarray)
        z_c in m, A in m and phi in rad of every root that is not stable.
    """
    check_instance("curve", curve, AmplitudeCurve)
    bad = ~curve.stable & np.isfinite(curve.amplitude)
    rows, cols = np.nonzero(bad)
    return curve.distance[rows], curve.amplitude[rows, cols], curve.phase[rows, cols]


#: Most separate coexistence regions a tapping figure shades (any further ones join the last).
COEXISTENCE_SPANS = 3


def _coexistence(curve: AmplitudeCurve) -> list:
    """[(low, high), ...] in m: each run of neighbouring distances where both branches are
    stable, in increasing distance (the attractive branch may vanish between two runs)."""
    order = np.argsort(curve.distance)
    z, both = curve.distance[order], curve.coexist[order]
    edges = np.flatnonzero(np.diff(np.concatenate(([0], both.astype(int), [0]))))
    return [(float(z[i]), float(z[j - 1])) for i, j in zip(edges[::2], edges[1::2])]


def _check_setpoint(setpoint):
    """``setpoint`` (None, or ``(ratio, z_c, phase, E_dis, attractive)``), or a named error."""
    if setpoint is None:
        return None
    if not isinstance(setpoint, (tuple, list)) or len(setpoint) != 5:
        raise TypeError(f"setpoint must be None or a tuple (setpoint_ratio, z_c, phase, E_dis, "
                        f"attractive), got {type(setpoint).__name__} {setpoint!r:.60}")
    *numbers, attractive = setpoint
    names = ("setpoint_ratio", "z_c", "phase", "E_dis")
    return (*(check_real(f"setpoint's {n}", v) for n, v in zip(names, numbers)),
            check_flag("setpoint's attractive", attractive))


def _check_jumps(jumps):
    """``jumps`` (None, or ``{"approach": [z, ...], "retract": [z, ...]}`` in m), or a named
    error."""
    if jumps is None:
        return {}
    if not isinstance(jumps, Mapping) or not set(jumps) <= {"approach", "retract"}:
        raise TypeError(f"jumps must be None or a dict with keys 'approach' and/or 'retract', "
                        f"got {type(jumps).__name__} {jumps!r:.60}")
    return {way: check_array(f"jumps[{way!r}]", at, "m", ndim=1) for way, at in jumps.items()}


class TappingFigure:
    """Amplitude, phase lag and E_dis against z_c: both branches, the jump, the setpoint.

    Parameters
    ----------
    curve : AmplitudeCurve
        The first curve to show (:func:`~afmsmiler.modes.amplitude_curve`).
    setpoint : tuple, optional
        ``(setpoint_ratio, z_c, phase, E_dis, attractive)``: the ratio A_sp / A0 and the state
        :func:`~afmsmiler.modes.setpoint_state` returns for it (z_c in m, phase lag in rad,
        E_dis in J, whether it is on the attractive branch).
    fig : matplotlib.figure.Figure, optional
        Where to draw (a panel's); default a new Figure 8 x 7.5 in.
    jumps : dict, optional
        ``{"approach": [z, ...], "retract": [z, ...]}``: the distances in m at which a slow
        approach and a slow retraction jump between the branches
        (:meth:`AmplitudeCurve.sweep <afmsmiler.modes.AmplitudeCurve.sweep>`); the first of
        each is marked.
    status : str, optional
        Shown as the title instead of the curve's numbers (the coexistence, the jumps, the
        held state): what the figure shows when it is not the whole answer (a panel's quick
        curve during a drag).

    Attributes
    ----------
    fig : matplotlib.figure.Figure
    axes : dict
        ``"amplitude"``, ``"phase"``, ``"energy"`` -> Axes.
    lines : dict
        (quantity, kind) -> Line2D, kind one of ``"attractive"``, ``"repulsive"``,
        ``"unstable"``, ``"point"``; ``("amplitude", "setpoint")`` is the setpoint's line,
        ``("amplitude", "contact")`` the line A = z_c - a0 above which a state's tip dips below
        a0 into the sample (:meth:`~afmsmiler.modes.TappingLever.indentation`), and
        ``(quantity, "jump approach")`` and ``(quantity, "jump retract")`` mark the jumps.
    spans : dict
        quantity -> list of :data:`COEXISTENCE_SPANS` Rectangles marking the coexistence
        regions, one per run of distances where both branches are stable (hidden when unused).
    """

    QUANTITIES = ("amplitude", "phase", "energy")

    def __init__(self, curve: AmplitudeCurve, setpoint=None, fig: Figure | None = None,
                 jumps=None, status: str = ""):
        check_instance("curve", curve, AmplitudeCurve)
        _check_setpoint(setpoint)
        _check_jumps(jumps)
        self.fig = (check_instance("fig", fig, Figure) if fig is not None
                    else Figure(figsize=(8.0, 7.5)))
        self.fig.set_layout_engine("constrained")
        axes = self.fig.subplots(3, 1, sharex=True)
        self.axes = dict(zip(self.QUANTITIES, axes))
        self.lines, self.spans = {}, {}
        for q, ax in self.axes.items():
            self.spans[q] = [ax.axvspan(0.0, 1.0, color="0.88", zorder=0)
                             for _ in range(COEXISTENCE_SPANS)]
            self.lines[q, "unstable"], = ax.plot([], [], ".", color=_COLORS["unstable"],
                                                 ms=3, label="unstable")
            for b in ("attractive", "repulsive"):
                self.lines[q, b], = ax.plot([], [], color=_COLORS[b], lw=1.8,
                                            label=f"{b} branch")
            self.lines[q, "point"], = ax.plot([], [], "o", color=_COLORS["point"], ms=7,
                                              label="feedback holds")
            if q == "amplitude":  # the tip dips below a0 where A > z_c - a0
                self.lines[q, "contact"], = ax.plot([], [], color="k", ls="-.", lw=0.8,
                                                    label="touches above: A = z_c - a0")
            self.lines[q, "jump approach"] = ax.axvline(0.0, color="k", ls="--", lw=1.0)
            self.lines[q, "jump retract"] = ax.axvline(0.0, color="k", ls=":", lw=1.0)
        self.lines["amplitude", "setpoint"] = self.axes["amplitude"].axhline(
            0.0, color=_COLORS["point"], ls="--", lw=1.0)
        nm, deg, zj = UNITS_SHOWN["amplitude"], UNITS_SHOWN["phase"], UNITS_SHOWN["energy"]
        self.axes["amplitude"].set_ylabel(f"amplitude A [{nm}]")
        self.axes["phase"].set_ylabel(f"phase lag [{deg}]")
        self.axes["energy"].set_ylabel(f"E_dis per cycle [{zj}]")
        self.axes["energy"].set_xlabel(f"rest tip-sample distance z_c [{UNITS_SHOWN['distance']}]")
        self.axes["amplitude"].legend(loc="lower right", fontsize="small")
        self._reset = True
        self.update(curve, setpoint, jumps, status)

    def update(self, curve: AmplitudeCurve, setpoint=None, jumps=None, status: str = "") -> None:
        """Show a new curve and operating point (artists updated in place).

        Parameters
        ----------
        curve : AmplitudeCurve
            The curve.
        setpoint : tuple, optional
            ``(setpoint_ratio, z_c, phase, E_dis, attractive)`` as for the constructor.
        jumps : dict, optional
            The jumps' distances, as for the constructor.
        status : str, optional
            As for the constructor.
        """
        check_instance("curve", curve, AmplitudeCurve)
        check_instance("status", status, str)
        setpoint, jumps = _check_setpoint(setpoint), _check_jumps(jumps)
        z = curve.distance * _NM
        order = np.argsort(z)
        data = {}
        for b in ("attractive", "repulsive"):
            a, p = curve.branch(b)
            e = curve.on_branch(curve.dissipated_energy, b)
            data[b] = dict(amplitude=a * _NM, phase=p * _DEG, energy=e * _ZJ)
        zu, au, pu = unstable_roots(curve)
        # the unstable roots carry no dissipation of their own worth showing: amplitude, phase
        unstable = dict(amplitude=au * _NM, phase=pu * _DEG, energy=np.full(au.shape, np.nan))
        span = _coexistence(curve)
        for q, ax in self.axes.items():
            for b in ("attractive", "repulsive"):
                self.lines[q, b].set_data(z[order], data[b][q][order])
            self.lines[q, "unstable"].set_data(zu * _NM, unstable[q])
            shaded = span[:COEXISTENCE_SPANS - 1] + ([(span[COEXISTENCE_SPANS - 1][0],
                                                       span[-1][1])]
                                                     if len(span) >= COEXISTENCE_SPANS else [])
            for rect, run in zip(self.spans[q], shaded + [None] * COEXISTENCE_SPANS):
                rect.set_visible(run is not None)
                if run is not None:
                    rect.set_x(run[0] * _NM)
                    rect.set_width((run[1] - run[0]) * _NM)
        contact = curve.distance[order] - curve.lever.intermolecular_distance
        self.lines["amplitude", "contact"].set_data(z[order], contact * _NM)
        ax = self.axes["amplitude"]
        ax.set_xlim(float(z.min()), float(z.max()))
        a0 = curve.lever.free_amplitude
        title = f"A0 = {a0 * _NM:.3g} nm" + ("" if not span else "; both branches " + " and ".join(
            f"from {lo * _NM:.3g} to {hi * _NM:.3g}" for lo, hi in span) + " nm (grey)")
        said = []
        for way in ("approach", "retract"):
            at = list(jumps.get(way, ()))
            for q in self.QUANTITIES:
                line = self.lines[q, f"jump {way}"]
                line.set_visible(bool(at))
                if at:
                    line.set_xdata([at[0] * _NM] * 2)
            if at:
                said.append(f"{'approach' if way == 'approach' else 'retraction'} jumps at "
                            f"{at[0] * _NM:.3g} nm ({'dashed' if way == 'approach' else 'dotted'})")
        if said:
            title += "\n" + ", ".join(said)
        if setpoint is None:
            for q in self.QUANTITIES:
                self.lines[q, "point"].set_data([], [])
            self.lines["amplitude", "setpoint"].set_visible(False)
        else:
            ratio, zc, phase, e_dis, attractive = setpoint
            values = dict(amplitude=ratio * a0 * _NM, phase=phase * _DEG, energy=e_dis * _ZJ)
            for q in self.QUANTITIES:
                self.lines[q, "point"].set_data([zc * _NM], [values[q]])
            line = self.lines["amplitude", "setpoint"]
            line.set_visible(True)
            line.set_ydata([values["amplitude"]] * 2)
            branch = "attractive" if attractive else "repulsive"
            depth = curve.lever.indentation(zc, ratio * a0)  # the model's own contact test
            touch = (f"tip {depth * _NM:.2g} nm into the sample" if depth > 0 else
                     f"tip {-depth * _NM:.2g} nm clear of it")
            title += (f"\nsetpoint {ratio:.3g} A0: held at z_c = {zc * _NM:.3g} nm, {branch} "
                      f"branch, {touch}")
        for q, a in self.axes.items():  # the curves and the held state, on a held scale
            lo, hi = data_range(data["attractive"][q], data["repulsive"][q], unstable[q],
                                self.lines[q, "point"].get_ydata())
            if math.isfinite(lo):
                hold(a, "y", lo, hi, reset=self._reset,
                     floor=ENERGY_FLOOR if q == "energy" else 1e-3)
        # E_dis is 0 where the model finds it zero within its accuracy: say it when all are
        energies = np.r_[data["attractive"]["energy"], data["repulsive"]["energy"]]
        energies = energies[np.isfinite(energies)]
        none = energies.size > 0 and not np.any(energies) and not status
        self.axes["energy"].set_title("E_dis = 0 on both branches (within the model's accuracy): "
                                      "the sample takes no energy" if none else "")
        ax.set_title(status or title, color="#b00020" if status else "k")
        self._reset = False


class LateralFigure:
    """A friction loop and its decomposition; the friction-coefficient and slope-term maps.

    Parameters
    ----------
    loop : FrictionLoop
        The loop of one line (:func:`~afmsmiler.modes.friction_loop`, or a row of a scan).
    images : FrictionImages, optional
        The scan's images (:func:`~afmsmiler.modes.friction_scan`); without them only the loop
        is drawn.
    row : int, optional
        The row of ``images`` the loop is, marked on the maps.
    fig : matplotlib.figure.Figure, optional
        Where to draw; default a new Figure 9 x 7 in.

    Attributes
    ----------
    fig : matplotlib.figure.Figure
    axes : dict
        ``"loop"``, and with images ``"friction"`` and ``"slope"`` -> Axes.
    lines : dict
        ``"trace"``, ``"retrace"``, ``"friction"``, ``"slope"`` (loop), ``"row"`` -> Line2D.
    images : dict
        ``"friction"``, ``"slope"`` -> AxesImage.
    """

    #: Margin of the slope map's colour scale, a fraction of its span on each side: the largest
    #: slope term falls at 1 / (1 + 2 * 0.25) = 2/3 of the half-span.
    SLOPE_MARGIN = 0.25

    def __init__(self, loop: FrictionLoop, images: FrictionImages | None = None,
                 row: int | None = None, fig: Figure | None = None):
        if row is not None:
            check_integer("row", row, 0)
        self.fig = (check_instance("fig", fig, Figure) if fig is not None
                    else Figure(figsize=(9.0, 7.0)))
        self.fig.set_layout_engine("constrained")
        self.has_maps = images is not None
        if self.has_maps:
            grid = self.fig.add_gridspec(2, 2, height_ratios=(1, 1))
            self.axes = dict(loop=self.fig.add_subplot(grid[0, :]),
                             friction=self.fig.add_subplot(grid[1, 0]),
                             slope=self.fig.add_subplot(grid[1, 1]))
        else:
            self.axes = dict(loop=self.fig.add_subplot())
        ax = self.axes["loop"]
        self.lines = {}
        self.lines["trace"], = ax.plot([], [], color=_COLORS["trace"], label="trace")
        self.lines["retrace"], = ax.plot([], [], color=_COLORS["retrace"], label="retrace")
        self.lines["friction"], = ax.plot([], [], color=_COLORS["friction"], ls="--", lw=2.0,
                                          label="(trace - retrace) / 2: friction")
        self.lines["slope"], = ax.plot([], [], color=_COLORS["slope"], ls=":", lw=2.0,
                                       label="(trace + retrace) / 2: slope")
        ax.axhline(0.0, color="0.6", lw=0.8)
        ax.set(xlabel=f"position along the line [{UNITS_SHOWN['position']}]",
               ylabel=f"lateral force [{UNITS_SHOWN['force']}]")
        ax.legend(loc="upper right", fontsize="small", ncol=2)
        self.images, self.colorbars = {}, {}
        if self.has_maps:
            mu_label = "mu (dimensionless)"  # the title says what mu is; the bar is short
            for key, cmap, label in (("friction", "viridis", mu_label),
                                     ("slope", "RdBu_r",
                                      f"slope term [{UNITS_SHOWN['force']}]")):
                im = self.axes[key].imshow(np.zeros((2, 2)), origin="lower", cmap=cmap,
                                           interpolation="nearest", extent=(0, 1, 0, 1))
                self.images[key] = im
                self.colorbars[key] = self.fig.colorbar(im, ax=self.axes[key], shrink=0.9,
                                                        label=label)
            self.lines["row"], = self.axes["friction"].plot([], [], color="w", lw=1.0)
        self._reset = True
        self.update(loop, images, row)

    def update(self, loop: FrictionLoop, images: FrictionImages | None = None,
               row: int | None = None) -> None:
        """Show a new loop (and maps), artists updated in place.

        Parameters
        ----------
        loop : FrictionLoop
            The loop.
        images : FrictionImages, optional
            The maps (needed if the figure was made with them).
        row : int, optional
            The row of the loop on the maps.
        """
        check_instance("loop", loop, FrictionLoop)
        if row is not None:
            rows = (np.shape(images.friction_coefficient.heights)[0]
                    if isinstance(images, FrictionImages) else math.inf)
            row = check_integer("row", row, 0, rows - 1)
        x = loop.x * _NM
        for key, values in (("trace", loop.trace), ("retrace", loop.retrace),
                            ("friction", loop.friction), ("slope", loop.slope_term)):
            self.lines[key].set_data(x, values * _NN)
        ax = self.axes["loop"]
        ax.set_xlim(float(x[0]), float(x[-1]))
        lo, hi = data_range(loop.trace * _NN, loop.retrace * _NN, 0.0)
        hold(ax, "y", lo, hi, reset=self._reset, floor=1e-3)
        sliding = loop.friction_coefficient[1:-1]
        ax.set_title(f"friction loop at load {loop.normal_force * _NN:.3g} nN: "
                     f"mean (trace - retrace) / 2 / load = {float(np.mean(sliding)):.3g}")
        if self.has_maps:
            if images is None:
                raise ValueError("images must be given to a figure made with maps")
            check_instance("images", images, FrictionImages)
            mu = images.friction_coefficient
            slope = images.slope_term
            rows, cols = np.shape(mu.heights)
            dx = mu.pixel_size * _NM
            dy = (mu.pixel_size_y or mu.pixel_size) * _NM
            extent = (-0.5 * dx, (cols - 0.5) * dx, -0.5 * dy, (rows - 0.5) * dy)
            for key, values in (("friction", mu.heights), ("slope", slope.heights * _NN)):
                im = self.images[key]
                im.set_data(values)
                im.set_extent(extent)
                # the colour scale leaves out the first and last columns: the stuck
                # turn-arounds, where the lateral force is not friction or slope
                lo, hi = data_range(values[..., 1:-1] if values.shape[-1] > 2 else values)
                if key == "slope":
                    # symmetric about zero (the diverging map's white), the largest slope term
                    # a third of the half-span inside the end (a uniform tilt's 1.05 nN sat at
                    # the end of +-1.05: saturated), held while it stays inside
                    m = max(abs(lo), abs(hi), 1e-3)
                    shown = None if self._reset else im.get_clim()
                    lo, hi = sticky_limits(shown, -m, m, margin=self.SLOPE_MARGIN)
                    m = max(abs(lo), abs(hi))
                    lo, hi = -m, m
                elif hi - lo < 1e-6:
                    lo, hi = lo - 0.05, hi + 0.05
                set_clim(im, lo, hi)
                self.axes[key].set(xlim=extent[:2], ylim=extent[2:],
                                   xlabel=f"x [{UNITS_SHOWN['position']}] (fast axis)",
                                   ylabel=f"y [{UNITS_SHOWN['position']}]")
            self.axes["friction"].set_title("friction map: (trace - retrace) / 2 / load")
            self.axes["slope"].set_title("slope map: (trace + retrace) / 2")
            if row is None:
                self.lines["row"].set_data([], [])
            else:
                y = row * dy
                self.lines["row"].set_data(list(extent[:2]), [y, y])
        self._reset = False


class FrequencyShiftFigure:
    """df(z) by Giessibl's formula and its small-amplitude limit; F put in and F recovered.

    Parameters
    ----------
    curve : FrequencyShiftCurve
        The round trip (:func:`~afmsmiler.modes.frequency_shift_curve`).
    fig : matplotlib.figure.Figure, optional
        Where to draw; default a new Figure 8 x 6.5 in.

    Attributes
    ----------
    fig : matplotlib.figure.Figure
    axes : dict
        ``"shift"``, ``"force"`` -> Axes.
    lines : dict
        ``"giessibl"``, ``"gradient"``, ``"input"``, ``"recovered"`` -> Line2D.
    """

    def __init__(self, curve: FrequencyShiftCurve, fig: Figure | None = None):
        self.fig = (check_instance("fig", fig, Figure) if fig is not None
                    else Figure(figsize=(8.0, 6.5)))
        self.fig.set_layout_engine("constrained")
        a1, a2 = self.fig.subplots(2, 1, sharex=True)
        self.axes = dict(shift=a1, force=a2)
        self.lines = {}
        self.lines["giessibl"], = a1.plot([], [], color=_COLORS["giessibl"], lw=1.8,
                                          label="df at amplitude A (Giessibl)")
        self.lines["gradient"], = a1.plot([], [], color=_COLORS["gradient"], ls="--",
                                          label="-f0 / (2k) dF/dz (A -> 0)")
        self.lines["input"], = a2.plot([], [], color=_COLORS["input"], lw=1.8,
                                       label="force put in")
        self.lines["recovered"], = a2.plot([], [], color=_COLORS["recovered"], ls="--",
                                           lw=1.8, label="recovered (Sader-Jarvis)")
        for ax in (a1, a2):
            ax.axhline(0.0, color="0.6", lw=0.8)
            ax.legend(loc="lower right", fontsize="small")
        a1.set_ylabel(f"frequency shift df [{UNITS_SHOWN['frequency']}]")
        a2.set_ylabel(f"tip-sample force [{UNITS_SHOWN['force']}]")
        # distances on a log axis: the force and df change over the first nanometre, which a
        # linear axis to 12 nm squeezed into its first twelfth
        a2.set_xscale("log")
        a2.set_xlabel(f"closest distance z [{UNITS_SHOWN['distance']}] (log scale)")
        self._reset = True
        self.update(curve)

    def update(self, curve: FrequencyShiftCurve) -> None:
        """Show a new round trip (artists updated in place).

        Parameters
        ----------
        curve : FrequencyShiftCurve
            The round trip.
        """
        check_instance("curve", curve, FrequencyShiftCurve)
        z = curve.z * _NM
        self.lines["giessibl"].set_data(z, curve.frequency_shift)
        self.lines["gradient"].set_data(z, curve.gradient_shift)
        self.lines["input"].set_data(z, curve.force * _NN)
        self.lines["recovered"].set_data(z, curve.recovered_force * _NN)
        self.axes["shift"].set_xlim(float(z[0]), float(z[-1]))
        # the small-amplitude shift can be far larger than df at a large A: frame the measured df
        lo, hi = data_range(curve.frequency_shift, 0.0)
        hold(self.axes["shift"], "y", lo, hi, reset=self._reset, floor=1e-3)
        lo, hi = data_range(curve.force * _NN, curve.recovered_force * _NN, 0.0)
        hold(self.axes["force"], "y", lo, hi, reset=self._reset, floor=1e-3)
        peak = float(np.max(np.abs(curve.force)))
        worst = float(np.max(np.abs(curve.error))) / peak if peak > 0 else 0.0
        self.axes["shift"].set_title(
            f"A = {curve.amplitude * _NM:.3g} nm, k = {curve.spring_constant:.3g} N/m, "
            f"f0 = {curve.resonance_frequency * _KHZ:.4g} kHz")
        self.axes["force"].set_title(f"Sader-Jarvis inversion: largest error "
                                     f"{100 * worst:.2g} % of the peak force")
        self._reset = False


def _extent(shape, dx, dy, k):
    """Pixel-edge extent (left, right, bottom, top) of an image, positions times ``k``."""
    rows, cols = shape
    return (-0.5 * dx * k, (cols - 0.5) * dx * k, -0.5 * dy * k, (rows - 0.5) * dy * k)


def _set_image(im, ax, values, extent, lu, frame=None):
    """Show ``values`` in ``im`` over ``extent``, the axes' limits ``frame`` (default the
    extent), the colour limits the data's range; the extent and the frame are set only when
    they change (a map moved in place skips matplotlib's relayout, ~0.4 ms per map)."""
    im.set_data(values)  # matplotlib masks the non-finite values (cbook.safe_masked_invalid)
    frame = extent if frame is None else frame
    labels = f"x [{lu}]", f"y [{lu}]"
    if tuple(im.get_extent()) != tuple(extent):
        if ax.get_autoscalex_on() or ax.get_autoscaley_on():
            im.set_extent(extent)
        else:  # the frame is set below: set_extent would only grow the unused data limits
            im._extent = tuple(extent)
            im.stale = True
    if not (ax.get_xlim() == tuple(frame[:2]) and ax.get_ylim() == tuple(frame[2:])
            and (ax.get_xlabel(), ax.get_ylabel()) == labels):
        ax.set(xlim=frame[:2], ylim=frame[2:], xlabel=labels[0], ylabel=labels[1])
    lo, hi = data_range(values)
    if not math.isfinite(lo):
        lo, hi = 0.0, 1.0
    elif hi - lo <= 1e-12 * max(abs(lo), abs(hi), 1e-30):
        pad = max(abs(lo) * 1e-3, 1e-3)
        lo, hi = lo - pad, hi + pad
    set_clim(im, lo, hi)


class JumpingFigure:
    """A jumping-mode pixel's force curve, against Z_np and time; the image and a profile.

    Parameters
    ----------
    curve : JumpCurve
        One pixel's curve (:func:`~afmsmiler.modes.jumping.jump_curve`).
    result : ScanResult
        The image (:class:`~afmsmiler.modes.jumping.JumpingMode` through module (f)'s scanner):
        its ``images`` (``"height trace"``, ``"height retrace"`` in m), ``pixel_size``,
        ``pixel_size_y``, ``lines_done`` and ``crashed``.
    fig : matplotlib.figure.Figure, optional
        Where to draw; default a new Figure 9.5 x 7 in.

    Attributes
    ----------
    fig : matplotlib.figure.Figure
    axes : dict
        ``"curve"``, ``"time"``, ``"image"``, ``"profile"`` -> Axes.
    lines : dict
        ``"approach"``, ``"retract"`` (against Z_np), ``"approach time"``, ``"retract time"``,
        ``"trigger"``, ``"trace"``, ``"retrace"``, ``"row"`` -> Line2D.
    images : dict
        ``"height"`` -> AxesImage.
    """

    def __init__(self, curve: JumpCurve, result, fig: Figure | None = None):
        check_instance("result", result, ScanResult)
        self.fig = (check_instance("fig", fig, Figure) if fig is not None
                    else Figure(figsize=(9.5, 7.0)))
        self.fig.set_layout_engine("constrained")
        grid = self.fig.add_gridspec(2, 2)
        ax = self.axes = dict(curve=self.fig.add_subplot(grid[0, 0]),
                              time=self.fig.add_subplot(grid[0, 1]),
                              image=self.fig.add_subplot(grid[1, 0]),
                              profile=self.fig.add_subplot(grid[1, 1]))
        self.lines = {}
        for key, where, color in (("approach", "curve", "C0"), ("retract", "curve", "C3"),
                                  ("approach time", "time", "C0"),
                                  ("retract time", "time", "C3")):
            self.lines[key], = ax[where].plot([], [], color=color,
                                              label=key.replace(" time", ""))
        self.lines["trigger"] = ax["curve"].axhline(0.0, color="C2", ls="--", lw=1.0,
                                                    label="trigger")
        for a in (ax["curve"], ax["time"]):
            a.axhline(0.0, color="0.6", lw=0.8)
        ax["curve"].legend(loc="upper left", fontsize="small")
        f, nm, ms = UNITS_SHOWN["force"], UNITS_SHOWN["distance"], UNITS_SHOWN["time"]
        ax["curve"].set(xlabel=f"positioner Z_np [{nm}]", ylabel=f"force [{f}]")
        ax["time"].set(xlabel=f"time [{ms}]", ylabel=f"force [{f}]")
        self.images = {"height": ax["image"].imshow(np.zeros((2, 2)), origin="lower",
                                                    cmap="afmhot", interpolation="nearest",
                                                    extent=(0, 1, 0, 1))}
        self.colorbar = self.fig.colorbar(self.images["height"], ax=ax["image"], shrink=0.9,
                                          label=f"height [{UNITS_SHOWN['height']}]")
        self.lines["row"], = ax["image"].plot([], [], color="C2", lw=1.0)
        self.lines["trace"], = ax["profile"].plot([], [], color="C0", label="trace")
        self.lines["retrace"], = ax["profile"].plot([], [], color="C3", ls="--",
                                                    label="retrace")
        ax["profile"].legend(loc="upper right", fontsize="small")
        self._reset = True
        self.update(curve, result)

    def update(self, curve: JumpCurve, result) -> None:
        """Show a new curve and image (artists updated in place).

        Parameters
        ----------
        curve : JumpCurve
            One pixel's curve.
        result : ScanResult
            The image.
        """
        check_instance("curve", curve, JumpCurve)
        ax = self.axes
        self.lines["approach"].set_data(curve.approach_z_np * _NM, curve.approach_force * _NN)
        self.lines["retract"].set_data(curve.retract_z_np * _NM, curve.retract_force * _NN)
        self.lines["approach time"].set_data(curve.approach_time * _MS,
                                             curve.approach_force * _NN)
        self.lines["retract time"].set_data(curve.retract_time * _MS, curve.retract_force * _NN)
        self.lines["trigger"].set_ydata([curve.trigger_force * _NN] * 2)
        forces = (curve.approach_force * _NN, curve.retract_force * _NN, 0.0)
        lo, hi = data_range(*forces)
        ax["curve"].set_xlim(float(curve.approach_z_np[0] * _NM),
                             float(curve.approach_z_np[-1] * _NM))
        ax["time"].set_xlim(0.0, float(curve.retract_time.max() * _MS))
        for key in ("curve", "time"):
            hold(ax[key], "y", lo, hi, reset=self._reset, floor=1e-3)
        ax["curve"].set_title(f"one pixel: trigger {curve.trigger_force * _NN:.3g} nN, "
                              f"pull-off {curve.pull_off_force * _NN:.3g} nN")
        ax["time"].set_title(f"approach and retract: {curve.cycle_time * _MS:.3g} ms per pixel")
        heights = np.asarray(result.images["height trace"], dtype=float)
        dx = float(result.pixel_size)
        dy = float(result.pixel_size_y or dx)
        extent = _extent(heights.shape, dx, dy, _NM)
        _set_image(self.images["height"], ax["image"], heights * _NM, extent, "nm")
        crashed = getattr(result, "crashed", None)
        # lines counted from 1, as module (f)'s figure counts them
        ax["image"].set_title("height (trace)" + ("" if crashed is None else
                                                  f": crashed on line {crashed.row + 1}"))
        done = int(result.lines_done)
        row = max(min(done, heights.shape[0]) - 1, 0) if crashed is None else crashed.row
        row = min(row, heights.shape[0] // 2) if crashed is None else row
        y = row * dy * _NM
        self.lines["row"].set_data(list(extent[:2]), [y, y])
        x = np.arange(heights.shape[1]) * dx * _NM
        trace = heights[row] * _NM
        retrace = np.asarray(result.images["height retrace"], dtype=float)[row] * _NM
        self.lines["trace"].set_data(x, trace)
        self.lines["retrace"].set_data(x, retrace)
        ax["profile"].set_xlim(extent[0], extent[1])
        lo, hi = data_range(trace, retrace)
        if math.isfinite(lo):
            hold(ax["profile"], "y", lo, hi, reset=self._reset, floor=1e-3)
        ax["profile"].set(xlabel=f"x [{UNITS_SHOWN['position']}]",
                          ylabel=f"height [{UNITS_SHOWN['height']}]",
                          title=f"line {row + 1}: trace and retrace")
        self._reset = False


class ForceVolumeFigure:
    """The four maps of a force-volume measurement and each material's force curve.

    Parameters
    ----------
    volume : ForceVolume
        The maps (:func:`~afmsmiler.modes.force_volume.force_volume`).
    names : sequence of str, optional
        The materials' names, for the curves' legend.
    fig : matplotlib.figure.Figure, optional
        Where to draw; default a new Figure 10 x 6.5 in.
    status : str
        What the maps are, shown over them (a coarse map's note); empty for a full map.

    Attributes
    ----------
    fig : matplotlib.figure.Figure
    axes : dict
        ``"modulus"``, ``"adhesion"``, ``"deformation"``, ``"dissipation"``, ``"curves"`` ->
        Axes.
    images : dict
        The four maps' AxesImage.
    lines : dict
        ``("approach", i)``, ``("retract", i)`` -> Line2D of material i's noise-free curves;
        ``("measured approach", i)``, ``("measured retract", i)`` -> one pixel's as measured.
    """

    MAPS = read_only({"modulus": ("Pa", "MPa", "viridis"), "adhesion": ("N", "nN", "magma"),
                      "deformation": ("m", "nm", "cividis"),
                      "dissipation": ("J", "zJ", "inferno")})

    def __init__(self, volume: ForceVolume, names=None, fig: Figure | None = None,
                 status: str = ""):
        check_instance("volume", volume, ForceVolume)
        n = volume.approach.shape[0]
        if names is not None:
            if not isinstance(names, (list, tuple)) or not all(isinstance(s, str) for s in names):
                raise TypeError(f"names must be a list of str, one per material, got "
                                f"{type(names).__name__} {names!r:.60}")
            if len(names) != n:
                raise ValueError(f"names must name the {n} materials, got {len(names)}")
        self.fig = (check_instance("fig", fig, Figure) if fig is not None
                    else Figure(figsize=(10.0, 6.5)))
        self.fig.set_layout_engine("constrained")
        grid = self.fig.add_gridspec(2, 3)
        self.axes = {"modulus": self.fig.add_subplot(grid[0, 0]),
                     "adhesion": self.fig.add_subplot(grid[0, 1]),
                     "deformation": self.fig.add_subplot(grid[1, 0]),
                     "dissipation": self.fig.add_subplot(grid[1, 1]),
                     "curves": self.fig.add_subplot(grid[:, 2])}
        self.images, self.colorbars = {}, {}
        for key, (_, shown_unit, cmap) in self.MAPS.items():
            im = self.axes[key].imshow(np.zeros((2, 2)), origin="lower", cmap=cmap,
                                       interpolation="nearest", extent=(0, 1, 0, 1))
            self.images[key] = im
            self.colorbars[key] = self.fig.colorbar(im, ax=self.axes[key], shrink=0.9,
                                                    label=f"{key} [{shown_unit}]")
            self.axes[key].set_title(f"{key} map")
        n = volume.approach.shape[0]
        names = [f"material {i}" for i in range(n)] if names is None else list(names)
        if len(names) != n:
            raise ValueError(f"names must name the {n} materials, got {len(names)}")
        self.lines = {}
        c = self.axes["curves"]
        # one pixel's curves as measured, noise and all (pale, under): the noise-free model
        # curves alone stayed smooth at 500 pN of noise while the maps scattered
        for i in range(n):
            for way in ("approach", "retract"):
                self.lines[f"measured {way}", i], = c.plot([], [], color=f"C{i}", lw=0.8,
                                                           alpha=0.35)
        for i in range(n):
            self.lines["approach", i], = c.plot([], [], color=f"C{i}", label=f"{names[i]}")
            self.lines["retract", i], = c.plot([], [], color=f"C{i}", ls="--")
        c.axhline(0.0, color="0.6", lw=0.8)
        c.set(xlabel=f"positioner Z_np [{UNITS_SHOWN['distance']}]",
              ylabel=f"force [{UNITS_SHOWN['force']}]",
              title="curves (dashed: retract;\npale: one pixel as measured)")
        c.legend(loc="upper left", fontsize="small")
        self._reset = True
        self._field = self._frame = None  # the maps' field (m) and their axes' frame (nm)
        self.update(volume, status)

    def update(self, volume: ForceVolume, status: str = "") -> None:
        """Show new maps and curves (artists updated in place).

        Parameters
        ----------
        volume : ForceVolume
            The maps.
        status : str
            What the maps are, shown over them (a coarse map's note); empty for a full map.
        """
        check_instance("volume", volume, ForceVolume)
        check_instance("status", status, str)
        self.fig.suptitle(status, fontsize="medium", color="#b00020")
        dx = float(volume.pixel_size)
        rows, cols = volume.modulus.shape
        extent = _extent((rows, cols), dx, dx, _NM)
        # a map of the field shown (a coarse map, stride s: s times fewer pixels, each s times
        # as large, centred on every s-th of the full map's) keeps the axes' frame: no
        # relayout between a coarse and a full map (~1.5 ms a move); another field is framed
        field = (cols * dx, rows * dx)
        if self._field is None or not np.allclose(field, self._field, rtol=1e-9, atol=0.0):
            self._field, self._frame = field, extent
        for key, (unit, shown_unit, _) in self.MAPS.items():
            values = np.asarray(getattr(volume, key), dtype=float) * unit_scale(shown_unit,
                                                                                 unit)
            _set_image(self.images[key], self.axes[key], values, extent, "nm",
                       frame=self._frame)
        n = volume.approach.shape[0]
        measured = volume.measured_approach, volume.measured_retract
        for i in range(n):
            z = volume.z_np[i] * _NM
            self.lines["approach", i].set_data(z, volume.approach[i] * _NN)
            self.lines["retract", i].set_data(z[::-1], volume.retract[i] * _NN)
            if measured[0] is not None:
                self.lines["measured approach", i].set_data(z, measured[0][i] * _NN)
                self.lines["measured retract", i].set_data(z[::-1], measured[1][i] * _NN)
        # the loop area of noisy curves scatters about its value, below zero where it is small:
        # say so, with the scatter the model gives the noise alone
        title = "dissipation map"
        noise = volume.dissipation_noise
        if noise is not None and np.nanmin(volume.dissipation) < 0:
            title += (f"\n< 0: noise (it alone scatters the loop area by "
                      f"{float(np.max(noise)) * _ZJ:.3g} zJ RMS)")
        self.axes["dissipation"].set_title(title)
        c = self.axes["curves"]
        c.set_xlim(float(volume.z_np.min() * _NM), float(volume.z_np.max() * _NM))
        lo, hi = data_range(volume.approach * _NN, volume.retract * _NN, 0.0,
                            *(() if measured[0] is None else (measured[0] * _NN,
                                                              measured[1] * _NN)))
        hold(c, "y", lo, hi, reset=self._reset, floor=1e-3)
        self._reset = False
