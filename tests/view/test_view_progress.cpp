// The viewpoint search's progress: best_viewpoint's callback hears every batch of views, its
// fractions never fall, pass through the middle (no jump from a quarter to done) and end at 1.
#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "cli/synthetic.h"
#include "meshsal/meshsal.h"
#include "view/viewpoint.h"
#include "test_util.h"

using namespace meshsal;

namespace {

struct Heard {
  std::vector<std::pair<std::string, double>> calls;
  // The fractions of one stage, in the order heard.
  std::vector<double> of(const std::string& stage) const {
    std::vector<double> f;
    for (const auto& [s, x] : calls)
      if (s == stage) f.push_back(x);
    return f;
  }
};

}  // namespace

TEST_CASE("viewpoint progress: the optimiser reports every batch, smoothly, then the map", "[view]") {
  Mesh s = make_bumpy_sphere(3);
  std::vector<double> score(s.vertex_count());
  for (size_t i = 0; i < score.size(); ++i) score[i] = std::max(0.0, double(s.positions[3 * i]));
  Heard heard;
  ViewpointOptions vo;  // 8 restarts, as `meshsal viewpoint` runs them
  vo.optimiser.progress = [&](const char* stage, double f) { heard.calls.emplace_back(stage, f); };
  vo.visibility.resolution = 64;
  vo.views = 300;
  const Viewpoint b = best_viewpoint(s, score, vo);
  const OptimiserOptions& opt = vo.optimiser;

  const std::vector<double> f = heard.of("best view");
  REQUIRE(f.size() >= 10);
  CHECK(f.front() == 0.0);
  CHECK(f.back() == 1.0);
  size_t middle = 0;
  double largest_jump = 0;
  for (size_t i = 1; i < f.size(); ++i) {
    INFO("call " << i << ": " << f[i - 1] << " -> " << f[i]);
    CHECK(f[i] >= f[i - 1]);
    largest_jump = std::max(largest_jump, f[i] - f[i - 1]);
    middle += f[i] > 0.3 && f[i] < 0.9;
  }
  INFO("largest jump " << largest_jump << ", " << middle << " calls between 30% and 90%");
  // One call per batch: the start, then a probe and a step batch per round at most.
  CHECK(f.size() <= 1 + 2 * size_t(opt.max_iterations) + 1);
  CHECK(f.size() >= 1 + b.optimised.views_evaluated / (5 * size_t(opt.restarts)));
  CHECK(middle >= 4);
  CHECK(largest_jump < 0.35);

  // The map after the optimiser: 300 views in batches, ending at 1.
  const std::vector<double> m = heard.of("view map");
  REQUIRE(m.size() >= 2);
  CHECK(heard.calls.back().first == "view map");
  CHECK(m.back() == 1.0);
  for (size_t i = 1; i < m.size(); ++i) CHECK(m[i] > m[i - 1]);
  CHECK(b.map.U.size() == 300);
}

TEST_CASE("viewpoint progress: a restart's estimate follows its iterations and its step", "[view]") {
  OptimiserOptions o;  // step 0.25 down to 0.01, 60 iterations
  CHECK(restart_progress(0, 0.25, o) == 0.0);
  CHECK(restart_progress(30, 0.25, o) == Approx(0.5));
  CHECK(restart_progress(0, 0.05, o) == Approx(0.5));  // half the way down in log scale
  CHECK(restart_progress(3, 1.0, o) == Approx(0.05));  // a grown step counts its iterations
  CHECK(restart_progress(0, 0.001, o) == 1.0);
  CHECK(restart_progress(60, 0.25, o) == 1.0);
}
