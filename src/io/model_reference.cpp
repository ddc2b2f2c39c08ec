#include "io/model_reference.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <climits>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "io/text_scan.h"
#include "meshsal/meshsal.h"

namespace meshsal {
namespace {

// The reference as folders and a name below the model's folder, '.' and empty parts
// dropped and '..' applied; false when a '..' climbs above the folder.
bool normalised_parts(const std::string& reference, std::vector<std::string>* parts) {
  size_t at = 0;
  while (at <= reference.size()) {
    const size_t slash = std::min(reference.find('/', at), reference.size());
    const std::string part = reference.substr(at, slash - at);
    at = slash + 1;
    if (part.empty() || part == ".") continue;
    if (part == "..") {
      if (parts->empty()) return false;
      parts->pop_back();
    } else {
      parts->push_back(part);
    }
  }
  return true;
}

bool has_scheme(const std::string& s) {
  // RFC 3986: ALPHA *( ALPHA / DIGIT / "+" / "-" / "." ) ":". A relative reference whose
  // first part holds a ':' must be written "./a:b", so this is never a file name.
  if (s.empty() || !std::isalpha(static_cast<unsigned char>(s[0]))) return false;
  for (char c : s) {
    if (c == ':') return true;
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '+' && c != '-' && c != '.') return false;
  }
  return false;
}

// The canonical path (links resolved) of an existing file or folder; "" when there is none.
std::string real_path(const std::string& path) {
  char* p = ::realpath(path.c_str(), nullptr);
  if (!p) return "";
  std::string out(p);
  std::free(p);
  return out;
}

bool lies_below(const std::string& path, const std::string& folder) {
  const std::string prefix = folder == "/" ? folder : folder + "/";
  return path.size() > prefix.size() && path.compare(0, prefix.size(), prefix) == 0;
}

struct Fd {
  int fd = -1;
  ~Fd() {
    if (fd >= 0) ::close(fd);
  }
};

}  // namespace

std::string reference_text_problem(const std::string& reference, bool uri) {
  if (reference.empty()) return "an empty file name";
  if (reference.find('\0') != std::string::npos) return "a file name with a NUL byte";
  if (uri && has_scheme(reference))
    return "a URI with the scheme '" + reference.substr(0, reference.find(':') + 1) +
           "' (only data: URIs and relative file names are read; " + kReferenceRule + ")";
  if (reference[0] == '/') return "an absolute path (" + std::string(kReferenceRule) + ")";
  std::vector<std::string> parts;
  if (!normalised_parts(reference, &parts)) return "a path that leaves the model's folder (" + std::string(kReferenceRule) + ")";
  if (parts.empty()) return "the model's folder itself, not a file";
  return "";
}

std::vector<unsigned char> read_model_reference(const std::string& folder, const std::string& reference, bool uri,
                                                uint64_t budget) {
  const std::string name = quoted(reference, 200);
  auto fail = [&](const std::string& problem) -> Error { return Error(name + ": " + problem); };
  auto refuse = [&](const std::string& problem) -> ReferenceRefused { return ReferenceRefused(name + ": " + problem); };
  if (const std::string problem = reference_text_problem(reference, uri); !problem.empty()) throw refuse(problem);
  const std::string base = real_path(folder.empty() ? "." : folder);
  if (base.empty()) throw fail("the model's folder cannot be resolved: " + std::string(std::strerror(errno)));
  std::vector<std::string> parts;
  normalised_parts(reference, &parts);
  std::string joined = base;
  for (const std::string& p : parts) joined += (joined == "/" ? "" : "/") + p;
  // Links resolved, the file must still lie below the folder; what is not there, or not
  // below it, gets one message (whether a file outside exists is none of the model's business).
  const std::string resolved = real_path(joined);
  if (resolved.empty() && errno != ENOENT && errno != ENOTDIR)
    throw fail(std::string("cannot be resolved: ") + std::strerror(errno));
  if (resolved.empty()) throw fail("no such file in the model's folder");
  if (!lies_below(resolved, base))
    throw refuse("leads out of the model's folder through a symbolic link (" + std::string(kReferenceRule) + ")");
  // O_NOFOLLOW: the resolved path has no link left; one put there since is refused.
  // O_NONBLOCK: a FIFO opens at once (and is refused below) instead of waiting for a writer.
  Fd f;
  f.fd = ::open(resolved.c_str(), O_RDONLY | O_CLOEXEC | O_NOCTTY | O_NONBLOCK | O_NOFOLLOW);
  if (f.fd < 0) throw fail(std::string("cannot open: ") + std::strerror(errno));
  // What was opened, where the system says (a folder on the way swapped for a link since).
  char link[64];
  std::snprintf(link, sizeof link, "/proc/self/fd/%d", f.fd);
  std::vector<char> target(PATH_MAX + 1);
  const ssize_t len = ::readlink(link, target.data(), target.size() - 1);
  if (len > 0 && !lies_below(std::string(target.data(), size_t(len)), base))
    throw refuse("leads out of the model's folder (" + std::string(kReferenceRule) + ")");
  struct stat st;
  if (::fstat(f.fd, &st) != 0) throw fail(std::string("cannot stat: ") + std::strerror(errno));
  if (!S_ISREG(st.st_mode)) throw fail("not a regular file (a model may name only regular files)");
  if (uint64_t(st.st_size) > budget)
    throw fail("more than the " + std::to_string(budget) +
               " bytes left of the input limit for a model's files (MESHSAL_MAX_INPUT raises it)");
  std::vector<unsigned char> out(size_t(st.st_size));
  size_t got = 0;
  while (got < out.size()) {
    const ssize_t n = ::read(f.fd, out.data() + got, out.size() - got);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) throw fail(std::string("cannot read: ") + std::strerror(errno));
    if (n == 0) break;  // shrank while being read: what is there
    got += size_t(n);
  }
  out.resize(got);
  return out;
}

}  // namespace meshsal
