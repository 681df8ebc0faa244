"""The widget panel of module (d): tip shape and parameters, lever, sample, Z_np and adhesion.

The tip-parameter sliders are generated from the registry :data:`afmsmiler.contact.TIPS` (their
labels, practical units, ranges and defaults come from each shape's
:class:`~afmsmiler.contact.TipParameter`), and only the current shape's sliders are shown.
:meth:`ContactPanel.update` converts the values to SI, runs
:func:`~afmsmiler.contact.approach_retract` over the Z_np ramp and at the current Z_np, and updates
the figure (:class:`~afmsmiler.plots.contact.ContactFigure`) and the 3D scene
(:class:`~afmsmiler.scenes.contact.ContactScene`) in place.

Every slider lies inside the model's valid range; the Z_np slider's upper end is lowered for a
sphere so that it can never be indented past its radius.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import ipywidgets as widgets
import numpy as np

from ..contact import (TIPS, ApproachRetract, IndentationCurve, Tip, approach_retract, make_tip,
                       reduced_modulus, z_np_limit)
from ..plots.contact import ContactCurves, ContactFigure, contact_curves
from .panel import Panel, log_slider, slider

__all__ = ["ContactPanel", "ContactState", "DEFAULTS", "BOUNDS", "TIP_CONTROLS"]

#: Initial control values in the units shown (a soft sample under a contact-mode lever).
DEFAULTS = dict(tip="parabolic", spring_constant=0.1, youngs_modulus=1.0, poisson_ratio=0.3,
                z_np=60.0, branch="approach", adhesion="none", work_of_adhesion=20.0)

#: Slider bounds (low, high) in the units shown; all inside the model's valid ranges.
BOUNDS = dict(spring_constant=(0.005, 100.0), youngs_modulus=(1e-3, 1e5), poisson_ratio=(0.0, 0.49),
              z_np=(-50.0, 200.0), work_of_adhesion=(1.0, 200.0))

#: Tip-parameter controls generated from the registry: name -> TipParameter (shared names once).
TIP_CONTROLS = {}
for _cls in TIPS.values():
    for _p in _cls.parameters:
        TIP_CONTROLS.setdefault(_p.name, _p)

_ADHESION = {"none": None, "DMT": "dmt", "JKR": "jkr"}
_RAMP_POINTS = 400
_SPHERE_MARGIN = 0.9  # the Z_np slider stops at 90 % of the depth at which the sphere is buried
_MIN_RANGE = 1e-9  # m: below this much room, adhesion is switched off for a sphere
_Z_NP_FLOOR = -2000.0  # nm: the Z_np slider never reaches lower (a very soft lever's snap-off)


@dataclass(frozen=True)
class ContactState:
    """What the panel last computed (SI units), for tests and exercises.

    Attributes
    ----------
    tip : Tip
        The tip built from the controls.
    spring_constant, youngs_modulus, poisson_ratio : float
        k [N/m], E [Pa], nu.
    adhesion : str or None
        The adhesion model used.
    work_of_adhesion : float
        w in J/m^2 (used only with adhesion).
    cycle : ApproachRetract
        The approach-retract curves over the ramp.
    current : IndentationCurve
        The state at the current Z_np (one point, on the branch chosen).
    curves : ContactCurves
        What the figure shows (nm, nN).
    """

    tip: Tip
    spring_constant: float
    youngs_modulus: float
    poisson_ratio: float
    adhesion: str | None
    work_of_adhesion: float
    cycle: ApproachRetract
    current: IndentationCurve
    curves: ContactCurves


def _tip_slider(p):
    d = p.display_scale
    lo, hi, v = p.slider_low / d, p.slider_high / d, p.default / d
    label = f"{p.label}"
    if p.log:
        return log_slider(label, v, lo, hi, unit=p.display_unit)
    return slider(label, v, lo, hi, unit=p.display_unit)


def _point(curve: IndentationCurve, i: int) -> IndentationCurve:
    return IndentationCurve(*(getattr(curve, f)[i:i + 1] for f in
                              ("z_np", "z_s", "z_c", "force", "contact_radius", "in_contact")))


class ContactPanel(Panel):
    """Sliders for the tip (shape and its parameters), k, E, nu, Z_np and adhesion.

    Controls (units as shown): ``tip`` (a key of :data:`~afmsmiler.contact.TIPS`), one slider per
    tip parameter of the registry (``radius`` [nm], ``half_angle`` [deg], ``face_angle`` [deg];
    only the current shape's are visible), ``spring_constant`` [N/m], ``youngs_modulus`` [MPa],
    ``poisson_ratio``, ``z_np`` [nm], ``branch`` ("approach" or "retract": which branch of the
    cycle the current point follows; they differ with adhesion, where on retract the tip stays
    stuck below Z_np = 0 down to the snap-off), ``adhesion`` ("none", "DMT", "JKR"; only for a
    paraboloid or a sphere) and ``work_of_adhesion`` [mJ/m^2].

    Parameters
    ----------
    scene : bool
        Draw the 3D view in the kernel's meshcat viewer (show it with
        ``get_viewer().jupyter_cell()``; close it with ``close_viewer()``).
    **initial
        Initial control values (keys of :data:`DEFAULTS` or :data:`TIP_CONTROLS`), as shown.

    Attributes
    ----------
    last : ContactState
        The last model result.
    figure : ContactFigure
        The force curve and the cross-section.
    scene : ContactScene or None
        The 3D view.
    readout : ipywidgets.HTML
        Current force, indentation, contact radius, pull-off force.
    """

    def __init__(self, scene: bool = False, **initial):
        valid = set(DEFAULTS) | set(TIP_CONTROLS)
        unknown = set(initial) - valid
        if unknown:
            raise TypeError(f"unknown control(s) {sorted(unknown)}; valid: {sorted(valid)}")
        v = {**DEFAULTS, **initial}
        b = BOUNDS
        options = [(cls.title, key) for key, cls in TIPS.items()]
        controls = dict(tip=widgets.Dropdown(options=options, value=v["tip"], description="tip"))
        for name, p in TIP_CONTROLS.items():
            controls[name] = _tip_slider(p)
            if name in initial:
                controls[name].value = initial[name]
        controls.update(
            spring_constant=log_slider("k", v["spring_constant"], *b["spring_constant"],
                                       unit="N/m"),
            youngs_modulus=log_slider("E", v["youngs_modulus"], *b["youngs_modulus"], unit="MPa"),
            poisson_ratio=slider("nu", v["poisson_ratio"], *b["poisson_ratio"], step=0.01),
            z_np=slider("Z_np", v["z_np"], *b["z_np"], step=0.5, unit="nm"),
            branch=widgets.ToggleButtons(options=["approach", "retract"], value=v["branch"],
                                         description="branch"),
            adhesion=widgets.Dropdown(options=list(_ADHESION), value=v["adhesion"],
                                      description="adhesion"),
            work_of_adhesion=slider("w", v["work_of_adhesion"], *b["work_of_adhesion"], step=1.0,
                                    unit="mJ/m^2"),
        )
        self.controls = controls
        self.readout = widgets.HTML()
        self.figure = None
        self.scene = None
        self._want_scene = bool(scene)
        self.fig = self.new_figure(figsize=(10.5, 4.2))
        super().__init__()

    # -- helpers --------------------------------------------------------------------------------
    def _show_tip_controls(self, key: str) -> None:
        names = {p.name for p in TIPS[key].parameters}
        for name in TIP_CONTROLS:
            self.controls[name].layout.display = None if name in names else "none"
        adhesive = key in ("parabolic", "spherical")
        self.controls["adhesion"].disabled = not adhesive
        self.controls["work_of_adhesion"].disabled = not adhesive

    def _set_z_np_range(self, low: float, high: float) -> None:
        """Move the Z_np slider's ends (nm) without triggering an update."""
        z = self.controls["z_np"]
        if (z.min, z.max) != (low, high):
            hold, self._hold = self._hold, True
            try:  # ipywidgets clamps the value into the new range; keep min < max throughout
                if low < z.max:
                    z.min, z.max = low, high
                else:
                    z.max, z.min = high, low
            finally:
                self._hold = hold

    # -- the callback ------------------------------------------------------------------------------
    def update(self, tip, spring_constant, youngs_modulus, poisson_ratio, z_np, branch, adhesion,
               work_of_adhesion, **tip_parameters) -> None:
        """Convert the control values to SI, run the model, update figure, scene and readouts."""
        self._show_tip_controls(tip)
        params = {p.name: tip_parameters[p.name] * p.display_scale for p in TIPS[tip].parameters}
        shape = make_tip(tip, **params)
        k = spring_constant
        e = youngs_modulus * 1e6
        nu = poisson_ratio
        model = _ADHESION[adhesion] if tip in ("parabolic", "spherical") else None
        w = work_of_adhesion * 1e-3
        self._note = ""
        # the model's own limit (finite for a sphere): the slider stops at 90 % of it
        limit = z_np_limit(k, shape, e, nu, adhesion=model, work_of_adhesion=w)
        if model and _SPHERE_MARGIN * limit < _MIN_RANGE:  # adhesion alone would bury the sphere
            self._note = "adhesion would pull this sphere in past its radius: shown without it"
            model = None
            limit = z_np_limit(k, shape, e, nu)
        kwargs = dict(adhesion=model, work_of_adhesion=w) if model else {}
        z_lo = BOUNDS["z_np"][0]  # nm
        if model:  # extend the ramp below the snap-off point so that the retract is complete
            probe = approach_retract(np.array([-1e-9, 0.0]), k, shape, e, nu, **kwargs)
            z_lo = min(z_lo, math.floor(1.25 * probe.snap_off_z_np * 1e9))
        # the slider reaches below the snap-off (so that the retract branch can let go), down to
        # _Z_NP_FLOOR, and stops at 90 % of the model's limit
        self._set_z_np_range(max(z_lo, _Z_NP_FLOOR),
                             min(BOUNDS["z_np"][1], _SPHERE_MARGIN * limit * 1e9))
        z_lo *= 1e-9
        z_now = self.controls["z_np"].value * 1e-9
        z_hi = self.controls["z_np"].max * 1e-9
        cycle = approach_retract(np.linspace(z_lo, z_hi, _RAMP_POINTS), k, shape, e, nu, **kwargs)
        here = approach_retract(np.array([z_now - 1e-9, z_now]), k, shape, e, nu, **kwargs)
        # the point at Z_np = z_now: last of the approach, first of the retract
        current = _point(here.retract, 0) if branch == "retract" else _point(here.approach, 1)
        extent = max(4.0 * float(current.contact_radius[0]), 2.0 * abs(float(current.z_s[0])),
                     30e-9)
        curves = contact_curves(cycle, current, shape, extent)
        if self.figure is None:
            self.figure = ContactFigure(curves, fig=self.fig)
        else:
            self.figure.update(curves)
        if self._want_scene and self.scene_open():  # not after close_viewer()
            if self.scene is None:
                from ..scenes.contact import ContactScene
                self.scene = ContactScene(shape, current)
            else:
                self.scene.update(shape, current)
        self.last = ContactState(shape, k, e, nu, model, w, cycle, current, curves)
        self.readout.value = self._readout_html()
        self.redraw()

    def _readout_html(self) -> str:
        s = self.last
        c = s.current
        rows = [("force F", f"{float(c.force[0]) * 1e9:.4g} nN"),
                ("indentation Z_s", f"{float(c.z_s[0]) * 1e9:.4g} nm"),
                ("lever deflection Z_c", f"{float(c.z_c[0]) * 1e9:.4g} nm"),
                ("contact radius r", f"{float(c.contact_radius[0]) * 1e9:.4g} nm"),
                ("reduced modulus E*",
                 f"{reduced_modulus(s.youngs_modulus, s.poisson_ratio) / 1e6:.4g} MPa")]
        if s.adhesion:
            rows.append(("pull-off force", f"{s.cycle.pull_off_force * 1e9:.4g} nN"))
            rows.append(("snap-off at Z_np", f"{s.cycle.snap_off_z_np * 1e9:.4g} nm"))
        table = "".join(f"<tr><td>{k}</td><td style='text-align:right'><b>{v}</b></td></tr>"
                        for k, v in rows)
        note = f"<div><i>{self._note}</i></div>" if self._note else ""
        if self.scene is not None:
            note += f"<div>3D view: 1 unit = {self.scene.unit * 1e9:g} nm, true to scale</div>"
        return f"<table>{table}</table>{note}"

    def widget(self) -> widgets.Widget:
        """Controls and readouts on the left, the figure on the right."""
        box = super().widget()
        left = widgets.VBox(list(self.controls.values()) + [self.readout])
        return widgets.HBox([left, box.children[1]])


del _cls, _p
