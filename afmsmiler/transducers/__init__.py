"""Module (b): the probe's transducers, all eleven principles of the paper's Table I.

Each principle is a model (a :class:`~afmsmiler.transducers.base.Transducer` subclass) that
turns its physical input into its output signal through the cantilever of module (a):

=======================  ==============================  ================
key                      model                           module
=======================  ==============================  ================
optical_beam_deflection  :class:`OpticalBeamDeflection`  :mod:`.optical`
astigmatic               :class:`AstigmaticDetection`    :mod:`.optical`
interferometry           :class:`Interferometer`         :mod:`.optical`
piezo_acoustic           :class:`PiezoAcoustic`          :mod:`.acoustic`
photothermal             :class:`Photothermal`           :mod:`.thermal`
electromagnetic          :class:`Electromagnetic`        :mod:`.electric`
electrostatic            :class:`Electrostatic`          :mod:`.electric`
optomechanical           :class:`Optomechanical`         :mod:`.embedded`
piezoresistive           :class:`Piezoresistive`         :mod:`.embedded`
electrothermal           :class:`Electrothermal`         :mod:`.thermal`
piezoelectric            :class:`Piezoelectric`          :mod:`.embedded`
=======================  ==============================  ================

:data:`PRINCIPLES` maps each key to its model class, in the order of Table I, and
:func:`table_one` generates the table's rows (name, function, signal, size) from the models'
attributes; :func:`table_one_markdown` and :func:`table_one_html` render it.
"""
from __future__ import annotations

from dataclasses import dataclass
from html import escape

from .acoustic import PiezoAcoustic
from .base import (FrequencyResponse, Harmonics, Operation, Parameter, Resolution, SignalChain,
                   Stage, Transducer, quantity)
from .electric import Electromagnetic, Electrostatic
from .embedded import Optomechanical, Piezoelectric, Piezoresistive
from .optical import AstigmaticDetection, Interferometer, OpticalBeamDeflection
from .thermal import Electrothermal, Photothermal
from ..validation import check_choice

__all__ = ["PRINCIPLES", "get_principle", "TableRow", "table_one", "table_one_markdown",
           "table_one_html", "Transducer", "Parameter", "quantity", "Operation", "SignalChain",
           "Stage", "FrequencyResponse", "Resolution", "Harmonics", "OpticalBeamDeflection",
           "AstigmaticDetection", "Interferometer", "PiezoAcoustic", "Photothermal",
           "Electromagnetic", "Electrostatic", "Optomechanical", "Piezoresistive", "Electrothermal",
           "Piezoelectric"]

#: Key -> model class of every principle, in the order of the paper's Table I.
PRINCIPLES: dict[str, type[Transducer]] = {cls.key: cls for cls in (
    OpticalBeamDeflection, AstigmaticDetection, Interferometer, PiezoAcoustic, Photothermal,
    Electromagnetic, Electrostatic, Optomechanical, Piezoresistive, Electrothermal, Piezoelectric)}


def get_principle(key: str, **params) -> Transducer:
    """An instance of the model ``key`` (see :data:`PRINCIPLES`) with ``params`` (SI units).

    Raises
    ------
    ValueError
        If ``key`` is not a principle, or a parameter is out of its range.
    TypeError
        If a parameter is unknown to that model.
    """
    check_choice("key", key, PRINCIPLES)
    return PRINCIPLES[key](**params)


@dataclass(frozen=True)
class TableRow:
    """A row of Table I, generated from a model's class attributes.

    Parameters
    ----------
    key : str
        The model's key in :data:`PRINCIPLES`.
    name : str
        The principle's name.
    function : str
        ``"sensing"``, ``"actuation"`` or ``"both"``.
    signal : str
        ``"DC&AC"``, ``"AC only"`` or ``"AC mostly"``.
    size : str
        ``"bulk"`` or ``"embedded"``.
    """

    key: str
    name: str
    function: str
    signal: str
    size: str


def table_one() -> list[TableRow]:
    """The rows of Table I, generated from the models' attributes (in the table's order)."""
    return [TableRow(c.key, c.name, c.function, c.signal, c.size) for c in PRINCIPLES.values()]


_HEADER = ("principle", "function", "signal", "size")


def table_one_markdown() -> str:
    """Table I as a Markdown table (for the book and notebook markdown)."""
    lines = ["| " + " | ".join(_HEADER) + " |", "|" + "---|" * len(_HEADER)]
    lines += [f"| {r.name} | {r.function} | {r.signal} | {r.size} |" for r in table_one()]
    return "\n".join(lines) + "\n"


def table_one_html() -> str:
    """Table I as an HTML table (for a notebook: ``HTML(table_one_html())``)."""
    head = "".join(f"<th>{escape(h)}</th>" for h in _HEADER)
    rows = "".join("<tr>" + "".join(f"<td>{escape(v)}</td>" for v in
                                    (r.name, r.function, r.signal, r.size)) + "</tr>"
                   for r in table_one())
    return f"<table><thead><tr>{head}</tr></thead><tbody>{rows}</tbody></table>"
