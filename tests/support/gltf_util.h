// Helpers of the glTF tests: hand-made glTF files (JSON with one base64 buffer) whose
// every field a test can bend, and the Khronos validator run on what meshsal writes.
#pragma once
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

namespace meshsal_test {

inline std::string base64(const std::vector<uint8_t>& in) {
  static const char* t = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  size_t i = 0;
  for (; i + 2 < in.size(); i += 3) {
    const uint32_t v = uint32_t(in[i]) << 16 | uint32_t(in[i + 1]) << 8 | in[i + 2];
    out += t[v >> 18], out += t[(v >> 12) & 63], out += t[(v >> 6) & 63], out += t[v & 63];
  }
  if (i + 1 == in.size()) {
    const uint32_t v = uint32_t(in[i]) << 16;
    out += t[v >> 18], out += t[(v >> 12) & 63], out += "==";
  } else if (i + 2 == in.size()) {
    const uint32_t v = uint32_t(in[i]) << 16 | uint32_t(in[i + 1]) << 8;
    out += t[v >> 18], out += t[(v >> 12) & 63], out += t[(v >> 6) & 63], out += '=';
  }
  return out;
}

// A glTF's binary data, built up piece by piece: each add() returns the byte offset.
struct GltfBytes {
  std::vector<uint8_t> data;
  template <class T>
  size_t add(const std::vector<T>& values) {
    while (data.size() % 4) data.push_back(0);
    const size_t at = data.size();
    const uint8_t* p = reinterpret_cast<const uint8_t*>(values.data());
    data.insert(data.end(), p, p + values.size() * sizeof(T));
    return at;
  }
  std::string buffer_json() const {
    return "{\"byteLength\":" + std::to_string(data.size()) + ",\"uri\":\"data:application/octet-stream;base64," +
           base64(data) + "\"}";
  }
};

// The folder of the validator (web, with node_modules from tools/setup.sh).
inline std::string web_tools_dir() { return std::string(MESHSAL_SOURCE_DIR) + "/web"; }

// Runs the Khronos glTF-Validator on `file`; returns its exit status (0: no error) and its
// report in `report`.
inline int validate_gltf(const std::string& file, std::string* report) {
  const std::string out = file + ".validator.txt";
  const std::string cmd = "node '" + web_tools_dir() + "/validate_gltf.mjs' '" + file + "' > '" + out + "' 2>&1";
  const int rc = std::system(cmd.c_str());
  if (report) {
    report->clear();
    if (FILE* f = std::fopen(out.c_str(), "rb")) {
      char buf[4096];
      size_t n;
      while ((n = std::fread(buf, 1, sizeof buf, f)) > 0) report->append(buf, n);
      std::fclose(f);
    }
  }
  std::remove(out.c_str());
  return rc == -1 ? -1 : WEXITSTATUS(rc);
}

}  // namespace meshsal_test

namespace meshsal_test {

// A GLB file: `json` as its JSON chunk (padded with blanks), `bin` (may be empty) as its
// BIN chunk (padded with zeros).
inline std::string glb_file(std::string json, std::vector<uint8_t> bin = {}) {
  while (json.size() % 4) json += ' ';
  while (bin.size() % 4) bin.push_back(0);
  auto u32 = [](uint32_t v) { return std::string(reinterpret_cast<const char*>(&v), 4); };
  const uint32_t total = uint32_t(12 + 8 + json.size() + (bin.empty() ? 0 : 8 + bin.size()));
  std::string out = "glTF" + u32(2) + u32(total) + u32(uint32_t(json.size())) + "JSON" + json;
  if (!bin.empty()) out += u32(uint32_t(bin.size())) + "BIN" + std::string(1, '\0') + std::string(bin.begin(), bin.end());
  return out;
}

}  // namespace meshsal_test
