// meshsal batch: the list of models a run works on, from files, folders, globs and list
// files, in a stable order.
#pragma once
#include <string>
#include <vector>

namespace meshsal::cli {

// True for the names the loaders read: .obj .ply .off .stl, each optionally + .gz (any case).
bool is_mesh_file_name(const std::string& path);

// Expands each item in order: a folder gives the mesh files directly inside it (by
// is_mesh_file_name, sorted by name); an item with * ? or [ is a glob (sorted matches);
// "@FILE" reads FILE (one item per line; blank lines and lines starting with # skipped;
// relative items are taken from FILE's folder), whose items expand the same way (a list
// inside a list is refused); anything else is a file, kept even when missing, unreadable
// or not a regular file (the run logs why it does not read it). `list_file` ("" = none) is
// read like "@FILE" after `items`. A list file is a regular file or "-" (standard input),
// of at most 64 MiB, 4096 bytes a line and 1,000,000 items, text without NUL or control
// characters. The same file (same path after resolving . and ..) is kept once, first
// place. Throws meshsal::Error "ITEM: problem" for a glob matching nothing, an unreadable
// folder, a list breaking those bounds, and when nothing at all is found.
std::vector<std::string> expand_batch_inputs(const std::vector<std::string>& items,
                                             const std::string& list_file);

}  // namespace meshsal::cli
