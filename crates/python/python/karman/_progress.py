"""Progress display of a Monte Carlo study: tqdm (a widget in notebooks, a bar in
terminals) when it is installed, else a text bar on a terminal's standard error, else
nothing."""

from __future__ import annotations

import sys
import time


class Progress:
    """Shows ``done`` of ``total`` samples; the study calls :meth:`update` and :meth:`close`."""

    def __init__(self, total: int) -> None:
        self.total = total
        self.done = 0
        self.started = time.monotonic()
        self.bar = None
        self.text = False
        try:
            from tqdm.auto import tqdm
        except ImportError:
            self.text = sys.stderr.isatty()
        else:
            self.bar = tqdm(total=total, unit="flight", desc="karman Monte Carlo")

    def update(self, done: int) -> None:
        if self.bar is not None:
            self.bar.update(done - self.done)
        elif self.text:
            width = 30
            filled = width * done // max(self.total, 1)
            rate = done / max(time.monotonic() - self.started, 1e-9)
            sys.stderr.write(
                f"\r[{'#' * filled}{'.' * (width - filled)}] {done}/{self.total}"
                f" ({rate:.0f} flights/s)"
            )
            sys.stderr.flush()
        self.done = done

    def close(self, done: int) -> None:
        self.update(done)
        if self.bar is not None:
            self.bar.close()
        elif self.text:
            sys.stderr.write("\n")
            sys.stderr.flush()
