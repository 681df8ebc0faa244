"""The fast steady states of the tapping lever: first-harmonic balance, both branches.

The fast solver (:func:`amplitude_curve`). With z = A cos(theta), theta = w t - phi, projecting
the equation of motion (:mod:`~afmsmiler.modes.tapping.lever`) on cos(theta) and sin(theta) over
one period (the virial and energy-balance equations of San Paulo and Garcia, Phys. Rev. B 64,
193411 (2001); Lee and Jhe, Phys. Rev. Lett. 97, 036104 (2006) in the same form)::

    F0 cos(phi) = k (1 - W^2) A - I_c(z_c, A),     I_c = (1/pi) int_0^2pi F_ts cos(theta) d theta
    F0 sin(phi) = (k W / Q) A + I_s(z_c, A),       I_s = (1/pi) int_0^2pi F_ts sin(theta) d theta

so the amplitude solves g(A) = |(k (1 - W^2) A - I_c, (k W / Q) A + I_s)| - F0 = 0. I_c > 0 is
a net attraction (phi above the free phase), I_c < 0 a net repulsion. Where two stable roots
coexist, the lower is the attractive (L) branch and the higher the repulsive (H) one (whose net
force turns attractive at its far end); a slow approach or retraction follows its branch until
it ends and jumps there (:meth:`AmplitudeCurve.sweep`). The names say the sign of the net force
over a cycle, not whether the tip touches: the tip touches where its closest distance z_c - A
falls below a0 (:meth:`TappingLever.indentation`), on the whole repulsive branch and, at the
defaults, on the attractive branch too near its end (at A0 = 12 nm and z_c between about 9.5 and
11.7 nm it dips up to 0.4 nm into the sample while the attraction still wins). Since I_s >= 0
(damping only takes energy), every root lies in (0, F0 Q / (k W)] (= A0 at resonance). Each I
is evaluated in closed form without contact (I_c = (H R / 3) A / (z_c^2 - A^2)^(3/2)) and by Gauss-Legendre quadrature over
the two parts of the period with contact (the contact part in the variable s, theta = theta_c +
(pi - theta_c) s^2, which makes the square-root edge smooth). All roots at every z_c are found at
once: g on a grid of :data:`AMPLITUDE_GRID` even steps up to A_max (and 11 geometric steps
from 1e-5 A_max up to the first), every sign change refined by the Illinois
method, all vectorised over z_c. A root is stable where g rises through zero (dg/dA > 0: the
slow flow of the averaged equations pushes a slightly larger amplitude back down; the middle of
three roots is the saddle; Nayfeh and Mook, *Nonlinear Oscillations* (1979)). Two roots
closer than one grid step (at the very ends of a coexistence region) can be missed; the region
then looks at most one grid step (A_max / AMPLITUDE_GRID) shorter in amplitude.

The energy the sample takes per cycle follows from the phase (energy balance: the drive's work
pi F0 A sin(phi) minus the lever's damping pi k W A^2 / Q; Cleveland et al., Appl. Phys. Lett. 72,
2613 (1998))::

    E_dis = pi F0 A sin(phi) - pi k W A^2 / Q = (pi k A^2 / Q) [(A0 / A) sin(phi) - W]   (W = 1)

in the convention that the phase lag phi is 90 deg for the free lever at resonance and that
positive E_dis is energy lost to the sample. At a root the balance makes it pi A I_s, the
difference of two nearly equal terms: where the sample takes nothing (out of contact, or no
viscosity) the formula leaves round-off, some 1e-11 zJ of either sign. Its accuracy is bounded
per root (``AmplitudeCurve.dissipated_energy_error``): the root's residual g(A) leaves
pi A S |g| / F0 (sin(phi) = S / (F0 + g)), and the rounding at most
:data:`DISSIPATION_ROUNDINGS` units of round-off eps of each term: of phi (a rounding of phi
moves F0 sin(phi) by F0 |cos(phi)| eps (|phi| + 1), which near phi = pi, where sin(phi) is
small, outweighs the term itself), of F0 sin(phi) and of k W A / Q. An E_dis within that bound
is zero within the model's accuracy and is returned as 0 (:func:`operating_point` interpolates
these values). The first-harmonic balance leaves out the static
deflection <F_ts> / k and the higher harmonics; for a stiff lever of high Q (k = 40 N/m, Q = 400,
the defaults) both move A by well under 1 % (the tests compare it with the time integration).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..._steps import run_steps
from ...validation import check_array, check_choice, check_instance, check_integer
from .lever import PARAMETERS, TappingLever, _check_lever

__all__ = ["BRANCHES", "AMPLITUDE_GRID", "MAX_DISTANCES", "DISSIPATION_ROUNDINGS",
           "SETPOINT_GRID", "SWEEPS", "AmplitudeCurve", "amplitude_curve",
           "amplitude_curve_steps", "setpoint_state", "operating_point"]

#: The two branches of the amplitude-distance curve.
BRANCHES = ("attractive", "repulsive")
#: The two slow sweeps of the rest distance (:meth:`AmplitudeCurve.sweep`).
SWEEPS = ("approach", "retract")
#: Amplitudes on which g(A) is sampled for its sign changes, per distance.
AMPLITUDE_GRID = 160
#: Most distances one :func:`amplitude_curve` call solves (10 000 take about a second).
MAX_DISTANCES = 10_000
#: Rounded operations in E_dis = pi A (F0 sin(phi) - k W A / Q) from the balance's (P, S): P
#: and S (1 each, as they enter atan2), atan2 (2 ulp), sin (1), F0 sin (1), k W A / Q (3, one
#: counted with the difference); pi A outside scales both terms alike. Each contributes at most
#: one unit of round-off (eps) of the quantity it rounds.
DISSIPATION_ROUNDINGS = 8

# Gauss-Legendre nodes on the free and the contact part of a half period
_FREE_NODES, _CONTACT_NODES = 32, 16
_X_FREE, _W_FREE = np.polynomial.legendre.leggauss(_FREE_NODES)
_X_CONTACT, _W_CONTACT = np.polynomial.legendre.leggauss(_CONTACT_NODES)
_T_FREE = 0.5 * (_X_FREE + 1.0)  # theta / theta_c at the free part's nodes
_S_CONTACT = 0.5 * (_X_CONTACT + 1.0)  # s at the contact part's nodes
_S2_CONTACT = _S_CONTACT * _S_CONTACT
_WS_CONTACT = _W_CONTACT * _S_CONTACT
_ILLINOIS_STEPS = 40
# the amplitude grid as a fraction of the largest amplitude: AMPLITUDE_GRID even steps, below the
# first of them a geometric run down to 1e-5 (the small amplitudes of a tip held near the sample)
_GRID = np.concatenate((np.geomspace(1e-5, 1.0 / AMPLITUDE_GRID, 12)[:-1],
                        np.arange(1, AMPLITUDE_GRID + 1) / AMPLITUDE_GRID))


# -- the first-harmonic integrals -----------------------------------------------------------------
def _integrals(lever: TappingLever, zc: np.ndarray, a: np.ndarray):
    """I_c and I_s in N for arrays of distances and amplitudes of one shape (a > 0).

    The module notes' quadratures, their weighted sums taken with ``einsum`` (one pass over
    the nodes), sin^2 = 1 - cos^2 at the contact nodes and temporaries reused in place (issue
    24: the grid of the tapping panel's curve, 68 400 points, in some 20 % less time).
    """
    hr = lever.hamaker_constant * lever.radius
    a0 = lever.intermolecular_distance
    i_c = np.empty_like(a)
    i_s = np.zeros_like(a)
    u = (a0 - zc) / a  # cos(theta_c): contact where cos(theta) < u
    free = u <= -1.0
    if free.any():
        z, b = zc[free], a[free]
        gap2 = z * z - b * b
        i_c[free] = hr / 3.0 * b / (gap2 * np.sqrt(gap2))  # (z^2 - A^2)^(3/2), without pow
    touch = ~free
    if touch.any():
        z, b = zc[touch, None], a[touch, None]
        tc = np.arccos(np.clip(u[touch], -1.0, 1.0))
        # free part, theta in [0, theta_c] (empty when the tip never leaves the sample):
        # sum_j W_j (-HR / 6) cos(theta_j) / d_j^2 * theta_c / 2, d = z_c + A cos(theta)
        c = np.multiply.outer(tc, _T_FREE)
        np.cos(c, out=c)
        d = b * c
        d += z
        d *= d
        np.divide(c, d, out=c)
        free_part = np.einsum("ij,j->i", c, _W_FREE) * (-hr / 6.0 * 0.5) * tc
        # contact part, theta = theta_c + (pi - theta_c) s^2, s in [0, 1], Jacobian
        # 0.5 (GL on [0, 1]) * 2 s span: sum_j (W_j s_j) f(theta_j) * span
        span = math.pi - tc
        c = np.multiply.outer(span, _S2_CONTACT)
        c += tc[:, None]
        np.cos(c, out=c)
        delta = b * c
        np.subtract(a0 - z, delta, out=delta)
        np.maximum(delta, 0.0, out=delta)
        sq = np.sqrt(lever.radius * delta)
        delta *= sq  # delta^(3/2) sqrt(R)
        delta *= c
        elastic = np.einsum("ij,j->i", delta, _WS_CONTACT) * span * \
            (4.0 / 3.0 * lever.reduced_modulus)
        # the constant adhesion integrates exactly: int_{theta_c}^{pi} cos = -sin(theta_c)
        contact_part = -hr / (6.0 * a0 * a0) * (-np.sin(tc)) + elastic
        i_c[touch] = 2.0 / math.pi * (free_part + contact_part)
        if lever.sample_viscosity > 0.0:
            w = 2.0 * math.pi * lever.resonance_frequency * lever.frequency_ratio
            c *= c
            np.subtract(1.0, c, out=c)  # sin^2(theta)
            c *= sq
            i_s[touch] = (2.0 / math.pi * w * lever.sample_viscosity) * b[:, 0] * span * \
                np.einsum("ij,j->i", c, _WS_CONTACT)
    return i_c, i_s


def _balance(lever: TappingLever, zc, a):
    """(g, P, S): g = |(P, S)| - F0 with P = F0 cos(phi), S = F0 sin(phi) of amplitude a."""
    i_c, i_s = _integrals(lever, zc, a)
    k, w, q = lever.spring_constant, lever.frequency_ratio, lever.quality_factor
    p = k * (1.0 - w * w) * a - i_c
    s = k * w / q * a + i_s
    return np.hypot(p, s) - lever.drive_force, p, s


@dataclass(frozen=True)
class AmplitudeCurve:
    """Every steady state of the first-harmonic balance at each distance (SI units).

    Arrays are (distances, roots), roots in increasing amplitude, NaN where a distance has fewer
    roots than the most any distance has.

    Parameters
    ----------
    lever : TappingLever
        The lever and sample.
    distance : ndarray, shape (n,)
        Rest tip-sample distances z_c in m.
    amplitude : ndarray, shape (n, r)
        Amplitudes A in m.
    phase : ndarray, shape (n, r)
        Phase lags phi in rad (pi / 2 for the free lever at resonance).
    stable : ndarray of bool, shape (n, r)
        Whether each root is stable.
    attractive : ndarray of bool, shape (n, r)
        Whether the net interaction over a cycle is attractive (I_c > 0, phase lag above the
        free one; else repulsive).
    repulsive_branch : ndarray of bool, shape (n, r)
        Whether a stable root lies on the high-amplitude (repulsive, H) branch rather than the
        low (attractive, L) one: the higher of two coexisting stable roots, or a lone stable
        root with a net repulsion. (At the far end of the H branch its net force turns
        attractive while it is still the higher root.)
    dissipated_energy : ndarray, shape (n, r)
        E_dis in J per cycle from the phase; 0 where it is zero within
        ``dissipated_energy_error``.
    dissipated_energy_error : ndarray, shape (n, r)
        The bound in J of E_dis's error at each root: the root's residual and the formula's
        round-off (module notes); NaN where there is no root.
    """

    lever: TappingLever
    distance: np.ndarray
    amplitude: np.ndarray
    phase: np.ndarray
    stable: np.ndarray
    attractive: np.ndarray
    repulsive_branch: np.ndarray
    dissipated_energy: np.ndarray
    dissipated_energy_error: np.ndarray

    def branch(self, name: str) -> tuple[np.ndarray, np.ndarray]:
        """Amplitude and phase of the stable root on one branch at each distance (NaN if none).

        Parameters
        ----------
        name : str
            ``"attractive"`` (low) or ``"repulsive"`` (high).

        Returns
        -------
        (ndarray, ndarray)
            A in m and phi in rad, shape (n,); where a branch has two stable roots (rare), the
            one of largest amplitude.
        """
        return self.on_branch(self.amplitude, name), self.on_branch(self.phase, name)

    def on_branch(self, values, name: str) -> np.ndarray:
        """One root's entry of ``values`` per distance: the stable root :meth:`branch` picks.

        So that a quantity of each root (``dissipated_energy``, ``indentation``, ...) lines up
        with the branch's amplitude and phase.

        Parameters
        ----------
        values : array_like
            An array shaped like ``amplitude`` (n, r).
        name : str
            ``"attractive"`` (low) or ``"repulsive"`` (high).

        Returns
        -------
        ndarray
            Shape (n,), NaN where the branch has no stable root; where it has two (rare), the
            one of largest amplitude.

        Raises
        ------
        ValueError
            If ``values`` is not shaped like ``amplitude`` or ``name`` is not a branch.
        """
        check_choice("name", name, BRANCHES)
        try:  # NaN where a curve has no root, so not check_array (finite values only)
            values = np.asarray(values)
            if values.dtype.kind not in "biuf":
                raise TypeError
            values = values.astype(float)
        except (TypeError, ValueError):
            raise TypeError(f"values must be an array of real numbers, got "
                            f"{type(values).__name__}") from None
        if values.shape != self.amplitude.shape:
            raise ValueError(f"values must be shaped like the curve's amplitude "
                             f"{self.amplitude.shape}, got {values.shape}")
        mask = self.stable & (~self.repulsive_branch if name == "attractive"
                              else self.repulsive_branch)
        j = np.argmax(np.where(mask, self.amplitude, -np.inf), axis=1)
        rows = np.arange(self.distance.size)
        return np.where(mask.any(axis=1), values[rows, j], np.nan)

    @property
    def indentation(self) -> np.ndarray:
        """Deepest indentation a0 - (z_c - A) in m of each root, shaped like ``amplitude``.

        Positive where that state's tip touches the sample once per cycle
        (:meth:`TappingLever.indentation`), NaN where there is no root.
        """
        return self.lever.intermolecular_distance - (self.distance[:, None] - self.amplitude)

    @property
    def coexist(self) -> np.ndarray:
        """Distances where both branches have a stable root, as a bool mask (n,)."""
        a, _ = self.branch("attractive")
        r, _ = self.branch("repulsive")
        return np.isfinite(a) & np.isfinite(r)

    def sweep(self, direction: str = "approach"):
        """The state a slow approach (or retraction) follows, with its jump.

        The tip stays on the branch it is on (the lower or the higher of two coexisting stable
        roots) while that branch exists; where it ends (two stable roots become one, nearer the
        other branch's amplitude) it jumps. The approach starts far away, on the low branch;
        the retraction starts close in, on the highest stable root.

        Parameters
        ----------
        direction : str
            ``"approach"`` (decreasing z_c) or ``"retract"`` (increasing z_c).

        Returns
        -------
        (ndarray, ndarray, list of float)
            Amplitude in m and phase lag in rad at each distance (in this curve's order), and
            the distances in m at which the tip jumped between branches. Each direction is
            followed once per curve (the arrays are read-only; :attr:`jumps` reads the same
            run).
        """
        check_choice("direction", direction, SWEEPS)
        cache = self.__dict__.setdefault("_sweeps", {})  # the frozen curve's own memo
        if direction not in cache:
            amp, phs, jumps = self._sweep(direction)
            amp.setflags(write=False)
            phs.setflags(write=False)
            cache[direction] = (amp, phs, tuple(jumps))
        amp, phs, jumps = cache[direction]
        return amp, phs, list(jumps)

    @property
    def jumps(self) -> dict:
        """Where a slow approach and a slow retraction jump between the branches.

        Returns
        -------
        dict
            ``{"approach": [z_c, ...], "retract": [z_c, ...]}`` in m, the third output of
            :meth:`sweep` in each direction (from the same run: a caller that follows the
            approach and marks both jumps follows each direction once).
        """
        return {way: self.sweep(way)[2] for way in SWEEPS}

    def _sweep(self, direction):
        order = np.argsort(self.distance)
        order = order[::-1] if direction == "approach" else order
        n = self.distance.size
        amp, phs = np.full(n, np.nan), np.full(n, np.nan)
        # each distance's stable roots in increasing amplitude (their columns, then plain
        # floats: the walk below is a loop of Python scalars, not of numpy calls)
        ok = self.stable & np.isfinite(self.amplitude)
        cols = np.argsort(np.where(ok, self.amplitude, np.inf), axis=1, kind="stable")
        counts = ok.sum(axis=1).tolist()
        rows = np.arange(n)[:, None]
        roots = self.amplitude[rows, cols].tolist()
        phases = self.phase[rows, cols].tolist()
        jumps, prev, side = [], None, None  # side: 0 lowest, -1 highest of the stable roots
        for i in order.tolist():  # bounded: one pass over the distances
            count = counts[i]
            if count == 0:
                continue
            here = roots[i][:count]
            if prev is None:  # far away: the one (low) root; close in: the highest
                pick = 0 if direction == "approach" else count - 1
            elif count >= 2 and len(prev) >= 2:
                pick = 0 if side == 0 else count - 1  # stay on the branch
            else:  # entering or leaving a coexistence: follow the nearest root
                mine = prev[side]
                pick = _nearest(here, mine)
                if len(prev) >= 2 and count == 1 and \
                        _nearest(prev, here[0]) != side % len(prev):
                    jumps.append(float(self.distance[i]))  # our branch ended
            side = 0 if pick == 0 else -1
            amp[i], phs[i] = here[pick], phases[i][pick]
            prev = here
        return amp, phs, jumps


def _nearest(values, target) -> int:
    """The index of the first of ``values`` nearest ``target`` (as ``np.argmin(abs(...))``)."""
    best, j = math.inf, 0
    for i, v in enumerate(values):
        d = abs(v - target)
        if d < best:
            best, j = d, i
    return j


def amplitude_curve(distances, lever: TappingLever | None = None) -> AmplitudeCurve:
    """All steady states (both branches, with stability) of the tapping lever at each distance.

    Parameters
    ----------
    distances : array_like
        Rest tip-sample distances z_c in m, each in (0, 1e-5], at most :data:`MAX_DISTANCES`.
    lever : TappingLever, optional
        Lever and sample (default :class:`TappingLever` ()).

    Returns
    -------
    AmplitudeCurve

    Raises
    ------
    ValueError
        On distances out of range or too many of them.
    TypeError
        If ``lever`` is not a :class:`TappingLever`.

    Examples
    --------
    >>> curve = amplitude_curve([30e-9, 5e-9])
    >>> round(float(curve.branch("attractive")[0][0]) * 1e9, 3)  # far: the free amplitude
    10.0
    """
    # a step per block of at least one distance, and the roots'
    return run_steps(amplitude_curve_steps(distances, lever), MAX_DISTANCES + 1,
                     "amplitude_curve_steps")


def amplitude_curve_steps(distances, lever: TappingLever | None = None, *,
                          block_distances: int | None = None):
    """:func:`amplitude_curve` in steps: a generator that samples g(A) at one block of
    distances per step, then refines every root at once.

    Every argument is checked when this is called, before any work. Each ``next()`` samples
    g on the amplitude grid at the next ``block_distances`` distances; the last one finds the
    roots (the Illinois refinement of every sign change together, as :func:`amplitude_curve`
    does) and returns the :class:`AmplitudeCurve` (``StopIteration.value``). g at a grid point
    depends on its own distance and amplitude only, so the curve equals
    :func:`amplitude_curve`'s bit for bit whatever the blocks (tested). A panel runs a step
    per turn of the kernel's loop, so that a slider move waits for one block, not the curve.

    Parameters
    ----------
    distances, lever
        As :func:`amplitude_curve`.
    block_distances : int, optional
        Distances sampled per step, 1 to :data:`MAX_DISTANCES`; default: all of them in one
        step.

    Returns
    -------
    generator
        Yields the number of distances sampled so far after each block; returns the
        AmplitudeCurve.

    Raises
    ------
    ValueError, TypeError
        As :func:`amplitude_curve`, and for ``block_distances`` out of range, when called.
    """
    lever = TappingLever() if lever is None else _check_lever(lever)
    zp = PARAMETERS["distance"]
    zc = check_array("distances", distances, "m", low=zp.low, high=zp.high,
                     low_inclusive=False, max_size=MAX_DISTANCES).ravel()
    rows = MAX_DISTANCES if block_distances is None else check_integer(
        "block_distances", block_distances, 1, MAX_DISTANCES)
    return _amplitude_curve_steps(zc, lever, rows)


def _amplitude_curve_steps(zc, lever, rows):
    """The work of :func:`amplitude_curve_steps`, of checked arguments (a generator)."""
    n = zc.size
    a_max = lever.max_amplitude * (1.0 + 1e-9)
    grid = a_max * _GRID
    m = grid.size
    g = np.empty((n, m))
    for start in range(0, n, rows):  # bounded: MAX_DISTANCES / rows blocks
        z_block = zc[start:start + rows]
        g[start:start + z_block.size] = _balance(lever, np.repeat(z_block, m),
                                                 np.tile(grid, z_block.size))[0].reshape(-1, m)
        yield start + z_block.size
    # sign changes of g between neighbouring grid amplitudes (an exact zero counts once)
    lo_neg = g[:, :-1] < 0
    change = lo_neg != (g[:, 1:] < 0)
    rows, cols = np.nonzero(change)
    lo, hi = grid[cols], grid[cols + 1]
    glo, ghi = g[rows, cols], g[rows, cols + 1]
    z = zc[rows]
    root = lo.copy()
    for _ in range(_ILLINOIS_STEPS):  # Illinois: regula falsi that halves a retained end's g
        new = hi - ghi * (hi - lo) / np.where(ghi != glo, ghi - glo, 1.0)
        gnew = _balance(lever, z, new)[0]
        keep = np.sign(gnew) == np.sign(ghi)  # hi is replaced; lo is retained once more
        lo, glo = np.where(keep, lo, hi), np.where(keep, 0.5 * glo, ghi)
        hi, ghi = new, gnew
        done = np.all(np.abs(new - root) <= 1e-13 * a_max)
        root = new
        if done:
            break
    residual, p, s = _balance(lever, z, root)
    i_c = lever.spring_constant * (1.0 - lever.frequency_ratio ** 2) * root - p
    rising = g[rows, cols] < 0
    counts = np.bincount(rows, minlength=n)
    r = max(int(counts.max()) if counts.size else 0, 1)
    slot = np.arange(rows.size) - np.concatenate(([0], np.cumsum(counts)[:-1]))[rows]
    shape = (n, r)
    amplitude, phase = np.full(shape, np.nan), np.full(shape, np.nan)
    stable, attractive = np.zeros(shape, bool), np.zeros(shape, bool)
    amplitude[rows, slot] = root
    phase[rows, slot] = np.arctan2(s, p)
    stable[rows, slot] = rising
    attractive[rows, slot] = i_c > 0
    # branch labels: where two stable roots coexist the higher is the repulsive (H) branch and
    # the lower the attractive (L) one, whatever the sign of the net force (which turns at the
    # far end of the H branch); a lone stable root is named by the sign of its net force
    high = stable & ~attractive
    two = stable.sum(axis=1) >= 2
    if two.any():
        top = np.argmax(np.where(stable, np.nan_to_num(amplitude, nan=-1.0), -1.0), axis=1)
        high[two] = False
        high[np.flatnonzero(two), top[two]] = True
    e_dis, e_err = np.full(shape, np.nan), np.full(shape, np.nan)
    phi = phase[rows, slot]
    drive = lever.drive_force * np.sin(phi)
    damping = lever.spring_constant * lever.frequency_ratio * root / lever.quality_factor
    e = math.pi * root * (drive - damping)
    # its accuracy (module notes): the root's residual, and the rounding of phi and the terms
    rounding = (lever.drive_force * np.abs(np.cos(phi)) * (np.abs(phi) + 1.0) + np.abs(drive) +
                np.abs(damping))
    err = math.pi * root * (np.abs(s) * np.abs(residual) / lever.drive_force +
                            DISSIPATION_ROUNDINGS * np.finfo(float).eps * rounding)
    e_dis[rows, slot] = np.where(np.abs(e) <= err, 0.0, e)
    e_err[rows, slot] = err
    return AmplitudeCurve(lever, zc, amplitude, phase, stable, attractive, high, e_dis, e_err)


#: Distances (as multiples of A0 from 0.01 A0 to 1.5 A0) on which :func:`setpoint_state` follows
#: the approach.
SETPOINT_GRID = 400


def setpoint_state(setpoint_ratio: float = PARAMETERS["setpoint_ratio"].default,
                   lever: TappingLever | None = None) -> tuple[float, float, float, bool]:
    """Where amplitude feedback holds the lever: the state of a slow approach at A = r A0.

    The approach (:meth:`AmplitudeCurve.sweep`, from far away, on the attractive branch until it
    ends) is followed on :data:`SETPOINT_GRID` distances from 1.5 A0 down to 0.01 A0, and the
    first distance at which the amplitude falls to r A0 is interpolated linearly.

    Parameters
    ----------
    setpoint_ratio : float
        Setpoint r = A_sp / A0, in (0, 1).
    lever : TappingLever, optional
        Lever and sample (default :class:`TappingLever` ()).

    Returns
    -------
    (float, float, float, bool)
        Rest distance z_c in m, phase lag in rad, E_dis in J per cycle there, and whether the
        state is on the attractive (low) branch.

    Raises
    ------
    ValueError
        If ``setpoint_ratio`` is outside (0, 1) (a setpoint at or above the free amplitude is
        never reached), or if the approach never gets down to it.
    """
    r = PARAMETERS["setpoint_ratio"].check(setpoint_ratio)
    lever = TappingLever() if lever is None else _check_lever(lever)
    z = lever.free_amplitude * np.linspace(1.5, 0.01, SETPOINT_GRID)
    return operating_point(amplitude_curve(z, lever), r)


def operating_point(curve: AmplitudeCurve,
                    setpoint_ratio: float) -> tuple[float, float, float, bool]:
    """The state amplitude feedback holds at ``setpoint_ratio``, read off ``curve``.

    Follow the slow approach (:meth:`AmplitudeCurve.sweep`) from the curve's farthest distance
    to the first distance at which the amplitude falls to r A0, and interpolate the distance,
    the phase and E_dis linearly between the two grid points around it. E_dis is the curve's
    own at the two roots (0 where zero within its accuracy), interpolated, not recomputed from
    the interpolated phase: it is very sensitive to the phase (pi F0 A cos(phi) per radian), and
    a phase interpolated to 1e-5 rad would invent some 0.1 zJ on a sample that dissipates
    nothing.
    :func:`setpoint_state` is this on A0 x linspace(1.5, 0.01, :data:`SETPOINT_GRID`).

    Parameters
    ----------
    curve : AmplitudeCurve
        An amplitude curve (:func:`amplitude_curve`) of the lever.
    setpoint_ratio : float
        r = A_sp / A0 in (0, 1).

    Returns
    -------
    (float, float, float, bool)
        Rest distance z_c in m, phase lag in rad, E_dis in J per cycle there, and whether the
        state is on the attractive (low) branch.

    Raises
    ------
    ValueError
        If ``setpoint_ratio`` is outside (0, 1), or if the approach never reaches it on the
        curve's distances.
    TypeError
        If ``curve`` is not an :class:`AmplitudeCurve`.
    """
    check_instance("curve", curve, AmplitudeCurve)
    r = PARAMETERS["setpoint_ratio"].check(setpoint_ratio)
    lever = curve.lever
    amp, phs, _ = curve.sweep("approach")
    order = np.argsort(curve.distance)[::-1]  # the sweep's order: the farthest distance first
    z, amp, phs = curve.distance[order], amp[order], phs[order]
    target = r * lever.free_amplitude
    below = np.flatnonzero(np.isfinite(amp) & (amp <= target))
    if below.size == 0 or below[0] == 0:
        raise ValueError(f"setpoint_ratio: the approach never reaches A = {r:g} A0 between "
                         f"z_c = {z[0]:g} and {z[-1]:g} m; choose a larger setpoint_ratio")
    i = below[0]
    f = (amp[i - 1] - target) / (amp[i - 1] - amp[i])
    zc = z[i - 1] + f * (z[i] - z[i - 1])
    phase = phs[i - 1] + f * (phs[i] - phs[i - 1])
    roots = [(order[k], int(np.nanargmin(np.abs(curve.amplitude[order[k]] - amp[k]))))
             for k in (i - 1, i)]  # the curve's roots the sweep took there
    e = [float(curve.dissipated_energy[r, j]) for r, j in roots]
    e_dis = e[0] + f * (e[1] - e[0])
    row, j = roots[1]
    return float(zc), float(phase), float(e_dis), not bool(curve.repulsive_branch[row, j])
