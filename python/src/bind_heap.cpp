// meshsal Python module: keep_freed_memory(). The library allocates its work buffers afresh
// in every call; where the C heap hands freed memory back to the system (glibc's default
// for large blocks), each call page-faults all of it in again. The meshsal command keeps
// its heap (src/cli/main.cpp calls keep_freed_memory_for_reuse, meshsal.h, at start-up);
// the module does not change the interpreter's heap on import, since that is the whole
// process's allocator: a Python program opts in with this call.
#include "bindings.h"
#include "meshsal/meshsal.h"

namespace meshsal_py {

void bind_heap(py::module_& m) {
  m.def("keep_freed_memory", [](bool on) { return meshsal::keep_freed_memory_for_reuse(on); },
        py::arg("on").noconvert() = true,
        R"(keep_freed_memory(on=True) -> bool

Makes this process's C heap (glibc's malloc) keep memory it frees for reuse (on=True), as the
meshsal command does, or hand large blocks back to the system again (on=False: glibc's
default values of M_MMAP_MAX and M_TRIM_THRESHOLD). `import meshsal` changes nothing: this
is process-wide (every allocation of the interpreter and of every other extension), so it
is the program's choice.

What it buys: each meshsal call allocates its work arrays afresh; with glibc's defaults
every block of 128 KiB or more is mapped when allocated and unmapped when freed, so every
call page-faults its whole working set in again. With it on, the next call reuses the
memory of the previous one (README, Python section, has measured figures). The price: the
process's resident memory stays at its peak, and large blocks are no longer separate
mappings. Returns False where the C library is not glibc (nothing changed).)");
}

}  // namespace meshsal_py
