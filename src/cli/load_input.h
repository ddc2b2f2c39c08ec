// meshsal CLI: loading an input mesh the way every command does (PLY seams found) with the
// notes a user should see (STL welding).
#pragma once
#include <string>

#include "meshsal/meshsal.h"

namespace meshsal::cli {

// The format a file name gives: its extension in lower case, a trailing .gz dropped
// (".ply" for "Scan.PLY.gz"); "" when it has none.
std::string mesh_extension(const std::string& path);

// The LoadOptions every command starts from: max_input_bytes from the environment variable
// MESHSAL_MAX_INPUT when it is set (bytes, with an optional K, M or G suffix; the library
// itself reads no environment), else 0 (the library's default rules). Throws Error when
// the variable is not a byte count.
meshsal::LoadOptions load_options();

// read_mesh with MESHSAL_MAX_INPUT's bound and LoadOptions::attributes = `attributes` (OBJ
// vt/vn, PLY properties into Mesh::attributes). A PLY's UV seams (vertices split at one position, told from plain
// duplicates by their properties: Mesh::position_vertex) are found either way, so that
// saliency sees one surface there; its properties are then kept only when asked.
// With `regular_only` a named pipe is refused too (LoadOptions::regular_files_only).
meshsal::LoadedMesh load_input_mesh(const std::string& path, bool attributes, bool regular_only = false);

// The mesh of load_input_mesh without attributes, then, unless `quiet`, one note on stderr
// when STL corners were welded: "note: PATH: welded N STL corners into V shared vertices".
meshsal::Mesh load_input(const std::string& path, bool quiet);

}  // namespace meshsal::cli
