"""The module (a) panel without a browser: set sliders, compare the plotted data with the model and
with closed forms; slider bounds can never produce a lever the model rejects."""
import itertools
import math

import numpy as np
import pytest

from afmsmiler.cantilever import PARAMETERS, Cantilever
from afmsmiler.materials import MATERIALS
from afmsmiler.ui.cantilever import SLIDERS, CantileverPanel
from afmsmiler.scenes.cantilever import DEFAULTS

#: Slider ends in the units shown, from the parameters (the panel types none of them).
BOUNDS = {n: (PARAMETERS[n].to_display(PARAMETERS[n].slider_low),
              PARAMETERS[n].to_display(PARAMETERS[n].slider_high)) for n in SLIDERS}

SET = dict(force=250.0, length=300.0, width=40.0, thickness=3.0, section=0.5)


@pytest.fixture
def panel():
    p = CantileverPanel(scene=False)
    p.set(**SET)
    return p


def test_lines_equal_the_model_in_the_units_shown(panel):
    v = panel.values()
    lever = Cantilever(v["length"] * 1e-6, v["width"] * 1e-6, v["thickness"] * 1e-6,
                       v["youngs_modulus"] * 1e9, v["density"])
    F = v["force"] * 1e-9
    lines = panel.figure.lines
    x_um, z_nm = lines["z"].get_data()
    assert x_um[0] == 0 and x_um[-1] == pytest.approx(300.0)
    x = np.asarray(x_um) * 1e-6
    np.testing.assert_allclose(z_nm, lever.deflection(x, F) * 1e9, rtol=1e-12)
    np.testing.assert_allclose(lines["theta"].get_data()[1], lever.slope(x, F) * 1e3, rtol=1e-12)
    np.testing.assert_allclose(lines["stress_top"].get_data()[1],
                               lever.stress(x, lever.thickness / 2, F) / 1e6, rtol=1e-12, atol=1e-15)
    s_mpa, zb_um = lines["section"].get_data()
    assert zb_um[0] == pytest.approx(-1.5) and zb_um[-1] == pytest.approx(1.5)
    np.testing.assert_allclose(s_mpa, lever.stress(150e-6, np.asarray(zb_um) * 1e-6, F) / 1e6,
                               rtol=1e-12, atol=1e-15)
    assert lines["section_marker_z"].get_xdata()[0] == pytest.approx(150.0)


def test_readouts_against_closed_forms(panel):
    E, L, w, h, rho = 169e9, 300e-6, 40e-6, 3e-6, 2330.0
    F = 250e-9
    k = E * w * h ** 3 / (4 * L ** 3)
    # f1 = (1.87510407)^2 / (2 pi L^2) sqrt(E J / (rho w h)) (Blevins, Table 8-1)
    f1 = 1.87510407 ** 2 / (2 * math.pi * L ** 2) * math.sqrt(E * h ** 2 / (12 * rho))
    last = panel.last
    assert last.spring_constant == pytest.approx(k, rel=1e-12)
    assert last.frequencies[0] == pytest.approx(f1, rel=1e-8)
    ratio = (7.85475744 / 1.87510407) ** 2
    assert last.frequencies[2] / last.frequencies[0] == pytest.approx(ratio, rel=1e-8)
    assert last.tip_deflection == pytest.approx(F / k, rel=1e-12)
    assert last.max_stress == pytest.approx(6 * F * L / (w * h ** 2), rel=1e-12)
    html = panel.readout.value
    assert f"{k:.4g} N/m" in html and f"{f1 / 1e3:.4g}" in html and "kHz" in html
    assert f"{F / k * 1e9:.4g} nm" in html and "MPa" in html


def test_material_sets_e_and_rho_in_one_update(panel):
    calls = []
    update = panel.update
    panel.update = lambda **v: (calls.append(v), update(**v))
    panel.controls["material"].value = "silicon_nitride"  # as a user would
    assert len(calls) == 1
    m = MATERIALS["silicon_nitride"]
    assert panel.values()["youngs_modulus"] == pytest.approx(m.youngs_modulus / 1e9)
    assert panel.values()["density"] == pytest.approx(m.density)
    assert panel.last.lever.youngs_modulus == pytest.approx(m.youngs_modulus)
    panel.set(material="gold")
    assert panel.last.lever.density == pytest.approx(MATERIALS["gold"].density)
    assert len(calls) == 2


def test_slider_bounds_keep_the_model_valid():
    p = CantileverPanel(scene=False)
    for name, (lo, hi) in BOUNDS.items():
        c = p.controls[name]
        assert c.parameter is PARAMETERS[name]  # built by ui.controls.control from the model's
        if name != "exaggeration":
            assert (c.min, c.max) == pytest.approx((lo, hi), rel=1e-12, abs=1e-12)
    # every corner of the slider box is a valid lever, and the section never leaves it
    names = ["force", "length", "width", "thickness", "youngs_modulus", "density"]
    for corner in itertools.product(*[BOUNDS[n] for n in names]):
        p.set(**dict(zip(names, corner)), section=1.0)
        assert p.last.curves.section_x_um == pytest.approx(p.last.lever.length * 1e6)
        assert np.isfinite(p.last.curves.z_nm).all()
    # a value typed beyond a bound is rejected with its name and range (a slider would clamp it)
    before = p.values()
    for bad in (dict(thickness=-5.0), dict(length=1e6), dict(section=7.0)):
        with pytest.raises(ValueError, match=f"{next(iter(bad))} must be in"):
            p.set(**bad)
    assert p.values() == before
    # every material preset lies inside the E and rho sliders
    for m in MATERIALS.values():
        assert BOUNDS["youngs_modulus"][0] <= m.youngs_modulus / 1e9 <= BOUNDS["youngs_modulus"][1]
        assert BOUNDS["density"][0] <= m.density <= BOUNDS["density"][1]


def test_unknown_controls_are_rejected(panel):
    with pytest.raises(TypeError, match="unknown control"):
        panel.set(youngs=100)
    with pytest.raises(TypeError, match="unknown control"):
        CantileverPanel(scene=False, stiffness=1.0)


@pytest.mark.slow
def test_panel_with_scene_updates_the_3d_view_in_place():
    p = CantileverPanel(scene=True, material="silicon_nitride")
    assert p.last.lever.youngs_modulus == pytest.approx(
        MATERIALS["silicon_nitride"].youngs_modulus, rel=1e-15)
    view = p.scene_view()
    p.set(force=-300.0, exaggeration=1000.0, length=200.0)
    lever = p.last.lever
    sc = p.scene
    assert sc.exaggeration == pytest.approx(1000.0) and sc.lever is lever
    nl, nt = sc.n_length, sc.n_thickness
    centre = sc.mesh.vertices[:nl * nt].reshape(nl, nt, 3)[:, nt // 2]
    np.testing.assert_allclose(centre[:, 2],
                               1000 * lever.deflection(centre[:, 0] * 1e-4, -3e-7) / 1e-4, rtol=1e-5,
                               atol=1e-9)
    assert p.scene_view() is view  # the same view throughout
    assert "MPa" in p.caption.value and "x1,000" in p.caption.value
    p.set(length=1000.0, width=5.0, thickness=0.2, youngs_modulus=10.0, force=500.0)
    assert "capped" in p.caption.value  # z(L) = 0.6 m would be drawn 6 km long otherwise
    assert f"at most {DEFAULTS['max_drawn_tip']:g} L" in p.caption.value
    w = p.widget()
    readouts = w.children[0].children[1]  # beside the controls, above the figure
    assert readouts.children == (p.readout, p.caption)


def test_mode_shapes_figure_and_strain_axis():
    from afmsmiler.plots.cantilever import mode_shapes_figure
    lever = Cantilever(450e-6, 50e-6, 2e-6, 169e9, 2330.0)
    fig, lines = mode_shapes_figure(lever, modes=(1, 2, 3))
    for n, line in enumerate(lines, start=1):
        u, phi = line.get_data()
        assert u[0] == 0 and u[-1] == 1 and phi[-1] == pytest.approx(1.0) and abs(phi[0]) < 1e-12
        assert np.count_nonzero(np.diff(np.sign(phi[1:]))) == n - 1  # n - 1 nodes
        bl = (1.87510407, 4.69409113, 7.85475744)[n - 1]  # Blevins, Table 8-1
        f = bl ** 2 / (2 * math.pi * lever.length ** 2) * math.sqrt(169e9 * 4e-12 / (12 * 2330.0))
        assert f"{f / 1e3:.4g} kHz" in line.get_label()


@pytest.mark.slow
def test_section_strain_axis_is_stress_over_e(panel):
    # the top axis of the section plot reads microstrain = stress / E
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    FigureCanvasAgg(panel.fig).draw()
    lo, hi = panel.figure.axes["section"].get_xlim()  # MPa
    slo, shi = panel.figure.strain_axis.get_xlim()  # microstrain
    assert (slo, shi) == pytest.approx((lo / 169e3 * 1e6, hi / 169e3 * 1e6), rel=1e-9)
    c = panel.last.curves
    np.testing.assert_allclose(c.section_strain_micro, c.section_stress_mpa * 1e6 / 169e9 * 1e6, rtol=1e-12)


@pytest.mark.slow
def test_the_3d_view_follows_every_slider_and_nothing_closes_it():
    # before: "Run All" ended with close_viewer(), and the 3D view froze while the plots moved
    p = CantileverPanel(scene=True)
    view, scene = p.scene_view(), p.scene
    sent = view.commands_sent
    p.controls["force"].value = 200.0  # as a user would move it
    lever = p.last.lever
    assert p.last.tip_deflection == pytest.approx(200e-9 / lever.spring_constant, rel=1e-12)
    assert f"{200e-9 / lever.spring_constant * 1e9:.4g} nm" in p.readout.value
    assert p.scene is scene and scene.force == pytest.approx(200e-9) and p.error is None
    assert view.commands_sent > sent and p.scene_view() is view


@pytest.mark.slow
def test_layout_fits_one_screen():
    # Side by side (about 430 + 1000 px) the figure wrapped below a 700 px column in JupyterLab;
    # controls and readouts now sit above the figure, all unsqueezed (flex: 0 0 auto).
    from afmsmiler.ui.panel import arrange
    p = CantileverPanel(scene=False)
    w = arrange(p.widget())
    top, figure = w.children
    controls, readouts = top.children
    assert list(controls.children) == list(p.controls.values())
    assert readouts.children == (p.readout, p.caption)  # the 3D view's caption under the numbers
    assert top.layout.flex_flow == "row wrap" and controls.layout.flex == "0 0 auto"
    assert readouts.layout.width == "460px"  # a long line (the slope warning) wraps inside it
    width, height = p.fig.get_size_inches() * p.fig.dpi
    assert width <= 1000 and height <= 600
    # the labels lie inside the figure (its static, Agg-drawn copy for the book)
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    canvas = FigureCanvasAgg(p.fig)
    canvas.draw()
    r = canvas.get_renderer()
    for ax in p.figure.axes.values():
        for label in (ax.yaxis.label, ax.xaxis.label, ax.title):
            box = label.get_window_extent(r)
            assert box.x0 >= 0 and box.y0 >= 0 and box.x1 <= width and box.y1 <= height


def _elastica_tip(alpha):
    """Tip deflection / L of the inextensible elastica under a vertical end force (independent of
    the linear model): EJ theta'' = -F cos(theta), theta(0) = 0, theta'(L) = 0, alpha = F L^2/EJ."""
    from scipy.integrate import solve_bvp
    s = np.linspace(0.0, 1.0, 101)
    sol = solve_bvp(lambda s, y: np.vstack([y[1], -alpha * np.cos(y[0]), np.sin(y[0])]),
                    lambda a, b: np.array([a[0], b[1], a[2]]), s, np.zeros((3, s.size)), tol=1e-10)
    assert sol.success
    return float(sol.sol(1.0)[2])


def test_readout_warns_beyond_small_deflections():
    from afmsmiler.ui.cantilever import SMALL_SLOPE
    # at the threshold, linear theory (z/L = alpha/3, theta(L) = alpha/2) is within 1 % of the elastica
    alpha = 2 * SMALL_SLOPE
    assert alpha / 3 == pytest.approx(_elastica_tip(alpha), rel=0.01)
    # at 0.5 rad it is not (10 %): the readout must say so
    assert 1 / 3 > 1.08 * _elastica_tip(1.0)
    p = CantileverPanel(scene=False)
    assert "beyond small deflections" not in p.readout.value  # the default lever: 1.8 mrad
    p.set(thickness=0.2, force=500.0)  # theta(L) = F L^2 / (2 E J), J = w h^3 / 12
    E, L, w, h = 169e9, 450e-6, 50e-6, 0.2e-6
    theta = 500e-9 * L ** 2 / (2 * E * w * h ** 3 / 12)
    assert theta > SMALL_SLOPE
    assert "beyond small deflections" in p.readout.value and f"{theta:.2g} rad" in p.readout.value
    p.set(force=-500.0)
    assert "beyond small deflections" in p.readout.value  # either sign
    p.set(force=500.0 * 0.9 * SMALL_SLOPE / theta)
    assert "beyond small deflections" not in p.readout.value


# --- one user action, one model run -----------------------------------------------------------------
def _count_model(monkeypatch):
    """Count the runs of the model and of each of its physics methods."""
    counts = {}
    for name in ("bending", "deflection", "slope", "stress", "strain", "curvature",
                 "resonance_frequency", "mode_shape"):
        original = getattr(Cantilever, name)

        def counted(self, *a, _name=name, _original=original, **k):
            counts[_name] = counts.get(_name, 0) + 1
            return _original(self, *a, **k)
        monkeypatch.setattr(Cantilever, name, counted)
    return counts


@pytest.mark.parametrize("scene", [False, pytest.param(True, marks=[pytest.mark.slow])])
def test_one_slider_move_runs_the_model_once(monkeypatch, scene):
    # Before: the figure sampled the lever (cantilever_curves) and the scene sampled it again
    # (stress_field), and the readout asked for f1..f3 on its own: 2 samplings per move. Now the
    # panel runs Cantilever.bending once and the figures and scene only draw its result.
    p = CantileverPanel(scene=scene)
    p.show_modes()  # the mode-shape figure follows too, from the same result
    lever = p.last.lever
    counts = _count_model(monkeypatch)
    lever.bending(1e-7, section=0.3, n_length=121, n_thickness=9, n_section=41, modes=3)
    one_run = dict(counts)
    assert one_run["bending"] == 1
    for move in (dict(force=250.0), dict(length=900.0), dict(section=0.5),
                 dict(exaggeration=1000.0), dict(material="gold")):
        counts.clear()
        name, value = next(iter(move.items()))
        p.controls[name].value = value  # as a user would
        assert counts == one_run, (move, counts)
    counts.clear()
    p.set(force=-100.0, thickness=3.0, width=40.0)  # several values, one update
    assert counts == one_run
    counts.clear()
    p.controls["force"].value = p.controls["force"].value + 0.1 * p.controls["force"].step
    assert counts == {}  # the browser's echo of a snapped value runs nothing


def test_material_drop_down_is_one_model_run(monkeypatch):
    p = CantileverPanel(scene=False)
    counts = _count_model(monkeypatch)
    p.controls["material"].value = "quartz"
    assert counts["bending"] == 1
    m = MATERIALS["quartz"]
    assert p.last.lever.youngs_modulus == pytest.approx(m.youngs_modulus)
    assert p.last.lever.density == pytest.approx(m.density)


def test_double_the_length_as_notebook_01_says():
    # from 450 um the slider used to end at 500 um; now doubling gives k / 8 and f1 / 4
    p = CantileverPanel(scene=False)
    k, f1 = p.last.spring_constant, p.last.frequencies[0]
    p.set(length=2 * p.values()["length"])
    assert p.last.lever.length == pytest.approx(900e-6, rel=1e-12)
    assert p.last.spring_constant == pytest.approx(k / 8, rel=1e-9)  # k ~ 1 / L^3
    assert p.last.frequencies[0] == pytest.approx(f1 / 4, rel=1e-9)  # f ~ 1 / L^2
    p.set(thickness=p.values()["thickness"] / 2)  # "halve h": k / 8 again, f1 / 2
    assert p.last.spring_constant == pytest.approx(k / 64, rel=1e-9)


def test_mode_shapes_follow_the_sliders():
    p = CantileverPanel(scene=False)
    p.show_modes()
    fig = p.modes_figure
    before = [line.get_label() for line in fig.lines]
    p.set(length=900.0)
    lever = p.last.lever
    for n, line in enumerate(fig.lines, start=1):
        f = lever.resonance_frequency(n)
        assert line.get_label() == f"mode {n}: f = {f / 1e3:.4g} kHz"
        # f_n = (b_n L)^2 / (2 pi L^2) sqrt(E h^2 / (12 rho)) with b_n L from Blevins, Table 8-1
        bl = (1.87510407, 4.69409113, 7.85475744)[n - 1]
        assert f == pytest.approx(bl ** 2 / (2 * math.pi * 900e-6 ** 2)
                                  * math.sqrt(169e9 * 4e-12 / (12 * 2330.0)), rel=1e-8)
        u, phi = line.get_data()
        np.testing.assert_allclose(phi, lever.mode_shape(np.asarray(u) * lever.length, n),
                                   atol=1e-12)
    assert [line.get_label() for line in fig.lines] != before
    assert [t.get_text() for t in fig.legend.get_texts()] == [ln.get_label() for ln in fig.lines]


def _legend_covers_data(fig, legend, lines):
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    canvas = FigureCanvasAgg(fig)
    canvas.draw()
    box = legend.get_window_extent(canvas.get_renderer())
    for line in lines:
        xy = line.axes.transData.transform(np.column_stack(line.get_data()))
        inside = ((xy[:, 0] >= box.x0) & (xy[:, 0] <= box.x1)
                  & (xy[:, 1] >= box.y0) & (xy[:, 1] <= box.y1))
        if inside.any():
            return True
    return False


@pytest.mark.slow
def test_mode_legend_covers_no_curve():
    p = CantileverPanel(scene=False)
    p.show_modes()
    for length in (20.0, 450.0, 1000.0):
        p.set(length=length)
        fig = p.modes_figure
        assert not _legend_covers_data(fig.fig, fig.legend, fig.lines)
        # and the legend stays inside the figure
        from matplotlib.backends.backend_agg import FigureCanvasAgg
        canvas = FigureCanvasAgg(fig.fig)
        canvas.draw()
        box = fig.legend.get_window_extent(canvas.get_renderer())
        w, h = fig.fig.get_size_inches() * fig.fig.dpi
        assert box.x0 >= 0 and box.x1 <= w and box.y0 >= 0 and box.y1 <= h


def test_initial_values_are_checked_by_name():
    with pytest.raises(ValueError, match=r"^length must be in \[20, 1000\] um, got 2000"):
        CantileverPanel(scene=False, length=2000.0)
    with pytest.raises(ValueError, match="material must be one of"):
        CantileverPanel(scene=False, material="unobtainium")
    with pytest.raises(ValueError, match="material must be one of"):
        CantileverPanel(scene=False).set(material="unobtainium")
    p = CantileverPanel(scene=False, material="gold", youngs_modulus=100.0)
    assert p.last.lever.youngs_modulus == pytest.approx(100e9)  # given beats the preset
    assert p.last.lever.density == pytest.approx(MATERIALS["gold"].density)
    with pytest.raises(TypeError):
        p.update(force=1.0)  # update takes every control value, by name
    for values in (dict(youngs_modulus=120.0, material="quartz"),
                   dict(material="quartz", youngs_modulus=120.0)):
        p.set(**values)  # E given with a material wins, whatever the order
        assert p.last.lever.youngs_modulus == pytest.approx(120e9)
        assert p.last.lever.density == pytest.approx(MATERIALS["quartz"].density)
        p.set(material="silicon")


def test_defaults_are_read_only_and_on_the_slider_grid():
    from afmsmiler.ui.cantilever import DEFAULTS as PANEL
    with pytest.raises(TypeError):
        PANEL["length"] = 500.0
    p = CantileverPanel(scene=False)
    for name in SLIDERS:
        c = p.controls[name]
        assert c.value == pytest.approx(PANEL[name], rel=1e-12)
        if name != "exaggeration":  # a log slider's grid is in the exponent
            n = (c.value - c.min) / c.step
            assert abs(n - round(n)) < 1e-6, name  # the browser echoes it unchanged


def test_exercise_1_can_be_checked_with_the_sliders():
    # notebook 01, exercise 1: "work out h for k = 0.1 N/m, then check it with the sliders"; the
    # closed form h = (4 k L^3 / (E w))^(1/3) = 1.628 um lies between two thickness steps, and the
    # nearer one gives k within 1 % of 0.1 N/m
    h = (4 * 0.1 * 450e-6 ** 3 / (169e9 * 50e-6)) ** (1 / 3) * 1e6
    p = CantileverPanel(scene=False)
    c = p.controls["thickness"]
    nearest = c.min + round((h - c.min) / c.step) * c.step
    p.set(thickness=nearest)
    assert p.last.spring_constant == pytest.approx(0.1, rel=0.01)


def test_update_names_a_bad_value_before_any_work():
    p = CantileverPanel(scene=False)
    good = p.to_si(p.values())  # update takes SI (the panel contract)
    assert good["length"] == pytest.approx(450e-6)
    last = p.last
    for name, bad in (("force", "lots"), ("length", None), ("thickness", math.inf),
                      ("force", 1e300), ("material", "cheese")):
        with pytest.raises((TypeError, ValueError), match=f"^{name} must"):
            p.update(**{**good, name: bad})
    assert p.last is last


def test_model_and_values_hold_the_decimals_shown_after_the_browser_echo():
    # In JupyterLab after Run All the panel held force 99.99999999999999 nN and a lever of
    # width 4.999999999999999e-05 m (a unit conversion's round-off), while the sliders read 100
    # and 50. The independent reference: notebook 01's lever, 450 x 50 x 2 um of silicon under
    # F = 100 nN, typed as decimals.
    shown = dict(force=100.0, length=450.0, width=50.0, thickness=2.0, youngs_modulus=169.0,
                 density=2330.0, section=0.0, exaggeration=100.0)
    from afmsmiler.ui.cantilever import DEFAULTS as PANEL
    assert {n: PANEL[n] for n in shown} == shown
    p = CantileverPanel(scene=False)
    for name, c in p.controls.items():  # the browser echoes the value it drew, as a decimal
        if name in shown:
            c.value = float(f"{c.value:.6g}")
    assert {n: p.values()[n] for n in shown} == shown
    assert p.last.lever == Cantilever(450e-6, 50e-6, 2e-6, 169e9, 2330.0)
    assert p.last.force == 100e-9
    p.set(width=40.0, length=300.0)
    assert (p.last.lever.width, p.last.lever.length) == (40e-6, 300e-6)


# --- limits that hold while the curves stay inside them (issue 9) ---------------------------------
def _limits(panel, key, axis="y"):
    return getattr(panel.figure.axes[key], f"get_{axis}lim")()


def test_one_force_step_moves_the_curve_not_the_axes(panel):
    # the axes autoscaled with the force, so the curves never seemed to move (issue 9)
    before = {k: _limits(panel, k) for k in ("z", "theta", "stress_top", "section")}
    section_x = _limits(panel, "section", "x")
    z_before = float(np.max(panel.figure.lines["z"].get_data()[1]))
    step = panel.controls["force"].step
    panel.set(force=SET["force"] + step)
    z_after = float(np.max(panel.figure.lines["z"].get_data()[1]))
    assert z_after == pytest.approx(z_before * (SET["force"] + step) / SET["force"], rel=1e-12)
    for key, lim in before.items():
        assert _limits(panel, key) == lim, key
    assert _limits(panel, "section", "x") == section_x
    panel.set(force=SET["force"] - step)
    assert _limits(panel, "z") == before["z"]


def test_a_big_force_move_rescales_and_shows_the_curve(panel):
    lo, hi = _limits(panel, "z")
    for force in (500.0, 20.0, -300.0):   # out through the top, shrunk to 8 %, sign flipped
        panel.set(force=force)
        z = np.asarray(panel.figure.lines["z"].get_data()[1])
        new = _limits(panel, "z")
        assert new != (lo, hi), force
        # the curve lies inside and fills at least the shrink fraction of the axis
        assert new[0] <= min(z.min(), 0.0) and max(z.max(), 0.0) <= new[1]
        assert np.ptp(np.r_[z, 0.0]) >= 0.3 * (new[1] - new[0])
        lo, hi = new


def test_the_first_draw_fits_the_data_and_f_0_stays_readable():
    p = CantileverPanel(scene=False, **SET)
    z = np.asarray(p.figure.lines["z"].get_data()[1])
    lo, hi = _limits(p, "z")
    assert lo < 0.0 < hi and hi < 1.5 * z.max()    # 8 % margins around [0, max z]
    assert _limits(p, "z", "x") == (0.0, pytest.approx(SET["length"]))
    p.set(force=0.0)
    for key in ("z", "theta", "stress_top"):
        lo, hi = _limits(p, key)
        assert lo < 0.0 < hi and np.isfinite(hi - lo) and hi - lo > 0, key


def test_the_lever_gets_longer_on_fixed_axes(panel):
    # one length step: the curve ends further along an x axis that stays put; a big one refits
    x_lim = _limits(panel, "z", "x")
    step = panel.controls["length"].step
    panel.set(length=SET["length"] - step)
    assert _limits(panel, "z", "x") == x_lim
    panel.set(length=600.0)
    lo, hi = _limits(panel, "z", "x")
    assert lo == 0.0 and 600.0 <= hi


def test_during_a_drag_the_3d_view_and_its_caption_follow_the_figure_s_paint(monkeypatch):
    # issue 24: the stress-coloured lever (21 commands, 240 kB) was built and sent while the
    # figure's frame was on its way; during a drag it is sent once the page painted that frame
    import afmsmiler.ui.panel as panel_module
    from afmsmiler.plots.live import LiveFigure
    from tests.recording import Recorder
    from tests.test_ui_panel import _Loop
    loop = _Loop()
    monkeypatch.setattr(panel_module, "_live_loop", lambda: loop)
    vis = Recorder()
    p = CantileverPanel(vis=vis)
    p.live = LiveFigure(p.fig)
    p.live._handle_message(p.live, {"painted": p.live.frames_sent}, [])  # a page painted it
    calls, frames = len(vis.calls), p.live.frames_sent
    p.in_drag = True
    p.set(force=-250.0, exaggeration=20.0)
    p.in_drag = False
    assert p.live.frames_sent == frames + 1 and f"{p.last.tip_deflection * 1e9:.4g} nm" in \
        p.readout.value  # the figure and the numbers at once
    assert len(vis.calls) == calls and "deflection x20," not in p.caption.value  # the view waits
    loop.run()
    assert len(vis.calls) == calls  # ... for the paint
    p.live._handle_message(p.live, {"painted": p.live.frames_sent}, [])
    loop.now += 0.01
    loop.run()
    assert len(vis.calls) > calls and "deflection x20," in p.caption.value
    assert p.scene.lever is p.last.lever and p.scene.exaggeration == pytest.approx(20.0)
