"""Colours: the ends of a scale map to the colormap's ends, values outside clip, limits round up to
1, 2 or 5 x 10^n."""
import matplotlib
import numpy as np
import pytest

from afmsmiler.scenes.colors import ColorScale, nice_ceil, rgb_hex


def test_color_scale_maps_extremes_to_the_colormap_ends_and_clips():
    scale = ColorScale.symmetric(2.0, "RdBu_r", "stress", "MPa")
    cmap = matplotlib.colormaps["RdBu_r"]
    rgb = scale.rgb([-2.0, 2.0, -50.0, 50.0, 0.0])
    np.testing.assert_allclose(rgb[0], cmap(0.0)[:3], atol=1e-6)
    np.testing.assert_allclose(rgb[1], cmap(1.0)[:3], atol=1e-6)
    np.testing.assert_allclose(rgb[2], rgb[0])  # clipped below
    np.testing.assert_allclose(rgb[3], rgb[1])  # clipped above
    assert rgb[1][0] > rgb[1][2] and rgb[0][2] > rgb[0][0]  # tension red, compression blue
    assert rgb[4].min() > 0.9  # the middle of a diverging map is (nearly) white
    assert scale.title == "stress [MPa]"
    assert rgb_hex([1.0, 0.0, 0.0]) == 0xff0000


def test_color_scale_shape_and_bad_input():
    scale = ColorScale(0.0, 1.0, "viridis")
    assert scale.rgb(np.zeros((4, 5))).shape == (4, 5, 3)
    with pytest.raises(ValueError, match="vmax must be in"):
        ColorScale(1.0, 1.0)
    with pytest.raises(ValueError, match="cmap must be"):
        ColorScale(0.0, 1.0, "no-such-map")
    with pytest.raises(ValueError, match="limit must be > 0"):
        ColorScale.symmetric(0.0)


@pytest.mark.parametrize("value, expected", [(0.13, 0.2), (1.0, 1.0), (3.0, 5.0), (7.0, 10.0),
                                             (-0.0042, 0.005), (0.0, 1e-3), (1.2e5, 2e5)])
def test_nice_ceil(value, expected):
    assert nice_ceil(value, floor=1e-3) == pytest.approx(expected, rel=1e-12)



def test_color_scale_rejects_nan_by_name_and_clips_infinities():
    # NaN went through np.rint(nan).astype(intp): an index of -2**63 and an IndexError (or, on
    # some platforms, the colour of an arbitrary end of the table)
    scale = ColorScale(0.0, 1.0, "viridis")
    with pytest.raises(ValueError, match=r"values must not be NaN, got 1 NaN of 3"):
        scale.rgb([0.0, np.nan, 1.0])
    with pytest.raises(ValueError, match="values must be real numbers"):
        scale.rgb(np.array([1 + 2j]))
    with pytest.raises(ValueError, match="values must be real numbers"):
        scale.rgb(["0.5"])
    rgb = scale.rgb([-np.inf, np.inf])  # beyond the scale: its end colours, like any far value
    np.testing.assert_allclose(rgb, scale.rgb([-1e300, 1e300]))


def test_color_scale_of_the_widest_limits_does_not_overflow():
    # before: vmax - vmin = inf, so every value mapped to the vmin end (0 was drawn as -1.8e308)
    scale = ColorScale(-1.7e308, 1.7e308, "viridis")
    np.testing.assert_allclose(scale.normalize([-1.7e308, 0.0, 1.7e308]), [0.0, 0.5, 1.0])
