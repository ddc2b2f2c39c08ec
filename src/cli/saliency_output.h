// meshsal CLI: the summary of a saliency result (text and JSON), and the saliency options' flags.
#pragma once
#include <string>

#include "json_object.h"
#include "meshsal/meshsal.h"
#include "saliency/saliency.h"

namespace CLI {
class App;
}

namespace meshsal::cli {

// Prints vertices, faces, eps, backend, time per stage, pairs/s and the statistics of S
// to stdout.
void print_saliency_summary(const meshsal::Mesh& mesh, const meshsal::SaliencyResult& result,
                            double load_seconds);

// The same as one JSON object (json_object.h); `output` is the PLY written. `meshsal
// batch` adds its own keys to it for its log.
JsonObject saliency_json(const std::string& input, const std::string& output, const meshsal::Mesh& mesh,
                         const meshsal::SaliencyResult& result, double load_seconds);

// The same for an out-of-core run (meshsal::saliency_file): its report, the limit, the
// seconds of the whole call and the peak resident memory (the largest over MPI ranks).
JsonObject out_of_core_json(const std::string& input, const std::string& output,
                            const meshsal::OutOfCoreReport& report, meshsal::Method method,
                            uint64_t memory_limit, double seconds, uint64_t peak_rss);

// saliency_json() printed on stdout.
void print_saliency_json(const std::string& input, const std::string& output, const meshsal::Mesh& mesh,
                         const meshsal::SaliencyResult& result, double load_seconds);

// meshsal::parse_backend ("auto" / "cpu" / "gpu"), its error a usage error naming --backend.
meshsal::Backend parse_backend(const std::string& name);

// --precision auto|mixed|double (the GPU sweep's arithmetic) into *name, for every
// command that has --backend; meshsal::parse_precision() turns it into the option.
void add_precision_option(CLI::App& app, std::string* name);

// --method exact|fast|auto (SPEC 5) into *name, for every command that computes saliency;
// meshsal::parse_method() turns it into the option.
void add_method_option(CLI::App& app, std::string* name);

}  // namespace meshsal::cli
