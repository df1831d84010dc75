"""The simulator's memory budget, checked before the data files or locals are allocated.

Sizes come from files (`size="9999 9999"`, a user type whose fields are big arrays, a stack
size of 10^12 bytes): allocating first and measuring after would take minutes and gigabytes
before any other budget could act. So every container is priced before it is built, from the
Python bytes one value of its type takes (measured with tracemalloc, CPython 3.11, rounded up),
against what the process may still grow (`--max-memory`, default 512 MB above what it used when
the machine was created: building 512 MB of VAL 3 values takes CPython about 10 s, and a real
application needs a few MB). The scheduler also looks at the process size periodically (`over`), to
end a run that grows by small steps. A refusal is `MemoryBudgetExceeded`, a MemoryError: in a
line it is runtime error 40 ("not enough system memory", manual 12.1); while the application is
loaded it ends the run with R006.
"""

from __future__ import annotations

import os

# Python bytes per value (a list slot included), measured on 1000-value arrays.
VALUE_BYTES = {
    "num": 16, "bool": 16, "string": 200, "dio": 400, "aio": 400, "sio": 400, "screen": 6000,
    "trsf": 120, "frame": 300, "tool": 300, "point": 500, "joint": 350, "config": 250, "mdesc": 350,
}
UNKNOWN_BYTES = 500
SMALL = 64 * 1024  # the process size is read again after this many bytes of allocations
try:
    _PAGE = os.sysconf("SC_PAGE_SIZE")
except (AttributeError, ValueError, OSError):  # not POSIX: rss_bytes falls back on the peak size
    _PAGE = None


class MemoryBudgetExceeded(MemoryError):
    pass


_statm: list = [None, -1]  # [descriptor of /proc/<pid>/statm, the pid that opened it]


def rss_bytes() -> int:
    """The resident size of this process (Linux: /proc/self/statm; elsewhere the peak size)."""
    try:
        # read at offset 0 of a descriptor kept open: the collision checks ask once per motion,
        # and open() costs several times the read; a forked child opens its own
        if _statm[1] != os.getpid():
            _statm[0], _statm[1] = os.open("/proc/self/statm", os.O_RDONLY), os.getpid()
        return int(os.pread(_statm[0], 256, 0).split()[1]) * _PAGE
    except (OSError, ValueError, IndexError, AttributeError, TypeError):
        try:
            import resource
            import sys

            peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
            return peak if sys.platform == "darwin" else peak * 1024
        except (ImportError, OSError):
            return 0


def _mb(n: float) -> str:
    return f"{n / (1024 * 1024):,.0f} MB"


class MemoryBudget:
    """`clock`: called with the process size check, to apply the wall-clock budget inside long
    allocations too (it raises to end the run)."""

    def __init__(self, limit_mb: float, clock=None) -> None:  # noqa: ANN001
        self.limit = int(limit_mb * 1024 * 1024)
        self.base = rss_bytes()
        self.clock = clock
        self.pending = 0.0  # bytes allocated since the process size was last read
        self.also: list = []  # other budgets asked with `over` (callables: why the run must end, or None)

    def used(self) -> int:
        return max(0, rss_bytes() - self.base)

    def reserve(self, nbytes: float, what: str) -> None:
        """Refuse an allocation of about `nbytes` that does not fit in what is left."""
        self.pending += nbytes
        if self.pending < SMALL:
            return
        self.pending = 0.0
        if self.clock is not None:
            self.clock()
        used = self.used()
        if used + nbytes > self.limit:
            raise MemoryBudgetExceeded(
                f"{what} would need about {_mb(nbytes)}; the simulator's memory budget is {_mb(self.limit)}"
                f" ({_mb(used)} used; --max-memory)")

    def over(self) -> str | None:
        """Why the run must end, when the process has grown beyond the budget."""
        used = self.used()
        if used > self.limit:
            return f"the simulation uses {_mb(used)}, more than its memory budget of {_mb(self.limit)} (--max-memory)"
        for other in self.also:
            why = other()
            if why:
                return why
        return None
