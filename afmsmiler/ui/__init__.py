"""Widget panels: ipywidgets sliders -> pure model calls -> figures and scenes updated in place.

Each panel is a class with a pure ``update(**values)`` callback that tests can call without a
browser; sliders are bounded to the model's valid ranges, in practical units (nm, um, nN, GPa, kHz).
"""
from .panel import Panel, arrange, log_slider, running_as_notebook, setup_notebook, slider

__all__ = ["Panel", "arrange", "slider", "log_slider", "running_as_notebook", "setup_notebook"]
