"""One table per device protocol: each spec (PROTOCOL.md, protocol.h, firmware limits) against it.

The codecs' :class:`~afmsmiler.hardware.protocol.ParamTable` describes each device's parameters
once. These tests parse every other place that states them -- the parameter table of each
``hardware/<device>/PROTOCOL.md``, each ``protocol.h`` (``PAR_``, ``ERR_``, ``PROTOCOL_VERSION``)
and, where firmware exists, its limits (the macroscopic AFM's ``config.h`` and ``param_valid``,
the haptic device's ``LIMITS``) -- and fail when one disagrees with the table. Each comparison is
also run on a copy with one deliberate mismatch, to show that it can fail.
"""
from __future__ import annotations

import math
import re
import shutil
from pathlib import Path

import pytest

from afmsmiler.hardware.educational import codec as edu
from afmsmiler.hardware.errors import ErrorCode
from afmsmiler.hardware.framing import PROTOCOL_VERSION
from afmsmiler.hardware.haptic import codec as haptic
from afmsmiler.hardware.macro import codec as macro
from afmsmiler.hardware.protocol import WIRE_UNITS, ParamTable, WireParam

HARDWARE = Path(__file__).resolve().parents[1] / "hardware"


# -- parsers ----------------------------------------------------------------------------------
def parse_md_parameters(text: str) -> dict:
    """The parameter table of a PROTOCOL.md: code -> {name, unit, low, high, default,
    read_only, multiple} (the first table whose header has code, unit, range and default)."""
    lines = text.splitlines()
    for i, line in enumerate(lines):
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        heads = [c.lower() for c in cells]
        if {"code", "unit", "range", "default"} <= set(heads):
            break
    else:
        raise AssertionError("no parameter table (code | unit | range | default) found")
    col = {h.split(" ")[0]: j for j, h in enumerate(heads)}
    rows = {}
    for line in lines[i + 2:]:
        if not line.startswith("|"):
            break
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        code = cells[col["code"]].strip("`")
        text_range = cells[col["range"]]
        bounds = re.search(r"(-?\d+)\.\.(-?\d+)", text_range)
        if bounds:
            low, high = int(bounds.group(1)), int(bounds.group(2))
        else:
            values = [int(v) for v in re.findall(r"-?\d+", text_range)]
            low, high = min(values), max(values)
        multiple = re.search(r"multiple of (\d+)", text_range)
        rows[code] = dict(name=cells[col["name"]], unit=cells[col["unit"]], low=low, high=high,
                          default=int(cells[col["default"]]),
                          read_only="read-only" in text_range,
                          multiple=int(multiple.group(1)) if multiple else 1)
    return rows


_DEFINE = re.compile(r'#define\s+(\w+)\s+("?)([^"\s]+)\2\s*(//.*)?$')


def parse_protocol_h(text: str) -> dict:
    """A protocol.h's defines: {"PAR": {name: code}, "ERR": {name: n}, "PROTOCOL_VERSION": n}."""
    out = {"PAR": {}, "ERR": {}}
    for line in text.splitlines():
        m = _DEFINE.match(line.strip())
        if not m:
            continue
        name, value = m.group(1), m.group(3) if m.group(2) else int(m.group(3).rstrip("L"))
        if name == "PROTOCOL_VERSION":
            out[name] = value
        elif name[:4] in ("PAR_", "ERR_"):
            out[name[:3]][name[4:]] = value
    return out


def _numbers(text: str) -> dict:
    """``#define NAME <integer>`` lines of a C header."""
    return {m.group(1): int(m.group(2)) for m in
            re.finditer(r"^#define\s+(\w+)\s+(-?\d+)L?\b", text, re.M)}


def _value(expr: str, constants: dict) -> int:
    expr = re.sub(r"(?<=\d)L$", "", expr.strip())
    return int(expr) if re.fullmatch(r"-?\d+", expr) else constants[expr]


def parse_macro_firmware(config_h: str, ino: str) -> dict:
    """The macroscopic AFM firmware's parameters: code name -> {low, high, default, multiple}.

    Ranges from ``param_valid`` (with config.h's constants), defaults from ``struct Params`` and
    ``Z_STEP_NM`` (ZS is the mechanics' micro-step).
    """
    constants = _numbers(config_h)
    body = re.search(r"static bool param_valid\(.*?\n}\n", ino, re.S).group(0)
    out = {}
    for m in re.finditer(r"PAR_(\w+)\)\)\s*return (.*?);", body, re.S):
        name, cond = m.group(1), m.group(2)
        low, high, multiple = -math.inf, math.inf, 1
        equals = [_value(v, constants) for v in re.findall(r"v == (\w+)", cond)]
        if equals and "||" in cond:
            low, high = min(equals), max(equals)
        for op, v in re.findall(r"v (>=|>|<=|<) (\w+)", cond):
            v = _value(v, constants)
            low = v if op == ">=" else v + 1 if op == ">" else low
            high = v if op == "<=" else v - 1 if op == "<" else high
        grid = re.search(r"\(v \* (\w+)\) % (\w+) == 0", cond)
        if grid:
            scale, step = _value(grid.group(1), constants), _value(grid.group(2), constants)
            multiple = step // math.gcd(scale, step)
        out[name] = dict(low=low, high=high, multiple=multiple)
    struct = re.search(r"struct Params \{(.*?)\};", ino, re.S).group(1)
    field_of = dict(re.findall(r"PAR_(\w+)\)\) \*slot = &par\.(\w+);", ino))
    defaults = {k: int(v) for k, v in re.findall(r"(\w+) = (-?\d+)", struct)}
    for name, field in field_of.items():
        out[name]["default"] = defaults[field]
    out.setdefault("ZSTEP", {})["default"] = constants["Z_STEP_NM"]
    return out


def parse_haptic_firmware(ino: str) -> dict:
    """The haptic firmware's ``LIMITS`` rows: name -> {low, high, default, read_only}."""
    rows = re.findall(r"\[P_(\w+)\]\s*=\s*\*/\s*\{\s*(-?\d+)L?,\s*(-?\d+)L?,\s*(-?\d+)L?,\s*"
                      r"(true|false)\s*\}", ino)
    return {name: dict(low=int(lo), high=int(hi), default=int(d), read_only=ro == "true")
            for name, lo, hi, d, ro in rows}


# -- comparisons ------------------------------------------------------------------------------
def md_mismatches(table: ParamTable, rows: dict) -> list:
    """Where a PROTOCOL.md parameter table disagrees with the codec's table."""
    out = []
    if set(rows) != {p.code for p in table}:
        out.append(f"codes: PROTOCOL.md {sorted(rows)} != table {sorted(p.code for p in table)}")
    for p in table:
        row = rows.get(p.code)
        if row is None:
            continue
        if row["name"] != p.name:
            out.append(f"{p.code}: name {row['name']!r} != {p.name!r}")
        if row["unit"] not in WIRE_UNITS[p.unit].spellings:
            out.append(f"{p.code}: unit {row['unit']!r} is not {p.unit!r} "
                       f"({WIRE_UNITS[p.unit].spellings})")
        for key in ("low", "high", "default", "read_only", "multiple"):
            if row[key] != getattr(p, key):
                out.append(f"{p.code}: {key} {row[key]!r} != {getattr(p, key)!r}")
    return out


def header_mismatches(table: ParamTable, header: dict) -> list:
    """Where a protocol.h disagrees with the table (PAR_), the shared ErrorCode and the version.

    (Its CMD_ and EVT_ lines are compared with the codecs' enums in each device's own tests.)"""
    out = []
    if header.get("PROTOCOL_VERSION") != PROTOCOL_VERSION:
        out.append(f"PROTOCOL_VERSION {header.get('PROTOCOL_VERSION')} != {PROTOCOL_VERSION}")
    if header["PAR"] != {p.name: p.code for p in table}:
        out.append(f"PAR_: {header['PAR']} != {({p.name: p.code for p in table})}")
    if header["ERR"] != {e.name: e.value for e in ErrorCode}:
        out.append(f"ERR_: {header['ERR']} != the shared ErrorCode")
    return out


def firmware_mismatches(table: ParamTable, firmware: dict) -> list:
    """Where the firmware's limits and defaults disagree with the table."""
    out = []
    for p in table:
        limits = firmware.get(p.name)
        if limits is None:
            out.append(f"{p.name}: not in the firmware")
            continue
        for key, value in limits.items():
            if value != getattr(p, key):
                out.append(f"{p.name}: firmware {key} {value!r} != table {getattr(p, key)!r}")
    return out


# -- the devices ------------------------------------------------------------------------------
MACRO = HARDWARE / "macro_afm"
EDU = HARDWARE / "educational_afm"
HAPTIC = HARDWARE / "haptic"
DEVICES = {
    "macro": (macro.TABLE, MACRO / "PROTOCOL.md", MACRO / "firmware" / "protocol.h"),
    "educational": (edu.TABLE, EDU / "PROTOCOL.md", EDU / "protocol.h"),
    "haptic": (haptic.TABLE, HAPTIC / "PROTOCOL.md", HAPTIC / "protocol.h"),
}


def _macro_firmware(root: Path = MACRO) -> dict:
    return parse_macro_firmware((root / "firmware" / "config.h").read_text(),
                                (root / "firmware" / "macro_afm.ino").read_text())


@pytest.mark.parametrize("device", DEVICES)
def test_protocol_md_parameter_table_matches_the_codec_table(device):
    table, md, _ = DEVICES[device]
    assert md_mismatches(table, parse_md_parameters(md.read_text())) == []


@pytest.mark.parametrize("device", DEVICES)
def test_protocol_h_matches_the_codec_table_and_the_shared_errors(device):
    table, _, header = DEVICES[device]
    assert header_mismatches(table, parse_protocol_h(header.read_text())) == []


def test_macro_firmware_limits_match_the_table():
    firmware = _macro_firmware()
    assert firmware["NX"] == dict(low=1, high=128, multiple=1, default=8)  # the parser works
    assert firmware_mismatches(macro.TABLE, firmware) == []


def test_macro_twin_presets_are_the_firmwares():
    """The START button's presets (PRESET 1..3 of the table) as the firmware defines them."""
    from afmsmiler.hardware.macro.twin import PRESETS
    ino = (MACRO / "firmware" / "macro_afm.ino").read_text()
    rows = re.search(r"PRESETS\[N_PRESETS\] = \{(.*?)\};", ino, re.S).group(1)
    firmware = [tuple(int(v) for v in row.split(","))
                for row in re.findall(r"\{([-\d, ]+)\}", rows)]
    assert len(firmware) == macro.TABLE[macro.Param.PRESET].high + 1 == len(PRESETS)
    assert [PRESETS[i] for i in range(1, len(firmware))] == firmware[1:]


def test_haptic_firmware_limits_match_the_table():
    firmware = parse_haptic_firmware((HAPTIC / "haptic.ino").read_text())
    assert len(firmware) == len(haptic.TABLE)
    assert firmware_mismatches(haptic.TABLE, firmware) == []


def test_the_codecs_enums_are_built_from_their_tables():
    for table, param in ((macro.TABLE, macro.Param), (edu.TABLE, edu.Param),
                         (haptic.TABLE, haptic.Param)):
        assert [(m.name, m.value) for m in param] == [(p.name, p.code) for p in table]
    # one ErrorCode: every codec names the shared one
    assert macro.ErrorCode is edu.ErrorCode is haptic.ErrorCode is ErrorCode


# -- each comparison can fail: one deliberate mismatch in a temporary copy ----------------------
def _copy(tmp_path: Path, root: Path) -> Path:
    target = tmp_path / root.name
    shutil.copytree(root, target, ignore=shutil.ignore_patterns("build", "*.hex", "*.elf"))
    return target


def _edit(path: Path, old: str, new: str) -> None:
    text = path.read_text()
    assert old in text, f"{old!r} not in {path.name}"
    path.write_text(text.replace(old, new, 1))


@pytest.mark.parametrize("device, old, new, named", [
    ("macro", "| NX | `NX` | pixels | 1..128 |", "| NX | `NX` | pixels | 1..1024 |", "NX: high"),
    ("macro", "| 0..3 | 0 |", "| 0..9 | 0 |", "PR: high"),
    ("macro", "25..10000, a multiple of 25", "1..10000", "DX: low"),
    ("educational", "| `DX` | nm |", "| `DX` | um |", "DX: unit"),
    ("haptic", "| `WD` | WATCHDOG | ms | 5..1000 | 50 |", "| `WD` | WATCHDOG | ms | 5..1000 | 60 |",
     "WD: default"),
    ("haptic", "1..100000, read-only | 7670", "1..100000 | 7670", "RE: read_only"),
])
def test_a_protocol_md_that_disagrees_fails(tmp_path, device, old, new, named):
    table, md, _ = DEVICES[device]
    copy = tmp_path / "PROTOCOL.md"
    shutil.copy(md, copy)
    _edit(copy, old, new)
    found = md_mismatches(table, parse_md_parameters(copy.read_text()))
    assert any(m.startswith(named) for m in found), found


@pytest.mark.parametrize("device, old, new", [
    ("macro", '#define PAR_PITCH "DX"', '#define PAR_PITCH "DP"'),
    ("educational", "#define ERR_STATE 10", "#define ERR_STATE 11"),
    ("haptic", '#define PAR_QGAIN "QG"', '#define PAR_Q_GAIN "QG"'),
])
def test_a_protocol_h_that_disagrees_fails(tmp_path, device, old, new):
    table, _, header = DEVICES[device]
    copy = tmp_path / "protocol.h"
    shutil.copy(header, copy)
    _edit(copy, old, new)
    assert header_mismatches(table, parse_protocol_h(copy.read_text())) != []


@pytest.mark.parametrize("old, new, named", [
    ("#define MAX_NX 128", "#define MAX_NX 1024", "NX: firmware high 1024"),
    ("#define N_PRESETS 4", "#define N_PRESETS 10", "PRESET: firmware high 9"),
    ("#define XY_STEP_NM 12500L", "#define XY_STEP_NM 1000L", "PITCH: firmware multiple 1"),
    ("#define Z_STEP_NM 2500L", "#define Z_STEP_NM 1250L", "ZSTEP: firmware default 1250"),
])
def test_macro_firmware_that_disagrees_fails(tmp_path, old, new, named):
    root = _copy(tmp_path, MACRO)
    _edit(root / "firmware" / "config.h", old, new)
    found = firmware_mismatches(macro.TABLE, _macro_firmware(root))
    assert any(m.startswith(named) for m in found), found


def test_macro_firmware_default_that_disagrees_fails(tmp_path):
    root = _copy(tmp_path, MACRO)
    _edit(root / "firmware" / "macro_afm.ino", "long speed = 4000", "long speed = 3000")
    assert "SPEED: firmware default 3000 != table 4000" in \
        firmware_mismatches(macro.TABLE, _macro_firmware(root))


def test_haptic_firmware_that_disagrees_fails(tmp_path):
    ino = tmp_path / "haptic.ino"
    shutil.copy(HAPTIC / "haptic.ino", ino)
    _edit(ino, "/* [P_VFILTER] = */ {10L, 500L, 200L, false}",
          "/* [P_VFILTER] = */ {10L, 600L, 200L, false}")
    assert firmware_mismatches(haptic.TABLE, parse_haptic_firmware(ino.read_text())) == [
        "VFILTER: firmware high 600 != table 500"]


# -- the table itself -------------------------------------------------------------------------
def test_wire_param_checks_name_the_parameter_value_and_range():
    p = macro.TABLE[macro.Param.PITCH]
    assert p.check(200) == 200
    with pytest.raises(ValueError, match=r"PITCH \(pixel spacing\) must be an integer "
                                         r"25..10000 um in steps of 25, got 30"):
        p.check(30)
    with pytest.raises(ValueError, match="ZSTEP .* is read-only"):
        macro.TABLE[macro.Param.ZSTEP].check(2500)
    assert p.to_wire(0.21e-3) == 200 and p.to_si(200) == pytest.approx(0.2e-3)
    with pytest.raises(ValueError, match=r"pitch must be in \[2.5e-05, 0.01\] m, got 1e-06"):
        p.to_wire(1e-6)


def test_wire_units_come_from_the_one_unit_table():
    from afmsmiler.parameters import UNITS
    for key in ("um", "nm", "pm", "uN", "mA", "ms", "Hz", "us"):
        assert WIRE_UNITS[key].scale == UNITS[key][1]
        assert WIRE_UNITS[key].si_unit == UNITS[key][0]
    assert WIRE_UNITS["mdeg"].scale == pytest.approx(math.pi / 180e3)


def test_a_table_refuses_duplicates_and_bad_descriptions():
    nx = WireParam("NX", "NX", "count", 1, 8, 1)
    with pytest.raises(ValueError, match="unique"):
        ParamTable("X", (nx, nx))
    with pytest.raises(ValueError, match="unit must be a key of WIRE_UNITS"):
        WireParam("NX", "NX", "furlong", 1, 8, 1)
    with pytest.raises(ValueError, match="default 9 outside"):
        WireParam("NX", "NX", "count", 1, 8, 9)
    with pytest.raises(KeyError, match="no parameter 'QQ'"):
        macro.TABLE["QQ"]
