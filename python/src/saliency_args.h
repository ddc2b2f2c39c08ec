// meshsal Python module: the saliency keyword arguments every function that computes
// saliency shares (the CLI's --scales, --eps-frac, --method, --backend, --precision,
// --device, --threads, --model, --up), turned into SaliencyOptions. Notices (e.g. the CPU fallback of
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
  py::object eps_frac;           // a number
  std::string method = "exact";
  std::string backend = "auto";
  std::string precision = "auto";
  py::object device;             // an int (a devices() index, -1 = choose) or a meshsal.Device
  py::object threads;            // an integer >= 0 (0 = all cores)
  std::string model = "lee2005";  // what S models (the CLI's --model)
  std::string up = "y";           // the up axis of the perceptual model's views and height (--up)
};

// SaliencyOptions from the arguments: device= goes to options.device (an int) or
// options.session (a meshsal.Device, which the caller's argument keeps alive for the call).
// Numbers as arg_values.h takes them; a device index that does not exist raises
// meshsal.Error (a ValueError) instead of running elsewhere.
meshsal::SaliencyOptions saliency_options(const SaliencyArgs& args, std::vector<std::string>* notices);

// device=N or Device(N): -1 (choose), else the index of a device list_devices() has.
// ValueError below -1 or beyond an int, meshsal.Error for an index no device has.
int device_index(const py::handle& device);

// The ViewpointOptions fields the saliency arguments decide (backend, device or session,
// notices), as for saliency: best_view and render share them.
void use_saliency_device(meshsal::ViewpointOptions& vo, const meshsal::SaliencyOptions& so);

// The docstring lines that describe these arguments (appended to each function's).
extern const char* const kSaliencyArgsDoc;

}  // namespace meshsal_py
