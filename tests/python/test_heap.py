"""keep_freed_memory(): the C heap keeps what it frees (the library's work buffers are then
reused by the next call instead of page-faulted in again). Process-wide, so the program's
choice: `import meshsal` must not make it."""
import os
import platform
import subprocess
import sys

import pytest

MiB = 1 << 20

# Run in a fresh interpreter: allocates and touches 64 MiB, frees it, prints how much of it
# stayed resident (glibc's default: a block this large is its own mapping, unmapped when
# freed, so nothing stays; with the heap kept, all of it does). ARG: what to do first.
PROBE = r"""
import ctypes, os, sys
libc = ctypes.CDLL("libc.so.6")
libc.malloc.restype = ctypes.c_void_p
libc.malloc.argtypes = [ctypes.c_size_t]
libc.free.argtypes = [ctypes.c_void_p]
def resident():
    with open("/proc/self/statm") as f:
        return int(f.read().split()[1]) * os.sysconf("SC_PAGE_SIZE")
step = sys.argv[1]
if step != "nothing":
    import meshsal
if step == "keep":
    assert meshsal.keep_freed_memory() is True
if step == "keep_then_off":
    assert meshsal.keep_freed_memory(True) is True
    assert meshsal.keep_freed_memory(False) is True
n = 64 << 20
p = libc.malloc(n)
ctypes.memset(p, 1, n)
before = resident()
libc.free(p)
print(n - (before - resident()))
"""


def kept_after_free(step):
    env = dict(os.environ)
    out = subprocess.run([sys.executable, "-c", PROBE, step], capture_output=True, text=True, env=env)
    assert out.returncode == 0, out.stderr
    return int(out.stdout)


# glibc's allocator only: under tools/sanitize.sh AddressSanitizer's replaces it (preloaded).
glibc_only = pytest.mark.skipif(platform.libc_ver()[0] != "glibc" or "libasan" in os.environ.get("LD_PRELOAD", ""),
                                reason="the heap policy is glibc's allocator's")


@glibc_only
def test_import_leaves_the_heap_as_it_was():
    n = 64 * MiB
    assert kept_after_free("nothing") < n // 4   # the interpreter's own default
    assert kept_after_free("import") < n // 4    # import meshsal changed nothing


@glibc_only
def test_keep_freed_memory_keeps_it_and_can_be_turned_off():
    n = 64 * MiB
    assert kept_after_free("keep") > n // 2
    assert kept_after_free("keep_then_off") < n // 4


def test_docstring_says_process_wide():
    import meshsal
    doc = meshsal.keep_freed_memory.__doc__
    assert doc.startswith("keep_freed_memory(")
    assert "process-wide" in doc and "import meshsal` changes nothing" in doc
