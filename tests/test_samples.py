"""Sample generators: shapes, physical sizes and statistics against their definitions; the real
WSxM image read in SI units, checked against its own header and AFMReader's published values."""
import numpy as np
import pytest

from afmsmiler import samples


def test_step_and_grating_geometry():
    s = samples.step(100, 2e-9, 30e-9, position=0.5)
    assert s.heights.shape == (100,) and s.pixel_size == 2e-9
    assert s.size == pytest.approx(99 * 2e-9)
    np.testing.assert_allclose(s.x, np.arange(100) * 2e-9)
    assert set(np.unique(s.heights)) == {0.0, 30e-9}
    assert np.count_nonzero(s.heights) == 50  # x/(n-1) >= 0.5 for the upper half
    g = samples.grating(400, 1e-9, period=100e-9, height=20e-9, duty=0.25)
    # 25 of every 100 pixels raised, 4 periods
    assert np.count_nonzero(g.heights) == 100
    np.testing.assert_array_equal(g.heights[:100], g.heights[100:200])
    assert g.heights[0] == 20e-9 and g.heights[25] == 0.0


def test_rough_surface_statistics():
    s = samples.rough_surface((256, 256), 2e-9, rms=3e-9, correlation_length=10e-9, seed=4)
    assert s.heights.std() == pytest.approx(3e-9, rel=1e-12)
    # Gaussian filter exp(-(pi l f)^2) on white noise: autocorrelation exp(-r^2 / (2 l^2)) / ...
    # so neighbours (r = l/5) are strongly correlated, points 5 l apart are not
    h = s.heights - s.heights.mean()
    near = np.mean(h[:, :-1] * h[:, 1:]) / h.var()
    far = np.mean(h[:, :-25] * h[:, 25:]) / h.var()
    assert near > 0.9 and abs(far) < 0.1
    np.testing.assert_array_equal(s.heights, samples.rough_surface(
        (256, 256), 2e-9, rms=3e-9, correlation_length=10e-9, seed=4).heights)
    assert samples.rough_surface(64, 1e-9).heights.shape == (64,)


def test_particles_and_profiles():
    img = samples.particles((64, 128), 4e-9, count=5, radius=20e-9, rms=0.5e-9)
    assert img.heights.shape == (64, 128)
    assert img.heights.max() == pytest.approx(40e-9, rel=0.02)  # sphere top at 2 r
    line = img.line(3)
    np.testing.assert_array_equal(line.heights, img.heights[3])
    for name in samples.PROFILES:
        p = samples.profile(name, 256, 4e-9, 50e-9)
        assert p.heights.shape == (256,) and p.pixel_size == 4e-9
        assert np.ptp(p.heights) == pytest.approx(50e-9, rel=0.1)


# --- the real image --------------------------------------------------------------------------
HEADER_SIZE = 2996  # "Image header size: 2996" on the file's third line


def test_real_image_units_from_its_header():
    """The header says: X/Y Amplitude 500 nm over 512 x 512 pixels, Z Amplitude 59.7449 nm,
    Minimum/Maximum -19468/-5073 (int16 counts)."""
    img = samples.from_file(samples.REAL_IMAGE)
    assert img.heights.shape == (512, 512)
    assert img.pixel_size == pytest.approx(500e-9 / 512, rel=1e-15)
    assert img.pixel_size_y == pytest.approx(500e-9 / 512, rel=1e-15)
    assert np.ptp(img.heights) == pytest.approx(59.7449e-9, rel=1e-12)
    # independently: the counts as stored, and their conversion through the electronics:
    # 13.6 nm/V ("Conversion Factor 00") over the DSP's 20 V range in 2^16 counts
    counts = np.fromfile(samples.REAL_IMAGE, "<i2", offset=HEADER_SIZE).reshape(512, 512)
    assert counts.min() == -19468 and counts.max() == -5073
    nm_per_count = 13.6 * 20 / 2 ** 16
    np.testing.assert_allclose(img.heights, counts * nm_per_count * 1e-9, rtol=2e-5)


def test_real_image_matches_afmreader_published_values():
    """AFMReader 0.0.7, tests/test_top.py, the same file (its resources/sample_0.top): pixel
    scaling 0.9765625 nm and image sum 6034386.429246264 nm, from its load_top, which shifts
    the minimum to 0 and reads only the integer part of Z Amplitude (59 nm, not 59.7449 nm:
    a 1.3 % height error that this reader does not make)."""
    img = samples.from_file(samples.REAL_IMAGE)
    assert img.pixel_size * 1e9 == pytest.approx(0.9765625, rel=1e-12)
    z_nm = (img.heights - img.heights.min()) * 1e9
    assert np.sum(z_nm * 59 / 59.7449) == pytest.approx(6034386.429246264, rel=1e-12)


def test_real_image_levelled_and_its_line():
    img = samples.real_image()
    np.testing.assert_allclose(np.median(img.heights, axis=1), 0.0, atol=1e-20)
    # molecules on a flat substrate: about 2 nm high, the substrate within a few Angstrom
    assert 1e-9 < np.max(img.heights) < 3e-9 and np.percentile(np.abs(img.heights), 50) < 3e-10
    row = img.heights[samples.REAL_LINE_ROW]
    line = samples.profile("real line", 300, 4e-9, 50e-9)
    assert np.ptp(line.heights) == pytest.approx(50e-9, rel=1e-12) and line.pixel_size == 4e-9
    # the same shape: an affine image of the real row's first 300 pixels
    assert np.corrcoef(line.heights, row[:300])[0, 1] == pytest.approx(1.0, abs=1e-12)
    with pytest.raises(ValueError, match="pixels must be an integer in"):
        samples.profile("real line", 600)


def test_wsxm_doubles_read_like_shorts(tmp_path):
    """The same image stored as doubles (as WSxM writes .stp files; AFMReader's 2 MB
    sample_0.stp of this very image reads to within 2e-23 m of the .top)."""
    raw = samples.REAL_IMAGE.read_bytes()
    header = raw[:HEADER_SIZE].replace(b"Image Data Type: short", b"Image Data Type: double")
    header = header.replace(b"Image header size: 2996", b"Image header size: 2997")
    counts = np.frombuffer(raw, "<i2", offset=HEADER_SIZE)
    path = tmp_path / "doubles.stp"
    path.write_bytes(header + (counts * 0.25 + 3.0).astype("<f8").tobytes())
    # values scale so that their range is Z Amplitude (59.7449 nm over 14395 counts), offset
    # included, as Gwyddion does: 3.0 is 12 counts' worth
    expected = samples.from_file(samples.REAL_IMAGE).heights + 12 * 59.7449e-9 / 14395
    np.testing.assert_allclose(samples.from_file(path).heights, expected, rtol=0, atol=1e-22)


def test_from_file_rejects_what_it_cannot_read(tmp_path):
    with pytest.raises(ValueError, match=r"path must name a file of type \['.stp', '.top'\]"):
        samples.from_file(tmp_path / "image.png")
    with pytest.raises(ValueError, match="path must name an existing file"):
        samples.from_file(tmp_path / "missing.top")
    bad = tmp_path / "bad.top"
    bad.write_bytes(b"not an image" * 10)
    with pytest.raises(ValueError, match="is not a WSxM image"):
        samples.from_file(bad)
    # a channel in volts is not a height image
    raw = samples.REAL_IMAGE.read_bytes().replace(b"Z Amplitude: 59.7449 nm",
                                                   b"Z Amplitude: 59.7449 V ")
    volts = tmp_path / "volts.top"
    volts.write_bytes(raw)
    with pytest.raises(ValueError, match="Z Amplitude must be a length"):
        samples.from_file(volts)
    # micrometres are read as such
    um = tmp_path / "um.top"
    um.write_bytes(samples.REAL_IMAGE.read_bytes().replace(b"X Amplitude: 500 nm",
                                                            b"X Amplitude: 0.5 \xb5m"))
    assert samples.from_file(um).pixel_size == pytest.approx(500e-9 / 512, rel=1e-12)


@pytest.mark.parametrize("call, match", [
    (lambda: samples.step(1), "pixels must be an integer in"),
    (lambda: samples.step(10, -1e-9), "pixel_size must be > 0 m"),
    (lambda: samples.step(10, 1e-9, np.nan), "height must be a finite"),
    (lambda: samples.grating(10, 1e-9, period=0.0), "period must be > 0 m"),
    (lambda: samples.grating(10, 1e-9, duty=1.0), r"duty must be in \(0, 1\)"),
    (lambda: samples.rough_surface((4, 4, 4)), "shape must be"),
    (lambda: samples.rough_surface(8, rms=-1e-9), "rms must be in"),
    (lambda: samples.profile("moon"), "name must be one of"),
    (lambda: samples.Sample(np.zeros((2, 2, 2)), 1e-9), "heights must be a 1-D or 2-D"),
    (lambda: samples.Sample([0.0, np.inf], 1e-9), "heights must be finite"),
    (lambda: samples.step(10).line(0), "line\\(\\) needs a 2-D sample"),
    (lambda: samples.Sample(np.zeros((2, 2)), 1e-9, pixel_size_y=0.0),
     "pixel_size_y must be > 0 m"),
])
def test_bad_input(call, match):
    with pytest.raises(ValueError, match=match):
        call()
