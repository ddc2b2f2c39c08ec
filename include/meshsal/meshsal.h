// meshsal: mesh saliency (Lee, Varshney, Jacobs, "Mesh Saliency", SIGGRAPH 2005) on the CPU
// and on Vulkan GPUs, saliency-guided simplification, best viewpoints and pictures.
//
// This is the whole public interface: link `meshsal::core` (CPU only, no Vulkan) or
// `meshsal::gpu` (adds the Vulkan backend) from `find_package(meshsal)`.
//
// Conventions, for every function below:
//  - A mesh is flat arrays, as in meshoptimizer: `positions` holds x,y,z per vertex (float,
//    in the model's own units), `triangles` 3 vertex indices per triangle (uint32). Polygons
//    are fan-triangulated by the loaders. Vertices no triangle uses are allowed: they keep
//    their index and get curvature and saliency 0. The *mesh points* are the vertices that
//    at least one triangle uses.
//  - Distances and the saliency scale unit eps are in model units; eps is eps_frac times the
//    bounding-box diagonal of the mesh points.
//  - Bad input (an unreadable or malformed file, an index out of range, NaN coordinates, an
//    option out of range) and device failures throw meshsal::Error, whose message is one
//    line meant for a person. std::bad_alloc can escape when memory runs out.
//  - Functions are reentrant: calls on different data may run on different threads at the
//    same time. A result never refers to its inputs (everything returned is owned by value).
//  - Results do not depend on the number of threads.
//  - Options in, result out: a function takes its settings as an options struct and returns
//    what it computes, as a struct when it is more than one thing (LoadedMesh, Simplified);
//    no result comes back through a pointer argument. An optional per-vertex input is a
//    vector passed empty when absent (never a null pointer).
// The method's fixed choices are documented in docs/method.md of the repository.
#pragma once

// The parts, by topic: each compiles alone and includes what it uses.
#include "meshsal/mesh.h"      // Error, Mesh and its helpers
#include "meshsal/io.h"        // reading and writing files, formats, the output check
#include "meshsal/device.h"    // backends, Vulkan devices and sessions, the C heap
#include "meshsal/saliency.h"  // compute_saliency and its options
#include "meshsal/simplify.h"  // simplification, weights, levels of detail, comparison
#include "meshsal/tiles.h"     // tiles, out of core, processes that share tiles
#include "meshsal/view.h"      // viewpoints, cameras, pictures, viewer pages
#include "meshsal/text.h"      // the option parsers (parse_*) and names
#include "meshsal/request.h"   // Request and run_request
#include "meshsal/eval.h"      // scoring a prediction against ground truth (meshsal eval)

// The version: CMake's project(VERSION) is the one source; the build checks that these agree.
#define MESHSAL_VERSION 400  // major * 10000 + minor * 100 + patch
#define MESHSAL_VERSION_STRING "0.4.0"
