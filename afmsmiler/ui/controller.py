"""The widget panel of module (c): tune the contact-mode loop and watch trace and retrace.

Sliders show the paper's practical units: masses in ng, damping in ng/us (= 1e-6 kg/s),
stiffness in N/m, K_I in 1/us, K_D in us, speed in um/s, setpoint and feature height in nm.
:meth:`ControllerPanel.update` converts them to SI, builds a
:class:`~afmsmiler.controller.ContactLoop`, scans the chosen profile (trace then retrace) and
updates the :class:`~afmsmiler.plots.controller.ScanFigure` in place, with the stability verdict
and the pole map. Parameters spanning decades have log sliders; every bound lies inside the
model's valid range (masses, stiffnesses and speed > 0, damping and gains >= 0).
"""
from __future__ import annotations

from dataclasses import dataclass

import ipywidgets as widgets

from ..controller import PRESETS, ContactLoop, ScanLine
from ..controller.defaults import LINE, NG, UM, US
from ..plots.controller import ScanCurves, ScanFigure, scan_curves
from ..samples import PROFILES, profile
from .panel import Panel, log_slider, slider

__all__ = ["ControllerPanel", "ControllerState", "DEFAULTS", "BOUNDS", "preset_values"]


def preset_values(name: str) -> dict:
    """Control values (units shown) of one of the Fig. 4 presets.

    Parameters
    ----------
    name : str
        A key of :data:`afmsmiler.controller.PRESETS`.

    Returns
    -------
    dict
    """
    p = PRESETS[name]
    lp = p.loop
    return dict(m_c=lp.m_c / NG, m_s=lp.m_s / NG, b_c=lp.b_c / (NG / US), b_s=lp.b_s / (NG / US),
                k_c=lp.k_c, k_s=lp.k_s, kp=lp.kp, ki=lp.ki * US, kd=lp.kd / US,
                speed=p.speed / UM, setpoint=p.setpoint * 1e9)


#: Initial control values, in the units the sliders show: preset (a) on the grating.
DEFAULTS = dict(preset="a_good_tracking", **preset_values("a_good_tracking"),
                profile=LINE["name"], height=LINE["height"] * 1e9)

#: Slider bounds (low, high) in the units shown; all inside the model's valid ranges.
BOUNDS = dict(m_c=(0.01, 100.0), m_s=(0.01, 100.0), b_c=(1e-4, 10.0), b_s=(1e-4, 10.0),
              k_c=(0.01, 100.0), k_s=(0.01, 1000.0), kp=(1e-3, 1e3), ki=(1e-5, 1e3),
              kd=(0.0, 2.0), speed=(1.0, 1e4), setpoint=(0.0, 100.0), height=(1.0, 500.0))

_LOG = ("m_c", "m_s", "b_c", "b_s", "k_c", "k_s", "kp", "ki", "speed")
_LABELS = dict(m_c=("m_c", "ng"), m_s=("m_s", "ng"), b_c=("b_c", "ng/us"), b_s=("b_s", "ng/us"),
               k_c=("k_c", "N/m"), k_s=("k_s", "N/m"), kp=("K_P", ""), ki=("K_I", "1/us"),
               kd=("K_D", "us"), speed=("scan speed", "um/s"), setpoint=("setpoint R", "nm"),
               height=("feature height", "nm"))


@dataclass(frozen=True)
class ControllerState:
    """What the panel last computed (SI units), for tests and exercises.

    Attributes
    ----------
    loop : ContactLoop
        The loop built from the sliders.
    scan : ScanLine
        Trace and retrace of the line.
    curves : ScanCurves
        The plotted curves (in the units shown).
    max_error : float
        Largest |estimate - T - steady offset| over both passes, in m.
    """

    loop: ContactLoop
    scan: ScanLine
    curves: ScanCurves
    max_error: float


class ControllerPanel(Panel):
    """Sliders for every loop parameter, the gains, the scan speed, setpoint and the profile.

    Controls (units as shown): ``preset`` (one of the paper's Fig. 4 scenarios; choosing one
    sets every slider), ``m_c``, ``m_s`` [ng], ``b_c``, ``b_s`` [ng/us], ``k_c``, ``k_s`` [N/m],
    ``kp``, ``ki`` [1/us], ``kd`` [us], ``speed`` [um/s], ``setpoint`` [nm], ``profile``
    (step, grating, real line) and ``height`` [nm] of its features.

    Parameters
    ----------
    **initial
        Initial control values (keys of :data:`DEFAULTS`), in the units shown.

    Attributes
    ----------
    last : ControllerState
        The last model result.
    figure : ScanFigure
        Trace/retrace plots and the pole map.
    indicator : ipywidgets.HTML
        Stability verdict, Routh-Hurwitz margin, poles and tracking error.
    """

    def __init__(self, **initial):
        unknown = set(initial) - set(DEFAULTS)
        if unknown:
            raise TypeError(f"unknown control(s) {sorted(unknown)}; valid: {sorted(DEFAULTS)}")
        v = {**DEFAULTS, **initial}
        if "preset" in initial:
            v = {**v, **preset_values(initial["preset"]),
                 **{k: x for k, x in initial.items() if k != "preset"}}
        controls = {"preset": widgets.Dropdown(
            options=[(p.description, name) for name, p in PRESETS.items()], value=v["preset"],
            description="preset", layout=widgets.Layout(width="420px"))}
        for name, (low, high) in BOUNDS.items():
            label, unit = _LABELS[name]
            make = log_slider if name in _LOG else slider
            controls[name] = make(label, v[name], low, high, unit=unit)
        controls["profile"] = widgets.Dropdown(options=list(PROFILES), value=v["profile"],
                                               description="profile")
        self.controls = controls
        self.indicator = widgets.HTML()
        self.figure = None
        self.fig = self.new_figure(figsize=(10.0, 6.0))  # 11 in was clipped in JupyterLab
        self.controls["preset"].observe(self._on_preset, names="value")
        super().__init__()

    def _on_preset(self, change) -> None:
        hold, self._hold = self._hold, True
        try:
            for name, value in preset_values(change["new"]).items():
                self.controls[name].value = value
        finally:
            self._hold = hold

    def update(self, preset, m_c, m_s, b_c, b_s, k_c, k_s, kp, ki, kd, speed, setpoint, height,
               profile) -> None:
        """Convert the control values to SI, scan the line, update plots and the indicator."""
        del preset  # it acts through the other sliders (see _on_preset)
        loop = ContactLoop(m_c=m_c * NG, m_s=m_s * NG, b_c=b_c * NG / US, b_s=b_s * NG / US,
                           k_c=k_c, k_s=k_s, kp=kp, ki=ki / US, kd=kd * US)
        sample = _profile(profile, height * 1e-9)
        scan = loop.scan_line(sample.x, sample.heights, speed * UM, setpoint * 1e-9)
        curves = scan_curves(scan, loop)
        if self.figure is None:
            self.figure = ScanFigure(curves, fig=self.fig)
        else:
            self.figure.update(curves)
        err = max(float(abs(scan.trace.error - scan.offset).max()),
                  float(abs(scan.retrace.error - scan.offset).max()))
        self.last = ControllerState(loop, scan, curves, err)
        self.indicator.value = self._indicator_html()
        self.redraw()

    def _indicator_html(self) -> str:
        s = self.last
        stab = s.loop.is_stable()
        color, verdict = ("green", "STABLE") if stab else ("red", "UNSTABLE")
        poles = ", ".join(f"{p * 1e-6:.3g}" for p in s.loop.poles)
        rows = [("Routh-Hurwitz margin", f"{stab.margin:.3g}"),
                ("poles", f"{poles} 1/us"),
                ("max |error| (less offset)", f"{s.max_error * 1e9:.3g} nm"),
                ("indentation offset", f"{s.scan.offset * 1e9:.3g} nm")]
        table = "".join(f"<tr><td>{k}</td><td><b>{v}</b></td></tr>" for k, v in rows)
        return (f"<div style='font-size:1.2em;color:{color}'><b>&#9679; {verdict}</b></div>"
                f"<table>{table}</table>")

    def widget(self) -> widgets.Widget:
        """Two columns of controls with the indicator beside them, the figure below.

        The fourteen controls in one column, the indicator under them and the figure under that
        made the panel about 1300 px high: the student could not see a slider and the plots it
        moves at the same time. Here the mechanics (preset, masses, damping, stiffnesses) and the
        scan (gains, speed, setpoint, profile) are two columns of seven beside the indicator, and
        the figure (1000 x 600 px) follows: about 850 px in all. In a notebook too narrow for the
        row (about 1200 px), :func:`~afmsmiler.ui.panel.arrange` wraps the indicator below the
        columns, still above the figure.

        Returns
        -------
        ipywidgets.VBox
            ``[HBox([mechanics column, scan column, indicator]), figure]``.
        """
        figure = super().widget().children[1]
        columns = [widgets.VBox([self.controls[name] for name in names]) for names in _COLUMNS]
        columns[1].layout.margin = "0 0 0 12px"
        self.indicator.layout.margin = "0 0 0 16px"
        self.indicator.layout.width = "320px"  # the list of poles wraps instead of moving it
        return widgets.VBox([widgets.HBox([*columns, self.indicator]), figure])


#: The two columns of controls in :meth:`ControllerPanel.widget` (every control once).
_COLUMNS = (("preset", "m_c", "m_s", "b_c", "b_s", "k_c", "k_s"),
            ("kp", "ki", "kd", "speed", "setpoint", "height", "profile"))


_CACHE: dict = {}


def _profile(name, height):
    key = (name, height)
    if key not in _CACHE:
        _CACHE.clear()
        _CACHE[key] = profile(name, LINE["pixels"], LINE["pixel_size"], height)
    return _CACHE[key]

