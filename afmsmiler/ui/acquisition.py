"""The one UI piece that drives an acquisition: buttons, a progress bar, the kernel's event loop.

:class:`AcquisitionControls` drives any :class:`~afmsmiler.acquisition.Acquisition` (module
(f)'s simulated scan, a device's session) for a panel:

- Start, Pause (Resume while paused) and Stop (or Abort) buttons and a progress bar, set from the
  acquisition's snapshot;
- :meth:`~AcquisitionControls.step`: the buttons' actions pressed since the last step, one step
  of the acquisition, at most one picture (the panel's ``show``);
- :meth:`~AcquisitionControls.run`: in a live notebook the steps run in an asyncio task on the
  kernel's event loop, paced by the instrument's line time (at most ``max_line_wait`` per line)
  or polling a device, drawing at most one picture per ``frame_interval``; the kernel handles the
  widgets' messages between two steps. Elsewhere (tests, nbval) the steps run to the end (or the
  pause) at once. A paused scan keeps its task, which sleeps until an action wakes it;
- the button queue: ipykernel 7 runs a click handler in another thread than the loop reading the
  scan. An action pressed there while a scan runs is queued and run by the next step, on the
  loop's thread (a device driver then never receives a command from a thread it does not read
  on; a Resume or Abort queued to a paused driver waited for its timeout before).

The image is the acquisition's: nothing here holds pixels. The panel draws snapshots.
"""
from __future__ import annotations

import asyncio
import threading
import time
from collections import deque
from typing import Callable

import ipywidgets as widgets

__all__ = ["AcquisitionControls", "Acquiring"]


class AcquisitionControls:
    """The buttons, the progress bar and the live loop for a panel's acquisitions.

    Parameters
    ----------
    start, pause, resume, stop : callable
        The panel's actions, called with no argument (Start configures and starts a scan).
    show : callable
        ``show()`` draws the panel from the acquisition's snapshot (one redraw) and calls
        :meth:`refresh`.
    report : callable
        ``report(exc)`` shows an error under the panel.
    live : callable
        ``live()`` is True in a live notebook (the panel's ``running_as_notebook``).
    stop_label : str
        The stop button's label (``"Stop"`` or ``"Abort"``).
    unit : str
        What the progress bar counts: ``"lines"`` or ``"pixels"``.

    Attributes
    ----------
    acquisition : Acquisition or None
        What the buttons drive (set by :meth:`attach`).
    buttons : dict
        ``"start"``, ``"pause"``, ``"stop"`` -> ipywidgets.Button.
    progress : ipywidgets.IntProgress
    """

    #: s a paused scan's task sleeps before it looks at the queued actions again.
    PAUSED_POLL = 0.1
    #: s between two reads of a device that paces itself (its reads wait for pixels).
    POLL = 0.01
    #: Seconds without a new pixel after which :meth:`run` (run to the end) gives up and aborts
    #: the scan (its finished lines kept): a device that answers without ever finishing a pixel
    #: cannot hold a cell forever (a first line, an approach, takes seconds, not a minute).
    IDLE_SECONDS = 60.0
    #: ... and the steps in a row that measure nothing, whatever they waited (a backstop).
    MAX_IDLE_STEPS = 100_000

    def __init__(self, *, start: Callable, pause: Callable, resume: Callable, stop: Callable,
                 show: Callable, report: Callable, live: Callable, stop_label: str = "Stop",
                 unit: str = "lines"):
        if unit not in ("lines", "pixels"):
            raise ValueError(f"unit must be 'lines' or 'pixels', got {unit!r}")
        self._pause, self._resume, self._stop = pause, resume, stop
        self._show, self._report, self._live = show, report, live
        self.unit = unit
        self.acquisition = None
        self.buttons = {
            "start": widgets.Button(description="Start", icon="play", button_style="success"),
            "pause": widgets.Button(description="Pause", icon="pause", button_style="warning",
                                    disabled=True),
            "stop": widgets.Button(description=stop_label, icon="stop", button_style="danger",
                                   disabled=True)}
        self.buttons["start"].on_click(lambda _b: self.act(start))
        self.buttons["pause"].on_click(lambda _b: self.request(
            self._resume if self.paused else self._pause))
        self.buttons["stop"].on_click(lambda _b: self.request(self._stop))
        self.progress = widgets.IntProgress(min=0, max=1, value=0, description=f"0 {unit}",
                                            style={"description_width": "initial"})
        self._actions = deque()
        self._task = None
        self._loop = None
        self._wake = None
        self._owner = threading.get_ident()
        self._reported = None

    # -- state -----------------------------------------------------------------------------------
    @property
    def running(self) -> bool:
        """A scan is under way (started, not ended; paused included)."""
        return self.acquisition is not None and self.acquisition.running

    @property
    def paused(self) -> bool:
        """The scan waits for Resume."""
        return self.acquisition is not None and self.acquisition.paused

    def attach(self, acquisition) -> None:
        """Drive ``acquisition`` from now on (a running loop goes on with it)."""
        self.acquisition = acquisition
        self._reported = None
        self.poke()

    # -- actions ---------------------------------------------------------------------------------
    def act(self, action: Callable) -> None:
        """Run a button's action; a failure is shown under the panel (raised again off a
        notebook, so that a test sees it)."""
        try:
            action()
        except Exception as exc:
            self._report(exc)
            self._show()
            if not self._live():
                raise

    def request(self, action: Callable) -> None:
        """A button's action: run now, or, while a scan runs, queued for the next :meth:`step`
        when a live loop runs it or the button was pressed in another thread than the one the
        panel was made in (see the module's notes)."""
        live = self._task is not None and not self._task.done()
        if self.running and (live or threading.get_ident() != self._owner):
            self._actions.append(action)
            self.poke()
        else:
            self.act(action)

    def run_actions(self) -> None:
        """The actions queued since the last step, in the order pressed."""
        while self._actions:
            self.act(self._actions.popleft())

    def poke(self) -> None:
        """Wake a paused scan's task (from any thread)."""
        loop, wake = self._loop, self._wake
        if loop is not None and wake is not None and not loop.is_closed():
            loop.call_soon_threadsafe(wake.set)

    def cancel(self) -> None:
        """End the live loop's task (the acquisition is left as it is)."""
        task, self._task = self._task, None
        if task is not None and not task.done():
            task.cancel()

    # -- stepping --------------------------------------------------------------------------------
    def step(self, show: bool = True, wait: float = 0.0) -> bool:
        """Run the queued actions, one step of the acquisition, and draw (``show``).

        Parameters
        ----------
        show : bool
            Draw after the step; a scan that ends or pauses is always drawn.
        wait : float
            The longest time in s a device's session waits for pixels.

        Returns
        -------
        bool
            True while the scan runs (paused included), False once it has ended.
        """
        self.run_actions()
        acq = self.acquisition
        if acq is None or not acq.running:
            return False
        if acq.paused:
            return True
        running = acq.step(wait)
        if not running or acq.paused:
            show = True
        fault = acq.snapshot().fault if acq.state == "fault" else None
        if isinstance(fault, Exception) and fault is not self._reported:
            self._reported = fault  # shown under the panel: a fault ends the scan, not the cell
            self._report(fault)
        if show:
            self._show()
        return running

    def run(self, *, wait: bool = False, frame_interval: float = 0.1,
            max_line_wait: float = 0.25, read_wait: float = 0.02) -> None:
        """Run the steps: a task on the kernel's loop in a live notebook, else at once.

        Parameters
        ----------
        wait : bool
            Run to the end before returning, also in a live notebook (a cell that uses the
            image next; the buttons act once the cell is done).
        frame_interval : float
            s between two pictures.
        max_line_wait : float
            The longest a live step waits per line of a simulated scan (its line time).
        read_wait : float
            The longest a live step waits for a device's pixels (off a notebook, or with
            ``wait``, a step waits up to ``max_line_wait``).
        """
        if self._live() and not wait:
            if self._task is None or self._task.done():
                self._task = asyncio.ensure_future(
                    self._run_async(frame_interval, max_line_wait, read_wait))
            else:
                self.poke()
            return
        shown_at = progress_at = time.monotonic()
        idle, done = 0, self._done()
        while idle < self.MAX_IDLE_STEPS and \
                time.monotonic() - progress_at < self.IDLE_SECONDS:
            picture = time.monotonic() - shown_at >= frame_interval
            if not self.step(show=picture, wait=max_line_wait) or self.paused:
                return
            if picture:
                shown_at = time.monotonic()
            if self._done() == done:
                idle += 1
            else:
                idle, done, progress_at = 0, self._done(), time.monotonic()
        self.acquisition.abort()
        self._report(RuntimeError(
            f"the scan measured nothing for {time.monotonic() - progress_at:.3g} s "
            f"({idle} steps): aborted, its finished lines kept"))
        self._show()

    def _done(self) -> tuple:
        """What the acquisition has measured so far: (lines, pixels)."""
        s = self.acquisition.snapshot()
        return s.lines_done, s.pixels_done

    async def _run_async(self, frame_interval, max_line_wait, read_wait) -> None:
        self._loop, self._wake = asyncio.get_running_loop(), asyncio.Event()
        try:
            shown = due = time.monotonic()
            while True:
                now = time.monotonic()
                picture = now - shown >= frame_interval
                if not self.step(show=picture, wait=read_wait):
                    break
                if picture:
                    shown = now
                acq = self.acquisition
                if acq.paused:  # wait for Resume (or a queued action) without scanning
                    self._wake.clear()
                    try:
                        await asyncio.wait_for(self._wake.wait(), self.PAUSED_POLL)
                    except asyncio.TimeoutError:
                        pass
                    due = time.monotonic()
                    continue
                line_time = acq.line_time
                if line_time is None:  # a device: its reads waited for the pixels
                    await asyncio.sleep(self.POLL)
                    continue
                line_time = min(line_time, max_line_wait)
                due = max(due + line_time, time.monotonic() - line_time)
                # the kernel handles the widgets' messages (a slider, Stop) while it waits
                await asyncio.sleep(max(0.0, due - time.monotonic()))
        except asyncio.CancelledError:
            raise
        except Exception as exc:  # shown under the panel: a task's exception is otherwise lost
            self._report(exc)
            self._show()
        finally:
            if self._task is asyncio.current_task():
                self._task = None
            self._wake = None

    # -- widgets ---------------------------------------------------------------------------------
    def refresh(self, snapshot=None) -> None:
        """Set the progress bar and the buttons from ``snapshot`` (default the acquisition's)."""
        if snapshot is None and self.acquisition is not None:
            snapshot = self.acquisition.snapshot()
        if snapshot is not None:
            total = snapshot.lines if self.unit == "lines" else snapshot.lines * snapshot.pixels
            done = snapshot.lines_done if self.unit == "lines" else snapshot.pixels_done
            self.progress.max = max(total, 1)
            self.progress.value = done
            self.progress.description = f"{done}/{total} {self.unit}"
        b, running, paused = self.buttons, self.running, self.paused
        b["start"].disabled = running and not paused
        b["stop"].disabled = not running
        b["pause"].disabled = not running
        b["pause"].description = "Resume" if paused else "Pause"
        b["pause"].icon = "play" if paused else "pause"


class Acquiring:
    """What a panel whose scans an :class:`AcquisitionControls` drives (``self.control``) says
    of its state."""

    control: AcquisitionControls

    @property
    def running(self) -> bool:
        """A scan is under way (started, neither finished, stopped nor faulted; paused counts)."""
        return self.control.running

    @property
    def paused(self) -> bool:
        """The running scan waits for Resume."""
        return self.control.paused
