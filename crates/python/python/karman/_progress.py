"""Progress display of a Monte Carlo study: tqdm (a widget in notebooks, a bar in terminals)
when it is installed, else one plain text line on standard error — rewritten in place on a
terminal or in a notebook, printed every ten seconds (and at the end) in a log."""

from __future__ import annotations

import sys
import time

#: Seconds between two text updates rewritten in place.
REDRAW_INTERVAL = 0.2
#: Seconds between two lines of a log (standard error neither a terminal nor a notebook).
LOG_INTERVAL = 10.0


def _rewrites_in_place() -> bool:
    """Whether standard error shows a carriage return as a rewrite of the line: a terminal or
    a Jupyter kernel's output."""
    isatty = getattr(sys.stderr, "isatty", None)
    return bool(isatty and isatty()) or "ipykernel" in sys.modules


class Progress:
    """Shows ``done`` of ``total`` samples; the study calls :meth:`update` and :meth:`close`."""

    def __init__(self, total: int) -> None:
        self.total = total
        self.done = 0
        self.started = time.monotonic()
        self.shown = float("-inf")
        self.bar = None
        try:
            from tqdm.auto import tqdm
        except ImportError:
            self.in_place = _rewrites_in_place()
        else:
            self.bar = tqdm(total=total, unit="flight", desc="karman Monte Carlo")

    def _line(self, done: int) -> str:
        rate = done / max(time.monotonic() - self.started, 1e-9)
        percent = 100.0 * done / max(self.total, 1)
        return (
            f"karman Monte Carlo: {done}/{self.total} samples ({percent:.0f} %), "
            f"{rate:.0f} flights/s"
        )

    def update(self, done: int) -> None:
        if self.bar is not None:
            self.bar.update(done - self.done)
        elif done != self.done:
            now = time.monotonic()
            interval = REDRAW_INTERVAL if self.in_place else LOG_INTERVAL
            if now - self.shown >= interval:
                self.shown = now
                line = self._line(done)
                sys.stderr.write("\r" + line if self.in_place else line + "\n")
                sys.stderr.flush()
        self.done = done

    def close(self, done: int) -> None:
        if self.bar is not None:
            self.update(done)
            self.bar.close()
            return
        self.done = done
        sys.stderr.write(("\r" if self.in_place else "") + self._line(done) + "\n")
        sys.stderr.flush()
