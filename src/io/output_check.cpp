// meshsal: check_outputs, the checks on the files a call will write, made before any work
// (loading, saliency, rendering), so that a typo costs nothing and an input is never lost.
// The meshsal command, Python and the library's own file-to-file calls share it.
#include "io/output_check.h"

#include <sys/stat.h>

#include <cctype>
#include <filesystem>
#include <utility>

#include "io/atomic_write.h"

namespace meshsal {

namespace {

bool ends_with_nocase(const std::string& s, const std::string& suffix) {
  if (s.size() < suffix.size()) return false;
  for (size_t i = 0; i < suffix.size(); ++i)
    if (std::tolower((unsigned char)s[s.size() - suffix.size() + i]) != suffix[i]) return false;
  return true;
}

std::string joined(const std::vector<std::string>& items, const char* last_sep) {
  std::string s;
  for (size_t i = 0; i < items.size(); ++i)
    s += (i == 0 ? "" : i + 1 == items.size() ? last_sep : ", ") + items[i];
  return s;
}

}  // namespace

void check_outputs(const std::vector<OutputFile>& outputs, const std::vector<std::string>& inputs) {
  std::vector<std::pair<std::string, std::filesystem::path>> seen;  // option, canonical path
  for (const OutputFile& out : outputs) {
    if (out.path.empty()) continue;
    bool known = out.extensions.empty();
    for (const std::string& ext : out.extensions) known = known || ends_with_nocase(out.path, ext);
    if (!known)
      throw Error(out.path + ": " + out.option + " must be a " + joined(out.extensions, " or ") + " file");
    // The writers' own rule (atomic_write.h): folders, disks and sockets refused, links followed.
    const OutputTarget target = output_target(out.path);
    struct stat os;
    if (::stat(target.path.c_str(), &os) == 0) {
      for (const std::string& in : inputs) {
        struct stat is;
        if (!in.empty() && ::stat(in.c_str(), &is) == 0 && is.st_dev == os.st_dev && is.st_ino == os.st_ino)
          throw Error(out.path + ": " + out.option + " is the input file '" + in +
                      "' (an output never replaces an input)");
      }
    }
    if (target.kind != OutputKind::Direct) remove_stale_temporaries_of(target.path);
    std::error_code ec;
    std::filesystem::path canonical = std::filesystem::weakly_canonical(out.path, ec);
    if (ec) canonical = out.path;
    for (const auto& [option, other] : seen)
      if (other == canonical)
        throw Error(out.path + ": given for both " + option + " and " + out.option);
    seen.emplace_back(out.option, canonical);
  }
}

void check_ply_output(const std::string& call, const std::string& output, const std::string& input) {
  if (output.empty()) output_target(output);  // "cannot write: empty output file name"
  if (mesh_output_format(output) != ".ply")
    throw Error(output + ": " + call + " writes a binary PLY: give an output name ending in .ply");
  check_outputs({{output, "the output", {".ply"}}}, {input});
}

void remove_stale_temporaries_of(const std::string& file) {
  const std::filesystem::path p(file);
  const std::string name = p.filename().string();
  const std::string folder = p.has_parent_path() ? p.parent_path().string() : ".";
  remove_stale_temporaries(folder, [&](const std::string& base) { return base == name; });
}

}  // namespace meshsal
