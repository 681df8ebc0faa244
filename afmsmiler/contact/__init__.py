"""Module (d): contact mechanics of a rigid tip on an elastic (or viscoelastic, adhesive) sample.

- :mod:`.tips`: the four tip shapes with F(Z_s), r(Z_s) and their metadata registry :data:`TIPS`;
- :mod:`.indent`: the cantilever equation k (Z_np - Z_s) = F(Z_s) solved exactly for whole curves,
  approach-retract cycles with DMT or JKR adhesion;
- :mod:`.viscoelastic`: a standard linear solid (Lee and Radok's hereditary integral on loading,
  Ting's solution on unloading);
- :mod:`.fit`: fitting E, contact point and baseline, synthetic curves, files via afmformats;
- :mod:`.surface`: the deformed surface around the contact (for the 3D scene).

All public functions take and return SI units.
"""
from .fit import FitResult, ForceCurve, fit_curve, load_curve, synthetic_curve
from .indent import (ADHESION_MODELS, ApproachRetract, IndentationCurve, approach_retract, indent,
                     jkr_curve, jkr_instability, residual, z_np_limit)
from .surface import surface_displacement
from .tips import (TIPS, Conical, Parabolic, Pyramidal, Spherical, Tip, TipParameter, make_tip,
                   reduced_modulus, tip_table)
from .viscoelastic import (StandardLinearSolid, ViscoelasticCycle, hereditary_force,
                           viscoelastic_approach_retract)

__all__ = ["TIPS", "Tip", "TipParameter", "Parabolic", "Spherical", "Conical", "Pyramidal",
           "make_tip", "reduced_modulus", "tip_table", "IndentationCurve", "ApproachRetract",
           "indent", "approach_retract", "residual", "ADHESION_MODELS", "jkr_curve",
           "jkr_instability", "z_np_limit", "StandardLinearSolid", "ViscoelasticCycle",
           "hereditary_force", "viscoelastic_approach_retract", "ForceCurve", "FitResult",
           "synthetic_curve", "load_curve", "fit_curve", "surface_displacement"]
