"""The frame format shared by every device of module (h), protocol version 1 (pure, no I/O).

A frame is one line ``BODY*CC\\n``: BODY is printable ASCII without ``*`` (at most
:data:`MAX_BODY` characters), tokens ``SEQ CODE [ARG ...]`` separated by one space; CC is the
CRC-8 of BODY's bytes as two uppercase hex digits. The CRC is CRC-8/SMBUS of the reveng catalogue
(polynomial 0x07, init 0x00, not reflected, xorout 0x00; check value 0xF4 for ``"123456789"``).

Examples
--------
>>> encode_frame(Frame(1, "ID"))
b'1 ID*C1\\n'
>>> decode_frame(b"1 OK ID MACROAFM 1 0.1.0*22\\r\\n")
Frame(seq=1, code='OK', args=('ID', 'MACROAFM', 1, '0.1.0'))
"""
from __future__ import annotations

import re
from dataclasses import dataclass
from numbers import Integral

from ..validation import _short
from .errors import ChecksumError, FrameError

__all__ = ["PROTOCOL_VERSION", "MAX_BODY", "crc8", "Frame", "encode_frame", "decode_frame",
           "as_bytes", "reply_frame", "error_frame", "event_frame"]

#: The protocol version this driver speaks (every device's ``ID`` reply must report it).
PROTOCOL_VERSION = 1
#: The most characters of a frame's body.
MAX_BODY = 120
#: The smallest and largest integer argument (int32).
INT_MIN, INT_MAX = -(2 ** 31), 2 ** 31 - 1

_INT = re.compile(r"-?[0-9]+")
_WORD = re.compile(r"[A-Za-z0-9_.:-]+")
_CODE = re.compile(r"[A-Z]{2}")
_SEQ = re.compile(r"0|[1-9][0-9]{0,2}")
_HEX = re.compile(rb"[0-9A-F]{2}")


def _table() -> tuple[int, ...]:
    table = []
    for byte in range(256):
        crc = byte
        for _ in range(8):
            crc = ((crc << 1) ^ 0x07) & 0xFF if crc & 0x80 else (crc << 1) & 0xFF
        table.append(crc)
    return tuple(table)


_CRC_TABLE = _table()

_BYTES = (bytes, bytearray, memoryview)


def as_bytes(name: str, data) -> bytes:
    """``data`` as bytes, refusing what is not bytes (an int would be taken as a byte count).

    Parameters
    ----------
    name : str
        The parameter's name, for the message.
    data : bytes, bytearray or memoryview
        The bytes.

    Returns
    -------
    bytes

    Raises
    ------
    TypeError
        Naming the parameter, for anything else (``bytes(10**10)`` would allocate 10 GB), or
        if ``name`` is not a str.

    Examples
    --------
    >>> as_bytes("data", bytearray(b"1 ID"))
    b'1 ID'
    """
    if not isinstance(name, str):
        raise TypeError(f"name must be the parameter's name (a str), got {_short(name)}")
    if not isinstance(data, _BYTES):
        raise TypeError(f"{name} must be bytes, got {type(data).__name__}")
    return bytes(data)


def crc8(data: bytes) -> int:
    """CRC-8/SMBUS of ``data`` (polynomial 0x07, init 0, not reflected, no final xor).

    Parameters
    ----------
    data : bytes
        The bytes to check (a frame's body).

    Returns
    -------
    int
        The checksum, 0..255.

    Raises
    ------
    TypeError
        If ``data`` is not bytes.

    Examples
    --------
    >>> hex(crc8(b"123456789"))
    '0xf4'
    """
    crc = 0
    for byte in as_bytes("data", data):
        crc = _CRC_TABLE[crc ^ byte]
    return crc


@dataclass(frozen=True)
class Frame:
    """One frame: a sequence number, a two-letter code and its arguments, checked when built.

    Parameters
    ----------
    seq : int
        0..255; 0 for frames that get no reply (stream frames, events).
    code : str
        Two uppercase letters (a command, ``OK``, ``ER`` or a stream code such as ``PX``).
    args : tuple of int or str
        Integer arguments (int32) and words (``[A-Za-z0-9_.:-]+``, not of an integer's form);
        the body ``SEQ CODE ARG ...`` has at most :data:`MAX_BODY` characters.

    Raises
    ------
    ValueError
        Naming the field (``seq``, ``code``, ``args[i]`` or the body's length), its value and
        what is valid, for a frame that could not go on the wire.
    """

    seq: int
    code: str
    args: tuple = ()

    def __post_init__(self):
        seq = self.seq
        if isinstance(seq, bool) or not isinstance(seq, Integral) or not 0 <= int(seq) <= 255:
            raise ValueError(f"seq must be an integer in 0..255, got {_short(seq)}")
        if not isinstance(self.code, str) or not _CODE.fullmatch(self.code):
            raise ValueError(f"code must be two uppercase letters, got {_short(self.code)}")
        if isinstance(self.args, (str, bytes)) or not hasattr(self.args, "__iter__"):
            raise ValueError(f"args must be a tuple of ints and words, got {_short(self.args)}")
        args = []
        for i, arg in enumerate(self.args):
            if i >= MAX_BODY // 2:  # each argument takes two characters at least
                raise ValueError(f"args must fit a body of at most {MAX_BODY} characters, "
                                 f"got more than {MAX_BODY // 2} arguments")
            _token(f"args[{i}]", arg)
            args.append(int(arg) if isinstance(arg, Integral) else arg)
        object.__setattr__(self, "seq", int(seq))
        object.__setattr__(self, "args", tuple(args))
        length = len(self._body())
        if length > MAX_BODY:
            raise ValueError(f"the frame's body must be at most {MAX_BODY} characters, "
                             f"got {length}")

    def _body(self) -> bytes:
        tokens = [str(self.seq), self.code] + [_token(f"args[{i}]", a)
                                         for i, a in enumerate(self.args)]
        return " ".join(tokens).encode("ascii")


def _wire(value):
    """An enum member as its value on the wire (``Param.PITCH`` -> ``"DX"``)."""
    return getattr(value, "value", value)


def _word(name: str, value) -> str:
    """``value`` (a str or a str enum member) as a word of a frame, else ValueError naming it."""
    word = _wire(value)
    if not isinstance(word, str) or not _WORD.fullmatch(word) or _INT.fullmatch(word):
        raise ValueError(f"{name} must be a word of [A-Za-z0-9_.:-] (not a number), got "
                         f"{_short(value)}")
    return word


def reply_frame(seq: int, code, *results) -> Frame:
    """A device's success reply ``SEQ OK CODE [RESULT ...]`` (every device's shape).

    Parameters
    ----------
    seq : int
        The command's sequence number, 0..255.
    code : str or enum
        The command echoed (two uppercase letters).
    *results : int or str or enum
        What the command returned.

    Returns
    -------
    Frame

    Raises
    ------
    ValueError
        Naming ``seq``, ``code`` or the result (``args[i]``) that cannot go on the wire.
    """
    command = _wire(code)
    if not isinstance(command, str) or not _CODE.fullmatch(command):
        raise ValueError(f"code must be a command's two uppercase letters, got {_short(code)}")
    return Frame(seq, "OK", (command, *(_wire(r) for r in results)))


def error_frame(seq: int, code: int, word: str | None = None) -> Frame:
    """A device's error ``SEQ ER ERRNO [WORD]`` (SEQ 0: an unreadable line or a fault).

    Parameters
    ----------
    seq : int
        The command's sequence number (0..255), 0 for an unsolicited error.
    code : int
        The error number (an :class:`~afmsmiler.hardware.errors.ErrorCode`), 0..2147483647.
    word : str, optional
        A word saying more (an axis, a parameter); None or "" for none.

    Returns
    -------
    Frame

    Raises
    ------
    ValueError
        Naming ``seq``, ``code`` or ``word``, with the value and what is valid.
    """
    if isinstance(code, bool) or not isinstance(code, Integral) or not 0 <= int(code) <= INT_MAX:
        raise ValueError(f"code must be an error number, an integer in 0..{INT_MAX}, got "
                         f"{_short(code)}")
    if word is None or (isinstance(word, str) and word == ""):
        return Frame(seq, "ER", (int(code),))
    return Frame(seq, "ER", (int(code), _word("word", word)))


def event_frame(word, *args) -> Frame:
    """A device's event ``0 EV WORD [ARG]``.

    Parameters
    ----------
    word : str or enum
        The event's word (an ``Event`` member of the device's codec).
    *args : int or str
        Its argument.

    Returns
    -------
    Frame

    Raises
    ------
    ValueError
        Naming ``word`` or the argument (``args[i]``) that cannot go on the wire.
    """
    return Frame(0, "EV", (_word("word", word), *(_wire(a) for a in args)))


def _token(name: str, arg) -> str:
    """The text of one argument on the wire (an int32 or a word), else ValueError naming it."""
    if isinstance(arg, Integral) and not isinstance(arg, bool):
        value = int(arg)
        if not INT_MIN <= value <= INT_MAX:
            raise ValueError(f"{name} must fit int32 ({INT_MIN}..{INT_MAX}), got "
                             f"{_short(value)}")
        return str(value)
    if isinstance(arg, str):
        if not _WORD.fullmatch(arg):
            raise ValueError(f"{name} must be a word of [A-Za-z0-9_.:-], got {_short(arg)}")
        if _INT.fullmatch(arg):
            raise ValueError(f"{name} {arg!r} is a number written as a word: pass an int")
        return arg
    raise ValueError(f"{name} must be an int32 or a word (str), got {_short(arg)}")


def encode_frame(frame: Frame) -> bytes:
    """The bytes of ``frame`` on the wire, ``BODY*CC\\n``.

    Parameters
    ----------
    frame : Frame
        The frame to send.

    Returns
    -------
    bytes
        The line, with its checksum and one ``\\n`` (never ``\\r``).

    Raises
    ------
    TypeError
        If ``frame`` is not a :class:`Frame` (whose fields are checked when it is built).
    """
    if not isinstance(frame, Frame):
        raise TypeError(f"frame must be a Frame, got {type(frame).__name__}")
    body = frame._body()  # a Frame is checked when built
    return body + b"*%02X\n" % crc8(body)


def decode_frame(line: bytes) -> Frame:
    """The frame in one received line.

    Parameters
    ----------
    line : bytes
        One line, with or without its trailing ``\\n`` (a ``\\r`` before it is accepted).

    Returns
    -------
    Frame
        With integer arguments as ``int`` and words as ``str``.

    Raises
    ------
    TypeError
        If ``line`` is not bytes.
    ChecksumError
        If the line has the form ``BODY*CC`` but CC is not the CRC-8 of BODY (a corrupted byte).
    FrameError
        If the line is not a frame at all (too long, no ``*CC``, non-printable bytes, bad tokens;
        a token of the integer's form ``-?[0-9]+`` outside int32 is a bad token, never a word,
        as in the firmware: devices answer such a line ``0 ER 9``).
    """
    raw = as_bytes("line", line)
    text = raw[:-1] if raw.endswith(b"\n") else raw
    text = text[:-1] if text.endswith(b"\r") else text
    star = text.rfind(b"*")
    if star < 0 or len(text) - star != 3:
        raise FrameError(f"not a frame (no '*CC' checksum at the end): {raw[:40]!r}", raw)
    body, check = text[:star], text[star + 1:]
    if len(body) > MAX_BODY:
        raise FrameError(f"frame body longer than {MAX_BODY} characters ({len(body)})", raw)
    if not _HEX.fullmatch(check):
        raise FrameError(f"checksum must be two uppercase hex digits, got {check!r}", raw)
    if int(check, 16) != crc8(body):
        raise ChecksumError(f"checksum {check.decode()} does not match the body "
                            f"(CRC-8 {crc8(body):02X}): {raw[:40]!r}", raw)
    if any(b < 0x20 or b > 0x7E or b == 0x2A for b in body):
        raise FrameError(f"frame body has bytes outside printable ASCII: {raw[:40]!r}", raw)
    tokens = body.decode("ascii").split(" ")
    if len(tokens) < 2:
        raise FrameError(f"a frame needs SEQ and CODE: {raw[:40]!r}", raw)
    seq, code, *args = tokens
    if not _SEQ.fullmatch(seq) or int(seq) > 255:
        raise FrameError(f"SEQ must be a decimal in 0..255, got {seq!r}", raw)
    if not _CODE.fullmatch(code):
        raise FrameError(f"CODE must be two uppercase letters, got {code!r}", raw)
    values = []
    for arg in args:
        if _INT.fullmatch(arg):
            value = int(arg)
            if not INT_MIN <= value <= INT_MAX:
                raise FrameError(f"integer argument {arg} does not fit int32", raw)
            values.append(value)
        elif _WORD.fullmatch(arg):
            values.append(arg)
        else:
            raise FrameError(f"argument {arg!r} is neither an integer nor a word", raw)
    return Frame(int(seq), code, tuple(values))
