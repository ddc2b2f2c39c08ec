// Headless Chromium for the tests of the viewer page (tools/setup.sh installs it).
#pragma once
#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <string>

#include "test_io_util.h"

namespace meshsal_test {

// Headless Chromium on `url` (file://..., WebGL through SwiftShader); `what`: --dump-dom or
// --screenshot=FILE; its standard output goes to `out`. Returns its exit status.
inline int chromium(const std::string& what, const std::string& url, const std::string& out) {
  const std::string cmd = "timeout 120 chromium --headless --no-sandbox --disable-gpu-sandbox --use-angle=swiftshader "
                          "--enable-unsafe-swiftshader --hide-scrollbars --window-size=900,600 "
                          "--virtual-time-budget=20000 " + what + " '" + url + "' > '" + out + "' 2>/dev/null";
  return WEXITSTATUS(std::system(cmd.c_str()));
}

// A file's bytes (pages, DOM dumps) by path.
inline std::string text_of(const std::filesystem::path& p) { return read_file(p.string()); }

}  // namespace meshsal_test
