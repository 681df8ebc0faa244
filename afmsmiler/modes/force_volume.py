"""Force volume (peak-force style) mapping: a force curve per pixel, maps of the mechanics.

At every pixel the positioner ramps the sample up until the force reaches a peak force F_p and
back down by a ramp size (the curve of a peak-force tapping or force-volume map; Heu, Berquand,
Elie-Caille and Nicod, J. Struct. Biol. 178, 1 (2012); Dufrene et al., Nat. Nanotechnol. 12,
295 (2017)). The curve is module (d)'s: the approach-retract cycle of a
:class:`~afmsmiler.contact.ContactSystem` (Hertz/Sneddon with the lever in series, DMT or JKR
adhesion), or on a viscoelastic material (a standard linear solid) Lee-Radok/Ting's cycle of
:func:`~afmsmiler.contact.viscoelastic_approach_retract` at the positioner speed; Gaussian force
noise of RMS sigma is added to every sample. Each curve is analysed as the instrument does:

- **adhesion**: the pull-off force, minus the minimum of the retract;
- **modulus**: the retract's contact part (from the peak down to the jump-off, the largest
  upward step of the retract) has the adhesion added back, so that it is a Hertz curve with the
  free part as its baseline (the DMT analysis of peak-force QNM: F - F_adh = (4/3) E* sqrt(R)
  d^(3/2), Derjaguin, Muller and Toporov, J. Colloid Interface Sci. 53, 314 (1975)); that curve,
  in tip position x = Z_np - F / k, is fitted with module (d)'s
  :func:`~afmsmiler.contact.fit.fit_curves` (the batched form of
  :func:`~afmsmiler.contact.fit_curve`: E, contact point, baseline; the standard error of E
  from its covariance). Exact for DMT; on a JKR sample the contact part is not Hertz plus a
  constant and E comes out biased (the fit assumes DMT). The adhesion added back is the noisy
  minimum, off from the true pull-off force by a few sigma (and by the contact force at the
  last sample before the jump, at most the Hertz force of one ramp step): an offset between
  the contact part and the baseline that the fit's standard error does not see, so that the
  pixel-to-pixel scatter of a modulus map is a few times that standard error (as with the
  instrument's DMT analysis);
- **deformation**: the indentation at the peak force, x(F_p) - x_0 (x_0 the fitted contact
  point);
- **dissipation**: the area of the loop, the work the positioner does over the cycle,
  W = int_approach F dZ_np + int_retract F dZ_np (trapezoidal; >= 0: the energy the jumps of an
  adhesive contact and a viscoelastic sample take). The noise enters it linearly: with the
  trapezoid's weights w_i (half a step at the ends, a step inside) on both branches, independent
  noise of RMS sigma gives the area a Gaussian scatter of RMS sigma sqrt(2 sum w_i^2)
  (``ForceVolume.dissipation_noise``), so that a map of an elastic sample (W = 0) shows values
  of either sign.

The curves of one material differ only by their noise, so the model is run once per material
and the noise, the adhesion, the DMT correction and the loop area are vectorised over all
pixels; so is the fit: module (d)'s batched fit takes the curves of a material in blocks of
up to 2^20 points (a 64 x 64 map of 500-point curves takes about a second, of 2000-point curves
about four; ``benchmarks/bench_force_volume.py``).

:func:`two_material_sample` makes a polymer-blend-like sample: round islands of one material in a
matrix of another, with the label map.
"""
from __future__ import annotations

import functools
import math
from dataclasses import dataclass, field

import numpy as np

from .._steps import run_steps
from ..contact import ContactSystem, StandardLinearSolid, Tip, viscoelastic_approach_retract
from ..contact.fit import fit_curves
from ..contact.quantities import PARAMETERS as CONTACT
from ..imaging.scan_modes import Mode, ModeLine, ScanPlan
from ..parameters import Parameter, read_only
from ..samples import Sample
from ..samples.sample import check_shape
from ..validation import check_choice, check_instance, check_integer, check_range
from .jumping import Z_SPEED, _material_index, _sequence, trigger_z_np

__all__ = ["PARAMETERS", "SampleMaterial", "ForceVolume", "ForceVolumeMode", "force_volume",
           "force_volume_steps",
           "two_material_sample", "MAX_MAP_PIXELS", "MAX_POINTS", "MAX_MATERIALS",
           "MAX_ISLAND_WORK", "MAX_STRIDE",
           "ADHESION_MODELS", "BLEND"]

#: Most pixels of one map (64 x 64: with 2000-point curves, 8.2e6 points to fit, within the
#: batched fit's ``MAX_BATCH_POINTS``; about a second with 500-point curves).
MAX_MAP_PIXELS = 64 * 64
#: Most samples per branch of a pixel's curve.
MAX_POINTS = 2000
#: Most materials of one map.
MAX_MATERIALS = 16
#: Most pixels :func:`two_material_sample` paints in all (islands x their bounding boxes).
MAX_ISLAND_WORK = 1 << 26
#: The adhesion models the curves may use (module (d)'s).
ADHESION_MODELS = (None, "dmt", "jkr")
# curves are analysed (and fitted, in one batched call) in blocks of at most this many points,
# which bounds the analysis' working memory (some 10 arrays of 8 MB) whatever the map's size
_ANALYSIS_POINTS = 1 << 20
# the largest upward step of the retract is the jump-off only if it stands out of the noise
_JUMP_SIGMAS = 8.0

#: The mapping's user-settable quantities (SI): a 10 N/m lever (stiff enough that the force
#: noise, through F / k, hardly moves the tip position) ramped to 10 nN over 30 nm, 500 samples
#: per branch, 20 pN of force noise, at 20 um/s.
PARAMETERS = read_only({p.name: p for p in (
    CONTACT["spring_constant"].with_(default=10.0),
    Parameter(name="peak_force", unit="N", display_unit="nN", default=10e-9, low=0.0,
              high=1e-3, low_inclusive=False, slider_low=0.5e-9, slider_high=100e-9, log=True,
              label="peak force F_p"),
    Parameter(name="ramp_size", unit="m", display_unit="nm", default=30e-9, low=0.0, high=1e-5,
              low_inclusive=False, slider_low=5e-9, slider_high=500e-9, log=True,
              label="ramp size"),
    Parameter(name="points", unit="", default=500, low=20, high=MAX_POINTS, slider_low=50,
              slider_high=1000, log=True, label="samples per branch"),
    Parameter(name="force_noise", unit="N", display_unit="pN", default=20e-12, low=0.0,
              high=1e-6, slider_low=0.0, slider_high=500e-12, label="force noise (RMS)"),
    Z_SPEED,
)})


@dataclass(frozen=True)
class SampleMaterial:
    """The mechanics of one material of a mapped sample (SI units).

    Parameters
    ----------
    name : str
        What it is (for legends).
    youngs_modulus : float
        Young's modulus E in Pa (ignored when ``viscoelastic`` is given).
    poisson_ratio : float
        Poisson's ratio nu, in [0, 0.5).
    work_of_adhesion : float
        w in J/m^2, 0 (no adhesion) to 10.
    viscoelastic : afmsmiler.contact.StandardLinearSolid or None
        A standard linear solid (E_inf, E_0, tau): the curve is Lee-Radok/Ting's at the ramp's
        speed (no adhesion then).

    Raises
    ------
    ValueError
        Naming the value out of range, or a viscoelastic material with adhesion.
    TypeError
        If ``name`` is not a str or ``viscoelastic`` not a StandardLinearSolid.
    """

    name: str = "material"
    youngs_modulus: float = CONTACT["youngs_modulus"].default
    poisson_ratio: float = CONTACT["poisson_ratio"].default
    work_of_adhesion: float = 0.0
    viscoelastic: StandardLinearSolid | None = None

    def __post_init__(self):
        check_instance("name", self.name, str)
        s = object.__setattr__
        s(self, "youngs_modulus", CONTACT["youngs_modulus"].check(self.youngs_modulus))
        s(self, "poisson_ratio", CONTACT["poisson_ratio"].check(self.poisson_ratio))
        s(self, "work_of_adhesion", check_range("work_of_adhesion", self.work_of_adhesion, 0.0,
                                                CONTACT["work_of_adhesion"].high, "J/m^2"))
        if self.viscoelastic is not None:
            check_instance("viscoelastic", self.viscoelastic, StandardLinearSolid)
            if self.work_of_adhesion > 0:
                raise ValueError(f"work_of_adhesion must be 0 for a viscoelastic material (the "
                                 f"hereditary model has no adhesion), got "
                                 f"{self.work_of_adhesion:g} J/m^2")

    def system(self, tip: Tip, spring_constant: float, adhesion: str | None) -> ContactSystem:
        """Module (d)'s contact system of this material (E_inf for a viscoelastic one).

        Parameters
        ----------
        tip : afmsmiler.contact.Tip
            The tip.
        spring_constant : float
            Lever spring constant k in N/m.
        adhesion : {None, "dmt", "jkr"}
            Adhesion model (used where ``work_of_adhesion`` > 0).

        Returns
        -------
        afmsmiler.contact.ContactSystem

        Raises
        ------
        ValueError
            If ``adhesion`` is not one of :data:`ADHESION_MODELS` (or k is out of range).
        """
        check_choice("adhesion", adhesion, ADHESION_MODELS)
        e = (self.viscoelastic.relaxed_modulus if self.viscoelastic is not None
             else self.youngs_modulus)
        sticky = adhesion is not None and self.work_of_adhesion > 0
        return ContactSystem(spring_constant=spring_constant, tip=tip, youngs_modulus=e,
                             poisson_ratio=self.poisson_ratio,
                             adhesion=adhesion if sticky else None,
                             work_of_adhesion=self.work_of_adhesion if sticky else
                             CONTACT["work_of_adhesion"].default)


#: A polymer-blend-like pair: a stiff, weakly adhesive matrix (1 GPa, 20 mJ/m^2) and soft, sticky
#: islands (100 MPa, 60 mJ/m^2).
BLEND = (SampleMaterial("matrix", 1e9, 0.3, 0.02), SampleMaterial("islands", 100e6, 0.3, 0.06))


@dataclass(frozen=True)
class ForceVolume:
    """Maps of a force-volume measurement (:func:`force_volume`), arrays (rows, columns), SI.

    Parameters
    ----------
    modulus, modulus_error : numpy.ndarray
        Fitted Young's modulus E and its standard error in Pa (NaN where the fit failed).
    adhesion : numpy.ndarray
        Pull-off force in N (minus the retract's minimum).
    deformation : numpy.ndarray
        Indentation at the peak force in m.
    dissipation : numpy.ndarray
        Work per cycle in J (area of the loop).
    labels : numpy.ndarray
        The material index of each pixel (the truth the maps are compared with).
    pixel_size : float
        Pixel size in m.
    z_np : numpy.ndarray
        Each material's approach ramp of Z_np in m, (materials, points) (the retract runs it
        backwards), from the contact with the undeformed surface.
    approach, retract : numpy.ndarray
        Each material's noise-free approach and retract forces in N, (materials, points) (the
        retract in its own order, from the peak down).
    noise : float
        RMS force noise in N that was added.
    measured_approach, measured_retract : numpy.ndarray
        One pixel's curves per material as measured, noise included, in N, (materials, points)
        (the first pixel of each material in raster order; NaN for a material not on the map).
    dissipation_noise : numpy.ndarray
        Per material, the RMS in J of the scatter the noise alone gives the loop area,
        sigma sqrt(2 sum w_i^2) (module notes).
    """

    modulus: np.ndarray
    modulus_error: np.ndarray
    adhesion: np.ndarray
    deformation: np.ndarray
    dissipation: np.ndarray
    labels: np.ndarray
    pixel_size: float
    z_np: np.ndarray = field(repr=False)
    approach: np.ndarray = field(repr=False)
    retract: np.ndarray = field(repr=False)
    noise: float = 0.0
    measured_approach: np.ndarray | None = field(default=None, repr=False)
    measured_retract: np.ndarray | None = field(default=None, repr=False)
    dissipation_noise: np.ndarray | None = field(default=None, repr=False)

    @property
    def maps(self) -> dict:
        """Name -> :class:`~afmsmiler.samples.Sample` of each map (with its SI unit)."""
        units = {"modulus": "Pa", "adhesion": "N", "deformation": "m", "dissipation": "J"}
        return {name: Sample(getattr(self, name), self.pixel_size, name, channel=name,
                             unit=unit) for name, unit in units.items()}


def two_material_sample(shape=(64, 64), pixel_size: float = 20e-9, *,
                        island_radius: float = 150e-9, island_count: int = 6,
                        island_height: float = 5e-9, seed: int | None = 0):
    """A polymer-blend-like sample: round islands of material 1 in a matrix of material 0.

    Parameters
    ----------
    shape : tuple of int
        (rows, columns), each >= 2.
    pixel_size : float
        Pixel size in m, 1 pm to 1 mm.
    island_radius : float
        Radius of the islands in m, at least a pixel.
    island_count : int
        Number of islands, 1 to 1000 (they may overlap), with count x (pixels of an island's
        bounding box) at most :data:`MAX_ISLAND_WORK`.
    island_height : float
        Height of the islands above the matrix in m (any sign, |h| <= 1 mm).
    seed : int or None
        Seed of the islands' positions (numpy's default_rng).

    Returns
    -------
    (Sample, numpy.ndarray)
        The heights (their metadata list the islands' centres (x, y) in m) and the integer
        label map (0 matrix, 1 islands: the pixels within ``island_radius`` of a centre).

    Raises
    ------
    ValueError
        Naming the argument out of range.

    Examples
    --------
    >>> sample, labels = two_material_sample((32, 32), 20e-9, island_count=2, seed=1)
    >>> sample.heights.shape, sorted(set(labels.ravel().tolist()))
    ((32, 32), [0, 1])
    """
    shape = check_shape(shape)
    if len(shape) != 2:
        raise ValueError(f"shape must be (rows, columns), got {shape}")
    px = check_range("pixel_size", pixel_size, 1e-12, 1e-3, "m")
    radius = check_range("island_radius", island_radius, px, 1e-3, "m")
    count = check_integer("island_count", island_count, 1, 1000)
    height = check_range("island_height", island_height, -1e-3, 1e-3, "m")
    if seed is not None:
        seed = check_integer("seed", seed, 0, 2 ** 63 - 1)
    rows, cols = shape
    reach = int(math.ceil(radius / px)) + 1  # pixels from a centre to its disc's edge
    box = min(2 * reach + 1, rows) * min(2 * reach + 1, cols)
    if count * box > MAX_ISLAND_WORK:
        raise ValueError(f"island_count x the pixels of an island's box must be at most "
                         f"{MAX_ISLAND_WORK} (a bound the generator honours in seconds), got "
                         f"{count} x {box}")
    rng = np.random.default_rng(seed)
    centres = rng.uniform((0.0, 0.0), ((cols - 1) * px, (rows - 1) * px), size=(count, 2))
    labels = np.zeros(shape, dtype=int)
    for cx, cy in centres:  # bounded: count x box <= MAX_ISLAND_WORK pixels painted
        j0, i0 = int(cx / px), int(cy / px)
        i = np.arange(max(i0 - reach, 0), min(i0 + reach + 2, rows))
        j = np.arange(max(j0 - reach, 0), min(j0 + reach + 2, cols))
        inside = (j[None, :] * px - cx) ** 2 + (i[:, None] * px - cy) ** 2 <= radius * radius
        labels[i[0]:i[-1] + 1, j[0]:j[-1] + 1][inside] = 1
    sample = Sample(np.where(labels == 1, height, 0.0), px, "two-material sample",
                    metadata=dict(generator="two_material_sample", island_radius=radius,
                                  island_count=count, island_height=height,
                                  island_centres=centres.tolist()))
    return sample, labels


def _check_materials(materials):
    materials = _sequence("materials", materials, SampleMaterial)
    if not 1 <= len(materials) <= MAX_MATERIALS:
        raise ValueError(f"materials must hold 1 to {MAX_MATERIALS} SampleMaterials, got "
                         f"{len(materials)}")
    return tuple(check_instance("materials", m, SampleMaterial) for m in materials)


def _curves(materials, tip, k, peak_force, ramp_size, points, z_speed, adhesion):
    """Each material's ramp and noise-free approach and retract forces, (materials, points)."""
    ramps, app, ret = [], [], []
    for i, m in enumerate(materials):
        system = m.system(tip, k, adhesion)
        z_peak = trigger_z_np(system, peak_force)
        off = z_peak - min(system.snap_off_z_np, 0.0)
        if ramp_size <= off:
            raise ValueError(f"ramp_size must be > {off:g} m so that the tip leaves material "
                             f"{i} ({m.name!r}) on every retract, got {ramp_size:g} m")
        z = np.linspace(z_peak - ramp_size, z_peak, points)
        if m.viscoelastic is not None:
            cycle = viscoelastic_approach_retract(z, k, tip, m.viscoelastic, m.poisson_ratio,
                                                  z_speed)
            retract = np.interp(z[::-1], cycle.retract.z_np[::-1], cycle.retract.force[::-1])
        else:
            cycle = system.approach_retract(z)
            retract = cycle.retract.force
        ramps.append(z)
        app.append(cycle.approach.force)
        ret.append(retract)
    return np.array(ramps), np.array(app), np.array(ret)


#: Largest ``stride`` of a coarse map (:func:`force_volume`).
MAX_STRIDE = 8

#: How many sets of noise-free curves :func:`force_volume` keeps (a move of the noise, the only
#: slider that leaves them unchanged, reuses them; see :func:`_noise_free_curves`).
CURVE_CACHE = 8


@functools.lru_cache(maxsize=CURVE_CACHE)
def _cached_curves(materials, tip, k, peak_force, ramp_size, points, z_speed, adhesion):
    out = _curves(materials, tip, k, peak_force, ramp_size, points, z_speed, adhesion)
    for a in out:
        a.setflags(write=False)  # shared by every map made with these arguments
    return out


def _noise_free_curves(materials, tip, k, peak_force, ramp_size, points, z_speed, adhesion):
    """:func:`_curves`, remembered for the last :data:`CURVE_CACHE` sets of arguments.

    The noise-free curves depend on the materials, the tip, k, the peak force, the ramp, the
    points, the speed and the adhesion model, and not on the noise or its seed: a map made
    again with another noise (the force-volume panel's noise slider) reuses them. The arrays
    are read-only. Arguments that cannot be hashed are computed afresh each time.
    """
    args = (tuple(materials), tip, float(k), float(peak_force), float(ramp_size), int(points),
            float(z_speed), adhesion)
    try:
        hash(args)
    except TypeError:
        return _curves(*args)
    return _cached_curves(*args)


#: How many seeds' noise records :func:`force_volume` keeps (see :func:`_unit_noise`).
NOISE_CACHE = 4


def _unit_noise(seed, pixels: int, points: int) -> np.ndarray:
    """The map's noise of ``seed`` in units of its RMS: (2, pixels, points), approach then retract.

    numpy's ``Generator.normal(0, sigma, size)`` draws ``0 + sigma * z`` from the same standard
    normal draws z as ``standard_normal(size)`` (``random_normal`` in numpy's
    ``distributions.c``), and two draws of (pixels, points) follow each other in one stream as
    the two halves of (2, pixels, points) do: sigma times these records is the noise the map
    drew before, bit for bit (tested against ``normal``). A seeded record of at most
    ``_ANALYSIS_POINTS`` values is kept for the next maps (the last :data:`NOISE_CACHE`, read-only):
    a move of the force-volume panel's noise or peak force draws no noise (some 2 ms of its
    coarse map's 10-15). Without a seed it is drawn afresh.
    """
    if seed is None or 2 * pixels * points > _ANALYSIS_POINTS:
        return np.random.default_rng(seed).standard_normal((2, pixels, points))
    return _cached_unit_noise(seed, pixels, points)


@functools.lru_cache(maxsize=NOISE_CACHE)
def _cached_unit_noise(seed: int, pixels: int, points: int) -> np.ndarray:
    out = np.random.default_rng(seed).standard_normal((2, pixels, points))
    out.setflags(write=False)  # shared by every map of this seed and size
    return out


def _analyse(z, f_app, f_ret, k, sigma, tip, nu):
    """Adhesion, modulus (and error), deformation and dissipation of curves (pixels, points).

    ``z`` (pixels, points) is each curve's approach ramp; the retract runs it backwards; ``nu``
    (pixels,) each pixel's Poisson's ratio.

    The curves of every material are fitted in one call of module (d)'s batched fit, with nu = 0:
    the fit's model and residuals depend on the reduced modulus E* = E / (1 - nu^2) only (Hertz,
    Johnson 1985, eq. 4.22), so its E* is nu's, and each pixel's E and its error are that E* and
    its error times its own 1 - nu^2 (equal to a fit with the material's nu, tested): one batch
    of Levenberg-Marquardt steps instead of one per material.
    """
    n_pix = f_app.shape[0]
    z_ret = z[:, ::-1]
    adhesion = -np.min(f_ret, axis=1)
    # loop area: the positioner's work over the cycle (the retract's dZ is negative)
    dissipation = np.trapezoid(f_app, z, axis=1) + np.trapezoid(f_ret, z_ret, axis=1)
    # the jump-off: the largest upward step of the retract, where it stands out of the noise
    steps = np.diff(f_ret, axis=1)
    jump = np.argmax(steps, axis=1)
    sticky = steps[np.arange(n_pix), jump] > _JUMP_SIGMAS * math.sqrt(2.0) * sigma + 1e-300
    contact = np.arange(f_ret.shape[1])[None, :] <= jump[:, None]
    corrected = np.where(sticky[:, None] & contact, f_ret + adhesion[:, None], f_ret)
    x = z_ret - f_ret / k  # tip position, from the measured deflection
    x_peak = x[:, 0]
    # module (d)'s fit of all these curves at once (NaN where no contact shows above the noise)
    fits = fit_curves(x, corrected, tip, 0.0)
    reduced = 1.0 - np.asarray(nu, dtype=float) ** 2
    return (adhesion, fits.youngs_modulus * reduced, fits.youngs_modulus_error * reduced,
            x_peak - fits.contact_point, dissipation)


def force_volume(sample: Sample, materials, tip: Tip, *, labels,
                 spring_constant: float = PARAMETERS["spring_constant"].default,
                 peak_force: float = PARAMETERS["peak_force"].default,
                 ramp_size: float = PARAMETERS["ramp_size"].default,
                 points: int = int(PARAMETERS["points"].default),
                 force_noise: float = PARAMETERS["force_noise"].default,
                 z_speed: float = PARAMETERS["z_speed"].default,
                 adhesion: str | None = "dmt", seed: int | None = None,
                 stride: int = 1) -> ForceVolume:
    """A force curve at every pixel of ``sample``, analysed into maps (see the module notes).

    Parameters
    ----------
    sample : afmsmiler.samples.Sample
        The sample (2-D, at most :data:`MAX_MAP_PIXELS` pixels); each pixel's ramp starts from
        its own surface, so the heights do not change the curves.
    materials : SampleMaterial or sequence of SampleMaterial
        The mechanics of each material (1 to :data:`MAX_MATERIALS`).
    tip : afmsmiler.contact.Tip
        The tip (DMT or JKR need a parabolic or spherical one).
    labels : array_like of int
        Material index of each pixel, shaped like the sample.
    spring_constant : float
        Lever spring constant k in N/m.
    peak_force : float
        Peak force F_p in N at which every approach turns.
    ramp_size : float
        Travel of the positioner per branch in m; it must take the tip off every material.
    points : int
        Samples per branch, 20 to :data:`MAX_POINTS`.
    force_noise : float
        RMS of the Gaussian force noise in N added to every sample.
    z_speed : float
        Positioner speed in m/s (only a viscoelastic material's curve depends on it).
    adhesion : {None, "dmt", "jkr"}
        Adhesion model of the materials with a work of adhesion.
    seed : int or None
        Seed of the noise.
    stride : int
        Analyse every ``stride``-th pixel of every ``stride``-th row only, 1 to
        :data:`MAX_STRIDE`: a coarse map for a quick look (a panel shows it while the full map is
        computed). Every pixel's curves and noise are made as in the full map, so each pixel
        analysed has exactly the full map's values; the maps hold those pixels, ``pixels[::stride,
        ::stride]`` of the full map, with a pixel size ``stride`` times the sample's.

    Returns
    -------
    ForceVolume

    Raises
    ------
    TypeError
        If ``sample``, ``tip`` or a material is of the wrong type.
    ValueError
        Naming the argument out of range (a ramp too short to take the tip off, labels of
        another shape or outside the materials, too many pixels), before any curve is made.

    Examples
    --------
    >>> from afmsmiler.contact import Parabolic
    >>> sample, labels = two_material_sample((8, 8), 20e-9, island_radius=60e-9,
    ...                                      island_count=1, seed=3)
    >>> fv = force_volume(sample, BLEND, Parabolic(radius=10e-9), labels=labels, seed=0)
    >>> bool(abs(np.nanmedian(fv.modulus[labels == 0]) / 1e9 - 1) < 0.05)
    True
    """
    steps = force_volume_steps(sample, materials, tip, labels=labels,
                               spring_constant=spring_constant, peak_force=peak_force,
                               ramp_size=ramp_size, points=points, force_noise=force_noise,
                               z_speed=z_speed, adhesion=adhesion, seed=seed, stride=stride)
    # the curves' step, a step per block of at least one pixel, and the maps'
    return run_steps(steps, MAX_MAP_PIXELS + 2, "force_volume_steps")


def force_volume_steps(sample: Sample, materials, tip: Tip, *, labels,
                       spring_constant: float = PARAMETERS["spring_constant"].default,
                       peak_force: float = PARAMETERS["peak_force"].default,
                       ramp_size: float = PARAMETERS["ramp_size"].default,
                       points: int = int(PARAMETERS["points"].default),
                       force_noise: float = PARAMETERS["force_noise"].default,
                       z_speed: float = PARAMETERS["z_speed"].default,
                       adhesion: str | None = "dmt", seed: int | None = None,
                       stride: int = 1, block_pixels: int | None = None):
    """:func:`force_volume` in steps: a generator that analyses one block of pixels per step.

    Every argument is checked when this is called, before any work; each ``next()`` then makes
    the curves (first step) or analyses the next ``block_pixels`` pixels, and the last one
    returns the :class:`ForceVolume` (``StopIteration.value``). :func:`force_volume` is these
    steps run to their end in blocks as large as memory allows; each pixel's curves and noise
    are made as in the whole map, and module (d)'s batched fit follows each curve on its own
    (it leaves the batch once converged), so smaller blocks give the same maps: bit for bit on
    maps like the course's (tested), within round-off where a curve's normal equations are
    singular (the fit then takes the pseudo-inverse step for every curve of that block's
    iteration, ``contact.fit._solve_rows``). A panel runs a step per turn of the kernel's
    loop, so that a slider move waits for one block, not for the whole map.

    Parameters
    ----------
    sample, materials, tip, labels, spring_constant, peak_force, ramp_size, points, force_noise,
    z_speed, adhesion, seed, stride
        As :func:`force_volume`.
    block_pixels : int, optional
        Pixels analysed per step, 1 to :data:`MAX_MAP_PIXELS`; default: as many as the
        analysis' working memory allows (``_ANALYSIS_POINTS`` values): for a map of the
        course's size one step makes the curves and one analyses every pixel.

    Returns
    -------
    generator
        Yields the number of pixels analysed so far after each step; returns the ForceVolume.

    Raises
    ------
    TypeError, ValueError
        As :func:`force_volume`, and for ``block_pixels`` out of range, when called; a ramp too
        short to take the tip off a material is found when the curves are made, at the first
        step.
    """
    check_instance("sample", sample, Sample)
    materials = _check_materials(materials)
    check_instance("tip", tip, Tip)
    h = sample.heights
    if h.ndim != 2:
        raise ValueError(f"sample must be a 2-D image, got heights of shape {h.shape}")
    if h.size > MAX_MAP_PIXELS:
        raise ValueError(f"sample must have at most {MAX_MAP_PIXELS} pixels (one fit each, a "
                         f"bound the map honours in seconds), got {h.shape}")
    lab = np.array(labels)  # a copy: the checked labels are the ones the steps use
    if lab.shape != h.shape or lab.dtype.kind not in "iu" or lab.min() < 0 or \
            lab.max() >= len(materials):
        raise ValueError(f"labels must be integers in [0, {len(materials) - 1}] shaped like the "
                         f"sample {h.shape}, got {lab.dtype} {lab.shape}")
    p = PARAMETERS
    k = p["spring_constant"].check(spring_constant)
    f_p = p["peak_force"].check(peak_force)
    ramp = p["ramp_size"].check(ramp_size)
    n = check_integer("points", points, int(p["points"].low), int(p["points"].high))
    sigma = p["force_noise"].check(force_noise)
    v = p["z_speed"].check(z_speed)
    check_choice("adhesion", adhesion, ADHESION_MODELS)
    if adhesion is not None and any(m.work_of_adhesion > 0 for m in materials) \
            and not tip.adhesive:
        raise ValueError(f"adhesion {adhesion!r} needs a parabolic or spherical tip, got "
                         f"{type(tip).__name__}")
    if seed is not None:
        seed = check_integer("seed", seed, 0, 2 ** 63 - 1)
    stride = check_integer("stride", stride, 1, MAX_STRIDE)
    rows = max(1, _ANALYSIS_POINTS // n)  # the working memory's bound
    if block_pixels is not None:
        rows = min(rows, check_integer("block_pixels", block_pixels, 1, MAX_MAP_PIXELS))
    return _force_volume_steps(sample, materials, tip, lab, k, f_p, ramp, n, sigma, v,
                               adhesion, seed, stride, rows)


def _force_volume_steps(sample, materials, tip, lab, k, f_p, ramp, n, sigma, v, adhesion, seed,
                        stride, rows):
    """The work of :func:`force_volume_steps`, of checked arguments (a generator)."""
    h = sample.heights
    z, app, ret = _noise_free_curves(materials, tip, k, f_p, ramp, n, v, adhesion)
    flat = lab.ravel()
    f_app, f_ret = app[flat], ret[flat]
    if sigma:
        noise = _unit_noise(seed, flat.size, n)
        f_app = f_app + sigma * noise[0]
        f_ret = f_ret + sigma * noise[1]
    nu = np.array([m.poisson_ratio for m in materials])
    analysed = np.zeros(h.shape, bool)
    analysed[::stride, ::stride] = True
    analysed = analysed.ravel()
    out = [np.full(flat.size, np.nan) for _ in range(5)]
    pixels = np.flatnonzero(analysed)
    yield 0  # the curves are made
    for start in range(0, pixels.size, rows):  # bounded: MAX_MAP_PIXELS / rows blocks
        block = pixels[start:start + rows]
        for arr, values in zip(out, _analyse(z[flat[block]], f_app[block], f_ret[block], k,
                                             sigma, tip, nu[flat[block]])):
            arr[block] = values
        yield start + block.size
    adh, modulus, error, deformation, dissipation = (a.reshape(h.shape)[::stride, ::stride]
                                                     for a in out)
    # one pixel's measured curves per material, and the loop area's scatter from the noise
    measured_app = np.full(app.shape, np.nan)
    measured_ret = np.full(ret.shape, np.nan)
    for m in range(len(materials)):
        pixels = np.flatnonzero(flat == m)
        if pixels.size:
            measured_app[m] = f_app[pixels[0]]
            measured_ret[m] = f_ret[pixels[0]]
    weights = np.abs(np.diff(z, axis=1))  # the trapezoid's weights: half a step at the ends
    w = np.zeros_like(z)
    w[:, :-1] += 0.5 * weights
    w[:, 1:] += 0.5 * weights
    noise_w = sigma * np.sqrt(2.0 * np.sum(w * w, axis=1))
    return ForceVolume(modulus, error, adh, deformation, dissipation,
                       lab[::stride, ::stride].copy(), sample.pixel_size * stride, z, app, ret,
                       sigma, measured_app, measured_ret, noise_w)


class ForceVolumeMode(Mode):
    """Force-volume mapping as an imaging mode of module (f)'s scanner.

    Parameters
    ----------
    materials : SampleMaterial or sequence of SampleMaterial
        The mechanics of each material.
    tip : afmsmiler.contact.Tip
        The tip (give the scanner the same one).
    material : callable, optional
        ``material(x, y)`` -> integer array (index into ``materials``) at positions x, y in m on
        the sample; default: the first everywhere.
    **settings
        Keyword arguments of :func:`force_volume` (``spring_constant``, ``peak_force``,
        ``ramp_size``, ``points``, ``force_noise``, ``z_speed``, ``adhesion``, ``seed``).

    Raises
    ------
    TypeError, ValueError
        As :func:`force_volume`, checked at construction on a one-pixel map.

    Notes
    -----
    Channels (trace only: a force-volume map is taken in one pass): ``"height trace"`` (the
    apex surface: each curve's contact point is found at the surface), ``"modulus trace"`` (Pa),
    ``"adhesion trace"`` (N), ``"deformation trace"`` (m), ``"dissipation trace"`` (J). Each
    line is one :func:`force_volume` of its pixels (the noise seeded from ``seed`` and the
    line).
    """

    channels = ("height trace", "modulus trace", "adhesion trace", "deformation trace",
                "dissipation trace")
    units = read_only({"modulus trace": "Pa", "adhesion trace": "N", "dissipation trace": "J"})

    def __init__(self, materials, tip: Tip, *, material=None, **settings):
        self.materials = _check_materials(materials)
        self.tip = check_instance("tip", tip, Tip)
        if material is not None and not callable(material):
            raise TypeError(f"material must be a callable material(x, y), got "
                            f"{type(material).__name__}")
        self.material = material
        unknown = set(settings) - {"spring_constant", "peak_force", "ramp_size", "points",
                                   "force_noise", "z_speed", "adhesion", "seed"}
        if unknown:
            raise TypeError(f"unknown settings {sorted(unknown)}")
        self.settings = dict(settings)
        # every argument checked now, on a one-pixel map per material (before any scan)
        for i in range(len(self.materials)):
            force_volume(Sample(np.zeros((1, 2)), 1e-9), self.materials, tip,
                         labels=np.full((1, 2), i), **{**self.settings, "force_noise": 0.0})

    def __repr__(self) -> str:
        return f"ForceVolumeMode({[m.name for m in self.materials]}, {self.tip!r})"

    def line(self, plan: ScanPlan, row: int, state=None) -> ModeLine:
        """One line of maps (trace only).

        Parameters
        ----------
        plan : afmsmiler.imaging.scan_modes.ScanPlan
            The scan.
        row : int
            Line index.
        state : None
            What :meth:`start` returned and each line passes on: None (a force-volume line
            carries nothing over from the previous one).

        Returns
        -------
        afmsmiler.imaging.scan_modes.ModeLine

        Raises
        ------
        TypeError
            If ``plan`` is not a ScanPlan or ``state`` is not None.
        ValueError
            If ``row`` is not a line of the plan.
        """
        row = self._row(plan, row)
        if state is not None:
            raise TypeError(f"state must be None (what ForceVolumeMode.start returns: nothing "
                            f"carries over between lines), got {type(state).__name__}")
        x, y = plan.x_trace[row], plan.y_trace[row]
        lab = _material_index(self.material, x, y, len(self.materials))
        settings = dict(self.settings)
        if settings.get("seed") is not None:
            settings["seed"] = (settings["seed"] + 7919 * row) % 2 ** 63
        fv = force_volume(Sample(np.zeros((1, x.size)), plan.pixel_size), self.materials,
                          self.tip, labels=lab[None, :], **settings)
        return ModeLine({"height trace": plan.trace[row].copy(),
                         "modulus trace": fv.modulus[0], "adhesion trace": fv.adhesion[0],
                         "deformation trace": fv.deformation[0],
                         "dissipation trace": fv.dissipation[0]}, state)
