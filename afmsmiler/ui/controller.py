"""The widget panel of module (c): tune the contact-mode loop and watch trace and retrace.

Every slider is built by :func:`~afmsmiler.ui.controls.control` from the model's own description,
:data:`afmsmiler.controller.PARAMETERS` (display units from its ``display_unit``: masses in ng,
damping in ng/us, stiffness in N/m, K_I in 1/us, K_D in us, speed in um/s, setpoint and feature
height in nm; log sliders where the parameter spans decades; every position inside the model's
valid range). :meth:`ControllerPanel.update` converts the values it is given to SI with the same
descriptions, builds one :class:`~afmsmiler.controller.ContactLoop`, scans the chosen profile once
(trace then retrace) and hands the result to the
:class:`~afmsmiler.plots.controller.ScanFigure` and the indicator, which compute nothing.
Choosing a preset runs one update with exactly the preset's values.
"""
from __future__ import annotations

import html
from dataclasses import dataclass

import ipywidgets as widgets
import numpy as np

from ..controller import PARAMETERS, PRESETS, ContactLoop, ScanLine
from ..controller.defaults import LINE
from ..controller.loop import LOOP_PARAMETERS
from ..parameters import read_only
from ..plots.controller import ScanCurves, ScanFigure, scan_curves
from ..samples import PROFILES, profile
from ..validation import check_choice
from .controls import WIDTH
from .panel import Panel, initial_values, slider

__all__ = ["ControllerPanel", "ControllerState", "DEFAULTS", "SLIDERS", "preset_values",
           "format_poles"]

#: The sliders of the panel, in order: the loop's parameters, then the scan's.
SLIDERS = (*LOOP_PARAMETERS, "speed", "setpoint", "height")


def preset_values(name: str) -> dict:
    """Control values (in the units shown) of one of the Fig. 4 presets.

    Parameters
    ----------
    name : str
        A key of :data:`afmsmiler.controller.PRESETS`.

    Returns
    -------
    dict
        Slider name -> value in the slider's display unit (from :data:`PARAMETERS`).

    Raises
    ------
    ValueError
        If ``name`` is not a preset.
    """
    check_choice("preset", name, list(PRESETS))
    p = PRESETS[name]
    si = {k: getattr(p.loop, k) for k in LOOP_PARAMETERS}
    si.update(speed=p.speed, setpoint=p.setpoint)
    # 12 digits: 10 nm shows as 10, not as 9.999999999999998 (the unit conversion's round-off)
    return {k: float(f"{PARAMETERS[k].to_display(v):.12g}") for k, v in si.items()}


#: Initial control values, in the units the sliders show: preset (a) on the grating.
DEFAULTS = read_only(dict(preset="a_good_tracking", **preset_values("a_good_tracking"),
                          height=float(f"{PARAMETERS['height'].to_display(LINE['height']):.12g}"),
                          profile=LINE["name"]))


def format_poles(poles, unit: str = "1/us") -> str:
    """The poles as an HTML list that wraps between poles, never inside a number.

    A conjugate pair is written once as ``a ± bi``; each pole is a no-wrap span.

    Parameters
    ----------
    poles : array_like of complex
        Poles in the unit shown.
    unit : str
        Their unit, appended once.

    Returns
    -------
    str
        HTML.
    """
    items, seen = [], []
    for p in sorted(np.asarray(poles, dtype=complex), key=lambda z: (z.real, -z.imag)):
        if p.imag < 0 and any(abs(q - p.conjugate()) <= 1e-12 * abs(p) for q in seen):
            continue
        seen.append(p)
        if p.imag > 0 and any(abs(q - p.conjugate()) <= 1e-12 * abs(p) for q in poles):
            text = f"{p.real:.3g} &plusmn; {p.imag:.3g}i"
        else:
            text = f"{p.real:.3g}"
        items.append(f"<span style='white-space:nowrap'>{text}</span>")
    return ", ".join(items) + f" {html.escape(unit)}"


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
        v = initial_values(initial, DEFAULTS)
        if "preset" in initial:
            v = {**v, **preset_values(initial["preset"]), **initial}
        check_choice("profile", v["profile"], list(PROFILES))
        controls = {"preset": widgets.Dropdown(
            options=[(p.description, name) for name, p in PRESETS.items()], value=v["preset"],
            description="preset", layout=widgets.Layout(width=WIDTH))}
        for name in SLIDERS:
            controls[name] = slider(name, PARAMETERS[name], v[name])
        controls["profile"] = widgets.Dropdown(options=list(PROFILES), value=v["profile"],
                                               description="profile")
        self.controls = controls
        self.indicator = widgets.HTML()
        self.figure = None
        self.fig = self.new_figure(figsize=(10.0, 6.0))  # 11 in was clipped in JupyterLab
        self.controls["preset"].observe(self._on_preset, names="value")
        super().__init__()

    def set(self, **values) -> None:
        """Set control values as a user would: one update, with exactly these values.

        Choosing a ``preset`` sets every slider to the preset's values (others given here win).

        Parameters
        ----------
        **values
            Control name -> value in the units shown.

        Raises
        ------
        TypeError, ValueError
            For an unknown control or a value it cannot hold (see :meth:`Panel.set`).
        """
        if "preset" in values:
            values = {**preset_values(values["preset"]), **values}
        super().set(**values)

    def _on_preset(self, change) -> None:
        """The student chose a preset: every slider moves to it and the model runs once with
        exactly the preset's values (the sliders' grids, the browser's echoes and the values
        before do not leak into them)."""
        if self._hold:  # inside set(), which runs the update itself
            return
        self.set(preset=change["new"])

    def update(self, preset, m_c, m_s, b_c, b_s, k_c, k_s, kp, ki, kd, speed, setpoint, height,
               profile) -> None:
        """Scan the line with exactly these values (sliders in SI), update plots and indicator.

        Parameters
        ----------
        preset : str
            The preset chosen (it acts through the other values, see :meth:`set`).
        m_c, m_s : float
            Masses in kg.
        b_c, b_s : float
            Damping in kg/s.
        k_c, k_s : float
            Stiffnesses in N/m.
        kp : float
            K_P (dimensionless).
        ki : float
            K_I in 1/s.
        kd : float
            K_D in s.
        speed : float
            Scan speed in m/s.
        setpoint : float
            Deflection setpoint R in m.
        height : float
            Feature height of the profile in m.
        profile : str
            One of :data:`afmsmiler.samples.PROFILES`.

        Raises
        ------
        TypeError, ValueError
            Naming a value that is not a number, not finite or outside its parameter's valid
            range, or an unknown preset or profile, before any work (the panel contract).
        """
        si = dict(m_c=m_c, m_s=m_s, b_c=b_c, b_s=b_s, k_c=k_c, k_s=k_s, kp=kp, ki=ki, kd=kd)
        loop = ContactLoop(**{k: si[k] for k in LOOP_PARAMETERS})
        sample = _profile(profile, height)
        scan = self.run_model(loop.scan_line, sample.x, sample.heights, speed=speed,
                              setpoint=setpoint)
        curves = scan_curves(scan, loop)
        self.draw(ScanFigure, curves)  # the figure's frame leaves first: its pixels wait for nothing else
        err = max(float(abs(scan.trace.error - scan.offset).max()),
                  float(abs(scan.retrace.error - scan.offset).max()))
        self.last = ControllerState(loop, scan, curves, err)
        self.indicator.value = self._indicator_html()

    def _indicator_html(self) -> str:
        s = self.last
        c = s.curves
        color, verdict = ("green", "STABLE") if c.stable else ("red", "UNSTABLE")
        nm = PARAMETERS["height"].scale
        rows = [("Routh-Hurwitz margin", f"{c.margin:.3g}"),
                ("poles", format_poles(c.poles_per_us)),
                ("max |error| (less offset)", f"{s.max_error * nm:.3g} nm"),
                ("trace-retrace gap of Z_np", f"{s.scan.gap * nm:.3g} nm"),
                ("indentation offset", f"{s.scan.offset * nm:.3g} nm")]
        table = "".join(f"<tr><td style='vertical-align:top'>{k}</td><td><b>{v}</b></td></tr>"
                        for k, v in rows)
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

