"""Material presets for cantilevers, tips and samples (SI units).

Values are textbook figures; each preset says where it comes from. Crystalline silicon is
anisotropic: the Young's modulus along <110>, the usual cantilever axis on a (100) wafer, is
169 GPa (Hopcroft, Nix and Kenny, J. Microelectromech. Syst. 19, 229 (2010)), which is also the
value AFM probe vendors use to compute nominal spring constants. Twisting such a lever shears it
in the (001) plane between <110> and <-110>, whose shear modulus is 50.9 GPa (same source), not
the isotropic E / (2 (1 + nu)) = 79.4 GPa of E<110> and nu = 0.064: a preset may therefore give
its shear modulus G explicitly; otherwise G = E / (2 (1 + nu)).
"""
from __future__ import annotations

from dataclasses import dataclass

from .parameters import Parameter, read_only
from .validation import check_instance, check_range

__all__ = ["Material", "MATERIALS", "get_material", "YOUNGS_MODULUS", "DENSITY"]

#: Young's modulus E: valid from 1 Pa to 10 TPa (every beam result stays finite), the slider of
#: module (a) from 10 to 400 GPa (every preset of :data:`MATERIALS` lies on it).
YOUNGS_MODULUS = Parameter(name="youngs_modulus", unit="Pa", display_unit="GPa", default=169e9,
                           low=1.0, high=1e13, slider_low=10e9, slider_high=400e9,
                           label="Young's modulus E")
#: Mass density rho: valid from 1 to 10^5 kg/m^3, the slider from 1000 to 20000 kg/m^3.
DENSITY = Parameter(name="density", unit="kg/m^3", default=2330.0, low=1.0, high=1e5,
                    slider_low=1000.0, slider_high=20000.0, label="density rho")


@dataclass(frozen=True)
class Material:
    """An isotropic, linear-elastic material.

    Parameters
    ----------
    name : str
        Human-readable name.
    youngs_modulus : float
        Young's modulus E in Pa.
    density : float
        Mass density rho in kg/m^3.
    poisson_ratio : float
        Poisson's ratio nu, in [0, 0.5).
    source : str
        Where the figures come from.
    shear_modulus : float or None
        Shear modulus G in Pa for twisting a lever made of it (1 Pa to 10 TPa); None: the
        isotropic G = E / (2 (1 + nu)).
    """

    name: str
    youngs_modulus: float
    density: float
    poisson_ratio: float = 0.25
    source: str = ""
    shear_modulus: float | None = None

    def __post_init__(self):
        check_instance("name", self.name, str)
        check_instance("source", self.source, str)
        object.__setattr__(self, "youngs_modulus", YOUNGS_MODULUS.check(self.youngs_modulus))
        object.__setattr__(self, "density", DENSITY.check(self.density))
        object.__setattr__(self, "poisson_ratio", check_range(
            "poisson_ratio", self.poisson_ratio, 0.0, 0.5, high_inclusive=False))
        g = (self.youngs_modulus / (2 * (1 + self.poisson_ratio)) if self.shear_modulus is None
             else check_range("shear_modulus", self.shear_modulus, 1.0, 1e13, "Pa"))
        object.__setattr__(self, "shear_modulus", g)


#: The presets by key (read-only).
MATERIALS = read_only({
    "silicon": Material("silicon <110>", 169e9, 2330.0, 0.064,
                        "Hopcroft et al., JMEMS 19, 229 (2010): E<110> = 169 GPa, nu = 0.064 and"
                        " G = 50.9 GPa for a lever along <110> on a (100) wafer", 50.9e9),
    "silicon_nitride": Material("silicon nitride (LPCVD)", 250e9, 3100.0, 0.23,
                                "LPCVD Si3N4 films, E reported 150-310 GPa; 250 GPa typical"),
    "silicon_dioxide": Material("silicon dioxide (thermal)", 70e9, 2200.0, 0.17,
                                "thermal SiO2, E = 70 GPa"),
    "gold": Material("gold", 79e9, 19300.0, 0.42, "bulk Au, CRC Handbook"),
    "aluminium": Material("aluminium", 70e9, 2700.0, 0.35, "bulk Al, CRC Handbook"),
    "quartz": Material("quartz (qPlus tuning fork)", 78.7e9, 2650.0, 0.17,
                       "Giessibl, Rev. Mod. Phys. 75, 949 (2003)"),
})


def get_material(name: str | Material) -> Material:
    """Return a preset by key (see :data:`MATERIALS`) or pass a :class:`Material` through.

    Parameters
    ----------
    name : str or Material
        A key of :data:`MATERIALS` (``"silicon"``, ``"silicon_nitride"``, ...) or a Material.

    Returns
    -------
    Material

    Raises
    ------
    TypeError
        If ``name`` is neither a string nor a Material.
    ValueError
        If ``name`` is not a key of :data:`MATERIALS`.
    """
    return lookup(name, "name")


def lookup(value, parameter: str) -> Material:
    """:func:`get_material` for a caller whose own parameter is called ``parameter``.

    The errors name the parameter the caller's user passed (``material`` for
    :meth:`~afmsmiler.cantilever.Cantilever.from_material`), not ``name``.

    Parameters
    ----------
    value : str or Material
        A key of :data:`MATERIALS` or a Material.
    parameter : str
        The name of the caller's parameter, for the messages.

    Returns
    -------
    Material
    """
    if isinstance(value, Material):
        return value
    check_instance(parameter, value, str, "key of MATERIALS (str) or a Material")
    if value not in MATERIALS:
        raise ValueError(f"{parameter} must be one of {sorted(MATERIALS)} or a Material, "
                         f"got {value!r}")
    return MATERIALS[value]
