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
  o.device = a.device;
  o.threads = a.threads;
  if (notices) o.notice = [notices](const std::string& line) { notices->push_back(line); };
  return o;
}

const char* const kSaliencyArgsDoc = R"(
Saliency arguments (as the CLI's options, same defaults):
  scales      center-surround scales in units of eps, a sequence or '2,3,4,5,6' (default)
  eps_frac    eps as a fraction of the bounding-box diagonal (0.003)
  method      'exact' (default), 'fast' (cell aggregates, linear cost, CPU) or 'auto'
  backend     'auto' (a GPU when present, else the CPU; default), 'cpu' or 'gpu' (any
              Vulkan device, lavapipe included)
  precision   the GPU sweep's arithmetic: 'auto' (default), 'mixed' or 'double'
  device      Vulkan device index (see devices()), -1 = choose
  threads     CPU threads, 0 = all cores)";

}  // namespace meshsal_py
