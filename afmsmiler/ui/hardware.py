"""The widget panel of module (h), part 1: drive the macroscopic AFM (or its twin), print an image.

Left: the link (the twin by default, or a serial port found by ``serial.tools.list_ports``), the
object the twin scans, the scan's settings (mode contact/jumping, pixels, pitch, setpoint, lift),
and the buttons Connect, Start, Pause/Resume, Abort, Save .gwy. Right: the print (the image to
print, its lateral and vertical scales, the base plate) and Export STL. Below: the figure
(:class:`~afmsmiler.plots.hardware.MacroFigure`): the height image forming from the streamed
pixels, the gauge's image, the current line; and the print compared with the scan of it.

The panel reads values -> acquisition -> view. The link and its scans are the machine's session
below the UI (:class:`~afmsmiler.hardware.macro.session.MacroSession`, an
:class:`~afmsmiler.acquisition.Acquisition`), which holds the image; the panel draws its
snapshots. The buttons, the progress bar and the live loop are module (f)'s
(:class:`~afmsmiler.ui.acquisition.AcquisitionControls`): :meth:`MacroAFMPanel.step` reads the
pixels the machine has streamed (at most one line's worth, or until
:attr:`MacroAFMPanel.MAX_LINE_WAIT`) and redraws once; in a live notebook
:meth:`MacroAFMPanel.start` runs the steps in an asyncio task on the kernel's event loop and draws
at most one picture per :attr:`MacroAFMPanel.FRAME_INTERVAL`, so Pause or Abort pressed during the
scan is handled between two steps (pressed in another thread, they are queued for the loop). Tests (and nbval) drive it synchronously:
``start(run=False)``, then ``step()``. A fault that ends the scan (a limit switch, the port
unplugged) is shown under the panel; the lines finished before it stay in the image and can be
saved.

One user action = one model run: moving a slider runs :meth:`update` (which checks the values and
recomputes the print's size, no mesh); Connect opens the link once; Start configures the machine
and starts one scan; Export STL builds one mesh and writes it.
"""
from __future__ import annotations

import math
import os
from dataclasses import dataclass

import ipywidgets as widgets
import numpy as np

from .. import samples as _samples
from ..acquisition import Snapshot
from ..hardware import printing
from ..hardware.macro.device import PARAMETERS as DEVICE_PARAMETERS
from ..hardware.macro.session import CHANNELS, MacroSession
from ..hardware.macro.twin import printed_sample
from ..parameters import read_only, shown
from ..plots.hardware import MacroFigure, comparison_view, macro_view
from ..samples import Sample
from ..validation import check_choice, check_finite
from .acquisition import Acquiring, AcquisitionControls
from .controls import WIDTH
from .panel import Panel, initial_values, running_as_notebook, slider

__all__ = ["MacroAFMPanel", "MacroResult", "DEFAULTS", "LIVE_TIME_SCALE", "TWIN", "MODES",
           "PIXELS", "SOURCES", "PITCHES", "SCAN_PARAMETERS", "TWIN_SAMPLES", "TWIN_PITCH",
           "serial_ports", "twin_sample", "source_image", "PRINT_SLIDERS"]

#: The twin's pace in a live notebook: 500 times the machine's (a 32 x 32 contact scan of the
#: seashell takes 3 s instead of 23 minutes, a jumping scan of the tall pillars 30 s).
LIVE_TIME_SCALE = 0.002

#: The port drop-down's value for the simulated machine.
TWIN = "twin"

#: Imaging modes of the macroscopic AFM (the firmware's MO 0 and 1).
MODES = ("contact", "jumping")

#: Pixels per line (and lines) offered; the firmware keeps at most 128 per line.
PIXELS = (8, 16, 32, 64, 128)

#: The printed objects the twin can scan: name -> (image, lateral scale, vertical scale). A
#: print made with Export STL is added as "your print (<file name>)".
TWIN_SAMPLES = read_only({
    "seashell (printed 400x)": ("seashell", 400.0, 400.0),
    "pillars (2 mm tall grating)": ("pillars", 1.0, 1.0),
})

#: The pitch in m of the height map the twin scans (the print read back by
#: :func:`~afmsmiler.hardware.printing.mesh_to_sample`): finer than every pitch offered.
TWIN_PITCH = 0.05e-3

#: Pixel spacings offered in mm (the firmware takes multiples of 25 um; the paper scans 0.2 mm).
PITCHES = (0.1, 0.2, 0.25, 0.4, 0.5, 1.0)

#: The scan's sliders, from :data:`afmsmiler.hardware.macro.device.PARAMETERS`: the setpoint force
#: (the driver turns it into gauge counts through the calibration) and the jumping lift.
SCAN_PARAMETERS = read_only({name: DEVICE_PARAMETERS[name]
                             for name in ("setpoint_force", "lift")})

#: The images Export STL can print: the machine's last scan or an AFM image.
SOURCES = ("seashell (AFM image, 80 um)", "real image (Bruker, 2 um)", "last scan")

#: The print's sliders, from :data:`afmsmiler.hardware.printing.PARAMETERS`.
PRINT_SLIDERS = ("lateral_scale", "vertical_scale", "base_thickness")


def serial_ports() -> list:
    """The serial ports pyserial finds, as (label, device) pairs for a drop-down.

    Returns
    -------
    list of tuple
        ``("/dev/ttyACM0 (Arduino Mega 2560)", "/dev/ttyACM0")``, ...; empty without pyserial
        or without ports.
    """
    try:
        from serial.tools import list_ports
    except ImportError:  # pragma: no cover - pyserial is a dependency
        return []
    out = []
    for port in sorted(list_ports.comports(), key=lambda p: p.device):
        description = port.description if port.description not in (None, "", "n/a") else ""
        out.append((f"{port.device} ({description})" if description else port.device,
                    port.device))
    return out


def _pillars() -> Sample:
    """The twin's tall calibration grating: square pillars 2 mm tall, 1.6 mm wide, 3.2 mm apart."""
    return printed_sample("grating", pixels=64, pixel_size=0.4e-3, height=2e-3)


_CACHE: dict = {}


def source_image(name: str) -> Sample:
    """An AFM image :data:`SOURCES` names (not "last scan", which the panel holds).

    Parameters
    ----------
    name : str
        ``"seashell (AFM image, 80 um)"`` or ``"real image (Bruker, 2 um)"``.

    Returns
    -------
    Sample
    """
    check_choice("source", name, [s for s in SOURCES if s != "last scan"])
    key = ("source", name)
    if key not in _CACHE:
        _CACHE[key] = (printing.seashell() if name.startswith("seashell")
                       else _samples.real_image())
    return _CACHE[key]


def twin_sample(name: str):
    """The printed object ``name`` of :data:`TWIN_SAMPLES` as a mesh in m (made once).

    Parameters
    ----------
    name : str
        A key of :data:`TWIN_SAMPLES`.

    Returns
    -------
    trimesh.Trimesh
    """
    check_choice("sample", name, list(TWIN_SAMPLES))
    key = ("twin", name)
    if key not in _CACHE:
        image, ls, vs = TWIN_SAMPLES[name]
        image = printing.seashell() if image == "seashell" else _pillars()
        _CACHE[key] = printing.sample_to_mesh(image, lateral_scale=ls, vertical_scale=vs,
                                              base_thickness=2e-3)
    return _CACHE[key]


@dataclass(frozen=True)
class MacroResult:
    """What the panel shows, for tests and exercises; SI units.

    The images are the session's snapshot (:class:`~afmsmiler.acquisition.Snapshot`: read-only,
    not copied again); the panel adds the state it shows, the comparison and the print's size.

    Attributes
    ----------
    height : numpy.ndarray
        Heights in m, (lines, pixels), NaN where no pixel came (read-only).
    gauge : numpy.ndarray
        Gauge counts above the free reading, NaN where no pixel came (read-only).
    pitch : float
        Pixel spacing in m.
    pixels_done : int
        Pixels received.
    lines_done : int
        Lines finished (rows 0 to ``lines_done - 1``).
    state : str
        "idle", "connected", "scanning", "paused", "done", "aborted" or "fault".
    error : str or None
        The fault that ended the scan, if any.
    comparison : PrintComparison or None
        The last scan of a print compared with the printed surface.
    print_size : tuple of float
        The print's (x, y, z) size in m with the present print settings.
    """

    height: np.ndarray
    gauge: np.ndarray
    pitch: float
    pixels_done: int
    lines_done: int
    state: str
    error: str | None = None
    comparison: object = None
    print_size: tuple = ()

    def finished(self) -> Sample:
        """The finished lines as a Sample (heights in m, at least two lines).

        Returns
        -------
        Sample
        """
        return _finished(self.height, self.lines_done, self.pitch)


def _defaults() -> dict:
    p = printing.PARAMETERS
    out = {name: p[name].to_display(p[name].default) for name in PRINT_SLIDERS}
    out.update({name: q.to_display(q.default) for name, q in SCAN_PARAMETERS.items()})
    return out


#: Initial control values, in the units the controls show.
DEFAULTS = read_only(dict(port=TWIN, sample=next(iter(TWIN_SAMPLES)), mode="contact", pixels=32,
                          pitch=0.2, source=SOURCES[0], **_defaults()))


class MacroAFMPanel(Acquiring, Panel):
    """Scan with the macroscopic AFM or its twin, watch the image form, print an image.

    Controls (units as shown): ``port`` (``"twin"`` or a serial port), ``sample`` (the printed
    object the twin scans), ``mode`` (contact, jumping), ``pixels`` (per line = lines),
    ``pitch`` [mm], ``setpoint_force`` [mN], ``lift`` [mm] (jumping), ``source`` (the
    image to print), ``lateral_scale`` [x], ``vertical_scale`` [x], ``base_thickness`` [mm].
    Buttons: Connect, Start, Pause (Resume), Abort, Save .gwy, Export STL; a progress bar.

    Parameters
    ----------
    time_scale : float
        The twin's pace, real seconds per second of the machine: 1 is the real machine's (a
        32 x 32 contact scan of the seashell takes 23 minutes), 0 as fast as the computer goes
        (tests). Default: 0 under test, else :data:`LIVE_TIME_SCALE`.
    **initial
        Initial control values (keys of :data:`DEFAULTS`), in the units shown.

    Attributes
    ----------
    last : MacroResult
        The image so far, the state, the print's size, the comparison.
    figure : MacroFigure
        The image forming and the print compared.
    progress : ipywidgets.IntProgress
        Pixels received out of the pixels of the scan.
    running : bool
        A scan is under way (started, neither finished, aborted nor faulted; paused counts).
    device : object or None
        The connected :class:`~afmsmiler.hardware.macro.device.MacroAFM` (None before Connect).
    """

    #: s between two pictures of a running scan in a live notebook.
    FRAME_INTERVAL = 0.1
    #: s: the longest one step waits for pixels (the kernel stays responsive between steps).
    MAX_LINE_WAIT = 0.25

    def __init__(self, time_scale: float | None = None, **initial):
        v = initial_values(initial, DEFAULTS)
        if time_scale is None:
            time_scale = 0.0 if not running_as_notebook() else LIVE_TIME_SCALE
        self.time_scale = check_finite("time_scale", time_scale)
        if not 0 <= self.time_scale <= 10:
            raise ValueError(f"time_scale must be in [0, 10], got {time_scale!r}")
        layout = widgets.Layout(width=WIDTH)
        ports = [("twin (simulated machine)", TWIN)] + serial_ports()
        check_choice("port", v["port"], [p[1] for p in ports])
        check_choice("sample", v["sample"], list(TWIN_SAMPLES))
        check_choice("mode", v["mode"], list(MODES))
        check_choice("pixels", v["pixels"], list(PIXELS))
        check_choice("pitch", v["pitch"], list(PITCHES))
        check_choice("source", v["source"], list(SOURCES))
        c = {"port": widgets.Dropdown(options=ports, value=v["port"], description="port",
                                      layout=layout),
             "sample": widgets.Dropdown(options=list(TWIN_SAMPLES), value=v["sample"],
                                        description="twin's sample", layout=layout),
             "mode": widgets.ToggleButtons(options=list(MODES), value=v["mode"],
                                           description="mode"),
             "pixels": widgets.Dropdown(options=list(PIXELS), value=v["pixels"],
                                        description="pixels per line", layout=layout),
             "pitch": widgets.Dropdown(options=list(PITCHES), value=v["pitch"],
                                       description="pitch [mm]", layout=layout)}
        for name, p in SCAN_PARAMETERS.items():
            c[name] = slider(name, p, v[name])
        c["source"] = widgets.Dropdown(options=list(SOURCES), value=v["source"],
                                       description="image to print", layout=layout)
        for name in PRINT_SLIDERS:
            c[name] = slider(name, printing.PARAMETERS[name], v[name])
        self.controls = c
        self.control = AcquisitionControls(
            start=self.start, pause=self.pause, resume=self.resume, stop=self.abort,
            show=self._show, report=self._report_error, live=lambda: running_as_notebook(),
            stop_label="Abort", unit="pixels")
        act = self.control.act
        self.buttons = {"connect": widgets.Button(description="Connect", icon="plug",
                                                  button_style="info"),
                        "start": self.control.buttons["start"],
                        "pause": self.control.buttons["pause"],
                        "abort": self.control.buttons["stop"],
                        "save": widgets.Button(description="Save .gwy", icon="save"),
                        "export": widgets.Button(description="Export STL", icon="cube")}
        b = self.buttons
        b["connect"].on_click(lambda _b: act(self.connect))
        b["save"].on_click(lambda _b: act(lambda: self.save_gwy(self.paths["gwy"].value)))
        b["export"].on_click(lambda _b: act(lambda: self.export_stl(self.paths["stl"].value)))
        self.paths = {"gwy": widgets.Text(value="macro_scan.gwy", description="image file"),
                      "stl": widgets.Text(value="print.stl", description="STL file")}
        self.progress = self.control.progress
        self.status = widgets.HTML()
        self.fig = self.new_figure(figsize=(10.0, 7.5))
        self.figure = None
        self.device = None
        self._session = None       # the MacroSession: the link and its scans (holds the image)
        self._kept = None          # the last scan's snapshot once its link is closed
        self._link = None          # (port, sample name) of the open link
        self._config = None        # what update decided (SI)
        self._scan_config = None   # the config the image shown was scanned with
        self._comparison = None
        self._compared = None      # the snapshot the comparison was made from
        self._prints = {}          # your prints: name -> mesh (m)
        self._maps = {}            # (what, name, pitch) -> height map of a print (m)
        self.mesh_runs = 0         # meshes built (Export STL, a twin's new sample)
        super().__init__()

    # -- state -----------------------------------------------------------------------------
    @property
    def last(self) -> "MacroResult":
        """The image so far (the session's snapshot), the state, the print's size, the
        comparison."""
        snap = self._snapshot()
        key = (snap, self._session, self._config, self._comparison)
        cached = getattr(self, "_last", None)
        if cached is not None and all(a is b for a, b in zip(cached[0], key)):
            return cached[1]  # nothing changed: the same result
        try:
            size = self._print_size(snap) if self._config is not None else ()
        except ValueError:
            size = ()
        result = MacroResult(snap.images["height"], snap.images["gauge"], snap.pixel_size,
                             snap.pixels_done, snap.lines_done, self._state(snap), snap.error,
                             self._comparison, size)
        self._last = (key, result)
        return result

    @last.setter
    def last(self, value) -> None:  # Panel.__init__ starts it at None: the session holds it
        pass

    def _snapshot(self) -> Snapshot:
        """What is shown: the session's scan, else the last scan kept, else an empty grid."""
        session = self._session
        if session is not None and session.state != "idle":
            return session.snapshot()
        if self._kept is not None:
            return self._kept
        n = self._config["scan"]["pixels"] if self._config is not None else 2
        pitch = self._config["scan"]["pitch"] if self._config is not None else 1.0
        blank = getattr(self, "_blank", None)
        if blank is None or blank.lines != n or blank.pixel_size != pitch:
            self._blank = blank = Snapshot.blank(CHANNELS, (n, n), pitch, main="height")
        return blank

    def _state(self, snap: Snapshot) -> str:
        """The snapshot's state; "connected" (or "idle") while the link has not scanned."""
        if snap.state == "idle" or (self._session is not None and self._session.state == "idle"):
            return "connected" if self._session is not None else "idle"
        return snap.state

    # -- the callback -----------------------------------------------------------------------
    def _configure(self, values: dict) -> dict:
        """Turn the values (checked, sliders in SI: the panel contract) into the scan's and the
        print's (SI; the pitch drop-down shows mm)."""
        scan = dict(mode=values["mode"], pixels=int(values["pixels"]),
                    pitch=DEVICE_PARAMETERS["pitch"].to_si(values["pitch"]),
                    **{name: values[name] for name in SCAN_PARAMETERS})
        prints = {name: values[name] for name in PRINT_SLIDERS}
        return dict(port=values["port"], sample=values["sample"], scan=scan,
                    source=values["source"], print=prints)

    def update(self, port, sample, mode, pixels, pitch, source, **sliders) -> None:
        """Keep the controls' values (sliders in SI) for the next action.

        Nothing is scanned or printed here: Connect, Start and Export STL act on the values
        kept. The print's size is recomputed (a product of three numbers, no mesh).

        Parameters
        ----------
        port : str
            ``"twin"`` or a serial port's device name.
        sample : str
            The printed object the twin scans (a key of :data:`TWIN_SAMPLES` or a print made
            with Export STL).
        mode : str
            ``"contact"`` or ``"jumping"``.
        pixels : int
            Pixels per line and lines, one of :data:`PIXELS`.
        pitch : float
            Pixel spacing in mm, one of :data:`PITCHES`.
        source : str
            The image Export STL prints, one of :data:`SOURCES`.
        **sliders : float
            ``setpoint_force`` [N], ``lift`` [m], ``lateral_scale``, ``vertical_scale`` and
            ``base_thickness`` [m], in SI.

        Raises
        ------
        TypeError, ValueError
            For an unknown or missing control or a value out of range, before any work (the
            panel contract).
        """
        values = dict(sliders, port=port, sample=sample, mode=mode, pixels=pixels, pitch=pitch,
                      source=source)
        self._config = self._configure(values)
        self._show()

    # -- the print --------------------------------------------------------------------------
    def _source(self, source: str, snap: Snapshot | None = None) -> Sample | None:
        if source == "last scan":
            snap = self._snapshot() if snap is None else snap
            if snap.lines_done < 2:
                return None
            return _finished(snap.images["height"], snap.lines_done, snap.pixel_size)
        return source_image(source)

    def _print_size(self, snap: Snapshot | None = None) -> tuple:
        image = self._source(self._config["source"], snap)
        if image is None:
            return ()
        p = self._config["print"]
        return printing.print_size(image, **p)

    def export_stl(self, path) -> "os.PathLike":
        """Write the chosen image (``source``) as a printable STL; the twin can then scan it.

        The print is added to the twin's samples as ``"your print (<file name>)"``: choose it
        and Start to scan the printed object, and the figure's bottom row compares the scan
        with the printed surface.

        Parameters
        ----------
        path : str or os.PathLike
            The file to write, ending in ``.stl``.

        Returns
        -------
        pathlib.Path
        """
        image = self._source(self._config["source"])
        if image is None:
            raise ValueError("source 'last scan' needs a scan with at least 2 finished lines; "
                             "scan first or choose an AFM image")
        p = self._config["print"]
        mesh = printing.sample_to_mesh(image, **p)
        self.mesh_runs += 1
        written = printing.write_stl(mesh, path)
        name = f"your print ({written.name})"
        self._prints[name] = mesh
        # a print written again under the same name replaces the old one everywhere
        self._maps = {k: v for k, v in self._maps.items() if k[0] != name}
        if self._link is not None and self._link[1] == name:
            self._link = None  # the next Start connects a twin of the new print
        options = list(TWIN_SAMPLES) + list(self._prints)
        hold, self._hold = self._hold, True
        try:  # new options keep the chosen sample
            chosen = self.controls["sample"].value
            self.controls["sample"].options = options
            self.controls["sample"].value = chosen
        finally:
            self._hold = hold
        x, y, z = printing.print_size(image, **p)
        self.status.value = (f"<b>wrote {written.name}</b>: {shown(x, 'mm', '.3g')} x "
                             f"{shown(y, 'mm', '.3g')} x {shown(z, 'mm', '.3g')}")
        return written

    def _mesh(self, name: str):
        return self._prints[name] if name in self._prints else twin_sample(name)

    def _twin_map(self, name: str) -> Sample:
        """The height map in m the twin scans for the printed object ``name`` (made once)."""
        return self._height_map(name, TWIN_PITCH)

    def _height_map(self, name: str, pitch: float) -> Sample:
        """A printed object read back at ``pitch`` (made once per print and pitch)."""
        key = (name, pitch)
        cache = _CACHE if name in TWIN_SAMPLES else self._maps
        if key not in cache:
            cache[key] = printing.mesh_to_sample(self._mesh(name), pitch, name=name)
        return cache[key]

    # -- the machine ------------------------------------------------------------------------
    def connect(self) -> str:
        """Open the chosen link (the twin, or a serial port) and identify the machine.

        A twin scans the printed object chosen as ``sample``. Connecting again closes the
        link open before.

        Returns
        -------
        str
            The machine's identity (device, protocol and firmware versions, z micro-step).
        """
        self.close()
        config = self._config
        twin = config["port"] == TWIN
        if twin:
            session = MacroSession.twin(self._twin_map(config["sample"]),
                                        time_scale=self.time_scale)
        else:
            session = MacroSession.port(config["port"])
        self._session, self.device = session, session.device
        self._link = (config["port"], config["sample"] if twin else None)
        self.control.attach(session)
        self._show()
        return session.identity

    def close(self) -> None:
        """Stop a running scan (abort) and close the link (the image shown stays)."""
        self.control.cancel()
        session = self._session
        if session is not None:
            session.close()
            if session.state != "idle":
                self._kept = session.snapshot()  # the image shown stays
        self._session, self.device, self._link = None, None, None
        self.control.attach(None)

    def start(self, run: bool = True, wait: bool = False) -> None:
        """Start one scan on the machine with the settings the controls hold.

        Connects first if no link is open (or the twin's sample changed since); a running scan
        is aborted first. The settings were checked when the controls last changed
        (:meth:`update`); the machine receives them once, here.

        Parameters
        ----------
        run : bool
            Run it: in a live notebook as an asyncio task on the kernel's loop (the cell returns
            at once, the buttons act during the scan); elsewhere (tests, nbval) to the end at
            once. With ``run=False`` the scan only starts: call :meth:`step` until it returns
            False.
        wait : bool
            Run it to the end before returning, also in a live notebook (the image still
            forms as the pixels come; the buttons act once the cell is done): for a cell that
            uses the image next.
        """
        config = self._config
        wanted = (config["port"], config["sample"] if config["port"] == TWIN else None)
        if self._session is None or self._link != wanted:
            self.connect()
        self._comparison = self._compared = None
        self._session.start(**config["scan"])
        self._scan_config = config
        self._show()
        if run:
            self.control.run(wait=wait, frame_interval=self.FRAME_INTERVAL,
                             max_line_wait=self.MAX_LINE_WAIT, read_wait=0.02)

    def step(self, show: bool = True, wait: float | None = None) -> bool:
        """Read the pixels streamed so far (up to the end of the line) and redraw once.

        Parameters
        ----------
        show : bool
            Redraw (figure, progress); the scan's end is always shown.
        wait : float, optional
            The longest time in s to wait for pixels; default :attr:`MAX_LINE_WAIT`.

        Returns
        -------
        bool
            True while the scan runs (paused included), False once it has ended (finished,
            aborted or faulted).
        """
        return self.control.step(show=show,
                                 wait=self.MAX_LINE_WAIT if wait is None else float(wait))

    def pause(self) -> None:
        """Pause the scan (the machine stops after the pixel under way)."""
        if not self.running or self.paused:
            return
        if not self._session.pause():
            self.status.value = "<b>the machine had already finished scanning</b>"
            return
        self._show()

    def resume(self) -> None:
        """Resume a paused scan."""
        if not self.paused:
            return
        self._session.resume()
        self._show()

    def abort(self) -> None:
        """Abort the scan: the machine stops; the lines finished so far stay in the image."""
        if not self.running:
            return
        self._session.abort()
        self._show()

    def save_gwy(self, path) -> "os.PathLike":
        """Save the finished lines as a Gwyddion ``.gwy`` file (heights in m, real pixel size).

        Parameters
        ----------
        path : str or os.PathLike
            The file to write, ending in ``.gwy``.

        Returns
        -------
        pathlib.Path
        """
        image = self.last.finished()
        written = _samples.save_gwy(image, path)
        self.status.value = f"<b>saved {written.name}</b> ({image.shape[0]} lines)"
        return written

    # -- the comparison ---------------------------------------------------------------------
    def _compare(self, snap: Snapshot) -> None:
        """The finished lines of a twin's scan against the print as the needle follows it.

        The needle's apex cannot enter a gap narrower than itself: the surface it follows is
        the print dilated by the apex (module (f)'s :func:`~afmsmiler.imaging.dilation.dilate`),
        which the twin computed once; it is read on the scan's grid (the scan starts at the
        print's first pixel, the pitch a multiple of :data:`TWIN_PITCH`).
        """
        config, session = self._scan_config, self._session
        self._comparison, self._compared = None, snap
        if (config is None or config["port"] != TWIN or session is None
                or session.server is None or snap.lines_done < 2):
            return
        apex = session.server.twin.apex
        k = int(round(config["scan"]["pitch"] / apex.pixel_size))
        reference = Sample(apex.heights[::k, ::k], k * apex.pixel_size,
                           "print as the needle follows it")
        image = _finished(snap.images["height"], snap.lines_done, snap.pixel_size)
        rows = min(image.shape[0], reference.shape[0])
        cols = min(image.shape[1], reference.shape[1])
        if rows < 2 or cols < 2:
            return
        self._comparison = printing.compare_scan(reference, Sample(
            image.heights[:rows, :cols], image.pixel_size, image.name))

    # -- what is shown ----------------------------------------------------------------------
    def _show(self) -> None:
        """The image so far into the figure (one redraw), the progress bar and the status."""
        snap = self._snapshot()
        if snap.state == "done" and self._compared is not snap and snap is not self._kept:
            self._compare(snap)
        result = self.last
        state = result.state + (": " + result.error if result.error else "")
        view = macro_view(result.height, result.gauge, result.pitch, result.pixels_done,
                          "" if result.state in ("scanning", "idle", "connected") else state)
        z_step = self._session.z_step if self._session is not None else math.nan
        comparison = comparison_view(self._comparison, z_step)
        self.draw(MacroFigure, view, comparison)
        self.control.refresh(snap)
        self.buttons["save"].disabled = snap.lines_done < 2
        size = result.print_size
        printed = (f" · print {shown(size[0], 'mm', '.3g')} x {shown(size[1], 'mm', '.3g')} x "
                   f"{shown(size[2], 'mm', '.3g')}" if size else "")
        link = "" if self._session is None else f" · {self._session.identity}"
        self.status.value = f"<b>{state}</b>{link}{printed}"

    def widget(self) -> widgets.Widget:
        """The machine's controls (left), the print's (right), buttons and progress, the figure.

        Returns
        -------
        ipywidgets.VBox
        """
        figure = super().widget().children[1]
        c, b = self.controls, self.buttons
        machine = widgets.VBox([c[n] for n in ("port", "sample", "mode", "pixels", "pitch",
                                               *SCAN_PARAMETERS)]
                               + [widgets.HBox([b["connect"], b["start"], b["pause"],
                                                b["abort"]]),
                                  self.progress, widgets.HBox([self.paths["gwy"], b["save"]])])
        printer = widgets.VBox([c[n] for n in ("source", *PRINT_SLIDERS)]
                               + [widgets.HBox([self.paths["stl"], b["export"]]), self.status])
        return widgets.VBox([widgets.HBox([machine, printer]), figure])



def _finished(height: np.ndarray, lines_done: int, pitch: float) -> Sample:
    """The finished lines of a scan's height image as a Sample (at least two lines)."""
    if lines_done < 2:
        raise ValueError(f"a Sample needs at least 2 finished lines, got {lines_done}")
    return Sample(height[:lines_done], pitch, "macroscopic AFM scan")
