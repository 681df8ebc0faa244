"""Module (d): contact mechanics of a rigid tip on an elastic (or viscoelastic, adhesive) sample.

- :mod:`.system`: :class:`ContactSystem`, tip + lever + sample + adhesion, the object the panel,
  the notebook and the exercises call (keyword arguments, one order everywhere);
- :mod:`.tips`: the four tip shapes with F(Z_s), r(Z_s) and their metadata registry :data:`TIPS`;
- :mod:`.indent`: the cantilever equation k (Z_np - Z_s) = F(Z_s) solved exactly for whole curves,
  approach-retract cycles with DMT or JKR adhesion;
- :mod:`.viscoelastic`: a standard linear solid (Lee and Radok's hereditary integral on loading,
  Ting's solution on unloading);
- :mod:`.fit`: fitting E, contact point and baseline, synthetic curves, files via afmformats;
- :mod:`.surface`: the deformed surface around the contact (for the 3D scene).

All public functions take and return SI units.
"""
from .fit import (MAX_BATCH_POINTS, FitResult, FitResults, ForceCurve, fit_curve, fit_curves,
                  load_curve, synthetic_curve)
from .indent import (ADHESION_MODELS, ApproachRetract, IndentationCurve, adhesion_extrema,
                     approach_retract, indent,
                     jkr_curve, jkr_instability, residual, z_np_limit)
from .surface import contact_surface, surface_displacement
from .quantities import PARAMETERS
from .system import BRANCHES, ContactSystem
from .tips import (PYRAMID_FORMS, TIPS, Conical, Parabolic, Pyramidal, Spherical, Tip, make_tip,
                   reduced_modulus, tip_table)
from .viscoelastic import (StandardLinearSolid, ViscoelasticCycle, hereditary_force,
                           viscoelastic_approach_retract)

__all__ = ["ContactSystem", "PARAMETERS", "BRANCHES", "PYRAMID_FORMS", "TIPS", "Tip", "Parabolic",
           "Spherical", "Conical", "Pyramidal", "make_tip", "reduced_modulus", "tip_table",
           "IndentationCurve", "ApproachRetract", "indent", "approach_retract", "adhesion_extrema",
           "residual", "ADHESION_MODELS", "jkr_curve", "jkr_instability", "z_np_limit",
           "StandardLinearSolid", "ViscoelasticCycle", "hereditary_force",
           "viscoelastic_approach_retract", "ForceCurve", "FitResult", "synthetic_curve",
           "load_curve", "fit_curve", "surface_displacement", "contact_surface", "fit_curves",
           "FitResults", "MAX_BATCH_POINTS"]
