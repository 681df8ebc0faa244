"""The one list of the course's widget panels.

Every panel a notebook shows is one :class:`PanelEntry` of :data:`PANELS`: its module's letter
(the paper's (a)-(h)), the notebook that shows it and the name it has there, the class, a title,
and the control a test or a benchmark moves. The book's static pages
(:mod:`afmsmiler.ui.pages`), the label and browser tests, the benchmarks and the README's table
iterate this list, and a test fails when a :class:`~afmsmiler.ui.panel.Panel` of
:mod:`afmsmiler.ui` is missing from it, so a new panel cannot be forgotten (python-control's
``kwargs_test.py`` works the same way for keyword arguments).
"""
from __future__ import annotations

import importlib
from dataclasses import dataclass

from ..validation import check_choice

__all__ = ["PanelEntry", "PANELS", "MODULES", "panel_entry", "panels", "markdown_table"]

#: The course's modules: letter -> (notebook, title).
MODULES = {
    "a": ("01_cantilever_mechanics.ipynb", "cantilever mechanics"),
    "b": ("02_probe_transducers.ipynb", "probe transducers"),
    "c": ("03_controller_tuning.ipynb", "controller tuning for contact-mode imaging"),
    "d": ("04_contact_mechanics.ipynb", "contact mechanics"),
    "e": ("05_system_overview.ipynb", "system overview"),
    "f": ("06_virtual_imaging.ipynb", "virtual imaging"),
    "g": ("07_imaging_modalities.ipynb", "imaging modalities"),
    "h": ("08_hardware_interaction.ipynb", "hardware interaction"),
}


@dataclass(frozen=True)
class PanelEntry:
    """One panel of the course.

    Attributes
    ----------
    key : str
        The panel's short name (its page is ``<key>.html``).
    module : str
        The module's letter, a key of :data:`MODULES`.
    variable : str
        The panel's name in the module's notebook.
    ui : str
        The submodule of :mod:`afmsmiler.ui` that defines it.
    cls : str
        The class name.
    title : str
        What the panel shows, in a few words.
    slider : str
        The control a test or a benchmark moves (a slider of the panel at its defaults).
    scene : bool
        Whether the notebook shows the panel with its 3D view.
    figure : bool
        Whether a move of :attr:`slider` redraws the figure at once (module (f)'s and the
        macroscopic AFM's sliders apply to the next scan).
    """

    key: str
    module: str
    variable: str
    ui: str
    cls: str
    title: str
    slider: str
    scene: bool = False
    figure: bool = True

    @property
    def selector(self) -> str:
        """The CSS selector of the panel's box on a page (:meth:`Panel.show` tags it)."""
        return f".afm-panel-{self.cls}"

    @property
    def slider_selector(self) -> str:
        """The CSS selector of :attr:`slider`'s widget on a page (every control is tagged)."""
        return f"{self.selector} .afm-control-{self.slider}"

    @property
    def notebook(self) -> str:
        """The notebook's file name (in ``notebooks/``)."""
        return MODULES[self.module][0]

    def load(self) -> type:
        """The panel's class (imported on demand: the UI stack only where a panel is asked for)."""
        return getattr(importlib.import_module(f"afmsmiler.ui.{self.ui}"), self.cls)

    def make(self, **kwargs):
        """A panel at its defaults, without a 3D view unless ``scene=True`` is given.

        Parameters
        ----------
        **kwargs
            Passed to the constructor.

        Returns
        -------
        Panel
        """
        return self.load()(**kwargs)


#: Every panel, in the order of the course.
PANELS = (
    PanelEntry("cantilever", "a", "panel", "cantilever", "CantileverPanel",
               "a lever's deflection, stress, stiffness and modes", "force", scene=True),
    PanelEntry("probe", "a", "probe", "probe", "ProbePanel",
               "your probe in air and water, calibrated, twisted", "spot", scene=True),
    PanelEntry("transducers", "b", "panel", "transducers", "TransducerPanel",
               "a sensing or actuation principle's chain and noise", "input", scene=True),
    PanelEntry("controller", "c", "panel", "controller", "ControllerPanel",
               "contact-mode feedback scanning a line", "ki"),
    PanelEntry("contact", "d", "panel", "contact", "ContactPanel",
               "a tip indenting a sample, with adhesion", "z_np", scene=True),
    PanelEntry("instrument", "e", "panel", "instrument", "InstrumentPanel",
               "an instrument's parts and its laser alignment", "laser_x", scene=True),
    PanelEntry("imaging", "f", "panel", "imaging", "ImagingPanel",
               "a scan line by line, its images and artefacts", "radius", scene=True, figure=False),
    PanelEntry("lateral", "g", "lateral", "modes", "LateralPanel",
               "friction loops and maps", "tilt", scene=True),
    PanelEntry("tapping", "g", "tapping", "modes", "TappingPanel",
               "tapping: amplitude and phase against distance", "setpoint_ratio", scene=True),
    PanelEntry("fm", "g", "fm", "modes", "FrequencyShiftPanel",
               "FM: frequency shift and the force it gives", "amplitude", scene=True),
    PanelEntry("jumping", "g", "jumping", "modes", "JumpingPanel",
               "jumping mode: a pixel's cycle and the image", "lift_height", scene=True),
    PanelEntry("force_volume", "g", "volume", "modes", "ForceVolumePanel",
               "force-volume maps of a two-material sample", "force_noise"),
    PanelEntry("macro_afm", "h", "panel", "hardware", "MacroAFMPanel",
               "the macroscopic AFM: scans and prints", "setpoint_force", figure=False),
    PanelEntry("bridge", "h", "bridge", "haptic", "BridgePanel",
               "a force law felt through the haptic device", "force_scale"),
    PanelEntry("q_control", "h", "q_panel", "haptic", "QControlPanel",
               "Q control: resonance and ring-down", "gain"),
    PanelEntry("lockin", "h", "lockin_panel", "lockin", "LockInPanel",
               "the lock-in amplifier's reading against the truth", "ac_voltage"),
)


def panel_entry(key: str) -> PanelEntry:
    """The entry of panel ``key``.

    Raises
    ------
    ValueError
        For an unknown key, listing the panels.
    """
    check_choice("key", key, [e.key for e in PANELS])
    return next(e for e in PANELS if e.key == key)


def panels(module: str | None = None) -> tuple:
    """The panels of one module (a letter of :data:`MODULES`), or all of them."""
    if module is None:
        return PANELS
    check_choice("module", module, list(MODULES))
    return tuple(e for e in PANELS if e.module == module)


def markdown_table() -> str:
    """The README's table of panels, one row per entry of :data:`PANELS` (a test compares them).

    Returns
    -------
    str
        A Markdown table, ending with a newline.
    """
    rows = ["| module | notebook | panel (its name there) | what it shows | 3D view |",
            "|---|---|---|---|---|"]
    for e in PANELS:
        rows.append(f"| {e.module} | `{e.notebook[:-6]}` | `{e.cls}` (`{e.variable}`) | "
                    f"{e.title} | {'yes' if e.scene else '-'} |")
    return "\n".join(rows) + "\n"


if __name__ == "__main__":
    print(markdown_table(), end="")
