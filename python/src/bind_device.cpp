// meshsal Python module: meshsal.Device (an open Vulkan device kept across calls, the C++
// meshsal::Device) and release_cached_devices().
#include <memory>
#include <string>

#include "bindings.h"
#include "meshsal/meshsal.h"
#include "saliency_args.h"

namespace meshsal_py {

void bind_device(py::module_& m) {
  py::class_<meshsal::Device>(m, "Device", R"(Device(index=-1)

An open Vulkan device, kept across calls: give it as device= to saliency(), simplify(),
best_view() and render() and they run on it without opening the device or compiling their
kernels again (the first call on it still compiles the kernels it needs). index: a
devices() index, -1 picks as backend='gpu' does (a discrete GPU, then an integrated one,
..., then a CPU device such as lavapipe). With a Device, backend='auto' (the default) and
'gpu' run on it; backend='cpu' is an error.

Released by close(), at the end of a with block, or when the object is deleted (a call
running on it keeps it until that call returns); using it after close() raises
meshsal.Error. Calls without a Device use a process-wide cache of devices instead, which
release_cached_devices() empties.

    with meshsal.Device(0) as gpu:
        r = meshsal.saliency(V, F, device=gpu)
)")
      .def(py::init([](const py::object& index_arg) {
             const int index = device_index(index_arg);  // -1, or one that exists (not -5 for "choose")
             py::gil_scoped_release unlocked;  // opening a device takes a while
             return std::make_unique<meshsal::Device>(index);
           }),
           py::arg("index") = -1)
      .def_property_readonly("index", [](const meshsal::Device& d) { return d.info().index; },
                             "the devices() index of the device")
      .def_property_readonly("name", [](const meshsal::Device& d) { return d.info().name; }, "the device's name")
      .def_property_readonly("type", [](const meshsal::Device& d) { return d.info().type; },
                             "'discrete', 'integrated', 'virtual', 'cpu' or 'other'")
      .def_property_readonly("device_local_bytes", [](const meshsal::Device& d) { return d.info().device_local_bytes; },
                             "the largest device-local memory heap, bytes")
      .def_property_readonly("api_version", [](const meshsal::Device& d) { return d.info().api_version; },
                             "the Vulkan version the device supports, e.g. '1.3.239'")
      .def_property_readonly("is_open", &meshsal::Device::is_open, "False once closed")
      .def("close", [](meshsal::Device& d) {
             py::gil_scoped_release unlocked;  // the last holder waits for the device
             d.close();
           },
           "close()\n\nReleases the device (once the calls running on it return). Idempotent.")
      .def("__enter__", [](py::object self) { return self; })
      .def("__exit__",
           [](meshsal::Device& d, const py::object&, const py::object&, const py::object&) {
             py::gil_scoped_release unlocked;
             d.close();
             return false;
           })
      .def("__repr__", [](const meshsal::Device& d) {
        return "<meshsal.Device " + std::to_string(d.info().index) + ": '" + d.info().name + "' (" + d.info().type +
               (d.is_open() ? ")>" : "), closed>");
      });
  m.def("release_cached_devices", [] {
    py::gil_scoped_release unlocked;
    meshsal::release_cached_devices();
  },
        R"(release_cached_devices() -> None

Closes the Vulkan devices that calls without a Device opened and keep for the next call (a
process-wide cache, one device per index); a call using one now closes it when it returns.
The next such call opens its device again. Use a meshsal.Device to hold a device yourself.)");
}

}  // namespace meshsal_py
