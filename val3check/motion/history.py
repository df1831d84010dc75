"""A run-long sequence of doubles held in chunks, the old ones in a temporary file (issue 29).

The profile's breakpoints (trajectory.Profile: T, S, SD) grow with the run: about 71 per motion
command, three doubles each, 104 MB at 8 h of the bundled cell. The run reads them near their end
(the arm's state now, the queue's times ahead); the record, the collision checks and the reports
read them after it, in order. So a `History` keeps the chunk being written and the KEEP full
chunks before it in memory, writes older chunks to an unlinked temporary file (gone at exit, even
on a crash) and reads them back: a slice or window exactly as asked (the record reads a few
breakpoints per command, here and there), single values and bisects through a cache of CACHE
chunks. What the process holds is bounded by the chunk size, not by the run's length, and the
values read back are the same bits.

It is the sequence the readers used when these were `array('d')`: len, int and slice indexing
(a slice is an `array('d')` copy), bisect (the module's functions, or the faster methods here for
sorted values), iteration, assignment of one item, append/extend/frombytes, and the replan's cut
at the end (`del h[k:]`). `window(lo, hi)` gives a numpy view inside one chunk, a copy across.
Chunks never resize (each is allocated full), so a view never blocks the sequence's growth; as with
the arrays, a reader drops its views before the sequence may be cut.

What the files of a process may hold in all is bounded (DISK_LIMIT): a run that would write more
ends with `HistoryFull`, a MemoryError (the run's memory budget refuses it the same way).
"""

from __future__ import annotations

import bisect
import operator
import os
from array import array

import numpy as np

CHUNK = 1 << 12  # doubles per chunk (32 KB: a chunk read back costs ~20 µs); a power of two, read at creation
KEEP = 8  # full chunks kept in memory behind the one being written (~450 commands: a replan cuts near the end)
CACHE = 32  # chunks read back from the file kept in memory, the most recent (the record reads a few places at once)
FIRST = 16  # doubles a new tail holds before it grows (doubling, to CHUNK): many profiles are short
DISK_LIMIT = 2 << 30  # bytes the histories of one process may hold in their files (~2,000 h of the bundled cell)

DISK_MARGIN = 64 << 20  # far more than a run writes between two budget checks (256 cycles, ~1.7 KB a command)

_on_disk = [0]  # bytes the live histories of this process hold in their files


class HistoryFull(MemoryError):
    """The histories would hold more than DISK_LIMIT bytes in their files."""


def disk_bytes() -> int:
    """Bytes the histories of this process hold in their temporary files."""
    return _on_disk[0]


def over() -> str | None:
    """Why the run must end, when the files come near DISK_LIMIT: asked with the memory budget
    (the scheduler, every 256 cycles), so the run ends with R006 between two lines rather than
    with `HistoryFull` inside one (a line's MemoryError is the application's runtime error 40)."""
    near = DISK_LIMIT - min(DISK_MARGIN, DISK_LIMIT // 4)
    if _on_disk[0] > near:
        return (f"the run's motion history holds {_on_disk[0] / (1 << 20):,.0f} MB in its temporary file, near its bound"
                f" of {DISK_LIMIT / (1 << 20):,.0f} MB (motion/history.py DISK_LIMIT): shorten --duration")
    return None


class History:
    """A sequence of doubles in chunks (module docstring). `tail`, `tail_start`, `tail_len`: the
    chunk being written, the index of its first value and how many it holds; `shift`: value k is
    at k & (2**shift - 1) in chunk k >> shift (the fast paths of the hot readers, trajectory.Profile)."""

    __slots__ = ("_n", "shift", "_chunks", "_firsts", "_len", "tail", "tail_start", "tail_len", "_file",
                 "_cache", "_held", "__weakref__")

    def __init__(self, values=()) -> None:
        """A history holding `values` (doubles)."""
        n = CHUNK
        if n < 1 or n & (n - 1):
            raise ValueError("CHUNK must be a power of two")
        self._held = 0  # bytes this history holds in its file
        self._file = None
        self._n, self.shift = n, n.bit_length() - 1
        self.tail = _new_chunk(min(FIRST, n))
        self._chunks: list = [self.tail]  # array('d') of n doubles each (the tail fewer); None when only in the file
        self._firsts: list[float] = []  # each chunk's first value (for the two-level bisect)
        self._len = 0
        self.tail_start = 0
        self.tail_len = 0
        self._cache: dict[int, array] = {}  # chunk index -> values read back, the most recent last
        self.extend(values)

    # ---- reading

    def __len__(self) -> int:
        return self._len

    def __getitem__(self, i):
        try:
            j = i - self.tail_start
        except TypeError:
            if isinstance(i, slice):
                return self._slice(i)
            raise TypeError(f"history indices must be integers or slices, not {type(i).__name__}") from None
        if j >= 0:
            if j < self.tail_len:
                return self.tail[j]
            raise IndexError("history index out of range")
        i = operator.index(i)
        if i < 0:
            i += self._len
            if i >= self.tail_start:
                return self.tail[i - self.tail_start]
            if i < 0:
                raise IndexError("history index out of range")
        return self.chunk(i >> self.shift)[i & (self._n - 1)]

    def chunk(self, c: int) -> array:
        """The values of chunk c (all of its n slots: only the first `tail_len` of the tail count)."""
        a = self._chunks[c]
        if a is not None:
            return a
        cache = self._cache
        a = cache.pop(c, None)
        if a is None:
            a = self._read(c)
            if len(cache) >= CACHE:
                del cache[next(iter(cache))]
        cache[c] = a
        return a

    def _slice(self, s: slice) -> array:
        start, stop, step = s.indices(self._len)
        if step != 1:
            return array("d", [self[i] for i in range(start, stop, step)])
        return self._range(start, stop)

    def _held_chunk(self, c: int) -> array | None:
        """Chunk c if it is in memory (written or read back), else None."""
        a = self._chunks[c]
        return a if a is not None else self._cache.get(c)

    def _range(self, start: int, stop: int) -> array:
        """values[start:stop] (a copy): from the chunks in memory, the rest read from the file in one
        read per run of chunks (the file holds chunk c at c·CHUNK doubles: the sequence itself), so
        that a reader of a few breakpoints here and there reads only those."""
        if stop <= start:
            return array("d")
        sh = self.shift
        c0 = start >> sh
        if c0 == (stop - 1) >> sh:
            a = self._held_chunk(c0)
            if a is not None:
                return a[start - (c0 << sh):stop - (c0 << sh)]
        out = array("d")
        i = start
        while i < stop:
            c = i >> sh
            a = self._held_chunk(c)
            end = min(stop, (c + 1) << sh)
            if a is not None:
                out += a[i - (c << sh):end - (c << sh)]
            else:
                while end < stop and self._held_chunk(end >> sh) is None:
                    end = min(stop, end + self._n)
                out.frombytes(os.pread(self._file.fileno(), 8 * (end - i), 8 * i))
            i = end
        return out

    def window(self, lo: int, hi: int) -> np.ndarray:
        """values[lo:hi] as a numpy array: a view inside one chunk in memory, else a copy."""
        hi = min(hi, self._len)
        if hi <= lo:
            return np.zeros(0)
        sh = self.shift
        c0 = lo >> sh
        if c0 == (hi - 1) >> sh:
            a = self._held_chunk(c0)
            if a is not None:
                return np.frombuffer(a, dtype=float, count=hi - lo, offset=8 * (lo - (c0 << sh)))
        return np.frombuffer(self._range(lo, hi), dtype=float)

    def __iter__(self):
        last = len(self._chunks) - 1
        for c in range(last):
            yield from self.chunk(c)
        yield from self.tail[:self.tail_len]

    def bisect_right(self, x: float, lo: int = 0, hi: int | None = None) -> int:
        """`bisect.bisect_right(self, x, lo, hi)` for sorted values, reading one chunk."""
        g = self._first_past(x, bisect.bisect_right)
        return max(min(g, self._len if hi is None else hi), lo)

    def bisect_left(self, x: float, lo: int = 0, hi: int | None = None) -> int:
        """`bisect.bisect_left(self, x, lo, hi)` for sorted values, reading one chunk."""
        g = self._first_past(x, bisect.bisect_left)
        return max(min(g, self._len if hi is None else hi), lo)

    def _first_past(self, x: float, search) -> int:
        firsts = self._firsts
        if not firsts:
            return 0
        # the chunk the answer falls in: the last whose first value is before x (for bisect_left)
        # or not after it (bisect_right); the next chunk's first value is past x
        last = len(firsts) - 1
        if search(firsts, x, last) > last:
            return self.tail_start + search(self.tail, x, 0, self.tail_len)
        c = search(firsts, x, 0, last) - 1
        if c < 0:
            return 0
        return (c << self.shift) + search(self.chunk(c), x)

    # ---- writing

    def __setitem__(self, i, x: float) -> None:
        if isinstance(i, slice):
            raise TypeError("a history's values are assigned one at a time")
        i = operator.index(i)
        if i < 0:
            i += self._len
        if not 0 <= i < self._len:
            raise IndexError("history assignment index out of range")
        c, k = i >> self.shift, i & (self._n - 1)
        a = self._chunks[c]
        if a is None:  # in the file (and maybe the cache): both changed
            a = self.chunk(c)
            a[k] = x
            os.pwrite(self._file.fileno(), memoryview(a)[k:k + 1], (i << 3))
        else:
            a[k] = x
        if k == 0:
            self._firsts[c] = a[0]

    def append(self, x: float) -> None:
        """Add x at the end."""
        if self.tail_len == len(self.tail):
            self._room(1)
        self.tail[self.tail_len] = x
        if self.tail_len == 0:
            self._firsts.append(self.tail[0])
        self.tail_len += 1
        self._len += 1

    def frombytes(self, data) -> None:
        """Add the doubles of `data` (bytes in machine order, as array.frombytes)."""
        self.extend(np.frombuffer(data, dtype=float))

    def extend(self, values) -> None:
        """Add `values` (doubles) at the end."""
        if values.__class__ is np.ndarray and values.dtype == _F8 and values.ndim == 1:
            tl, total = self.tail_len, len(values)
            if tl and tl + total <= len(self.tail):  # (most plans: room in the tail, copied in place)
                self.tail[tl:tl + total] = array("d", values.tobytes())
                self.tail_len = tl + total
                self._len += total
                return
        v = np.asarray(values if isinstance(values, (np.ndarray, array)) else list(values), dtype=float).ravel()
        at, total = 0, len(v)
        while at < total:
            if self.tail_len == len(self.tail):
                self._room(total - at)
            room = min(len(self.tail) - self.tail_len, total - at)
            view = np.frombuffer(self.tail, dtype=float)
            view[self.tail_len:self.tail_len + room] = v[at:at + room]
            del view
            if self.tail_len == 0:
                self._firsts.append(self.tail[0])
            self.tail_len += room
            self._len += room
            at += room

    def __delitem__(self, s) -> None:
        """Only the cut at the end: `del h[k:]`."""
        if not isinstance(s, slice):
            raise TypeError("a history is only cut at its end: del h[k:]")
        start, stop, step = s.indices(self._len)
        if stop <= start and step == 1:
            return
        if step != 1 or stop != self._len:
            raise TypeError("a history is only cut at its end: del h[k:]")
        self._truncate(start)

    def _truncate(self, length: int) -> None:
        if length > self.tail_start:
            # (most cuts, a replan near the end: inside the chunk being written, which stays the tail;
            # no chunk leaves, none is read back or in the file at or after it)
            self.tail_len = length - self.tail_start
            self._len = length
            return
        n, sh = self._n, self.shift
        held = self._held
        keep = max((length + n - 1) >> sh, 1)  # chunks that still hold values (at least the tail)
        for c in range(keep, len(self._chunks)):
            if self._chunks[c] is None:
                self._release(n * 8)
        del self._chunks[keep:]
        del self._firsts[keep:]
        last = keep - 1
        if self._chunks[last] is None:  # written again from here: back in memory
            a = self._cache.pop(last, None)
            if a is None:
                a = self._read(last)
            self._chunks[last] = a
            self._release(n * 8)
        for c in [c for c in self._cache if c >= last]:  # their place in the file is written again
            del self._cache[c]
        if self._file is not None and self._held != held:  # (the file is `_held` long: shortened when chunks left it)
            self._file.truncate(self._held)
        self.tail = self._chunks[last]
        self.tail_start = last << sh
        self.tail_len = length - self.tail_start
        self._len = length
        if self.tail_len == 0:
            del self._firsts[last:]

    def _room(self, more: int) -> None:
        """The tail is full: grown (a new array: a view of the old one stays valid) until it holds a
        whole chunk, then a new tail, and the oldest chunk kept in memory beyond KEEP to the file."""
        n = self._n
        if len(self.tail) < n:
            grown = _new_chunk(min(n, max(2 * len(self.tail), self.tail_len + more)))
            grown[:self.tail_len] = self.tail[:self.tail_len]
            self.tail = self._chunks[-1] = grown
            return
        old = len(self._chunks) - 1 - KEEP
        if old >= 0 and self._chunks[old] is not None:
            self._spill(old)
        self.tail = _new_chunk(min(FIRST, n))
        self._chunks.append(self.tail)
        self.tail_start += self._n
        self.tail_len = 0

    def reserve(self, more: int, copies: int = 1) -> None:
        """Raise HistoryFull, before anything changes, when adding `more` values to `copies`
        histories like this one could take the files past DISK_LIMIT (a profile appends to its
        three at once: none of them may be left longer than the others)."""
        chunks = (self.tail_len + more + self._n - 1) >> self.shift  # new chunks at most: a spill each
        if chunks and _on_disk[0] + copies * chunks * self._n * 8 > DISK_LIMIT:
            raise HistoryFull(f"the run's motion history would hold more than {DISK_LIMIT / (1 << 20):,.0f} MB in its"
                              f" temporary file (motion/history.py DISK_LIMIT): shorten --duration")

    def _read(self, c: int) -> array:
        """Chunk c read back from the file."""
        a = array("d")
        a.frombytes(os.pread(self._file.fileno(), self._n * 8, c * self._n * 8))
        return a

    def _spill(self, c: int) -> None:
        nbytes = self._n * 8
        if _on_disk[0] + nbytes > DISK_LIMIT:
            raise HistoryFull(f"the run's motion history would hold more than {DISK_LIMIT / (1 << 20):,.0f} MB in its"
                              f" temporary file (motion/history.py DISK_LIMIT): shorten --duration")
        if self._file is None:
            import tempfile  # only a long run spills: its import (shutil, bz2, lzma) is 0.5 % of a 60 s run

            self._file = tempfile.TemporaryFile(prefix="val3check-history-")
        os.pwrite(self._file.fileno(), self._chunks[c], c * nbytes)
        self._chunks[c] = None
        self._held += nbytes
        _on_disk[0] += nbytes

    def _release(self, nbytes: int) -> None:
        self._held -= nbytes
        _on_disk[0] -= nbytes

    def __del__(self) -> None:
        held, self._held = getattr(self, "_held", 0), 0
        try:
            _on_disk[0] -= held
        except TypeError:  # the module torn down at exit
            pass
        f = getattr(self, "_file", None)
        if f is not None:
            f.close()

    def __repr__(self) -> str:
        return f"History({len(self)} doubles, {self._held} bytes in its file)"


_F8 = np.dtype(float)  # native doubles: what `extend` copies as bytes


def _new_chunk(n: int) -> array:
    return array("d", [0.0]) * n
