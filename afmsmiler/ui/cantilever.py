"""The widget panel of module (a): sliders for the lever and its load, four plots, the 3D view.

Every slider is built by :func:`~afmsmiler.ui.controls.control` from the model's own description
of its parameter (:data:`afmsmiler.cantilever.PARAMETERS`: SI unit, display unit nN, um, GPa,
kg/m^3, valid and slider ranges), so no slider position can make the model raise and no unit
factor is typed here. One user action is one :meth:`CantileverPanel.update`, which runs the model
once (:meth:`~afmsmiler.cantilever.Cantilever.bending`) and hands that result to the figure
(:class:`~afmsmiler.plots.cantilever.CantileverFigure`), the mode-shape figure
(:class:`~afmsmiler.plots.cantilever.ModeShapesFigure`, see :meth:`CantileverPanel.show_modes`)
and the meshcat scene (:class:`~afmsmiler.scenes.cantilever.CantileverScene`), which compute
nothing themselves.
"""
from __future__ import annotations

from dataclasses import dataclass

import ipywidgets as widgets
from IPython.display import display

from ..cantilever import FORCE, PARAMETERS, Bending, Cantilever
from ..materials import MATERIALS
from ..parameters import read_only, unit_scale
from ..plots.cantilever import DEFAULTS as PLOTS
from ..plots.cantilever import (CantileverCurves, CantileverFigure, ModeShapesFigure,
                                cantilever_curves)
from ..validation import check_choice
from .panel import Panel, initial_values, show_static, slider

__all__ = ["CantileverPanel", "CantileverState", "DEFAULTS", "SLIDERS"]

#: The sliders, in the order shown (the material drop-down comes after the thickness).
SLIDERS = ("force", "length", "width", "thickness", "youngs_modulus", "density", "section",
           "exaggeration")


#: Initial control values in the units shown, from the parameters' defaults (a contact-mode
#: silicon lever like BudgetSensors ContAl-G: 450 x 50 x 2 um, nominal k = 0.2 N/m, f0 = 13 kHz).
DEFAULTS = read_only({**{n: PARAMETERS[n].to_display(PARAMETERS[n].default)
                         for n in SLIDERS}, "material": "silicon"})

_N_MODES = 3
_N_THICKNESS = 9   # levels of the stress field through the thickness (odd: the neutral plane)
_N_SECTION = 41    # levels of the cross-section profile
_FIGSIZE = (10.0, 5.6)  # inches: with the controls above it, the panel fits one screen
#: Largest end slope |theta(L)| in rad (of the linear theory) for which the readout calls the
#: small-deflection beam theory good: F L^3 / (3 E J) then overestimates the tip deflection of the
#: end-loaded elastica by about 0.45 theta^2, 0.5 % at 0.1 rad but 10 % at 0.5 rad (checked
#: against the elastica solved numerically in tests/test_cantilever_ui.py).
SMALL_SLOPE = 0.1
#: Units of the readouts.
_READOUT = read_only(dict(spring_constant="N/m", frequency="kHz", deflection="nm", stress="MPa"))


@dataclass(frozen=True)
class CantileverState:
    """What the panel last computed (SI units), for tests and exercises.

    Attributes
    ----------
    lever : Cantilever
        The lever built from the sliders.
    force : float
        End force in N.
    bending : Bending
        The model's result, drawn by the figures and the scene.
    curves : CantileverCurves
        The plotted curves (in the units shown).
    spring_constant : float
        k in N/m.
    frequencies : tuple of float
        f1, f2, f3 in Hz.
    tip_deflection : float
        z(L) in m.
    max_stress : float
        Largest |sigma| in Pa (on a surface at the clamp).
    """

    lever: Cantilever
    force: float
    bending: Bending
    curves: CantileverCurves
    spring_constant: float
    frequencies: tuple
    tip_deflection: float
    max_stress: float


class CantileverPanel(Panel):
    """Sliders for F, L, w, h, material, E, rho, the cross-section and the exaggeration.

    Controls (units as shown): ``force`` [nN], ``length`` [um], ``width`` [um], ``thickness``
    [um], ``material`` (a key of :data:`afmsmiler.materials.MATERIALS`; choosing one sets E and
    rho), ``youngs_modulus`` [GPa], ``density`` [kg/m^3], ``section`` (cross-section position as
    a fraction x/L, so it can never leave the lever) and ``exaggeration`` (of the drawn
    deflection in the 3D view).

    Parameters
    ----------
    scene : bool
        Draw the 3D view in its own widget, shown below the panel by
        :meth:`show` (over the kernel's connection; nothing to close).
    vis : meshcat.Visualizer, optional
        Where to draw instead (tests pass a recorder); implies ``scene``.
    **initial
        Initial control values (keys of :data:`DEFAULTS`), in the units shown.

    Attributes
    ----------
    last : CantileverState
        The last model result.
    figure : CantileverFigure
        The four plots.
    modes_figure : ModeShapesFigure or None
        The mode shapes and frequencies, once :meth:`show_modes` drew them; they follow the
        sliders from then on.
    scene : CantileverScene or None
        The 3D view.
    readout : ipywidgets.HTML
        k [N/m], f1..f3 [kHz], tip deflection [nm] and max stress [MPa].
    caption : ipywidgets.HTML
        The 3D view's exaggeration and colour legend, under the readout (set with the view:
        during a drag once the figure painted, :meth:`~afmsmiler.ui.panel.Panel.after_frame`).
    """

    def __init__(self, scene: bool = False, vis=None, **initial):
        v = initial_values(initial, DEFAULTS)
        check_choice("material", v["material"], list(MATERIALS))
        if "material" in initial:  # a material sets E and rho unless they are given too
            m = MATERIALS[v["material"]]
            if "youngs_modulus" not in initial:
                v["youngs_modulus"] = PARAMETERS["youngs_modulus"].to_display(m.youngs_modulus)
            if "density" not in initial:
                v["density"] = PARAMETERS["density"].to_display(m.density)
        sliders = {name: slider(name, PARAMETERS[name], v[name]) for name in SLIDERS}
        self.controls = dict(
            force=sliders["force"], length=sliders["length"], width=sliders["width"],
            thickness=sliders["thickness"],
            material=widgets.Dropdown(options=[(m.name, key) for key, m in MATERIALS.items()],
                                      value=v["material"], description="material"),
            youngs_modulus=sliders["youngs_modulus"], density=sliders["density"],
            section=sliders["section"], exaggeration=sliders["exaggeration"],
        )
        self.readout = widgets.HTML()
        self.caption = widgets.HTML()
        self.figure = None
        self.modes_figure = None  # the mode shapes, once show_modes() drew them
        self.modes_fig = None
        self.modes_live = None  # the mode shapes drawn in the browser
        self.scene = None
        self.fig = self.new_figure(figsize=_FIGSIZE)
        # registered before Panel's own observer, so one material change gives one update
        self.controls["material"].observe(self._on_material, names="value")
        super().__init__(scene=scene, vis=vis)

    def set(self, **values) -> None:
        """Set control values as a user would, in one update (see :meth:`Panel.set`).

        A material is applied first, so that E or rho given in the same call win over its preset
        whatever the order of the keywords.

        Parameters
        ----------
        **values
            Control names and values, in the units shown.
        """
        if "material" in values:
            values = {"material": values.pop("material"), **values}
        super().set(**values)

    def _on_material(self, change) -> None:
        """A material was chosen: move E and rho to its values without an update of their own
        (the drop-down's own change then runs the one update)."""
        m = MATERIALS[change["new"]]
        self.sync_controls({
            "youngs_modulus": PARAMETERS["youngs_modulus"].to_display(m.youngs_modulus),
            "density": PARAMETERS["density"].to_display(m.density)})

    def update(self, *, force, length, width, thickness, material, youngs_modulus, density,
               section, exaggeration) -> None:
        """Run the model once for these control values and show the result everywhere.

        Parameters
        ----------
        force : float
            End force F in N.
        length, width, thickness : float
            L, w, h in m.
        material : str
            A key of :data:`afmsmiler.materials.MATERIALS`; it acts through E and rho (a choice
            in the drop-down moves their sliders).
        youngs_modulus : float
            E in Pa.
        density : float
            rho in kg/m^3.
        section : float
            Cross-section position x/L.
        exaggeration : float
            Of the deflection drawn in the 3D view.
        """
        lever = Cantilever(length, width, thickness, youngs_modulus, density)
        bending = self.run_model(lever.bending, force, section=section,
                                 n_length=PLOTS["n_points"], n_thickness=_N_THICKNESS,
                                 n_section=_N_SECTION, modes=_N_MODES)
        curves = cantilever_curves(bending)
        if self.modes_figure is not None:
            self.modes_figure.update(curves)
        self.draw(CantileverFigure, curves)  # the figures' frames leave first
        self.last = CantileverState(
            lever=lever, force=bending.force, bending=bending, curves=curves,
            spring_constant=bending.spring_constant, frequencies=bending.frequencies,
            tip_deflection=bending.tip_deflection, max_stress=bending.max_stress)
        self.readout.value = self._readout_html()
        if self._want_scene:
            self.after_frame(lambda: self._show_scene(bending, exaggeration))

    def _show_scene(self, bending, exaggeration: float) -> None:
        """Draw ``bending`` in the 3D view and write its caption."""
        if self.scene is None:
            from ..scenes.cantilever import CantileverScene
            self.scene = CantileverScene(bending, vis=self.scene_root(),
                                         exaggeration=exaggeration,
                                         force_per_unit=FORCE.slider_high / 1.5)
        else:
            self.scene.update(bending, exaggeration=exaggeration)
        self.caption.value = self._caption_html()

    # -- the mode shapes ------------------------------------------------------------------
    def modes_widget(self) -> widgets.Widget:
        """The mode shapes of the lever on the sliders, as a figure that follows them.

        Returns
        -------
        LiveFigure
            Drawn in the browser (see :class:`~afmsmiler.plots.live.LiveFigure`).
        """
        if self.modes_figure is None:
            from ..plots.live import LiveFigure
            self.modes_fig = self.new_figure(figsize=PLOTS["modes_figsize"])
            self.modes_figure = ModeShapesFigure(self.last.curves, fig=self.modes_fig)
            self.modes_live = LiveFigure(self.modes_fig)
        return self.modes_live

    def show_modes(self) -> None:
        """Display the mode shapes under the cell; every later slider move updates them."""
        display(self.modes_widget())
        show_static(self.modes_fig)

    def redraw(self) -> None:
        """Send the figure and, once shown, the mode shapes to the browser (see
        :meth:`Panel.redraw`)."""
        super().redraw()
        if self.modes_live is not None:
            self.modes_live.sync()

    def _readout_html(self) -> str:
        s, u = self.last, _READOUT
        f = ", ".join(f"{x * unit_scale(u['frequency']):.4g}" for x in s.frequencies)
        rows = [("spring constant k", f"{s.spring_constant:.4g} {u['spring_constant']}"),
                ("f1, f2, f3", f"{f} {u['frequency']}"),
                ("tip deflection z(L)",
                 f"{s.tip_deflection * unit_scale(u['deflection']):.4g} {u['deflection']}"),
                ("max |stress| (clamp surface)",
                 f"{s.max_stress * unit_scale(u['stress']):.4g} {u['stress']}")]
        table = "".join(f"<tr><td>{k}</td><td style='text-align:right'><b>{v}</b></td></tr>"
                        for k, v in rows)
        slope = abs(s.bending.tip_slope)  # rad, largest at the free end
        if slope > SMALL_SLOPE:
            table += ("<tr><td colspan='2' style='color:#b00020'>beyond small deflections: "
                      f"|theta(L)| = {slope:.2g} rad &gt; {SMALL_SLOPE:g} rad, so linear beam "
                      "theory (these curves) overestimates z</td></tr>")
        return f"<table>{table}</table>"

    def _caption_html(self) -> str:
        """The 3D view's exaggeration as drawn and its colour legend."""
        from ..scenes.cantilever import DEFAULTS as SCENE
        from ..scenes.legends import legend_html
        ex = self.scene.drawn_exaggeration
        note = ("" if ex == self.scene.exaggeration else
                f" (capped: tip drawn at most {SCENE['max_drawn_tip']:g} L away)")
        shown = f"{ex:,.0f}" if ex >= 10 else f"{ex:.2g}"
        return (f"<div style='margin-top:6px'>3D view: deflection x{shown}{note}, "
                "1 unit = 100 um</div>" + legend_html(self.scene.scale))

    def widget(self) -> widgets.Widget:
        """Controls with the readouts beside them, the figure below.

        Controls and figure side by side need about 1450 px, wider than a notebook on most
        screens: the figure would move below a tall column and leave the sliders when the
        student scrolls to it. This way the whole panel (about 900 px high) fits on one screen.
        """
        figure = super().widget().children[1]
        readouts = widgets.VBox([self.readout, self.caption])
        readouts.layout.margin = "0 0 0 16px"
        readouts.layout.width = "460px"  # a long warning wraps instead of pushing it below
        top = widgets.HBox([widgets.VBox(list(self.controls.values())), readouts])
        return widgets.VBox([top, figure])
