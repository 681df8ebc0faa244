"""Real files through AFMReader and gwyfile, in SI units: each checked against the numbers its own
software reports (the reader's own tests) or its header, decoded here independently; bad files
named before any work; a .gwy export read back by gwyfile and AFMReader."""
import hashlib
import re
import struct

import numpy as np
import pytest

from afmsmiler import data, samples
from afmsmiler.samples import readers

DATA = __import__("pathlib").Path(__file__).parent / "data"
WSXM = DATA / "afmreader_sample_0.top"
WSXM_HEADER = 2996  # "Image header size: 2996" on the file's third line
SPM = samples.REAL_IMAGE
SPM_OFFSETS = {"Height": 40960, "Amplitude": 565248}  # "Data offset" of each Ciao image


IBW = DATA / "scifidatasets_btfo_dso.ibw"
GWY = DATA / "scifidatasets_pto_110_virgin0001.gwy"
JPK = DATA / "afmreader_sample_0.jpk"
STP = DATA / "afmreader_sample_0.stp"
ASD = DATA / "playnano_asd_sample_0.asd"
#: one real file of every instrument format that load() reads
REAL_FILES = (SPM, WSXM, STP, IBW, JPK, ASD, GWY)


def test_data_files_are_the_ones_the_readmes_name():
    def sha(p):
        return hashlib.sha256(p.read_bytes()).hexdigest()
    readme = (DATA / "README.md").read_text()
    files = sorted(p for p in DATA.iterdir() if p.name != "README.md")
    assert len(files) == 9
    for path in files:
        assert f"`{path.name}`" in readme and sha(path) in readme, path.name
    assert sha(SPM) in (SPM.parent / "README.md").read_text()
    assert "wsxm_sample_0.top" not in data.names()  # the GPL file no longer ships
    # under 1.2 MB, or under 2.7 MB where no smaller real file of the format was found
    assert all(p.stat().st_size < 2.7e6 for p in files)
    assert sum(p.stat().st_size < 1.2e6 for p in files) == 5


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


def test_wsxm_stp_real_file_matches_afmreader_and_its_top_twin():
    """AFMReader 0.0.7 tests/test_stp.py, sample_0.stp: pixel scaling 0.9765625 nm and image
    sum -15070620.440757688 nm. The same scan as the .top above, saved by WSxM as doubles in nm:
    the .top's int16 counts times 13.6 nm/V ("Conversion Factor 00") x 20 V / 2^16 (to the
    5e-5 nm the .stp was rounded to), between the header's "Minimum: -80.7998" and
    "Maximum: -21.0549" (nm)."""
    img = samples.load(STP)
    assert img.shape == (512, 512) and img.channel == "Topography" and img.unit == "m"
    assert (img.pixel_size, img.pixel_size_y) == pytest.approx((0.9765625e-9,) * 2, rel=1e-12)
    assert np.sum(img.heights) * 1e9 == pytest.approx(-15070620.440757688, rel=1e-12)
    doubles = np.fromfile(STP, "<f8", offset=5272).reshape(512, 512)  # Image header size 5272
    np.testing.assert_allclose(img.heights, doubles * 1e-9, rtol=1e-14)
    counts = np.fromfile(WSXM, "<i2", offset=WSXM_HEADER).reshape(512, 512)
    np.testing.assert_allclose(img.heights, counts * (13.6 * 20 / 2 ** 16) * 1e-9, rtol=0,
                               atol=5e-14)
    assert img.heights.min() * 1e9 == pytest.approx(-80.7998, abs=5e-5)
    assert img.heights.max() * 1e9 == pytest.approx(-21.0549, abs=5e-5)
    assert samples.channels(STP) == ["Topography"] and img.metadata["Z Amplitude"] == "59.7449 nm"


# --- Asylum Research / Igor (.ibw): a Cypher image --------------------------------------------
def _igor_wave():
    from igor2 import binarywave
    return binarywave.load(str(IBW))["wave"]


def test_ibw_asylum_image_matches_igor_and_scifireaders():
    """A Cypher PFM image, read with igor2 directly. SciFiReaders' tests/.../test_igor.py on this
    file publish its channels (HeightRetrace, AmplitudeRetrace, DeflectionRetrace in m,
    PhaseRetrace in deg) and note (ScanSize 2e-06, ScanPoints 256, ScanLines 256). The pixel
    size is Igor's own wave scaling (``SetScale`` delta, m), 2 um / 255 points as Asylum's
    software writes it and Gwyddion's igorfile.c reads it (see the .gwy test below); AFMReader
    divides ScanSize by 256 instead. The default "Height" takes "HeightRetrace" (it failed
    with this real file before)."""
    wave = _igor_wave()
    note = wave["note"].decode("latin-1")
    assert "ScanSize: 2e-06\r" in note and "ScanPoints: 256\r" in note
    assert "ScanLines: 256\r" in note
    scaling = wave["wave_header"]["sfA"][:2]
    assert list(wave["wave_header"]["dimUnits"][:2, 0]) == [b"m", b"m"]
    np.testing.assert_allclose(scaling, 2e-6 / 255, rtol=1e-7)  # float32 in the file
    img = samples.load(IBW)
    assert img.shape == (256, 256) and img.channel == "HeightRetrace" and img.unit == "m"
    assert (img.pixel_size, img.pixel_size_y) == tuple(scaling)
    # Igor's image has x (fast) first and y up: the rows, top down, are y reversed
    stored = wave["wData"].astype(float)
    np.testing.assert_array_equal(img.heights, np.flipud(stored[:, :, 0].T))
    from AFMReader.ibw import load_ibw  # the same orientation; its nm are float32 (rel 6e-8)
    np.testing.assert_allclose(img.heights, load_ibw(IBW, "HeightRetrace")[0] * 1e-9, rtol=2e-7)
    assert img.metadata["ScanRate"] == "2.0032" and img.metadata["MicroscopeModel"] == "Cypher"
    assert samples.channels(IBW) == ["HeightRetrace", "AmplitudeRetrace", "DeflectionRetrace",
                                     "PhaseRetracerace"]  # Asylum's label, as stored
    phase = samples.load(IBW, "PhaseRetracerace", unit="deg")
    np.testing.assert_array_equal(phase.heights, np.flipud(stored[:, :, 3].T))
    amp = samples.load(IBW, "AmplitudeRetrace")
    np.testing.assert_array_equal(amp.heights, np.flipud(stored[:, :, 1].T))
    with pytest.raises(ValueError, match="channel 'PhaseRetracerace' of "
                                         "scifidatasets_btfo_dso.ibw is in 'deg', not 'm'"):
        samples.load(IBW, "PhaseRetracerace")


def test_ibw_units_and_orientation_follow_gwyddion(tmp_path):
    """Gwyddion's igorfile.c (igor_read_data_field, channel_title_to_units): an image is
    n_dim[0] x n_dim[1] points with x fast, xreal = sfA[0] * xres, then inverted about the x
    axis (first stored line at the bottom), as load() and AFMReader orient the rows (tested
    above); units by the channel's name after a "DAC" or "Nap" prefix:
    Height, ZSensor, Deflection, Amplitude in m, Phase in deg, Current in A, Frequency in Hz,
    Potential and any other channel in V. Here the file's labels renamed (same length)."""
    raw = IBW.read_bytes()
    for old, new, unit in ((b"DeflectionRetrace", b"NapCurrentRetrace", "A"),
                           (b"DeflectionRetrace", b"UserIn0Retrace\0\0\0", "V"),
                           (b"AmplitudeRetrace", b"FrequencyRetrace", "Hz")):
        assert raw.count(old) >= 1 and len(old) == len(new)
        path = tmp_path / f"{unit}.ibw"
        path.write_bytes(raw.replace(old, new, 1))
        name = new.rstrip(b"\0").decode()
        assert name in samples.channels(path)
        assert samples.load(path, name, unit=unit).unit == unit
    # dimUnits, 4 characters per dimension at byte 64 + 152 of a version-5 file: "um", not "m"
    scaled = bytearray(raw)
    assert scaled[216:224] == b"m\0\0\0m\0\0\0"
    scaled[216:224] = b"um\0\0um\0\0"
    (tmp_path / "um.ibw").write_bytes(scaled)
    img = samples.load(tmp_path / "um.ibw")
    assert (img.pixel_size, img.pixel_size_y) == pytest.approx((2e-12 / 255,) * 2, rel=1e-7)
    capacitance = tmp_path / "F.ibw"
    capacitance.write_bytes(raw.replace(b"AmplitudeRetrace", b"CapacitanceRetra", 1))
    with pytest.raises(ValueError, match="channel 'CapacitanceRetra' is in 'F', which a sample "
                                         "does not carry"):
        samples.load(capacitance, "CapacitanceRetra", unit="F")


# --- JPK (.jpk): a NanoWizard image --------------------------------------------------------------
def test_jpk_image_matches_afmreader_and_its_tags():
    """AFMReader 0.0.7 tests/test_jpk.py, sample_0.jpk, "height_trace": pixel scaling
    1.2770176335964876 nm, shape (256, 256), image sum 219242202.8256843 nm. The JPK TIFF tags
    (as Gwyddion's jpkscan.c names them): grid-uLength (32834) 3.269e-7 m over grid-iLength
    (32838) 256 pixels; each channel page's int32 values times the multiplier plus the offset
    of its default calibration slot, in that slot's unit (m, deg, V), lines stored bottom up
    (tag 32843 "bottomUp"). Phase and error came back as 'm' divided by 1e9 before."""
    import tifffile
    img = samples.load(JPK)
    assert img.shape == (256, 256) and img.channel == "height_trace" and img.unit == "m"
    assert img.pixel_size * 1e9 == pytest.approx(1.2770176335964876, rel=1e-12)
    assert np.sum(img.heights) * 1e9 == pytest.approx(219242202.8256843, rel=1e-12)
    names = ["height", "measuredHeight", "amplitude", "phase", "error"]
    assert samples.channels(JPK) == [f"{n}_retrace" for n in names] + [f"{n}_trace" for n in names]
    with tifffile.TiffFile(str(JPK)) as tif:
        tags = {t.code: t.value for t in tif.pages[0].tags.values()}
        assert tags[32843] == "bottomUp" and (tags[32838], tags[32839]) == (256, 256)
        assert img.pixel_size == pytest.approx(tags[32834] / tags[32838], rel=1e-15)
        assert img.pixel_size_y == pytest.approx(tags[32835] / tags[32839], rel=1e-15)
        for page, channel, unit in ((6, "height_trace", "m"), (9, "phase_trace", "deg"),
                                    (10, "error_trace", "V")):
            t = {tag.code: tag.value for tag in tif.pages[page].tags.values()}
            slot = [k for k in range(t[32896]) if t[32912 + 48 * k] == t[32897]][0]
            assert t[32930 + 48 * slot] == unit and t[32849] == 0
            expected = tif.pages[page].asarray() * t[32932 + 48 * slot] + t[32933 + 48 * slot]
            got = samples.load(JPK, channel, unit=unit)
            assert got.unit == unit
            np.testing.assert_allclose(got.heights, np.flipud(expected), rtol=1e-12)


def test_jpk_qi_image_channels_in_their_own_units():
    """AFMReader 0.0.7 tests/test_jpk.py, sample_0.jpk-qi-image (a JPK QI map: one force curve
    per pixel, its results as images): pixel scaling 4.999999999999986 nm, shape (100, 100),
    sums height_trace 31593146.16051172 nm, measuredHeight_trace 32181137.138706185 nm,
    vDeflection_trace -1.3615033224242345e-05 and adhesion_trace 1.579363986493833e-06 (N, the
    calibration slot "force"), slope_trace 626.3810326940231 (N/m). Before, every channel was
    read as nm: forces came back 1e9 times too small, in 'm'."""
    qi = DATA / "afmreader_sample_0_qi.jpk"
    assert samples.channels(qi) == ["measuredHeight_trace", "vDeflection_trace",
                                    "adhesion_trace", "height_trace", "slope_trace"]
    for channel, unit, total in (("height_trace", "m", 31593146.16051172e-9),
                                 ("measuredHeight_trace", "m", 32181137.138706185e-9),
                                 ("vDeflection_trace", "N", -1.3615033224242345e-05),
                                 ("adhesion_trace", "N", 1.579363986493833e-06),
                                 ("slope_trace", "N/m", 626.3810326940231)):
        img = samples.load(qi, channel, unit=unit)
        assert img.shape == (100, 100) and img.unit == unit
        assert img.pixel_size == img.pixel_size_y == pytest.approx(5e-9, rel=1e-12)
        assert np.sum(img.heights) == pytest.approx(total, rel=1e-12)
    assert samples.load(qi).channel == "height_trace"


# --- high-speed AFM (.asd): a movie of 32 frames ---------------------------------------------
def test_asd_movie_matches_playnano_and_its_header():
    """playNano's tests/test_formats.py (test_read_asd_valid_file) on this file: channel "TP",
    pixel size 0.5 nm, 32 frames of 200 x 200, stack sum -251179816.91781396 nm. Decoded here
    from the bytes: a version-1 header of 174 bytes, then per frame a 32-byte frame header and
    200 x 200 int16 levels; topography = -level x 9.99 V / 4096 (AD range code 3: 0 to 9.99 V,
    12 bits) x z piezo gain (2.0, float32 at byte 161) x z piezo extension (12.48 nm/V, float32
    at byte 157), as AFMReader's asd.py converts them. load() returns the first frame."""
    raw = ASD.read_bytes()
    version, header_size, frame_header = struct.unpack_from("<3i", raw, 0)
    assert (version, header_size, frame_header) == (1, 174, 32)
    assert raw[24:26] == b"TP" and raw[28:32] == bytes(4)  # channel 1, no channel 2
    frames, _, _, _, nx, ny, x_nm = struct.unpack_from("<7i", raw, 32)
    y_nm = struct.unpack_from("<i", raw, 60)[0]
    assert (frames, nx, ny, x_nm, y_nm) == (32, 200, 200, 100, 100)
    extension, gain = struct.unpack_from("<2f", raw, 157)
    assert (round(extension, 5), gain) == (12.48, 2.0)
    step = frame_header + nx * ny * 2
    assert len(raw) == header_size + frames * step
    levels = np.stack([np.frombuffer(raw, "<i2", nx * ny, header_size + k * step + frame_header)
                       for k in range(frames)]).reshape(frames, ny, nx)
    nm = -levels * (9.99 / 4096) * gain * extension
    assert np.sum(nm) == pytest.approx(-251179816.91781396, rel=1e-12)
    img = samples.load(ASD)
    assert img.shape == (200, 200) and img.channel == "TP" and img.unit == "m"
    assert (img.pixel_size, img.pixel_size_y) == (0.5e-9, 0.5e-9)
    np.testing.assert_allclose(img.heights, nm[0] * 1e-9, rtol=1e-12)
    assert samples.channels(ASD) == ["TP"] and img.metadata["num_frames"] == 32


# --- Gwyddion (.gwy): a file Gwyddion made, and one written here ------------------------------
def test_gwy_made_by_gwyddion_matches_gwyfile_afmreader_and_scifireaders():
    """Gwyddion's own import of an Asylum Cypher image (its log: "file::igorfile(...)"):
    SciFiReaders' tests/.../test_gwy.py on this file publish four 256-pixel channels
    HeightRetrace, AmplitudeRetrace, DeflectionRetrace (m) and PhaseRetrace (deg). gwyfile and
    AFMReader's own .gwy parser read it here independently. Gwyddion's pixel size,
    xreal / xres = 1e-5 m / 255, is Igor's wave scaling of the instrument's "ScanSize: 1e-05"
    over 256 points (the metadata it kept): the same as the .ibw reader's. The default
    "Height" takes HeightRetrace (it failed with this real file before)."""
    import gwyfile
    from AFMReader.gwy import load_gwy
    container = gwyfile.load(str(GWY))
    assert container["/0/data/log"]["strings"][0].startswith("file::igorfile(")
    assert container["/0/meta"]["ScanSize"] == "1e-05"
    assert samples.channels(GWY) == ["HeightRetrace", "AmplitudeRetrace", "DeflectionRetrace",
                                     "PhaseRetrace"]
    for index, channel, unit in ((0, "HeightRetrace", "m"), (1, "AmplitudeRetrace", "m"),
                                 (2, "DeflectionRetrace", "m"), (3, "PhaseRetrace", "deg")):
        field = container[f"/{index}/data"]
        assert (field["xres"], field["yres"]) == (256, 256)
        assert (field.si_unit_xy.unitstr, field.si_unit_z.unitstr) == ("m", unit)
        img = samples.load(GWY, channel, unit=unit)
        np.testing.assert_array_equal(img.heights, field.data)
        assert img.pixel_size == img.pixel_size_y == pytest.approx(1e-5 / 255, rel=1e-15)
    img = samples.load(GWY)
    assert img.channel == "HeightRetrace" and img.metadata["ScanSize"] == "1e-05"
    assert img.metadata["MicroscopeModel"] == "Cypher" and img.metadata["xres"] == 256
    nm, px_nm = load_gwy(GWY, "HeightRetrace")
    np.testing.assert_allclose(img.heights, nm * 1e-9, rtol=1e-15)
    assert px_nm == pytest.approx(1e4 / 255, rel=1e-12)


def test_gwyfile_own_test_file_without_units_is_named():
    """gwyfile's tests/test.gwy, made by Gwyddion's lattice synthesis (its log: "lat_synth"):
    gwyfile's test_gwyobject.py publishes channel "Test", 128 x 128, data[0][0] = 0.00082494 and
    data[44][33] = 0.00085301. Its lateral and value units are empty (dimensionless): load()
    names that, as a sample needs lengths in m."""
    import gwyfile
    field = gwyfile.load(str(DATA / "gwyfile_test.gwy"))["/0/data"]
    assert field.data.shape == (128, 128)
    assert field.data[0][0] == pytest.approx(0.00082494, rel=1e-5)
    assert field.data[44][33] == pytest.approx(0.00085301, rel=1e-5)
    assert samples.channels(DATA / "gwyfile_test.gwy") == ["Test"]
    with pytest.raises(ValueError, match="gwyfile_test.gwy: channel 'Test' must have lateral "
                                         "unit 'm' and values in one of .*, got '' and ''"):
        samples.load(DATA / "gwyfile_test.gwy", "Test")


@pytest.mark.slow
def test_afmreader_logs_nothing_when_files_are_read():
    """AFMReader logs every step at INFO to stderr (loguru, enabled as each of its modules is
    imported): a fresh interpreter reading every format through channels() and load() prints
    nothing (this printed ".asd ... file version: 1" from channels() before)."""
    import subprocess
    import sys
    code = ("import sys\nfrom afmsmiler import samples\n"
            "for p in sys.argv[1:]:\n    samples.channels(p)\n    samples.load(p)\n")
    args = [str(p) for p in REAL_FILES[::-1]]  # the .asd before any other AFMReader format
    run = subprocess.run([sys.executable, "-c", code, *args], capture_output=True, text=True,
                         timeout=120)
    assert run.returncode == 0, run.stderr
    assert run.stderr == "" and run.stdout == ""


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
    # files made here, beside the real ones: a TIFF without JPK's tags, headers cut short
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


def test_truncated_and_hostile_headers(tmp_path, hang_guard):
    # a 64 GiB file (sparse) that is not an image: refused from its size, no read of its body
    # (reading it would take far longer than the guard)
    big = tmp_path / "big.top"
    with open(big, "wb") as f:
        f.write(b"not an image")
        f.truncate(64 << 30)
    with hang_guard(5, expected=0.01), pytest.raises(ValueError, match="more than any AFM image"):
        samples.load(big)
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


def test_truncated_real_files_are_named_before_their_data_is_read(tmp_path, capfd):
    """Each real file cut in half: its header announces more than the file holds. Before, a cut
    .ibw went to igor2, which logged the raw bytes of the file to stderr."""
    for path, what in ((IBW, r"the Igor header announces 1069782 bytes, the file has 567815"),
                       (JPK, r"a page of \(256, 256\) pixels, its data ending at byte"),
                       (ASD, r"the header's 32 frames of 200 x 200 pixels in channels \['TP'\] "
                             r"need 2561198 bytes, the file has 1280599"),
                       (STP, r"the header's 512 x 512 double values need 2102424 bytes, the "
                             r"file has 1051212"),
                       (GWY, r"not a readable Gwyddion file")):
        raw = path.read_bytes()
        cut = tmp_path / f"cut{path.suffix}"
        cut.write_bytes(raw[:len(raw) // 2])
        for read in (samples.channels, samples.load):
            with pytest.raises(ValueError, match=f"cut{path.suffix}: {what}"):
                read(cut)
    bad = tmp_path / "bad.ibw"  # a version-5 header whose sizes sum past the file
    bad.write_bytes(IBW.read_bytes()[:64] + bytes(100))
    with pytest.raises(ValueError, match="bad.ibw: the Igor header announces 1069782 bytes"):
        samples.load(bad)
    garbled = tmp_path / "garbled.ibw"  # sizes that fit, contents that do not parse
    garbled.write_bytes(b"\x05\x00" + bytes(62) + bytes(range(256)) * 8)
    with pytest.raises(ValueError, match="garbled.ibw: not a readable Igor binary wave"):
        samples.load(garbled)
    out, err = capfd.readouterr()
    assert out == "" and err == ""


def test_from_file_is_load():
    assert samples.from_file is samples.load


def test_a_saved_sample_loads_back_with_the_default_channel(tmp_path):
    """load(save_gwy(sample)) raised: save_gwy names a Sample's heights "height", and the default
    channel "Height" did not find it."""
    s = samples.Sample(1e-9 * np.arange(12.0).reshape(3, 4), 2e-9, "height")
    path = samples.save_gwy(s, tmp_path / "s.gwy")
    back = samples.load(path)
    np.testing.assert_allclose(back.heights, s.heights, rtol=1e-12)
    assert back.pixel_size == pytest.approx(2e-9, rel=1e-12)


# --- damaged files: a named error about the file, never an error from inside a reader ----------
def _gwy_with(tmp_path, name, change):
    """A .gwy written by gwyfile whose data field ``change`` damages (in the container)."""
    from gwyfile.objects import GwyContainer, GwyDataField, GwySIUnit
    field = GwyDataField(np.ones((4, 4)), xreal=4e-9, yreal=4e-9,
                         si_unit_xy=GwySIUnit(unitstr="m"), si_unit_z=GwySIUnit(unitstr="m"))
    container = GwyContainer()
    container["/0/data"] = field
    container["/0/data/title"] = "Height"
    change(container, field)
    path = tmp_path / name
    container.tofile(str(path))
    return path


@pytest.mark.parametrize("change, what", [
    (lambda c, f: c.__setitem__("/0/data", "not a field"),
     "channel 'Height' must be a GwyDataField, the file holds a str"),
    (lambda c, f: f.__setitem__("data", "abc"), "channel 'Height' must hold an array of floats"),
    (lambda c, f: f.__setitem__("data", np.ones(7)), r"channel 'Height' holds 7 values, its "
                                                     r"xres x yres say 4 x 4 \(truncated\?\)"),
    (lambda c, f: f.__setitem__("xres", -4), "channel 'Height' must have xres and yres of 1 to"),
    (lambda c, f: f.__setitem__("yres", 2**31 - 1), "channel .Height. must have xres and yres"),
    (lambda c, f: f.__setitem__("xreal", -1.0), "channel .Height. must have positive finite xreal"),
    (lambda c, f: f.__delitem__("yreal"), "channel .Height. must have positive finite xreal"),
    (lambda c, f: f.__setitem__("si_unit_z", "m"), "channel .Height. must have a GwySIUnit as si_unit_z"),
])
def test_a_damaged_gwy_data_field_is_named(tmp_path, change, what):
    """gwyfile returns a damaged file's components as they are: a string where the data field
    should be raised AttributeError from inside gwyfile's ``data`` property."""
    path = _gwy_with(tmp_path, "damaged.gwy", change)
    with pytest.raises(ValueError, match=f"damaged.gwy: {what}"):
        samples.load(path)


def test_a_gwy_channel_title_that_is_not_text_is_named(tmp_path):
    path = _gwy_with(tmp_path, "title.gwy", lambda c, f: c.__setitem__("/0/data/title", 7))
    for read in (samples.channels, samples.load):
        with pytest.raises(ValueError, match="title.gwy: a channel's title must be text, got 7"):
            read(path)


@pytest.mark.parametrize("old, new, what", [
    (b"\\Data offset: 40960", b"\\Data offset: -40960",  # pySPM's seek raised OSError
     r"an image's Data offset must be at or after the header's end \(byte \d+\), got -40960"),
    (b"\\Data offset: 40960", b"\\Data offset: 100",  # inside the header: text read as counts
     r"an image's Data offset must be at or after the header's end"),
    (b"\\Data length: 524288", b"\\Data length: 100000000000",  # pySPM's bpp: KeyError
     r"an image's Data length must be its 512 x 512 pixels of 2 bytes \(524288\), "
     r"got 100000000000"),
    (b"\\*File list end", b"\\*File list endless",  # pySPM would read lines past the end
     r"the NanoScope header has no '\\\*File list end' line"),
    (b"\\@2:Image Data: S [Height]", b"\\@2:Image Data: S  Height ",  # pySPM's regex: None
     r"channel 'Height' is not readable by pySPM \(AttributeError"),
])
def test_a_damaged_nanoscope_header_is_named(tmp_path, old, new, what):
    raw = SPM.read_bytes()
    assert raw.count(old) >= 1
    path = tmp_path / "damaged.spm"
    path.write_bytes(raw.replace(old, new, 1))
    with pytest.raises(ValueError, match=f"damaged.spm: {what}"):
        samples.load(path)


def _npy_with_shape(tmp_path, shape: bytes):
    """A float64 .npy of 4 x 4 values whose header claims ``shape`` (header length kept)."""
    np.save(tmp_path / "ok.npy", np.zeros((4, 4)))
    raw = (tmp_path / "ok.npy").read_bytes()
    header_end = raw.index(b"\n") + 1
    head = raw[:header_end].replace(b"(4, 4)", shape).rstrip(b" \n")
    head = head + b" " * (header_end - 1 - len(head)) + b"\n"
    path = tmp_path / "damaged.npy"
    path.write_bytes(head + raw[header_end:])
    return path


@pytest.mark.parametrize("shape, what", [
    (b"(-4, 4)", r"the header's shape \(-4, 4\) has a negative length"),
    (b"(99999999999999999999999, 4)", "a height map must be 1-D or 2-D with 2 to 4194304 "
                                      "values"),  # numpy's memmap: OverflowError
    (b"(0, 4)", r"a height map must be .* the header says shape \(0, 4\)"),
    (b"(8, 4)", r"the header's \(8, 4\) float64 values need \d+ bytes, the file has"),
])
def test_a_damaged_npy_header_is_named(tmp_path, shape, what):
    path = _npy_with_shape(tmp_path, shape)
    with pytest.raises(ValueError, match=f"damaged.npy: {what}"):
        samples.load(path, pixel_size=1e-9)


@pytest.mark.parametrize("values, what", [
    (np.ones((4, 4)) + 1j, r"holds complex values \(complex128\); a height map is real"),
    (np.ones((4, 4), bool), "must hold real numbers, it holds bool"),
    (np.array([["a", "b"]]), "must hold real numbers, it holds <U1"),
    (np.zeros(3, dtype=[("a", "f8"), ("b", "f8")]), "must hold real numbers"),
])
def test_an_npy_of_other_than_real_numbers_is_named(tmp_path, values, what):
    """A complex .npy loaded with its imaginary part dropped (a ComplexWarning only)."""
    np.save(tmp_path / "other.npy", values)
    with pytest.raises(ValueError, match=f"other.npy: the array {what}"):
        samples.load(tmp_path / "other.npy", pixel_size=1e-9)
