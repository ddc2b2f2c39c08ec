// meshsal Python module: the saliency keyword arguments every function that computes
// saliency shares (the CLI's --scales, --eps-frac, --method, --backend, --precision,
// --device, --threads), turned into SaliencyOptions. Notices (e.g. the CPU fallback of
// backend='auto') are collected in `notices`, since the call runs without the GIL.
#pragma once
#include <string>
#include <vector>

#include <pybind11/pybind11.h>

#include "meshsal/meshsal.h"

namespace meshsal_py {

namespace py = pybind11;

struct SaliencyArgs {
  py::object scales;             // None: 2,3,4,5,6
  double eps_frac = 0.003;
  std::string method = "exact";
  std::string backend = "auto";
  std::string precision = "auto";
  py::object device;             // an int (a devices() index, -1 = choose) or a meshsal.Device
  unsigned threads = 0;
};

// SaliencyOptions from the arguments: device= goes to options.device (an int) or
// options.session (a meshsal.Device, which the caller's argument keeps alive for the call).
meshsal::SaliencyOptions saliency_options(const SaliencyArgs& args, std::vector<std::string>* notices);

// The ViewpointOptions fields the saliency arguments decide (backend, device or session,
// notices), as for saliency: best_view and render share them.
void use_saliency_device(meshsal::ViewpointOptions& vo, const meshsal::SaliencyOptions& so);

// The docstring lines that describe these arguments (appended to each function's).
extern const char* const kSaliencyArgsDoc;

}  // namespace meshsal_py
