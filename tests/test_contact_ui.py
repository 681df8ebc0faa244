"""Module (d)'s figures, 3D scene, widget panel and exercise checkers, without a browser: the data
they show must equal what the model says."""
import math

import numpy as np
import pytest

from afmsmiler.contact import (TIPS, Conical, Parabolic, Pyramidal, Spherical, approach_retract,
                               fit_curve, indent, jkr_curve, jkr_instability, reduced_modulus,
                               surface_displacement)
from afmsmiler.exercises.contact import (FitExercise, check_contact_point, check_fitted_modulus,
                                         pull_off_feedback, check_pull_off_forces,
                                         fitting_exercise)
from afmsmiler.plots.contact import (ContactFigure, contact_curves, cycles_figure, fit_figure,
                                     fit_label, fit_window, tip_geometries_figure)
from afmsmiler.scenes.contact import ContactScene, surface_mesh, tip_mesh
from afmsmiler.ui.contact import SLIDERS, TIP_CONTROLS, ContactPanel
from tests.recording import Recorder


# --- figures -------------------------------------------------------------------------------------
@pytest.mark.parametrize("cls", list(TIPS.values()), ids=list(TIPS))
def test_tip_outline_is_the_profile(cls):
    tip = cls()
    x, z = tip.outline(80e-9)
    assert z.min() == 0.0 and x[np.argmin(z)] == 0.0
    flank = (x >= 0) & ((x < tip.radius) if isinstance(tip, Spherical) else True)
    np.testing.assert_allclose(z[flank], tip.profile(x[flank]), rtol=1e-12, atol=1e-20)
    assert np.isclose(z.max(), 80e-9)


def test_geometry_figure_draws_all_four_to_one_scale():
    fig = tip_geometries_figure()
    axes = fig.axes
    assert len(axes) == 4
    assert len({ax.get_xlim() for ax in axes}) == 1 and len({ax.get_ylim() for ax in axes}) == 1
    assert all(ax.get_aspect() == 1.0 for ax in axes)


def test_contact_figure_shows_the_model():
    tip = Parabolic(30e-9)
    z = np.linspace(-50e-9, 100e-9, 200)
    cyc = approach_retract(z, 0.1, tip, 1e6, 0.3)
    cur = indent([70e-9], 0.1, tip, 1e6, 0.3)
    curves = contact_curves(cyc, cur, tip, 100e-9)
    fig = ContactFigure(curves)
    np.testing.assert_allclose(fig.approach.get_xdata(), z * 1e9)
    np.testing.assert_allclose(fig.approach.get_ydata(), cyc.approach.force * 1e9)
    assert fig.point.get_ydata()[0] == pytest.approx(cur.force[0] * 1e9)
    # the drawn surface is the model's displacement, the apex at -Z_s
    rho = curves.rho_nm * 1e-9
    u = surface_displacement(tip, cur.z_s[0], np.abs(rho))
    np.testing.assert_allclose(curves.surface_nm, -u * 1e9)
    assert curves.tip_z_nm.min() == pytest.approx(-cur.z_s[0] * 1e9)


def test_cycles_and_fit_figures():
    tip = Parabolic(30e-9)
    z = np.linspace(-200e-9, 50e-9, 200)
    cyc = approach_retract(z, 0.1, tip, 1e6, 0.3, adhesion="jkr", work_of_adhesion=0.02)
    fig = cycles_figure({"JKR": cyc})
    assert len(fig.axes[0].lines) == 3
    ex = fitting_exercise(1)
    r = fit_curve(ex.curve.z_np, ex.curve.force, ex.tip, ex.poisson_ratio,
                  spring_constant=ex.curve.spring_constant)
    fig = fit_figure(ex.curve, r)
    assert len(fig.axes) == 2


def _legend_texts(ax):
    return [t.get_text() for t in ax.get_legend().get_texts()]


def test_fit_figure_of_the_real_curve_states_nu_and_zooms_on_the_contact():
    # spot3-0192.jpk-force, fitted at nu = 0 (the model refuses the vendor's nu = 0.5): the legend
    # must say which nu the E it shows belongs to, and give E at nu = 0.5 as the vendor's software
    # reports it, 233.1 kPa (nanite, tests/test_model_hertz_parabol.py), to the digit it prints
    from afmsmiler import data
    from afmsmiler.contact import load_curve
    pytest.importorskip("afmformats")
    curve = load_curve(data.path("spot3-0192.jpk-force"))
    r = fit_curve(curve.tip_position, curve.force, Parabolic(40e-9), 0.0)
    fig = fit_figure(curve, r, report_poisson_ratio=0.5)
    ax, axr = fig.axes
    label = _legend_texts(ax)[1]
    assert label == fit_label(r, 0.5)
    first, second = label.split("\n")
    assert first.startswith("fit at nu = 0: E = ")
    e_at_0 = float(first.split("E = ")[1].split(" ")[0])
    assert e_at_0 == pytest.approx(r.youngs_modulus / 1e3, abs=0.05)  # E* = E at nu = 0
    assert second.startswith("E(nu = 0.5) = (1 - nu^2) E* = ")
    assert float(second.split("E* = ")[1].split(" ")[0]) == pytest.approx(233.1, abs=0.05)
    # nu = 0.499, the closest the model accepts, would not print the vendor's value
    assert (1 - 0.499 ** 2) * r.youngs_modulus / 1e3 > 233.1 + 0.2
    # default view: 1 um, the whole contact region (contact point to the curve's end, where the
    # force is largest) and baseline before it; y limits fit the data in view
    lo, hi = (v / 1e9 for v in axr.get_xlim())
    assert hi - lo == pytest.approx(1e-6, rel=1e-9)
    x_peak = r.x[np.argmax(curve.force)]
    assert lo < r.contact_point < hi and lo <= x_peak <= hi
    assert hi == pytest.approx(r.x.max())  # contact side: tip position grows into the sample
    inside = (r.x >= lo) & (r.x <= hi)
    y0, y1 = ax.get_ylim()
    assert y0 <= curve.force[inside].min() * 1e9 and curve.force[inside].max() * 1e9 <= y1
    assert y1 - y0 < 1.2 * np.ptp(curve.force[inside]) * 1e9  # zoomed in y too
    assert "um around the contact point" in axr.get_xlabel() and "[nm]" in axr.get_xlabel()
    # no zoom: the whole curve
    lo, hi = (v / 1e9 for v in fit_figure(curve, r, zoom=None).axes[1].get_xlim())
    assert lo <= r.x.min() and hi >= r.x.max()


def test_fit_window_geometry():
    ex = fitting_exercise(1)
    r = fit_curve(ex.curve.z_np, ex.curve.force, ex.tip, ex.poisson_ratio,
                  spring_constant=ex.curve.spring_constant)
    # the contact region (Z_np from the contact point, ~55 nm, to 400 nm) is narrower than 1 um:
    # the view reaches the curve's end and goes 1 um back, clipped to the data (from -300 nm)
    assert fit_window(r, 1e-6) == (pytest.approx(ex.curve.z_np.min()),
                                   pytest.approx(ex.curve.z_np.max()))
    lo, hi = fit_window(r, 0.3e-6)
    assert hi == pytest.approx(ex.curve.z_np.max())
    # contact region (about 345 nm) wider than the window: all of it and half a window of baseline
    assert ex.curve.z_np.max() - r.contact_point > 0.3e-6
    assert lo == pytest.approx(r.contact_point - 0.15e-6)
    assert fit_label(r).startswith(f"fit at nu = {ex.poisson_ratio:g}: E = ")
    e_star = float(fit_label(r).split("E* = E/(1 - nu^2) = ")[1].split(" ")[0]) * 1e3
    assert e_star == pytest.approx(r.youngs_modulus / (1 - ex.poisson_ratio ** 2), rel=1e-3)


@pytest.mark.parametrize("kwargs, match", [
    (dict(report_poisson_ratio=0.6), "report_poisson_ratio"), (dict(zoom=0.0), "zoom"),
    (dict(zoom=-1e-6), "zoom")])
def test_fit_figure_bad_input(kwargs, match):
    ex = fitting_exercise(1)
    r = fit_curve(ex.curve.z_np, ex.curve.force, ex.tip, ex.poisson_ratio,
                  spring_constant=ex.curve.spring_constant)
    with pytest.raises(ValueError, match=match):
        fit_figure(ex.curve, r, **kwargs)


# --- scene ----------------------------------------------------------------------------------------
@pytest.mark.parametrize("tip", [Parabolic(20e-9), Spherical(40e-9), Conical(0.4), Pyramidal(0.6)],
                         ids=lambda t: t.key)
def test_meshes_are_well_formed_and_follow_the_solution(tip):
    v, f = tip_mesh(tip, 100e-9, 20e-9)
    assert f.min() == 0 and f.max() == v.shape[0] - 1 and np.isfinite(v).all()
    assert v[:, 2].min() == 0.0  # apex at the origin
    cur = indent([40e-9], 0.2, tip, 2e6, 0.3)
    v, f, depth = surface_mesh(tip, cur, 150e-9, 20e-9)
    assert f.max() == v.shape[0] - 1
    centre = np.argmin(np.hypot(v[:, 0], v[:, 1]))
    assert depth[centre] == pytest.approx(cur.z_s[0], rel=1e-12)  # pushed down by Z_s
    rho = np.hypot(v[:, 0], v[:, 1]).astype(float) * 20e-9
    np.testing.assert_allclose(depth, surface_displacement(tip, cur.z_s[0], rho), rtol=1e-5,
                               atol=1e-15)



def test_scene_updates_in_place():
    rec = Recorder()
    tip = Parabolic(20e-9)
    scene = ContactScene(tip, indent([30e-9], 0.1, tip, 1e6, 0.3), vis=rec)
    n_tip = sum(1 for c in rec.calls if c[:2] == ("set_object", "/afmsmiler/contact/tip"))
    cur = indent([60e-9], 0.1, tip, 1e6, 0.3)
    scene.update(tip, cur)
    # the tip mesh is not rebuilt, only moved: apex at -Z_s (scene units)
    assert sum(1 for c in rec.calls if c[:2] == ("set_object", "/afmsmiler/contact/tip")) == n_tip
    move = [c for c in rec.calls if c[0] == "set_transform"][-1]
    assert move[2][2, 3] == pytest.approx(-cur.z_s[0] / scene.unit)
    scene.update(Conical(0.4), cur)  # a new shape rebuilds the tip
    tip_calls = [c for c in rec.calls if c[:2] == ("set_object", "/afmsmiler/contact/tip")]
    assert len(tip_calls) == n_tip + 1


def test_scene_in_a_real_view_updates_in_place():
    from afmsmiler.scenes import static_html
    tip = Pyramidal(0.6)
    scene = ContactScene(tip, indent([30e-9], 0.1, tip, 1e6, 0.3))
    size0 = len(static_html(scene.root))
    assert size0 > 1000
    for z in np.linspace(10e-9, 90e-9, 8):
        scene.update(tip, indent([z], 0.1, tip, 1e6, 0.3))
    # the stored scene does not grow with updates (same paths replaced)
    assert abs(len(static_html(scene.root)) - size0) < 0.05 * size0


# --- panel ----------------------------------------------------------------------------------------
def test_tip_sliders_are_generated_from_the_registry():
    names = {p.name for cls in TIPS.values() for p in cls.parameters}
    assert set(TIP_CONTROLS) == names
    panel = ContactPanel()
    for name, p in TIP_CONTROLS.items():
        w = panel.controls[name]
        assert p.display_unit in w.description
        low = 10 ** w.min if hasattr(w, "base") else w.min
        high = 10 ** w.max if hasattr(w, "base") else w.max
        assert p.low < p.to_si(low) and p.to_si(high) < p.high


def test_panel_shows_what_the_model_says():
    panel = ContactPanel()
    panel.set(tip="conical", half_angle=30.0, spring_constant=0.5, youngs_modulus=2.0,
              poisson_ratio=0.4, z_np=80.0)
    s = panel.last
    assert s.tip == Conical(math.radians(30.0))
    ref = indent([80e-9], 0.5, s.tip, 2e6, 0.4)
    assert s.current.force[0] == pytest.approx(ref.force[0], rel=1e-12)
    assert panel.figure.point.get_ydata()[0] == pytest.approx(ref.force[0] * 1e9, rel=1e-12)
    assert panel.controls["radius"].layout.display == "none"
    assert panel.controls["half_angle"].layout.display is None
    assert panel.controls["adhesion"].disabled


def test_panel_adhesion_and_sphere_limit():
    panel = ContactPanel(tip="parabolic")
    panel.set(adhesion="JKR", work_of_adhesion=40.0, radius=50.0)
    s = panel.last
    assert s.adhesion == "jkr"
    assert s.cycle.pull_off_force == pytest.approx(1.5 * math.pi * 50e-9 * 0.04, rel=1e-12)
    # the ramp reaches below the snap-off, so the drawn retract leaves the surface
    assert not s.cycle.retract.in_contact[-1]
    # a small sphere: the Z_np slider stops before the sphere is buried; the model never raises
    panel.set(tip="spherical", radius=5.0, youngs_modulus=1e-3, spring_constant=100.0,
              adhesion="none")
    k, e_star = 100.0, reduced_modulus(1e3, 0.3)
    assert panel.controls["z_np"].max < Spherical(5e-9).max_z_np(k, e_star) * 1e9
    with pytest.raises(ValueError, match="z_np must be in"):  # rejected, not clamped
        panel.set(z_np=SLIDERS["z_np"].to_display(SLIDERS["z_np"].slider_high))
    panel.set(z_np=panel.controls["z_np"].max)
    assert panel.last.current.z_s[0] < 5e-9


def test_panel_rejects_unknown_controls():
    with pytest.raises(TypeError, match="unknown control"):
        ContactPanel(stiffness=1.0)


# --- exercises ------------------------------------------------------------------------------------
def test_fitting_exercise_checker():
    ex = fitting_exercise(7)
    assert isinstance(ex, FitExercise) and "youngs_modulus" not in repr(ex)
    r = fit_curve(ex.curve.z_np, ex.curve.force, ex.tip, ex.poisson_ratio,
                  spring_constant=ex.curve.spring_constant)
    assert check_fitted_modulus(r.youngs_modulus, ex)
    assert check_contact_point(r.contact_point, ex)
    # a fit that ignores the lever's bending (x = Z_np) overestimates the indentation: wrong E
    naive = fit_curve(ex.curve.z_np, ex.curve.force, ex.tip, ex.poisson_ratio)
    assert not check_fitted_modulus(naive.youngs_modulus, ex)
    assert not check_fitted_modulus(None, ex) and not check_fitted_modulus("soft", ex)
    assert not check_contact_point(r.contact_point + 10e-9, ex)
    assert fitting_exercise(7).curve.force.tolist() == ex.curve.force.tolist()  # reproducible


def test_pull_off_checker_uses_the_published_values():
    R, w = 20e-9, 0.05
    assert pull_off_feedback(2 * math.pi * R * w, "dmt", R, w)
    assert pull_off_feedback(1.5 * math.pi * R * w, "jkr", R, w)
    assert not pull_off_feedback(2 * math.pi * R * w, "jkr", R, w)
    # the other model's law (DMT 2 pi R w, JKR 3/2 pi R w: Derjaguin et al. 1975, Johnson et al.
    # 1971) is named as such, without the value asked for
    for answer, model, other in ((1.5 * math.pi * R * w, "dmt", "JKR"),
                                 (2 * math.pi * R * w, "jkr", "DMT")):
        fb = pull_off_feedback(answer, model, R, w)
        assert not fb and f"that is the {other} pull-off force" in fb.message, fb.message
        right = (2 if model == "dmt" else 1.5) * math.pi * R * w
        assert f"{right:.3g}" not in fb.message and f"{right:.2e}" not in fb.message
    assert "that is the" not in pull_off_feedback(3 * math.pi * R * w, "dmt", R, w).message
    with pytest.raises(ValueError, match="model must be one of"):
        pull_off_feedback(1e-9, "maugis")


def test_the_pull_off_exercise_grades_both_models_and_names_each_slip():
    # DMT 2 pi R w (Derjaguin, Muller, Toporov 1975), JKR 3/2 pi R w (Johnson, Kendall, Roberts
    # 1971): exercise 04.2 asks both, and its verdict says which part is wrong without a value
    R, w = 20e-9, 0.05
    dmt, jkr = 2 * math.pi * R * w, 1.5 * math.pi * R * w
    assert check_pull_off_forces(dmt, jkr, R, w)
    assert check_pull_off_forces.exercise.answers == ("dmt", "jkr")
    for answers, words in (((dmt, dmt), ["DMT right", "that is the DMT pull-off force"]),
                           ((jkr, dmt), ["that is the JKR", "that is the DMT"]),
                           ((dmt * 1e9, jkr), ["JKR right", "10^9 times"]),
                           ((None, jkr), ["JKR right", "enter the DMT"]),
                           ((-dmt, jkr), ["JKR right", "sign is wrong"])):
        fb = check_pull_off_forces(*answers, R, w)
        assert not fb and all(word in fb.message for word in words), (answers, fb.message)
        assert "model:" not in fb.message, fb.message  # the model's values only once right
        if answers[0] is not None and answers[0] > 0:  # (a sign slip echoes its own size)
            assert f"{dmt:.4g}" not in fb.message and f"{jkr:.4g}" not in fb.message, fb.message
    with pytest.raises(ValueError, match="radius"):
        check_pull_off_forces(dmt, jkr, radius=-1.0)


@pytest.mark.slow
@pytest.mark.parametrize("tip", list(TIPS))
def test_no_slider_position_makes_the_model_raise(tip):
    # every tip at the corners of the slider ranges (softest/stiffest lever and sample, smallest and
    # largest tip parameter, largest Z_np, adhesion on where offered): the panel must never raise
    panel = ContactPanel(tip=tip)
    c = panel.controls

    def ends(w):
        return (10 ** w.min, 10 ** w.max) if hasattr(w, "base") else (w.min, w.max)

    names = [p.name for p in TIPS[tip].parameters]
    adhesion = ["none", "DMT", "JKR"] if tip in ("parabolic", "spherical") else ["none"]
    for k in ends(c["spring_constant"]):
        for e in ends(c["youngs_modulus"]):
            for value in ends(c[names[0]]):
                for model in adhesion:
                    panel.set(spring_constant=k, youngs_modulus=e,
                              poisson_ratio=c["poisson_ratio"].max, adhesion=model,
                              work_of_adhesion=c["work_of_adhesion"].max, **{names[0]: value})
                    panel.set(z_np=c["z_np"].max)
                    s = panel.last
                    assert np.isfinite(s.current.force).all()
                    assert np.isfinite(s.cycle.retract.force).all()
                    panel.set(branch="retract", z_np=c["z_np"].min)
                    assert np.isfinite(panel.last.current.force).all()
                    panel.set(branch="approach")


def test_panel_follows_the_retract_branch_through_the_hysteresis():
    # JKR: on the approach branch the tip is free below Z_np = 0; on the retract branch it stays
    # stuck down to the snap-off (the lever's instability), and the slider reaches below it
    panel = ContactPanel(tip="parabolic")
    panel.set(adhesion="JKR", work_of_adhesion=40.0, radius=50.0, youngs_modulus=10.0)
    e_star = reduced_modulus(10e6, 0.3)
    _, z_snap, f_snap = jkr_instability(0.1, 50e-9, 0.04, e_star)
    assert panel.controls["z_np"].min < z_snap * 1e9
    inside = 0.9 * z_snap * 1e9
    panel.set(z_np=inside)
    assert not panel.last.current.in_contact[0] and panel.last.current.force[0] == 0
    panel.set(branch="retract")
    cur = panel.last.current
    assert cur.in_contact[0] and f_snap < cur.force[0] < 0  # stuck, pulled down
    zs, f = jkr_curve(cur.contact_radius, 50e-9, 0.04, e_star)
    assert cur.force[0] == pytest.approx(float(f[0]), rel=1e-12)
    assert cur.z_s[0] + cur.force[0] / 0.1 == pytest.approx(inside * 1e-9, rel=1e-12)
    assert panel.figure.point.get_ydata()[0] == pytest.approx(cur.force[0] * 1e9, rel=1e-12)
    panel.set(z_np=1.05 * z_snap * 1e9)  # past the snap-off: free
    assert not panel.last.current.in_contact[0]
    # without adhesion both branches are the elastic curve and the slider keeps its bounds
    panel.set(adhesion="none", z_np=40.0)
    assert panel.controls["z_np"].min == pytest.approx(SLIDERS["z_np"].to_display(
        SLIDERS["z_np"].slider_low))
    ref = indent([40e-9], 0.1, Parabolic(50e-9), 10e6, 0.3)
    assert panel.last.current.force[0] == pytest.approx(ref.force[0], rel=1e-12)


# --- the panel uses what it is given, once per move, on the slider grid ---------------------------
def test_update_uses_the_values_it_is_given():
    panel = ContactPanel()
    assert panel.last.current.z_np[0] == pytest.approx(60e-9, rel=1e-12)
    si = panel.to_si(panel.values())  # update takes SI (the panel contract)
    panel.update(**{**si, "z_np": 5e-9})  # before: ignored, kept the slider's 60 nm
    assert panel.last.current.z_np[0] == pytest.approx(5e-9, rel=1e-12)
    ref = indent([5e-9], 0.1, Parabolic(20e-9), 1e6, 0.3)
    assert panel.last.current.force[0] == pytest.approx(ref.force[0], rel=1e-12)
    panel.update(**{**si, "spring_constant": 2.0, "youngs_modulus": 3e6})
    assert (panel.last.spring_constant, panel.last.youngs_modulus) == (2.0, 3e6)


def test_an_unknown_tip_is_a_value_error_naming_the_choices():
    panel = ContactPanel()
    with pytest.raises(ValueError, match=r"tip must be one of .*'parabolic'.*got 'cube'"):
        panel.update(**{**panel.to_si(panel.values()), "tip": "cube"})
    with pytest.raises(ValueError, match=r"tip must be one of"):
        panel.set(tip="cube")
    with pytest.raises(ValueError, match=r"tip must be one of"):
        ContactPanel(tip="cube")
    with pytest.raises(ValueError, match=r"adhesion must be one of"):
        panel.update(**{**panel.to_si(panel.values()), "adhesion": "Maugis"})


def _browser_echo(w):
    """The value a browser sends back after snapping the kernel's value to the slider's grid."""
    if hasattr(w, "base"):
        n = round((math.log10(w.value) - w.min) / w.step)
        return 10 ** (w.min + n * w.step)
    return w.min + round((w.value - w.min) / w.step) * w.step


def test_defaults_sit_on_the_slider_grid_and_the_echo_changes_nothing():
    # before: k 0.1 came back from the browser as 0.0998 N/m and the cone's 20 deg as 20.2 deg
    panel = ContactPanel(tip="conical")
    for name, shown in (("spring_constant", 0.1), ("half_angle", 20.0), ("youngs_modulus", 1.0),
                        ("z_np", 60.0), ("work_of_adhesion", 20.0), ("radius", 20.0)):
        w = panel.controls[name]
        assert _browser_echo(w) == pytest.approx(shown, rel=1e-12), name
        w.value = _browser_echo(w)  # the echo arrives
    assert panel.last.spring_constant == 0.1
    assert panel.last.tip.half_angle == pytest.approx(math.radians(20.0), rel=1e-15)


def test_one_slider_move_runs_the_model_once_for_the_ramp_and_once_for_the_point(monkeypatch):
    from afmsmiler.contact import ContactSystem
    calls = []
    for name in ("approach_retract", "indent"):
        original = getattr(ContactSystem, name)

        def counted(self, z_np, _original=original, _name=name):
            calls.append((_name, np.size(z_np)))
            return _original(self, z_np)

        monkeypatch.setattr(ContactSystem, name, counted)
    panel = ContactPanel()
    for values in (dict(youngs_modulus=2.0), dict(adhesion="JKR"), dict(z_np=-20.0),
                   dict(branch="retract"), dict(tip="spherical"), dict(radius=50.0)):
        calls.clear()
        panel.set(**values)
        ramps = [c for c in calls if c[1] > 2]
        assert len(ramps) == 1, (values, calls)  # the ramp, once
        assert len(calls) == 2, (values, calls)  # and the current point, once


def test_figure_and_scene_draw_the_state_the_readout_gives_on_the_jkr_neck():
    # the review's state: JKR retract at Z_np = -20 nm, stuck (F = -1.7 nN, r = 35 nm); before,
    # the drawing and the 3D view showed the tip floating 3 nm above a flat surface
    from afmsmiler.contact import contact_surface
    panel = ContactPanel()
    panel.set(adhesion="JKR", branch="retract", z_np=-20.0)
    cur = panel.last.current
    assert cur.in_contact[0] and cur.z_s[0] < 0
    assert cur.force[0] == pytest.approx(-1.739e-9, rel=1e-3)
    assert cur.contact_radius[0] == pytest.approx(34.77e-9, rel=1e-3)
    assert "-1.739 nN" in panel.readout.value
    c = panel.figure.curves
    mid = np.argmin(np.abs(c.rho_nm))
    apex_nm = c.tip_z_nm.min()
    # the tip touches the surface: apex height = surface height on the axis = -Z_s > 0
    assert apex_nm == pytest.approx(-cur.z_s[0] * 1e9, rel=1e-12)
    assert c.surface_nm[mid] == pytest.approx(apex_nm, rel=1e-12)
    # the surface follows the tip over the contact radius (the neck), not a flat plane
    rho = np.abs(c.rho_nm) * 1e-9
    inside = rho <= cur.contact_radius[0]
    assert c.surface_nm.max() > 5.0  # pulled up around the tip
    np.testing.assert_allclose(c.surface_nm[inside],
                               -contact_surface(panel.last.tip, cur, rho[inside]) * 1e9)
    # the 3D view draws the same state: centre vertex of the surface at the apex
    scene = ContactScene(panel.last.tip, cur, vis=Recorder(), camera=False)
    v = scene.last_vertices  # the height map's vertex on the axis
    centre = float(v[np.argmin(np.hypot(v[:, 0], v[:, 1])), 2]) * scene.unit
    assert centre == pytest.approx(scene.last_apex, rel=1e-6)
    assert scene.last_apex == pytest.approx(-cur.z_s[0], rel=1e-12)
    assert scene.depth_scale.vmin < 0  # the colour scale reaches the neck


def _overlaps(fig, ax, legend):
    fig.canvas.draw() if hasattr(fig.canvas, "draw") else None
    box = legend.get_window_extent()
    for line in ax.get_lines():
        xy = ax.transData.transform(np.c_[line.get_xdata(), line.get_ydata()])
        inside = ((xy[:, 0] > box.x0) & (xy[:, 0] < box.x1) & (xy[:, 1] > box.y0)
                  & (xy[:, 1] < box.y1))
        if inside.any():
            return True
    return False


@pytest.mark.slow
def test_legends_do_not_cover_data():
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    panel = ContactPanel()
    panel.set(adhesion="JKR", branch="retract", z_np=-20.0)
    figs = [panel.fig]
    tip = Parabolic(50e-9)
    ramp = np.linspace(-150e-9, 40e-9, 200)
    figs.append(cycles_figure({m: approach_retract(ramp, 0.1, tip, 20e6, 0.3, adhesion=m,
                                                   work_of_adhesion=0.03) for m in ("dmt", "jkr")}))
    for fig in figs:
        FigureCanvasAgg(fig)
        fig.canvas.draw()
        for ax in fig.axes:
            if ax.get_legend() is not None:
                assert not _overlaps(fig, ax, ax.get_legend()), ax.get_xlabel()


# --- hints that run, hints that do not give the answer away, slips named --------------------------
def _notebook_namespace():
    import json
    from pathlib import Path
    nb = json.loads((Path(__file__).parents[1] / "notebooks" / "04_contact_mechanics.ipynb")
                    .read_text())
    imports = next("".join(c["source"]) for c in nb["cells"]
                   if c["cell_type"] == "code" and "fitting_exercise" in "".join(c["source"]))
    ns = {}
    exec(imports, ns)  # the notebook's own import cell
    exercise_cell = next("".join(c["source"]) for c in nb["cells"]
                         if c["cell_type"] == "code" and "ex = fitting_exercise" in
                         "".join(c["source"]))
    exec(exercise_cell.splitlines()[0], ns)  # ex = fitting_exercise(seed=...)
    return ns


def test_every_hint_s_code_runs_in_the_notebook():
    # before: exercise 1's hint named `exercise` and `curve`, which the notebook does not have
    # (NameError when pasted)
    import re
    from afmsmiler.exercises.contact import HINTS
    ns = _notebook_namespace()
    ex = ns["ex"]
    messages = list(HINTS.values()) + [check_fitted_modulus(1.0, ex).message,
                                       check_fitted_modulus(None, ex).message,
                                       check_contact_point(1.0, ex).message,
                                       pull_off_feedback(1e-3, "jkr").message]
    snippets = [code for m in messages for code in re.findall(r"`([^`]+)`", m)]
    assert snippets, "the fitting hint shows the call"
    for code in snippets:
        result = eval(code, ns)
        if hasattr(result, "youngs_modulus"):
            assert check_fitted_modulus(result.youngs_modulus, ex)


def test_the_pull_off_hint_points_to_the_sources_without_the_formulas():
    from afmsmiler.exercises.contact import HINTS
    text = pull_off_feedback(1e-3, "dmt").message + HINTS["pull_off"]
    for giveaway in ("pi R w", "2 pi", "3/2", "1.5", "(3/2)"):
        assert giveaway not in text
    assert "book" in text and "1971" in text and "1975" in text


def test_checkers_name_unit_slips():
    ex = fitting_exercise(4)
    r = fit_curve(ex.curve.z_np, ex.curve.force, ex.tip, ex.poisson_ratio,
                  spring_constant=ex.curve.spring_constant)
    in_kpa = check_fitted_modulus(r.youngs_modulus / 1e3, ex)
    assert not in_kpa and "10^-3 times" in in_kpa.message and "prefix" in in_kpa.message
    in_nm = check_contact_point(r.contact_point * 1e9, ex)  # before: only "... nm off"
    assert not in_nm and "10^9 times" in in_nm.message and "prefix" in in_nm.message
    in_nn = pull_off_feedback(1.5 * math.pi * 20e-9 * 0.05 * 1e9, "jkr", 20e-9, 0.05)
    assert not in_nn and "10^9 times" in in_nn.message


def test_things_to_try_lever_against_sample():
    # notebook 04: "make the lever stiffer than the sample and the sample stiffer than the lever
    # (when is Z_s ~ Z_np?)": a stiff lever on a soft sample indents by almost all of Z_np
    panel = ContactPanel()
    panel.set(spring_constant=100.0, youngs_modulus=panel.controls["youngs_modulus"].base ** (
        panel.controls["youngs_modulus"].min), z_np=100.0)
    assert panel.last.current.z_s[0] > 0.95 * 100e-9
    panel.set(spring_constant=panel.controls["spring_constant"].base ** (
        panel.controls["spring_constant"].min), youngs_modulus=1e4)
    assert panel.last.current.z_s[0] < 0.05 * 100e-9


def test_a_z_np_beyond_the_sphere_s_limit_is_clipped_and_said():
    panel = ContactPanel()
    panel.set(z_np=200.0)
    panel.set(tip="spherical", radius=5.0, spring_constant=100.0)  # a 5 nm sphere, stiff lever
    top = panel.controls["z_np"].max
    assert top < 200.0 and panel.controls["z_np"].value == top
    assert panel.last.current.z_np[0] == pytest.approx(top * 1e-9, rel=1e-12)
    assert "outside" in panel.readout.value and "shown at" in panel.readout.value


def test_the_z_np_slider_keeps_its_ends():
    # 200e-9 / 1e-9 is 199.99999999999997 in floating point: the slider's end must not drop
    panel = ContactPanel()
    assert (panel.controls["z_np"].min, panel.controls["z_np"].max) == (-50.0, 200.0)
    panel.set(youngs_modulus=2.0)
    assert panel.controls["z_np"].max == 200.0


# --- limits that hold while the curves stay inside them (issue 9) ---------------------------------
def _curve_limits(panel):
    return panel.figure.ax_curve.get_xlim(), panel.figure.ax_curve.get_ylim()


def test_one_slider_step_moves_the_force_curve_not_the_axes():
    panel = ContactPanel()
    before = _curve_limits(panel)
    top = np.max(panel.figure.approach.get_data()[1])
    e = panel.controls["youngs_modulus"]
    panel.set(youngs_modulus=e.value * 10 ** e.step)   # a log slider: its step in decades
    assert np.max(panel.figure.approach.get_data()[1]) > top
    assert _curve_limits(panel) == before
    panel.set(z_np=panel.controls["z_np"].value + panel.controls["z_np"].step)
    assert _curve_limits(panel) == before


def test_a_big_move_rescales_the_force_curve_and_keeps_it_inside():
    panel = ContactPanel()
    before = _curve_limits(panel)
    for values in (dict(youngs_modulus=100.0), dict(adhesion="JKR", work_of_adhesion=200.0),
                   dict(youngs_modulus=0.01, adhesion="none")):
        panel.set(**values)
        (x0, x1), (y0, y1) = after = _curve_limits(panel)
        assert after != before, values
        for line in (panel.figure.approach, panel.figure.retract, panel.figure.point):
            x, y = (np.asarray(v, dtype=float) for v in line.get_data())
            assert x0 <= x.min() and x.max() <= x1 and y0 <= y.min() and y.max() <= y1, values
        assert y0 < 0.0 < y1
        before = after


def test_a_drag_of_z_np_never_sends_an_older_step_back():
    # During a drag ipywidgets holds the moves made while one update is in flight and sends
    # them merged, so the kernel's copy of Z_np lags the student's; the panel set that stale
    # copy to the value it drew, which reached the browser as an older step: the slider jumped
    # back and forth. The browser's updates arrive as ipywidgets applies them (set_state).
    p = ContactPanel(scene=False)
    z = p.controls["z_np"]
    sent = []
    z.send_state = lambda key=None: sent.append(key)  # what the kernel would send the slider
    start = z.value
    steps = [start + k * z.step for k in range(1, 6)]
    for v in steps:
        z.set_state({"value": v})
    assert float(p.last.current.z_np[0]) == pytest.approx(steps[-1] * 1e-9)  # the model ran for the last step
    assert p.moves_received == len(steps)
    assert sent == []  # and the kernel sent the slider no value of its own
