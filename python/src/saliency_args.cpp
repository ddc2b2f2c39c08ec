#include "saliency_args.h"

#include "numpy_in.h"

namespace meshsal_py {

meshsal::SaliencyOptions saliency_options(const SaliencyArgs& a, std::vector<std::string>* notices) {
  meshsal::SaliencyOptions o;
  if (!a.scales.is_none()) o.scales = scales_from(a.scales);
  o.eps_frac = a.eps_frac;
  o.method = meshsal::parse_method(a.method);  // the library's parsers (meshsal.Error is a ValueError)
  o.backend = meshsal::parse_backend(a.backend);
  o.precision = meshsal::parse_precision(a.precision);
  if (!a.device || a.device.is_none() || py::isinstance<py::bool_>(a.device)) {
    throw py::type_error("device must be an int (a devices() index, -1 = choose) or a meshsal.Device, got " +
                         std::string(py::str(a.device.get_type().attr("__name__"))));
  } else if (py::isinstance<meshsal::Device>(a.device)) {
    o.session = a.device.cast<meshsal::Device*>();
  } else if (PyIndex_Check(a.device.ptr())) {
    o.device = a.device.cast<int>();
  } else {
    throw py::type_error("device must be an int (a devices() index, -1 = choose) or a meshsal.Device, got " +
                         std::string(py::str(a.device.get_type().attr("__name__"))));
  }
  o.threads = a.threads;
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
  threads     CPU threads, 0 = all cores)";

}  // namespace meshsal_py
