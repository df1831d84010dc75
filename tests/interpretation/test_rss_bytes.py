"""memory_budget.rss_bytes reads /proc/self/statm through a descriptor kept open: it must follow
the process as it grows, and a forked child must read its own size, not its parent's."""

import mmap
import os

import pytest

from val3check.interpretation import memory_budget
from val3check.interpretation.memory_budget import rss_bytes

pytestmark = pytest.mark.skipif(not os.path.exists("/proc/self/statm"), reason="Linux /proc")


def _statm_rss() -> int:
    with open("/proc/self/statm", "rb") as fh:
        return int(fh.read().split()[1]) * os.sysconf("SC_PAGE_SIZE")


def test_follows_growth():
    # fresh pages from mmap, each written: a bytearray could reuse memory an earlier test freed
    # and that is still resident (the full suite's process), and then nothing would grow
    size = 64 * 1024 * 1024
    before = rss_bytes()
    block = mmap.mmap(-1, size)
    try:
        page = mmap.PAGESIZE
        for offset in range(0, size, page):
            block[offset] = 1
        grown = rss_bytes()
        assert grown - before >= 60 * 1024 * 1024
        assert abs(grown - _statm_rss()) < 4 * 1024 * 1024
    finally:
        block.close()


@pytest.mark.skipif(not hasattr(os, "fork"), reason="fork")
def test_forked_child_reads_its_own_size():
    rss_bytes()  # the parent's descriptor is open, and inherited
    r, w = os.pipe()
    pid = os.fork()
    if pid == 0:  # the child grows by 64 MB; the parent does not
        try:
            os.close(r)
            block = bytearray(64 * 1024 * 1024)
            grown = rss_bytes()
            ok = memory_budget._statm[1] == os.getpid() and abs(grown - _statm_rss()) < 4 * 1024 * 1024
            os.write(w, b"1" if ok and len(block) else b"0")
        finally:
            os._exit(0)
    os.close(w)
    answer = os.read(r, 1)
    os.close(r)
    os.waitpid(pid, 0)
    assert answer == b"1"
    assert memory_budget._statm[1] == os.getpid()
    assert abs(rss_bytes() - _statm_rss()) < 4 * 1024 * 1024
