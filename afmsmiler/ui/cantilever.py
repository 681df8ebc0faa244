"""The widget panel of module (a): sliders for the lever and its load, four plots, the 3D view.

Sliders show practical units (nN, um, GPa, kg/m^3); :meth:`CantileverPanel.update` converts them
to SI, builds a :class:`~afmsmiler.cantilever.Cantilever`, and updates the figure
(:class:`~afmsmiler.plots.cantilever.CantileverFigure`) and the meshcat scene
(:class:`~afmsmiler.scenes.cantilever.CantileverScene`) in place. All slider bounds lie inside the
model's valid ranges (every dimension > 0, the cross-section given as a fraction of L), so no
slider position can make the model raise.
"""
from __future__ import annotations

from dataclasses import dataclass

import ipywidgets as widgets

from ..cantilever import Cantilever
from ..materials import MATERIALS
from ..plots.cantilever import CantileverCurves, CantileverFigure, cantilever_curves
from .panel import Panel, log_slider, slider

__all__ = ["CantileverPanel", "CantileverState", "DEFAULTS", "BOUNDS"]

#: Initial control values (a contact-mode silicon lever like BudgetSensors ContAl-G:
#: 450 x 50 x 2 um, nominal k = 0.2 N/m, f0 = 13 kHz), in the units the sliders show.
DEFAULTS = dict(force=100.0, length=450.0, width=50.0, thickness=2.0, material="silicon",
                youngs_modulus=169.0, density=2330.0, section=0.0, exaggeration=100.0)

#: Slider bounds (low, high) in the units shown; all inside the model's valid ranges.
BOUNDS = dict(force=(-500.0, 500.0), length=(20.0, 500.0), width=(5.0, 100.0),
              thickness=(0.2, 10.0), youngs_modulus=(10.0, 400.0), density=(1000.0, 20000.0),
              section=(0.0, 1.0), exaggeration=(1.0, 1e4))

_N_MODES = 3
_FIGSIZE = (10.0, 5.6)  # inches: with the controls above it, the panel fits one screen
#: Largest end slope |theta(L)| in rad (of the linear theory) for which the readout calls the
#: small-deflection beam theory good: F L^3 / (3 E J) then overestimates the tip deflection of the
#: end-loaded elastica by about 0.45 theta^2, 0.5 % at 0.1 rad but 10 % at 0.5 rad (checked
#: against the elastica solved numerically in tests/test_cantilever_ui.py).
SMALL_SLOPE = 0.1


@dataclass(frozen=True)
class CantileverState:
    """What the panel last computed (SI units), for tests and exercises.

    Attributes
    ----------
    lever : Cantilever
        The lever built from the sliders.
    force : float
        End force in N.
    curves : CantileverCurves
        The plotted curves (in the units shown).
    spring_constant : float
        k in N/m.
    frequencies : tuple of float
        f1, f2, f3 in Hz.
    tip_deflection : float
        z(L) in m.
    max_stress : float
        Largest |sigma| on the surface in Pa.
    """

    lever: Cantilever
    force: float
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
        Draw the 3D view in the kernel's meshcat viewer (show it with
        ``get_viewer().jupyter_cell()``; close it with ``close_viewer()``).
    **initial
        Initial control values (keys of :data:`DEFAULTS`), in the units shown.

    Attributes
    ----------
    last : CantileverState
        The last model result.
    figure : CantileverFigure
        The four plots.
    scene : CantileverScene or None
        The 3D view.
    readout : ipywidgets.HTML
        k [N/m], f1..f3 [kHz], tip deflection [nm], max stress [MPa] and the color legend.
    """

    def __init__(self, scene: bool = True, **initial):
        unknown = set(initial) - set(DEFAULTS)
        if unknown:
            raise TypeError(f"unknown control(s) {sorted(unknown)}; valid: {sorted(DEFAULTS)}")
        v = {**DEFAULTS, **initial}
        if "material" in initial and not {"youngs_modulus", "density"} & set(initial):
            m = MATERIALS[initial["material"]]
            v["youngs_modulus"], v["density"] = m.youngs_modulus / 1e9, m.density
        b = BOUNDS
        self.controls = dict(
            force=slider("F", v["force"], *b["force"], step=1.0, unit="nN"),
            length=slider("L", v["length"], *b["length"], step=1.0, unit="um"),
            width=slider("w", v["width"], *b["width"], step=0.5, unit="um"),
            thickness=slider("h", v["thickness"], *b["thickness"], step=0.01, unit="um"),
            material=widgets.Dropdown(options=[(m.name, key) for key, m in MATERIALS.items()],
                                      value=v["material"], description="material"),
            youngs_modulus=slider("E", v["youngs_modulus"], *b["youngs_modulus"], step=0.1,
                                  unit="GPa"),
            density=slider("rho", v["density"], *b["density"], step=10.0, unit="kg/m^3"),
            section=slider("section x/L", v["section"], *b["section"], step=0.01),
            exaggeration=log_slider("exaggeration", v["exaggeration"], *b["exaggeration"],
                                    unit="x"),
        )
        self.readout = widgets.HTML()
        self.figure = None
        self.scene = None
        self._want_scene = bool(scene)
        self.fig = self.new_figure(figsize=_FIGSIZE)
        # registered before Panel's own observer, so one material change gives one update
        self.controls["material"].observe(self._on_material, names="value")
        super().__init__()

    def _on_material(self, change) -> None:
        m = MATERIALS[change["new"]]
        hold, self._hold = self._hold, True
        try:
            self.controls["youngs_modulus"].value = m.youngs_modulus / 1e9
            self.controls["density"].value = m.density
        finally:
            self._hold = hold

    def update(self, force, length, width, thickness, material, youngs_modulus, density,
               section, exaggeration) -> None:
        """Convert the control values to SI, run the model, update plots, scene and readouts."""
        del material  # it acts through E and rho (see _on_material)
        lever = Cantilever(length * 1e-6, width * 1e-6, thickness * 1e-6, youngs_modulus * 1e9,
                           density)
        f = force * 1e-9
        curves = cantilever_curves(lever, f, section * lever.length)
        if self.figure is None:
            self.figure = CantileverFigure(curves, fig=self.fig)
        else:
            self.figure.update(curves)
        if self._want_scene and self.scene_open():  # not after close_viewer()
            if self.scene is None:
                from ..scenes.cantilever import CantileverScene
                self.scene = CantileverScene(lever, f, exaggeration=exaggeration,
                                             force_per_unit=BOUNDS["force"][1] * 1e-9 / 1.5)
            else:
                self.scene.update(lever, f, exaggeration=exaggeration)
        freqs = tuple(lever.resonance_frequency(n) for n in range(1, _N_MODES + 1))
        self.last = CantileverState(
            lever=lever, force=f, curves=curves, spring_constant=lever.spring_constant,
            frequencies=freqs, tip_deflection=float(curves.z_nm[-1]) * 1e-9,
            max_stress=float(abs(curves.stress_top_mpa).max()) * 1e6)
        self.readout.value = self._readout_html()
        self.redraw()

    def _readout_html(self) -> str:
        s = self.last
        f = ", ".join(f"{x / 1e3:.4g}" for x in s.frequencies)
        rows = [("spring constant k", f"{s.spring_constant:.4g} N/m"),
                ("f1, f2, f3", f"{f} kHz"),
                ("tip deflection z(L)", f"{s.tip_deflection * 1e9:.4g} nm"),
                ("max |stress| (clamp surface)", f"{s.max_stress / 1e6:.4g} MPa")]
        table = "".join(f"<tr><td>{k}</td><td style='text-align:right'><b>{v}</b></td></tr>"
                        for k, v in rows)
        slope = abs(float(s.curves.theta_mrad[-1])) / 1e3  # rad, largest at the free end
        if slope > SMALL_SLOPE:
            table += ("<tr><td colspan='2' style='color:#b00020'>beyond small deflections: "
                      f"|theta(L)| = {slope:.2g} rad &gt; {SMALL_SLOPE:g} rad, so linear beam "
                      "theory (these curves) overestimates z</td></tr>")
        legend = ""
        if self.scene is not None:
            from ..scenes.legends import legend_html
            ex = self.scene.drawn_exaggeration
            from ..scenes.cantilever import DEFAULTS as SCENE
            note = ("" if ex == self.scene.exaggeration else
                    f" (capped: tip drawn at most {SCENE['max_drawn_tip']:g} L away)")
            shown = f"{ex:,.0f}" if ex >= 10 else f"{ex:.2g}"
            legend = (f"<div style='margin-top:6px'>3D view: deflection x{shown}{note}, "
                      "1 unit = 100 um</div>" + legend_html(self.scene.scale))
        elif self._want_scene and self._viewer_closed:
            legend = ("<div style='margin-top:6px'>3D view closed (<code>close_viewer()</code>); "
                      "run <code>get_viewer().jupyter_cell()</code> and move a slider to see it again"
                      "</div>")
        return f"<table>{table}</table>{legend}"

    def widget(self) -> widgets.Widget:
        """Controls with the readouts beside them, the figure below.

        Controls and figure side by side need about 1450 px, wider than a notebook on most
        screens: the figure would move below a tall column and leave the sliders when the
        student scrolls to it. This way the whole panel (about 900 px high) fits on one screen.
        """
        figure = super().widget().children[1]
        self.readout.layout.margin = "0 0 0 16px"
        self.readout.layout.width = "460px"  # a long warning wraps instead of pushing it below
        top = widgets.HBox([widgets.VBox(list(self.controls.values())), self.readout])
        return widgets.VBox([top, figure])
