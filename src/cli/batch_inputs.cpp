// meshsal batch: expand_batch_inputs (see batch_inputs.h).
#include "batch_inputs.h"

#include <fcntl.h>
#include <glob.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <set>

#include "meshsal/meshsal.h"
#include "load_input.h"

namespace meshsal::cli {
namespace {

namespace fs = std::filesystem;
using meshsal::Error;

// Bounds on a list file: it is read whole, so it must not be endless (/dev/zero) or huge.
constexpr size_t kMaxListBytes = size_t(64) << 20;
constexpr size_t kMaxListLine = 4096;  // PATH_MAX
constexpr size_t kMaxListItems = 1000000;

std::string list_name(const std::string& path) { return path == "-" ? "standard input" : path; }

// A list file's text: a regular file, or "-" for standard input, at most kMaxListBytes.
std::string read_list_file(const std::string& path) {
  const bool stdin_list = path == "-";
  // O_NONBLOCK: a FIFO given as a list is refused below, not waited on.
  const int fd = stdin_list ? 0 : ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK);
  if (fd < 0) throw Error(path + ": cannot read the list file: " + std::strerror(errno));
  struct stat st;
  if (!stdin_list && (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode))) {
    ::close(fd);
    throw Error(path + ": a list file must be a regular file, or - for standard input");
  }
  std::string text;
  char buf[1 << 16];
  for (;;) {
    const ssize_t n = ::read(fd, buf, sizeof buf);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      const int e = errno;
      if (!stdin_list) ::close(fd);
      throw Error(list_name(path) + ": cannot read the list file: " + std::strerror(e));
    }
    if (n == 0) break;
    text.append(buf, size_t(n));
    if (text.size() > kMaxListBytes) {
      if (!stdin_list) ::close(fd);
      throw Error(list_name(path) + ": a list file larger than " + std::to_string(kMaxListBytes >> 20) +
                  " MiB (a list holds one path per line)");
    }
  }
  if (!stdin_list) ::close(fd);
  return text;
}

bool is_glob(const std::string& item) { return item.find_first_of("*?[") != std::string::npos; }

std::vector<std::string> folder_meshes(const std::string& dir) {
  std::vector<std::string> found;
  std::error_code ec;
  fs::directory_iterator it(dir, ec), end;
  if (ec) throw Error(dir + ": cannot list the folder: " + ec.message());
  for (; it != end; it.increment(ec)) {
    if (ec) throw Error(dir + ": cannot list the folder: " + ec.message());
    const fs::path& p = it->path();
    std::error_code ec2;
    if (is_mesh_file_name(p.filename().string()) && !fs::is_directory(p, ec2)) found.push_back(p.string());
  }
  std::sort(found.begin(), found.end());
  return found;
}

std::vector<std::string> glob_matches(const std::string& pattern) {
  glob_t g{};
  const int rc = ::glob(pattern.c_str(), 0, nullptr, &g);
  std::vector<std::string> found;
  if (rc == 0)
    for (size_t i = 0; i < g.gl_pathc; ++i) found.push_back(g.gl_pathv[i]);  // glob sorts them
  ::globfree(&g);
  if (rc == GLOB_NOMATCH || (rc == 0 && found.empty())) throw Error(pattern + ": no file matches");
  if (rc != 0) throw Error(pattern + ": cannot expand the pattern");
  return found;
}

class Expander {
 public:
  std::vector<std::string> out;

  void item(const std::string& it, bool in_list) {
    if (it.size() > 1 && it[0] == '@') {
      if (in_list) throw Error(it + ": a list file inside a list file is not read");
      list(it.substr(1));
      return;
    }
    std::error_code ec;
    if (!is_glob(it) && fs::is_directory(it, ec)) {
      for (const std::string& f : folder_meshes(it)) add(f);
    } else if (is_glob(it) && !fs::exists(it, ec)) {
      for (const std::string& f : glob_matches(it))
        if (fs::is_directory(f, ec)) {
          for (const std::string& g : folder_meshes(f)) add(g);
        } else {
          add(f);
        }
    } else {
      add(it);
    }
  }

  void list(const std::string& path) {
    const fs::path base = path == "-" ? fs::path() : fs::path(path).parent_path();
    const std::string text = read_list_file(path);
    size_t line_no = 0, items = 0;
    for (size_t at = 0; at < text.size();) {
      size_t end = text.find('\n', at);
      if (end == std::string::npos) end = text.size();
      std::string line = text.substr(at, end - at);
      at = end + 1;
      ++line_no;
      const std::string where = list_name(path) + ":" + std::to_string(line_no);
      if (line.size() > kMaxListLine)
        throw Error(where + ": a line longer than " + std::to_string(kMaxListLine) + " bytes (a list holds one path per line)");
      while (!line.empty() && std::isspace(static_cast<unsigned char>(line.back()))) line.pop_back();
      size_t start = 0;
      while (start < line.size() && std::isspace(static_cast<unsigned char>(line[start]))) ++start;
      line = line.substr(start);
      if (line.empty() || line[0] == '#') continue;
      for (unsigned char c : line)
        if (c < 0x20 && c != '\t')
          throw Error(where + ": not a line of text (a " + (c == 0 ? std::string("NUL byte") : "control character") +
                      "): a list file holds one path per line");
      if (++items > kMaxListItems)
        throw Error(list_name(path) + ": more than " + std::to_string(kMaxListItems) + " items");
      const fs::path p(line);
      item(p.is_absolute() || base.empty() ? line : (base / p).string(), true);
    }
  }

 private:
  std::set<std::string> seen_;

  void add(const std::string& path) {
    std::error_code ec;
    fs::path key = fs::weakly_canonical(path, ec);
    if (ec) key = fs::path(path).lexically_normal();
    if (seen_.insert(key.string()).second) out.push_back(path);
  }
};

}  // namespace

bool is_mesh_file_name(const std::string& path) {
  const std::string ext = mesh_extension(path);
  return ext == ".obj" || ext == ".ply" || ext == ".off" || ext == ".stl" || ext == ".gltf" || ext == ".glb";
}

std::vector<std::string> expand_batch_inputs(const std::vector<std::string>& items,
                                             const std::string& list_file) {
  Expander e;
  for (const std::string& it : items) e.item(it, false);
  if (!list_file.empty()) e.list(list_file);
  if (e.out.empty()) throw Error("batch: no mesh file found in the inputs given");
  return e.out;
}

}  // namespace meshsal::cli
