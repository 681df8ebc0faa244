"""afmsmiler: open courseware on how an atomic force microscope works.

Pure physics models live in modules named after the physics (:mod:`afmsmiler.cantilever`, ...),
in SI units; :mod:`afmsmiler.scenes` draws them in 3D with meshcat, :mod:`afmsmiler.plots` in 2D
with matplotlib, and :mod:`afmsmiler.ui` wires them to ipywidgets for the notebooks.
"""
from .cantilever import Cantilever
from .materials import MATERIALS, Material, get_material

__version__ = "0.1.0"
__all__ = ["Cantilever", "Material", "MATERIALS", "get_material", "__version__"]
