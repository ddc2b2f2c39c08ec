"""keep_freed_memory: `import meshsal` makes the C heap keep what it frees (the library's
work buffers are then reused by the next call instead of page-faulted in again)."""
import ctypes
import os
import platform

import pytest

import meshsal

MiB = 1 << 20


def resident_bytes():
    with open("/proc/self/statm") as f:
        return int(f.read().split()[1]) * os.sysconf("SC_PAGE_SIZE")


def rss_drop_after_free(libc, n):
    """Allocates and touches n bytes, frees them, returns how much resident memory fell."""
    p = libc.malloc(n)
    assert p
    ctypes.memset(p, 1, n)
    before = resident_bytes()
    libc.free(p)
    return before - resident_bytes()


@pytest.mark.skipif(platform.libc_ver()[0] != "glibc", reason="the heap policy is glibc's")
def test_import_keeps_freed_memory_and_it_can_be_turned_off():
    libc = ctypes.CDLL("libc.so.6")
    libc.malloc.restype = ctypes.c_void_p
    libc.malloc.argtypes = [ctypes.c_size_t]
    libc.free.argtypes = [ctypes.c_void_p]
    n = 64 * MiB
    # As the import left it: a freed 64 MiB block stays resident for the next allocation.
    assert rss_drop_after_free(libc, n) < n // 4
    try:
        assert meshsal.keep_freed_memory(False) is True
        # glibc's defaults: a block this large is its own mapping, unmapped when freed.
        assert rss_drop_after_free(libc, n) > n // 2
    finally:
        meshsal.keep_freed_memory(True)
    assert rss_drop_after_free(libc, n) < n // 4
