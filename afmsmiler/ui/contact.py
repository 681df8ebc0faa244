"""The widget panel of module (d): tip shape and parameters, lever, sample, Z_np and adhesion.

Every slider is built by :func:`afmsmiler.ui.controls.control` from a
:class:`~afmsmiler.parameters.Parameter` of the model layer: the tip parameters from the registry
:data:`afmsmiler.contact.TIPS`, k, E, nu, Z_np and w from :data:`afmsmiler.contact.PARAMETERS`
(labels, display units, ranges and defaults on the slider grid, so the browser's echo never
changes a value nobody chose). Only the current shape's sliders are shown.

:meth:`ContactPanel.update` takes the values in SI (the panel contract), builds one
:class:`~afmsmiler.contact.ContactSystem`, runs its approach-retract cycle over the Z_np ramp once
and its state at the current Z_np once, and hands both to the figure
(:class:`~afmsmiler.plots.contact.ContactFigure`) and the 3D scene
(:class:`~afmsmiler.scenes.contact.ContactScene`), which draw them and compute no physics.

Every slider lies inside the model's valid range; the Z_np slider's upper end is lowered for a
sphere so that it can never be indented past its radius, and its lower end reaches below the
snap-off with adhesion.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import ipywidgets as widgets
import numpy as np

from ..contact import (PARAMETERS, TIPS, ApproachRetract, ContactSystem, IndentationCurve, Tip,
                       make_tip)
from ..parameters import read_only, shown
from ..plots.contact import ContactCurves, ContactFigure, contact_curves
from ..validation import check_choice
from .panel import Panel, _decimal, initial_values, slider

__all__ = ["ContactPanel", "ContactState", "DEFAULTS", "TIP_CONTROLS", "SLIDERS"]

#: Tip-parameter controls generated from the registry: name -> Parameter (shared names once).
TIP_CONTROLS = read_only({p.name: p for cls in TIPS.values() for p in cls.parameters})

#: The other sliders: control name -> Parameter of the model layer.
SLIDERS = read_only({name: PARAMETERS[name] for name in
                     ("spring_constant", "youngs_modulus", "poisson_ratio", "z_np",
                      "work_of_adhesion")})

_ADHESION = read_only({"none": None, "DMT": "dmt", "JKR": "jkr"})

#: Initial control values in the units shown (a soft sample under a contact-mode lever).
DEFAULTS = read_only(dict(
    tip="parabolic", branch="approach", adhesion="none",
    **{name: p.to_display(p.default) for name, p in SLIDERS.items()}))

_RAMP_POINTS = 400


@dataclass(frozen=True)
class ContactState:
    """What the panel last computed (SI units), for tests and exercises.

    Attributes
    ----------
    system : ContactSystem
        The tip, lever, sample and adhesion the controls describe.
    cycle : ApproachRetract
        The approach-retract curves over the ramp.
    current : IndentationCurve
        The state at the current Z_np (one point, on the branch chosen).
    curves : ContactCurves
        What the figure shows (nm, nN).
    """

    system: ContactSystem
    cycle: ApproachRetract
    current: IndentationCurve
    curves: ContactCurves

    @property
    def tip(self) -> Tip:
        """The tip built from the controls."""
        return self.system.tip

    @property
    def spring_constant(self) -> float:
        """k in N/m."""
        return self.system.spring_constant

    @property
    def youngs_modulus(self) -> float:
        """E in Pa."""
        return self.system.youngs_modulus

    @property
    def poisson_ratio(self) -> float:
        """nu."""
        return self.system.poisson_ratio

    @property
    def adhesion(self) -> str | None:
        """The adhesion model used (None, "dmt", "jkr")."""
        return self.system.adhesion

    @property
    def work_of_adhesion(self) -> float:
        """w in J/m^2 (used only with adhesion)."""
        return self.system.work_of_adhesion


class ContactPanel(Panel):
    """Sliders for the tip (shape and its parameters), k, E, nu, Z_np and adhesion.

    Controls (units as shown, from the Parameters): ``tip`` (a key of
    :data:`~afmsmiler.contact.TIPS`), one slider per tip parameter of the registry (``radius``
    [nm], ``half_angle`` [deg], ``face_angle`` [deg]; only the current shape's are visible),
    ``spring_constant`` [N/m], ``youngs_modulus`` [MPa], ``poisson_ratio``, ``z_np`` [nm],
    ``branch`` ("approach" or "retract": which branch of the cycle the current point follows;
    they differ with adhesion, where on retract the tip stays stuck below Z_np = 0 down to the
    snap-off), ``adhesion`` ("none", "DMT", "JKR"; only for a paraboloid or a sphere) and
    ``work_of_adhesion`` [mJ/m^2].

    Parameters
    ----------
    scene : bool
        Draw the 3D view in its own widget, shown below the panel by
        :meth:`show` (over the kernel's connection; nothing to close).
    vis : meshcat.Visualizer, optional
        Where to draw instead (tests pass a recorder); implies ``scene``.
    **initial
        Initial control values (keys of :data:`DEFAULTS` or :data:`TIP_CONTROLS`), as shown.

    Raises
    ------
    TypeError
        For an unknown control name.
    ValueError
        For a value outside a slider's range or not among a drop-down's options, naming it.

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

    def __init__(self, scene: bool = False, vis=None, **initial):
        tip_defaults = {name: p.to_display(p.default) for name, p in TIP_CONTROLS.items()}
        v = initial_values(initial, {**DEFAULTS, **tip_defaults})
        check_choice("tip", v["tip"], tuple(TIPS))
        check_choice("branch", v["branch"], ("approach", "retract"))
        check_choice("adhesion", v["adhesion"], tuple(_ADHESION))
        options = [(cls.title, key) for key, cls in TIPS.items()]
        controls = dict(tip=widgets.Dropdown(options=options, value=v["tip"], description="tip"))
        for name, p in TIP_CONTROLS.items():
            controls[name] = slider(name, p, v[name])
        for name, p in SLIDERS.items():
            if name == "work_of_adhesion":
                controls["branch"] = widgets.ToggleButtons(
                    options=["approach", "retract"], value=v["branch"], description="branch")
                controls["adhesion"] = widgets.Dropdown(options=list(_ADHESION),
                                                        value=v["adhesion"],
                                                        description="adhesion")
            controls[name] = slider(name, p, v[name])
        self.controls = controls
        self.readout = widgets.HTML()
        self.figure = None
        self.scene = None
        self._note = ""
        self.fig = self.new_figure(figsize=(10.5, 4.6))
        super().__init__(scene=scene, vis=vis)

    # -- helpers --------------------------------------------------------------------------------
    def _show_tip_controls(self, key: str) -> None:
        names = {p.name for p in TIPS[key].parameters}
        for name in TIP_CONTROLS:
            self.controls[name].layout.display = None if name in names else "none"
        adhesive = TIPS[key].adhesive
        self.controls["adhesion"].disabled = not adhesive
        self.controls["work_of_adhesion"].disabled = not adhesive

    def _set_z_np_range(self, low: float, high: float, value: float, clipped: bool) -> None:
        """Move the Z_np slider's ends (nm) without triggering an update, and its value where the
        model moved it (``clipped``) or the new ends would.

        Otherwise the value is left alone: during a drag ipywidgets holds the moves made while
        one update is in flight and sends them merged, so the kernel's copy of the value lags the
        student's; setting it sent an older step back and the slider jumped back and forth.
        """
        z = self.controls["z_np"]
        hold, self._hold = self._hold, True
        try:  # ipywidgets clamps the value into the new range; keep min < max throughout
            moved = (z.min, z.max) != (low, high)
            if moved:
                if low < z.max:
                    z.min, z.max = low, high
                else:
                    z.max, z.min = high, low
            if (clipped or moved) and z.value != value:
                z.value = value
        finally:
            self._hold = hold

    def _z_np_range(self, system: ContactSystem) -> tuple[float, float]:
        """The Z_np slider's range as shown (nm, on its grid): below the snap-off, up to 90 % of
        the model's limit."""
        p = SLIDERS["z_np"]
        step = self.controls["z_np"].step
        low, high = system.ramp(p.slider_low, p.slider_high)  # the model's whole cycle
        # whole steps in the display unit (in SI, 200e-9 / 1e-9 is 199.99999999999997)
        n_low = math.floor(p.to_display(low) / step + 1e-9)
        n_high = max(math.floor(p.to_display(high) / step + 1e-9), n_low + 1)
        return n_low * step, n_high * step

    # -- the callback ------------------------------------------------------------------------------
    def update(self, tip, spring_constant, youngs_modulus, poisson_ratio, z_np, branch, adhesion,
               work_of_adhesion, **tip_parameters) -> None:
        """Run the model once for the ramp and once for the current Z_np with exactly these values.

        Parameters
        ----------
        tip : str
            A key of :data:`~afmsmiler.contact.TIPS`.
        spring_constant : float
            k in N/m.
        youngs_modulus : float
            E in Pa.
        poisson_ratio : float
            nu.
        z_np : float
            The current positioner displacement in m (clipped, with a note, to the range the
            model allows for this tip: a sphere's limit, the snap-off below).
        branch : {"approach", "retract"}
            Which branch the current point follows.
        adhesion : {"none", "DMT", "JKR"}
            Adhesion model (ignored for a cone or a pyramid).
        work_of_adhesion : float
            w in J/m^2.
        **tip_parameters
            Every tip slider's value in SI (m, rad); those of other shapes are ignored.

        Raises
        ------
        TypeError, ValueError
            For a missing or unknown control, an unknown tip, branch or adhesion model (naming
            the choices) or a value the model rejects, before any work (the panel contract).
        """
        self._show_tip_controls(tip)
        shape = make_tip(tip, **{p.name: tip_parameters[p.name] for p in TIPS[tip].parameters})
        model = _ADHESION[adhesion] if shape.adhesive else None
        system = ContactSystem(tip=shape, adhesion=model, spring_constant=spring_constant,
                               youngs_modulus=youngs_modulus, poisson_ratio=poisson_ratio,
                               work_of_adhesion=work_of_adhesion).for_ramp()
        self._note = ("" if system.adhesion == model else
                      "adhesion would pull this sphere in past its radius: shown without it")
        lo, hi = self._z_np_range(system)  # as shown, nm
        p_z = SLIDERS["z_np"]
        shown = _decimal(p_z.to_display(z_np))
        clipped = not lo <= shown <= hi
        if clipped:
            inside = min(max(shown, lo), hi)
            self._note += (f" Z_np {shown:g} nm is outside [{lo:g}, {hi:g}] nm for this tip: "
                           f"shown at {inside:g} nm.")
            shown = inside
        self._set_z_np_range(lo, hi, shown, clipped)
        cycle = self.run_model(system.approach_retract,
                               np.linspace(p_z.to_si(lo), p_z.to_si(hi), _RAMP_POINTS))
        current = system.at(p_z.to_si(shown) if clipped else z_np, branch)
        extent = max(4.0 * float(current.contact_radius[0]), 2.0 * abs(float(current.z_s[0])),
                     30e-9)
        curves = contact_curves(cycle, current, shape, extent)
        self.draw(ContactFigure, curves)  # the figure's frame leaves first: its pixels wait for nothing else
        if self._want_scene:
            if self.scene is None:
                from ..scenes.contact import ContactScene
                self.scene = ContactScene(shape, current, vis=self.scene_root())
            else:
                scene = self.scene
                self.after_frame(lambda: scene.update(shape, current))
        self.last = ContactState(system, cycle, current, curves)
        self.readout.value = self._readout_html()

    def _readout_html(self) -> str:
        s = self.last
        c = s.current
        rows = [("force F", shown(float(c.force[0]), "nN")),
                ("indentation Z_s", shown(float(c.z_s[0]), "nm")),
                ("lever deflection Z_c", shown(float(c.z_c[0]), "nm")),
                ("contact radius r", shown(float(c.contact_radius[0]), "nm")),
                ("reduced modulus E*", shown(s.system.reduced_modulus, "MPa"))]
        if s.adhesion:
            rows.append(("pull-off force", shown(s.cycle.pull_off_force, "nN")))
            rows.append(("snap-off at Z_np", shown(s.cycle.snap_off_z_np, "nm")))
        table = "".join(f"<tr><td>{k}</td><td style='text-align:right'><b>{v}</b></td></tr>"
                        for k, v in rows)
        note = f"<div><i>{self._note.strip()}</i></div>" if self._note else ""
        if self.scene is not None:
            note += f"<div>3D view: 1 unit = {shown(self.scene.unit, 'nm', 'g')}, true to scale</div>"
        return f"<table>{table}</table>{note}"

    def widget(self) -> widgets.Widget:
        """Controls and readouts on the left, the figure on the right."""
        box = super().widget()
        left = widgets.VBox(list(self.controls.values()) + [self.readout])
        return widgets.HBox([left, box.children[1]])
