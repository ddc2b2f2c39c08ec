// meshsal: where the benchmark programs look for the shared test meshes.
#pragma once
#include <string>

namespace meshsal {

// $MESHSAL_DATA if set; else ../shared/data/meshes from the working directory; else the same
// folder relative to the executable (build/meshsal -> ../shared/data/meshes beside the
// checkout). Returns the relative default when none exists (callers report what is missing).
std::string benchmark_data_dir();

}  // namespace meshsal
