"""Real files through AFMReader and gwyfile, in SI units: each checked against the numbers its own
software reports (the reader's own tests) or its header, decoded here independently; bad files
named before any work; a .gwy export read back by gwyfile and AFMReader."""
import hashlib
import re
import time

import numpy as np
import pytest

from afmsmiler import data, samples
from afmsmiler.samples import readers

DATA = __import__("pathlib").Path(__file__).parent / "data"
WSXM = DATA / "afmreader_sample_0.top"
WSXM_HEADER = 2996  # "Image header size: 2996" on the file's third line
SPM = samples.REAL_IMAGE
SPM_OFFSETS = {"Height": 40960, "Amplitude": 565248}  # "Data offset" of each Ciao image


def test_data_files_are_the_ones_the_readmes_name():
    def sha(p):
        return hashlib.sha256(p.read_bytes()).hexdigest()
    for name in ("afmreader_sample_0.top", "afmreader_sample_1_um_scale.top"):
        assert sha(DATA / name) in (DATA / "README.md").read_text()
    assert sha(SPM) in (SPM.parent / "README.md").read_text()
    assert "wsxm_sample_0.top" not in data.names()  # the GPL file no longer ships
    assert all(p.stat().st_size < 2e6 for p in DATA.iterdir())


# --- Bruker NanoScope (.spm): the shipped real image ------------------------------------------
def test_spm_height_is_the_header_scale_times_the_stored_counts():
    """nanoscope's own test (jmarini/nanoscope tests/test_file.py, the same file) reads the
    height counts as they are stored (its reference_raw.csv starts -8417, -8416, -8414); the
    header converts them: "@2:Z scale: V [Sens. Zscan] (0.006693481 V/LSB)" times
    "@Sens. Zscan: V 12.95302 nm/V", over "Scan size: 2 2 ~m" in 512 x 512 pixels."""
    img = samples.load(SPM)
    assert img.shape == (512, 512) and img.channel == "Height" and img.unit == "m"
    assert img.pixel_size == pytest.approx(2e-6 / 512, rel=1e-15)
    assert img.pixel_size_y == pytest.approx(2e-6 / 512, rel=1e-15)
    counts = np.fromfile(SPM, "<i2", offset=SPM_OFFSETS["Height"], count=512 * 512)
    counts = counts.reshape(512, 512)
    np.testing.assert_array_equal(counts[0, :3], [-8417, -8416, -8414])
    nm_per_count = 0.006693481 * 12.95302  # the header's printed values: 7 digits
    # NanoScope stores the lines from the bottom up: the first stored line is the last row
    np.testing.assert_allclose(img.heights, np.flipud(counts) * nm_per_count * 1e-9, rtol=2e-5)
    assert img.metadata["Samps/line"] == "512" and img.metadata["Frame direction"] == "Down"


def test_spm_height_statistics_match_the_nanoscope_library():
    """nanoscope's tests/test_image.py on this file, after its process(order=1) (a straight
    line fitted to each scan line and subtracted, in counts rounded to integers, then converted
    to nm): Ra 3.433 nm, RMS 4.325 nm, highest peak 14.478 nm and deepest valley 12.918 nm above
    and below the mean (to 0.001 nm). The rounding to whole counts (0.087 nm) moves the RMS and
    Ra by about 1e-4 nm and an extreme by up to 0.043 nm."""
    h = samples.load(SPM).heights * 1e9
    x = np.arange(h.shape[1])
    fits = np.polynomial.polynomial.polyfit(x, h.T, 1)  # one line per row
    flat = h - (fits[0][:, None] + fits[1][:, None] * x[None, :])
    dev = flat - flat.mean()
    assert np.mean(np.abs(dev)) == pytest.approx(3.433, abs=0.002)
    assert np.sqrt(np.mean(dev ** 2)) == pytest.approx(4.325, abs=0.002)
    assert dev.max() == pytest.approx(14.478, abs=0.05)
    assert -dev.min() == pytest.approx(12.918, abs=0.05)


def test_spm_channels_and_units():
    assert samples.channels(SPM) == ["Height", "Amplitude"]
    amp = samples.load(SPM, "Amplitude", unit="V")
    counts = np.fromfile(SPM, "<i2", offset=SPM_OFFSETS["Amplitude"], count=512 * 512)
    # one scale factor from counts to volts for every pixel
    with np.errstate(invalid="ignore", divide="ignore"):
        ratio = amp.heights / np.flipud(counts.reshape(512, 512))
    assert amp.unit == "V" and np.allclose(ratio[np.isfinite(ratio)], ratio.flat[0], rtol=1e-9)
    with pytest.raises(ValueError, match=re.escape("channel must be one of the channels of "
                                                   "bruker_d3100.spm: ['Height', 'Amplitude'], "
                                                   "got 'Phase'")):
        samples.load(SPM, "Phase")
    with pytest.raises(ValueError, match="channel 'Amplitude' of bruker_d3100.spm is in 'V', "
                                         "not 'm'"):
        samples.load(SPM, "Amplitude")


def test_real_image_levelled_and_its_line():
    img = samples.real_image()
    np.testing.assert_allclose(np.median(img.heights, axis=1), 0.0, atol=1e-20)
    row = img.heights[samples.REAL_LINE_ROW]
    line = samples.profile("real line", 300, 4e-9, 50e-9)
    assert np.ptp(line.heights) == pytest.approx(50e-9, rel=1e-12) and line.pixel_size == 4e-9
    # the same shape: an affine image of the real row's first 300 pixels
    assert np.corrcoef(line.heights, row[:300])[0, 1] == pytest.approx(1.0, abs=1e-12)
    with pytest.raises(ValueError, match="pixels must be an integer in"):
        samples.profile("real line", 600)


def test_the_real_line_claims_of_notebook_03():
    """Notebook 03, exercise 1: on the real line (row REAL_LINE_ROW, scaled to 50 nm on 4 nm
    pixels) preset (a)'s own gains at 1000 um/s "give about 5 nm" of RMS height error, and
    faster gains can bring it under 1 nm (the checker's own example answer)."""
    from afmsmiler.controller import PRESETS
    from afmsmiler.exercises.controller import height_error
    assert samples.REAL_LINE_ROW == 256
    loop = PRESETS["a_good_tracking"].loop
    assert 4.5e-9 < height_error(loop, 1e-3) < 5.5e-9
    assert height_error(loop.replace(kp=30, ki=3e6, kd=1e-7), 1e-3) < 1e-9


# --- WSxM (.top): AFMReader's own test file ---------------------------------------------------
def test_wsxm_top_matches_its_header_and_afmreader_published_values():
    """AFMReader 0.0.7 tests/test_top.py on this file: pixel scaling 0.9765625 nm and image sum
    6034386.429246264 nm (its load_top shifts the minimum to 0 and spreads the counts over the
    integer part of Z Amplitude: 59 nm, not the header's 59.7449 nm). The header: X/Y Amplitude
    500 nm over 512 x 512, Minimum/Maximum -19468/-5073 int16 counts."""
    img = samples.load(WSXM)
    assert img.shape == (512, 512) and img.channel == "Topography" and img.unit == "m"
    assert img.pixel_size * 1e9 == pytest.approx(0.9765625, rel=1e-12)
    assert np.ptp(img.heights) == pytest.approx(59.7449e-9, rel=1e-12)
    z_nm = (img.heights - img.heights.min()) * 1e9
    assert np.sum(z_nm * 59 / 59.7449) == pytest.approx(6034386.429246264, rel=1e-12)
    counts = np.fromfile(WSXM, "<i2", offset=WSXM_HEADER).reshape(512, 512)
    assert counts.min() == -19468 and counts.max() == -5073
    # and through the electronics: 13.6 nm/V ("Conversion Factor 00") over 20 V in 2^16 counts
    nm_per_count = 13.6 * 20 / 2 ** 16
    np.testing.assert_allclose(img.heights, (counts - counts.min()) * nm_per_count * 1e-9,
                               rtol=2e-5, atol=1e-14)
    assert samples.channels(WSXM) == ["Topography"]
    assert img.metadata["X Amplitude"] == "500 nm"


def test_wsxm_top_in_micrometres_matches_afmreader_published_values():
    """AFMReader 0.0.7 tests/test_top.py, sample_1_um_scale.top: pixel scaling 3.90625 nm
    ("X Amplitude: 2 um" over 512 columns) and image sum 125175.99999999997 nm, its counts spread
    over 4 nm, the integer part of the header's "Z Amplitude: 4.53125 nm" (a 12 % height error
    that this reader does not make: the heights span 4.53125 nm)."""
    img = samples.load(DATA / "afmreader_sample_1_um_scale.top")
    assert img.pixel_size == pytest.approx(3.90625e-9, rel=1e-12)
    assert np.ptp(img.heights) == pytest.approx(4.53125e-9, rel=1e-12)
    z_nm = (img.heights - img.heights.min()) * 1e9
    assert np.sum(z_nm * 4 / 4.53125) == pytest.approx(125175.99999999997, rel=1e-12)
    counts = np.fromfile(DATA / "afmreader_sample_1_um_scale.top", "<i2", offset=3193)
    assert counts.min() == -2848 and counts.max() == -2616  # the header's Minimum, Maximum


def _wsxm(tmp_path, old, new, name="image.top"):
    """The WSxM test file with one header field changed (to a text of the same length)."""
    raw = WSXM.read_bytes()
    old, new = old.encode("latin-1"), new.encode("latin-1")
    assert len(old) == len(new) and old in raw[:WSXM_HEADER]
    path = tmp_path / name
    path.write_bytes(raw.replace(old, new, 1))
    return path


def test_wsxm_units_from_the_header(tmp_path):
    um = _wsxm(tmp_path, "X Amplitude: 500 nm", "X Amplitude: 0.5 \u00b5m")
    assert samples.load(um).pixel_size == pytest.approx(500e-9 / 512, rel=1e-12)
    volts = _wsxm(tmp_path, "Z Amplitude: 59.7449 nm", "Z Amplitude: 59.7449 V ")
    with pytest.raises(ValueError, match="Z Amplitude must be a length"):
        samples.load(volts)
    for old, new, field in (("Z Amplitude: 59.7449", "Z Amplitude: -59.745", "Z"),
                            ("X Amplitude: 500 nm", "X Amplitude: -50 nm", "X")):
        with pytest.raises(ValueError, match=f"{field} Amplitude must be a positive length"):
            samples.load(_wsxm(tmp_path, old, new))


def test_wsxm_stp_doubles_are_nm_and_rectangular_scans_are_named(tmp_path):
    """AFMReader reads .stp doubles as nm (its sample_0.stp of the .top above sums to
    -15070620 nm: a mean of -57.5 nm, the .top's counts times 13.6 nm/V x 20 V / 2^16). Here the
    .top's counts stored as doubles in nm, under the .top's header made a double one."""
    raw = WSXM.read_bytes()
    header = raw[:WSXM_HEADER].replace(b"Image Data Type: short", b"Image Data Type: double")
    header = header.replace(b"Image header size: 2996", b"Image header size: 2997")
    counts = np.frombuffer(raw, "<i2", offset=WSXM_HEADER).reshape(512, 512)
    nm = counts * (13.6 * 20 / 2 ** 16)
    path = tmp_path / "doubles.stp"
    path.write_bytes(header + nm.astype("<f8").tobytes())
    img = samples.load(path)
    np.testing.assert_allclose(img.heights, nm * 1e-9, rtol=1e-15)
    assert img.pixel_size == pytest.approx(500e-9 / 512, rel=1e-12)
    assert np.mean(nm) == pytest.approx(-15070620.440757688 / 512 ** 2, rel=0.01)
    wide = _wsxm(tmp_path, "Y Amplitude: 500 nm", "Y Amplitude: 400 nm")
    with pytest.raises(ValueError, match="image.top: AFMReader cannot read it .*square"):
        samples.load(wide)


# --- Gwyddion (.gwy): written here, read by gwyfile and AFMReader -----------------------------
def test_gwy_export_round_trips_through_gwyfile_and_afmreader(tmp_path):
    import gwyfile
    from AFMReader.gwy import load_gwy
    img = samples.load(SPM).crop(x=(0, 255 * 3.90625e-9), y=(0, 255 * 3.90625e-9))
    path = samples.save_gwy(img, tmp_path / "image.gwy")
    field = gwyfile.load(str(path))["/0/data"]
    np.testing.assert_array_equal(field.data, img.heights)
    assert field.xreal == 256 * img.pixel_size and field.yreal == 256 * img.pixel_size_y
    assert field.si_unit_xy.unitstr == "m" and field.si_unit_z.unitstr == "m"
    nm, px_nm = load_gwy(path, "Height")
    np.testing.assert_allclose(nm, img.heights * 1e9, rtol=1e-15)
    assert px_nm == pytest.approx(img.pixel_size * 1e9, rel=1e-15)
    back = samples.load(path)
    np.testing.assert_array_equal(back.heights, img.heights)
    assert back.pixel_size == pytest.approx(img.pixel_size, rel=1e-15)
    assert samples.channels(path) == ["Height"]


def test_gwy_keeps_rectangular_pixels_and_other_units(tmp_path):
    s = samples.Sample(np.arange(12.0).reshape(3, 4) * 0.1, 2e-9, "amp", 5e-9, channel="Amp",
                       unit="V")
    back = samples.load(samples.save_gwy(s, tmp_path / "a.gwy"), "Amp", unit="V")
    np.testing.assert_array_equal(back.heights, s.heights)
    assert (back.pixel_size, back.pixel_size_y) == pytest.approx((2e-9, 5e-9), rel=1e-15)
    assert back.unit == "V"
    with pytest.raises(ValueError, match="sample must be an image"):
        samples.save_gwy(samples.step(10), tmp_path / "line.gwy")
    with pytest.raises(ValueError, match="path must end in .gwy"):
        samples.save_gwy(s, tmp_path / "a.png")


# --- plain maps -------------------------------------------------------------------------------
def test_npy_and_text_maps_need_their_pixel_size(tmp_path):
    h = np.arange(20.0).reshape(4, 5)
    np.save(tmp_path / "h.npy", h)
    np.savetxt(tmp_path / "h.txt", h)
    np.savetxt(tmp_path / "h.csv", h, delimiter=",")
    for name in ("h.npy", "h.txt", "h.csv"):
        s = samples.load(tmp_path / name, pixel_size=2e-9, unit="nm")
        np.testing.assert_allclose(s.heights, h * 1e-9, rtol=1e-15)
        assert s.pixel_size == 2e-9 and s.unit == "m"
        with pytest.raises(ValueError, match="pixel_size must be given"):
            samples.load(tmp_path / name)
    bad = h.copy()
    bad[1, 2] = np.nan
    np.save(tmp_path / "nan.npy", bad)
    with pytest.raises(ValueError, match=r"nan.npy: the image holds 1 values that are not "
                                         r"finite"):
        samples.load(tmp_path / "nan.npy", pixel_size=1e-9)
    with pytest.raises(ValueError, match="pixel_size must be None for a .spm file"):
        samples.load(SPM, pixel_size=1e-9)


# --- bad files --------------------------------------------------------------------------------
def test_bad_files_are_named_before_any_work(tmp_path):
    with pytest.raises(ValueError, match=r"path must name a file of type \['.asc', '.asd'"):
        samples.load(tmp_path / "image.png")
    with pytest.raises(ValueError, match="path must name an existing file"):
        samples.load(tmp_path / "missing.top")
    with pytest.raises(ValueError, match="path must be a str or os.PathLike"):
        samples.load(3)
    empty = tmp_path / "empty.spm"
    empty.write_bytes(b"")
    with pytest.raises(ValueError, match="empty.spm: the file is empty"):
        samples.load(empty)
    for suffix, what in ((".top", "is not a WSxM image"), (".spm", "is not a Bruker NanoScope"),
                         (".gwy", "is not a Gwyddion file"), (".ibw", "is not an Igor binary"),
                         (".jpk", "is not a JPK image")):
        bad = tmp_path / f"bad{suffix}"
        bad.write_bytes(b"not an image" * 10)
        with pytest.raises(ValueError, match=what):
            samples.load(bad)


def test_an_unreadable_file_is_named(tmp_path, monkeypatch):
    locked = tmp_path / "locked.spm"
    locked.write_bytes(SPM.read_bytes()[:1000])

    def refuse(*args, **kwargs):  # as open() on a file without read permission (root reads all)
        raise PermissionError(13, "Permission denied")
    monkeypatch.setattr(readers, "open", refuse, raising=False)
    with pytest.raises(ValueError, match="locked.spm: the file cannot be read "
                                         r"\(Permission denied\)"):
        samples.load(locked)


def test_files_of_the_afmreader_only_formats_are_checked_first(tmp_path):
    # no small real .ibw, .jpk or .asd file with a licence that allows it was found (see
    # tests/data/README.md): these check the pre-flight checks on files made here
    import tifffile
    plain = tmp_path / "plain.jpk"  # a TIFF without JPK's channels
    tifffile.imwrite(plain, np.zeros((8, 8), np.float32))
    with pytest.raises(ValueError, match=r"channel must be one of the channels of plain.jpk: "
                                         r"\[\]"):
        samples.load(plain)
    asd = tmp_path / "cut.asd"
    asd.write_bytes(b"\x01\x00\x00\x00" + bytes(40))  # version 1, header cut short
    with pytest.raises(ValueError, match="cut.asd: not a readable .asd file"):
        samples.load(asd)
    ibw = tmp_path / "cut.ibw"
    ibw.write_bytes(b"\x05\x00" + bytes(100))  # version 5, header cut short
    with pytest.raises(ValueError, match="cut.ibw: not a readable Igor binary wave"):
        samples.load(ibw)


def test_truncated_and_hostile_headers(tmp_path):
    # a 2 GiB file (sparse) that is not an image: refused from its size, no read of its body
    big = tmp_path / "big.top"
    with open(big, "wb") as f:
        f.write(b"not an image")
        f.truncate(2 << 30)
    start = time.perf_counter()
    with pytest.raises(ValueError, match="more than any AFM image"):
        samples.load(big)
    assert time.perf_counter() - start < 1.0
    # WSxM: more rows than the file holds, or too many
    short = _wsxm(tmp_path, "Number of rows: 512", "Number of rows: 999")
    with pytest.raises(ValueError, match=r"512 short values need \d+ bytes, the file has"):
        samples.load(short)
    huge = _wsxm(tmp_path, "Number of rows: 512", "Number of rows: 9e9")
    with pytest.raises(ValueError, match=r"Number of rows must be an integer in \[2, 2097152\]"):
        samples.load(huge)
    # NanoScope: the file cut in the middle of its second image
    cut = tmp_path / "cut.spm"
    cut.write_bytes(SPM.read_bytes()[:700000])
    with pytest.raises(ValueError, match=r"cut.spm: the header's 512 x 512 image at byte "
                                         r"565248 needs 1089536 bytes, the file has 700000"):
        samples.load(cut)
    # NanoScope: a header that claims 2^31 lines is refused, not allocated
    raw = SPM.read_bytes()
    hostile = tmp_path / "hostile.spm"
    hostile.write_bytes(raw.replace(b"\\Number of lines: 512", b"\\Number of lines: 2147483647",
                                    1))
    with pytest.raises(ValueError, match="an image must have 2 to 4194304 pixels"):
        samples.load(hostile)
    # Gwyddion: a data field cut short
    path = samples.save_gwy(samples.Sample(np.ones((64, 64)), 1e-9), tmp_path / "x.gwy")
    cut = tmp_path / "cut.gwy"
    cut.write_bytes(path.read_bytes()[:20000])
    with pytest.raises(ValueError, match="cut.gwy"):
        samples.load(cut)


def test_from_file_is_load():
    assert samples.from_file is samples.load
