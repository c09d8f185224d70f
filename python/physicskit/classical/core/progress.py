"""Progress bars for ``integrate_sampled(..., progress=True)``.

The native integrators call ``reporter(step, n_steps)`` every few thousand steps (every 128
for systems written in Python) through the same observer that checks for Ctrl-C
(``python/src/interrupt.rs``), with the GIL taken for that moment only. The reporter draws a
``tqdm`` bar if tqdm is installed (``tqdm.auto``, a widget in Jupyter, where ipywidgets is
installed too) and a plain text bar on standard error otherwise. After the run, ``close`` brings the bar to the
final step count (runs shorter than one check interval are never called back) and ends it.
"""

from __future__ import annotations

import importlib
import sys
import time
from typing import Any, Callable, Optional

__all__ = ["progress_reporter", "PlainBar", "TqdmBar"]

#: Description shown before the bar.
_DESC = "integrate"


class PlainBar:
    """A one-line text bar on ``stream`` (standard error by default), redrawn with ``\\r`` at
    most every ``min_interval`` seconds: ``integrate [#######-------]  50% 5000/10000 steps``.
    """

    min_interval: float = 0.25
    """Seconds between redraws (the final count is always drawn)."""

    def __init__(self, stream=None, width: int = 30):
        self.stream = sys.stderr if stream is None else stream
        self.width = width
        self.drawn = False
        self._last = -float("inf")

    def _draw(self, step: int, n_steps: int) -> None:
        frac = step / n_steps if n_steps > 0 else 1.0
        filled = int(round(self.width * frac))
        bar = "#" * filled + "-" * (self.width - filled)
        self.stream.write(f"\r{_DESC} [{bar}] {100 * frac:3.0f}% {step}/{n_steps} steps")
        self.stream.flush()
        self.drawn = True

    def __call__(self, step: int, n_steps: int) -> None:
        now = time.monotonic()
        if now - self._last >= self.min_interval:
            self._last = now
            self._draw(step, n_steps)

    def close(self, n_steps: Optional[int]) -> None:
        """Draw the final count (``None``: the run failed, leave the bar where it stopped) and
        end the line."""
        if n_steps is not None:
            self._draw(n_steps, n_steps)
        if self.drawn:
            self.stream.write("\n")
            self.stream.flush()


class TqdmBar:
    """A ``tqdm`` bar, created at the first report (when the step count is known)."""

    def __init__(self, tqdm: Callable[..., Any]):
        self._tqdm = tqdm
        self._bar: Any = None
        self._done = 0

    def _advance(self, step: int, n_steps: int) -> None:
        if self._bar is None:
            self._bar = self._tqdm(total=n_steps, desc=_DESC, unit="step")
        if step > self._done:
            self._bar.update(step - self._done)
            self._done = step

    def __call__(self, step: int, n_steps: int) -> None:
        self._advance(step, n_steps)

    def close(self, n_steps: Optional[int]) -> None:
        """Advance to ``n_steps`` (``None``: the run failed) and close the bar."""
        if n_steps is not None:
            self._advance(n_steps, n_steps)
        if self._bar is not None:
            self._bar.close()


def progress_reporter(stream=None):
    """A :class:`TqdmBar` if ``tqdm`` can be imported, else a :class:`PlainBar` on
    ``stream`` (default: standard error).

    With ipywidgets too, the bar is ``tqdm.auto``'s (a widget in Jupyter); without, tqdm's
    text bar (``tqdm.auto`` would fail in a notebook lacking ipywidgets)."""
    try:
        tqdm = importlib.import_module("tqdm")
    except ImportError:
        return PlainBar(stream)
    try:
        importlib.import_module("ipywidgets")
        return TqdmBar(importlib.import_module("tqdm.auto").tqdm)
    except ImportError:
        return TqdmBar(tqdm.tqdm)
