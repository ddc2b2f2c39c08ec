#include "saliency_args.h"

#include <limits>

#include "arg_values.h"
#include "numpy_in.h"

namespace meshsal_py {

int device_index(const py::handle& device) {
  const int index = int(integer_arg(device, "device", -1, std::numeric_limits<int>::max()));
  if (index < 0) return index;
  // An index no device has: said here, for backend 'auto' would run on the CPU after a
  // notice, and 'cpu' would not read it at all.
  size_t count = 0;
  std::string why;
  try {
    py::gil_scoped_release unlocked;  // enumerating the devices takes a moment
    count = meshsal::list_devices().size();
  } catch (const meshsal::Cancelled&) {
    throw;
  } catch (const meshsal::Error& e) {
    why = e.what();
  }
  if (size_t(index) < count) return index;
  throw meshsal::Error("no Vulkan device " + std::to_string(index) + " (" +
                       (why.empty() ? "there are " + std::to_string(count) + "; see meshsal.devices()" : why) + ")");
}

meshsal::SaliencyOptions saliency_options(const SaliencyArgs& a, std::vector<std::string>* notices) {
  meshsal::SaliencyOptions o;
  if (!a.scales.is_none()) o.scales = scales_from(a.scales);
  o.eps_frac = number_arg(a.eps_frac, "eps_frac");
  o.method = meshsal::parse_method(a.method);  // the library's parsers (meshsal.Error is a ValueError)
  o.backend = meshsal::parse_backend(a.backend);
  o.precision = meshsal::parse_precision(a.precision);
  o.model = meshsal::parse_model(a.model);
  o.up = meshsal::parse_up_axis(a.up);
  if (!a.device || a.device.is_none() || py::isinstance<py::bool_>(a.device)) {
    throw py::type_error("device must be an int (a devices() index, -1 = choose) or a meshsal.Device, got " +
                         std::string(py::str(a.device.get_type().attr("__name__"))));
  } else if (py::isinstance<meshsal::Device>(a.device)) {
    o.session = a.device.cast<meshsal::Device*>();
  } else if (PyIndex_Check(a.device.ptr())) {
    o.device = device_index(a.device);
  } else {
    throw py::type_error("device must be an int (a devices() index, -1 = choose) or a meshsal.Device, got " +
                         std::string(py::str(a.device.get_type().attr("__name__"))));
  }
  o.threads = count_arg(a.threads, "threads");  // the library uses at most 1024
  if (notices) o.notice = [notices](const std::string& line) { notices->push_back(line); };
  return o;
}

void use_saliency_device(meshsal::ViewpointOptions& vo, const meshsal::SaliencyOptions& so) {
  vo.backend = so.backend;
  vo.device = so.device;
  vo.session = so.session;
  vo.notice = so.notice;
}

const char* const kSaliencyArgsDoc = R"(
Saliency arguments (as the CLI's options, same defaults):
  scales      center-surround scales in units of eps, a sequence or '2,3,4,5,6' (default)
  eps_frac    eps as a fraction of the bounding-box diagonal (0.003)
  method      'exact' (default), 'fast' (cell aggregates, linear cost; on the CPU or a
              Vulkan device, as backend says) or 'auto'
  backend     'auto' (a GPU when present, else the CPU; default), 'cpu' or 'gpu' (any
              Vulkan device, lavapipe included)
  precision   the GPU sweep's arithmetic: 'auto' (default), 'mixed' or 'double'
  device      Vulkan device index (see devices()), -1 = choose; or a meshsal.Device
              (open across calls: no device start-up or kernel compilation per call)
  threads     CPU threads, 0 = all cores
  model       what S models: 'lee2005' (the paper's, default), 'perceptual' (where people
              look at the rendered object: docs/method.md), or one of its cues alone:
              'exposure', 'centre', 'height', 'rarity', 'coarse'
  up          the up axis of the perceptual model's views and height: 'y' (default), 'z',
              'x', '-x', '-y', '-z' (render and best_view: also the picture's and views'))";

}  // namespace meshsal_py
