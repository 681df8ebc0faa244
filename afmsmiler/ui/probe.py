"""Module (a)'s "your probe" panel: a vendor's lever or your own, in air and water, calibrated.

:class:`ProbePanel` has a drop-down of the vendor presets (:data:`afmsmiler.planform.PRESETS`)
and ``"custom"``, the geometry of a custom lever (planform, material, length, width, thickness,
point length, arm width: sliders made from the models' :class:`~afmsmiler.parameters.Parameter`
descriptions), the fluid the thermal spectrum is recorded in and the laser spot's position.
Choosing a preset moves the geometry controls to its nominal values; moving one of them makes
the lever custom (a preset's coating and tip height are then left out). One move is one
:meth:`ProbePanel.update`: the model (:func:`afmsmiler.probe.probe_report`) runs once and its
result goes to the figure (:class:`~afmsmiler.plots.probe.ProbeFigure`) and the readouts, which
compute nothing. The thermal spectrum has 2^14 bins of 16 averages (the model's default for the
panel; exercise 5 records 2^18 bins of 64), so that a step takes milliseconds.
"""
from __future__ import annotations

import html
import math

import ipywidgets as widgets

from ..cantilever import LENGTH, THICKNESS, WIDTH
from ..modes.lateral import LATERAL_FORCE, LateralLever
from ..materials import MATERIALS
from ..parameters import read_only, shown
from ..planform import ARM_WIDTH, PLANFORMS, POINT_LENGTH, PRESETS, Lever, preset
from ..plots.probe import ProbeFigure, probe_curves
from ..probe import DEFAULTS as MODEL
from ..probe import FLUID_NAMES, SPOT, ProbeReport, probe_report
from ..validation import check_choice, check_integer
from .panel import Panel, initial_values

__all__ = ["ProbePanel", "DEFAULTS", "SLIDERS", "GEOMETRY", "SHAPE", "CUSTOM"]

#: The drop-down's entry for a lever described by the sliders.
CUSTOM = "custom"
#: Width of the lever at the clamp: module (a)'s width, its slider reaching the V-shaped presets'
#: 195 um.
PROBE_WIDTH = WIDTH.with_(slider_high=250e-6)
#: The panel's sliders, by control name.
SLIDERS = read_only({"length": LENGTH, "width": PROBE_WIDTH, "thickness": THICKNESS,
                     "point_length": POINT_LENGTH, "arm_width": ARM_WIDTH, "spot": SPOT,
                     "lateral_force": LATERAL_FORCE})
#: The controls that describe a custom lever (moving one makes the lever custom).
GEOMETRY = ("planform", "material", "length", "width", "thickness", "point_length", "arm_width")
#: The sliders that shape one planform only: slider -> the planform it shapes (disabled for the
#: others).
SHAPE = read_only({"point_length": "pointed", "arm_width": "v_shaped"})
#: Initial control values in the units shown: BudgetSensors' ContAl-G (450 x 50 x 2 um of
#: silicon, module (a)'s default lever) in air, the spot at the free end.
DEFAULTS = read_only({"probe": "ContAl-G", "planform": "rectangular", "material": "silicon",
                      **{n: p.to_display(p.default) for n, p in SLIDERS.items()},
                      "fluid": "air"})
_READOUT = read_only(dict(spring_constant="N/m", frequency="kHz"))
#: rad: the largest twist the readout gives without a warning (linear torsion, sin phi ~ phi to
#: 0.2 %).
SMALL_TWIST = 0.1
_FIGSIZE = (10.0, 3.6)


def _preset_values(name: str) -> dict:
    """The geometry controls' values (units shown) of preset ``name``."""
    p = PRESETS[name]
    return {"planform": p.planform, "material": p.material,
            "length": LENGTH.to_display(p.length), "width": PROBE_WIDTH.to_display(p.width),
            "thickness": THICKNESS.to_display(p.thickness),
            "point_length": POINT_LENGTH.to_display(p.point_length or POINT_LENGTH.default),
            "arm_width": ARM_WIDTH.to_display(p.arm_width or ARM_WIDTH.default)}


class ProbePanel(Panel):
    """A vendor's probe or a custom lever: k, f0 and Q in air and water, calibrated two ways.

    Controls (units as shown): ``probe`` (a key of :data:`afmsmiler.planform.PRESETS` or
    ``"custom"``), ``planform``, ``material`` (a key of :data:`afmsmiler.materials.MATERIALS`),
    ``length``, ``width`` (at the clamp), ``thickness``, ``point_length`` (a pointed lever's
    end) and ``arm_width`` (a V's arms) in um, ``fluid`` (``"air"`` or ``"water"``: where the
    thermal spectrum is recorded) and ``spot`` (where the laser spot really sits, x/L; the
    calibration assumes the free end).

    Parameters
    ----------
    seed : int
        Seed of the spectrum's noise, 0 to 2**32 - 1 (the same for every update, so that a move
        changes only what it moves).
    **initial
        Initial control values in the units shown (keys of :data:`DEFAULTS`); with a preset,
        the geometry is the preset's (give geometry with ``probe="custom"``).

    Attributes
    ----------
    last : ProbeReport
        The last model run.
    readout : ipywidgets.HTML
        k, f0 and Q in air and water; the thermal and Sader spring constants against the true
        k, and why they differ.
    """

    SLIDERS = SLIDERS
    DEFAULTS = DEFAULTS

    def __init__(self, *, seed: int = MODEL["seed"], scene: bool = False, vis=None, **initial):
        self.seed = check_integer("seed", seed, 0, 2 ** 32 - 1)
        v = initial_values(initial, DEFAULTS)
        check_choice("probe", v["probe"], [CUSTOM, *PRESETS])
        if v["probe"] != CUSTOM:
            given = sorted(set(initial) & set(GEOMETRY))
            if given:
                raise ValueError(f"probe must be {CUSTOM!r} when the geometry {given} is given "
                                 f"(a preset has its own), got {v['probe']!r}")
            v.update(_preset_values(v["probe"]))
        check_choice("planform", v["planform"], PLANFORMS)
        check_choice("material", v["material"], list(MATERIALS))
        check_choice("fluid", v["fluid"], FLUID_NAMES)
        sliders = self.declared_controls({k: v[k] for k in SLIDERS})
        self.controls = {
            "probe": widgets.Dropdown(options=[CUSTOM, *PRESETS], value=v["probe"],
                                      description="probe"),
            "planform": widgets.Dropdown(options=list(PLANFORMS), value=v["planform"],
                                         description="planform"),
            "material": widgets.Dropdown(options=[(m.name, k) for k, m in MATERIALS.items()],
                                         value=v["material"], description="material"),
            **{k: sliders[k] for k in ("length", "width", "thickness", "point_length",
                                       "arm_width")},
            "fluid": widgets.Dropdown(options=list(FLUID_NAMES), value=v["fluid"],
                                      description="fluid"),
            "spot": sliders["spot"],
            "lateral_force": sliders["lateral_force"],
        }
        self.readout = widgets.HTML()
        self.fig = self.new_figure(figsize=_FIGSIZE)
        self._custom = (None, None)   # (geometry, Lever) of the last custom lever
        # registered before Panel's observers, so that one choice is one update
        self.controls["probe"].observe(self._on_probe, names="value")
        for name in GEOMETRY:
            self.controls[name].observe(self._on_geometry, names="value")
        self.controls["planform"].observe(self._enable_shape, names="value")
        self._enable_shape()
        self.scene = None
        self.twist = 0.0
        super().__init__(scene=scene, vis=vis)

    def _enable_shape(self, change=None) -> None:
        """Enable the sliders that shape the chosen planform only (a rectangle has no point
        length and no arms): a slider that would change nothing cannot be moved. Their values
        are kept."""
        planform = self.controls["planform"].value
        for name, used_by in SHAPE.items():
            self.controls[name].disabled = planform != used_by

    # -- the preset and the custom geometry ------------------------------------------------
    def _on_probe(self, change) -> None:
        """A preset was chosen: move the geometry controls to its values, without an update of
        their own (the drop-down's own change runs the one update)."""
        if change["new"] == CUSTOM:
            return
        self.sync_controls(_preset_values(change["new"]))

    def _on_geometry(self, change) -> None:
        """A geometry control moved: the lever is now custom (no update of its own).

        The browser's echo of a value it snapped to a slider's grid (a preset's 195.14 um width)
        is no move (:meth:`Panel.values` reports the value the model ran with) and leaves the
        preset chosen.
        """
        if self.controls["probe"].value == CUSTOM or self.is_echo(change):
            return
        self.sync_controls({"probe": CUSTOM})

    def set(self, **values) -> None:
        """Set control values as a user would, in one update (see :meth:`Panel.set`).

        A preset is applied first; geometry given with it then makes the lever custom, starting
        from the preset's geometry.

        Parameters
        ----------
        **values
            Control names and values, in the units shown.
        """
        self.check_values(values)
        super().set(**self.choice_first(values, ("probe",), GEOMETRY, CUSTOM))

    def _lever(self, probe, planform, material, length, width, thickness, point_length,
               arm_width) -> Lever:
        """The preset's lever, or the custom one (kept while its geometry does not change)."""
        if probe != CUSTOM:
            return _preset_lever(probe)
        key = (planform, material, length, width, thickness, point_length, arm_width)
        if self._custom[0] != key:
            if planform == "rectangular":
                lever = Lever.rectangular(material, length, width, thickness)
            elif planform == "pointed":
                lever = Lever.pointed(material, length, width, thickness, point_length)
            else:
                lever = Lever.v_shaped(material, length, arm_width, width, thickness)
            self._custom = (key, lever)
        return self._custom[1]

    # -- the callback ---------------------------------------------------------------------
    def update(self, *, probe, planform, material, length, width, thickness, point_length,
               arm_width, fluid, spot, lateral_force) -> None:
        """Run the model once for these control values (sliders in SI) and draw the result.

        Parameters
        ----------
        probe : str
            A preset's name or ``"custom"``.
        planform, material : str
            The custom lever's planform and material.
        length, width, thickness, point_length, arm_width : float
            The custom lever's dimensions in m (a preset has its own).
        fluid : str
            ``"air"`` or ``"water"``.
        spot : float
            The laser spot's position x/L.
        lateral_force : float
            The friction force at the tip's apex in N: it twists the lever (the 3D view; a move
            of it alone runs no report again).
        """
        lever = self._lever(probe, planform, material, length, width, thickness, point_length,
                            arm_width)
        last = self.last
        if last is None or (last.lever, last.fluid, last.spot) != (lever, fluid, spot):
            report = self.run_model(probe_report, lever, fluid, spot=spot, seed=self.seed)
            self.last = report
            self.draw(ProbeFigure, probe_curves(report))
        lateral = LateralLever(lever)
        self.twist = lateral.twist(lateral_force)
        if self._want_scene:
            if self.scene is None:
                from ..scenes.probe import ProbeScene
                self.scene = ProbeScene(lever, self.twist, vis=self.scene_root())
            else:
                self.scene.update(lever, self.twist)
        self.readout.value = _readout_html(self.last, lateral, lateral_force, self.twist,
                                           self.scene)

    @property
    def report(self) -> ProbeReport:
        """The last model run (the same as :attr:`last`)."""
        return self.last

    def widget(self) -> widgets.Widget:
        """Controls with the readouts beside them, the figure below."""
        figure = super().widget().children[1]
        self.readout.layout.margin = "0 0 0 16px"
        self.readout.layout.width = "520px"
        top = widgets.HBox([widgets.VBox(list(self.controls.values())), self.readout])
        return widgets.VBox([top, figure])


_PRESET_LEVERS = {}


def _preset_lever(name: str) -> Lever:
    """The preset's Lever, made once (its frame model solved once per kernel)."""
    if name not in _PRESET_LEVERS:
        _PRESET_LEVERS[name] = preset(name)
    return _PRESET_LEVERS[name]


def _percent(x: float) -> str:
    return f"{100 * x:+.1f} %" if math.isfinite(x) else "n/a"


def _readout_html(r: ProbeReport, lateral: LateralLever, force: float, twist: float,
                  scene=None) -> str:
    u = _READOUT
    k = u["spring_constant"]
    air, water = r.modes["air"], r.modes["water"]
    rows = [("", "<b>vacuum</b>", "<b>air</b>", "<b>water</b>"),
            ("f0", shown(r.vacuum_frequency, u["frequency"]),
             shown(air.resonance_frequency, u["frequency"]),
             shown(water.resonance_frequency, u["frequency"])),
            ("Q", "-", f"{air.quality_factor:.3g}", f"{water.quality_factor:.3g}")]
    table = "".join("<tr>" + "".join(f"<td style='padding:0 8px'>{c}</td>" for c in row)
                    + "</tr>" for row in rows)
    t = r.thermal
    cal = [("true k (the model)", f"{r.spring_constant:.4g} {k}", ""),
           ("thermal noise", f"{t.spring_constant:.4g} &plusmn; {t.uncertainty:.2g} {k}",
            _percent(r.thermal_error)),
           ("Sader (plan view, fitted f0 and Q)",
            f"{r.sader:.4g} {k}" if math.isfinite(r.sader) else "n/a", _percent(r.sader_error))]
    cal_rows = "".join(f"<tr><td>{a}</td><td style='text-align:right'><b>{b}</b></td>"
                       f"<td style='padding-left:8px'>{c}</td></tr>" for a, b, c in cal)
    why = "".join(f"<li>{html.escape(s)}</li>" for s in r.reasons())
    twist_rows = (f"<tr><td>torsional stiffness k_phi</td><td style='text-align:right'><b>"
                  f"{lateral.torsional_stiffness:.4g} N m/rad</b></td></tr>"
                  f"<tr><td>lateral k of the apex from twist, k_phi / (h_tip + t/2)^2</td>"
                  f"<td style='text-align:right'><b>{lateral.spring_constant:.4g} {k}</b>"
                  f"</td></tr><tr><td>twist at F_L = {shown(force, 'nN', '.3g')}</td>"
                  f"<td style='text-align:right'><b>{shown(twist, 'mrad', '.3g')}</b></td></tr>"
                  + ("" if abs(twist) <= SMALL_TWIST else
                     f"<tr><td colspan='2' style='color:#b00020'>beyond small twists: |phi| &gt; "
                     f"{SMALL_TWIST:g} rad, where the linear torsion of this model no longer "
                     "holds</td></tr>"))
    view = "" if scene is None else f"<div>3D view: {html.escape(scene.caption)}</div>"
    name = html.escape(r.lever.name or CUSTOM)
    return (f"<div><b>{name}</b> ({r.lever.planform}): k = {r.spring_constant:.4g} {k} at the "
            "tip</div>"
            f"<table>{table}</table>"
            f"<div style='margin-top:6px'>calibrated in {r.fluid}, spot at x/L = "
            f"{r.spot:.3g} (assumed {r.assumed_spot:g}):</div><table>{cal_rows}</table>"
            f"<div style='margin-top:6px'>why they differ:</div><ul style='margin:0'>{why}</ul>"
            f"<div style='margin-top:6px'>twisted by the friction force at its apex:</div>"
            f"<table>{twist_rows}</table>{view}")
