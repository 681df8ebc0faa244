"""Widget panels: ipywidgets sliders -> pure model calls -> figures and scenes updated in place.

Each panel is a class with a pure ``update(**values)`` callback that tests can call without a
browser; sliders are bounded to the model's valid ranges, in practical units (nm, um, nN, GPa, kHz).
"""
from .controls import control
from .panel import Panel, arrange, running_as_notebook, setup_notebook

__all__ = ["Panel", "arrange", "control", "running_as_notebook", "setup_notebook"]
