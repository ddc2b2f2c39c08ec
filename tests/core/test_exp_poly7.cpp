// The degree-7 exp polynomial (core/exp_poly7.h) and its GPU copy (exp_poly7.glsl): the
// same coefficients to the bit, and the error the documentation states.
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <ios>
#include <map>
#include <sstream>
#include <string>

#include "core/exp_poly7.h"
#include "test_util.h"

using namespace meshsal;

namespace {

std::string read_text(const std::string& path) {
  std::ifstream f(path);
  REQUIRE(f.good());
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

// A GLSL double literal ("-1.0LF"), whole text or fail.
double glsl_double(std::string t) {
  while (!t.empty() && t.front() == ' ') t.erase(t.begin());
  while (!t.empty() && t.back() == ' ') t.pop_back();
  INFO("literal '" << t << "'");
  REQUIRE(t.size() > 2);
  REQUIRE(t.substr(t.size() - 2) == "LF");
  t.resize(t.size() - 2);
  char* end = nullptr;
  const double v = std::strtod(t.c_str(), &end);
  REQUIRE(end == t.c_str() + t.size());
  return v;
}

// The value of "(a)" or "(a / b)" with GLSL double literals a, b: what glslang folds it to
// (a correctly rounded double division, as in C++).
double glsl_constant(std::string e) {
  INFO("expression '" << e << "'");
  REQUIRE(e.size() > 2);
  REQUIRE(e.front() == '(');
  REQUIRE(e.back() == ')');
  e = e.substr(1, e.size() - 2);
  const size_t slash = e.find('/');
  if (slash == std::string::npos) return glsl_double(e);
  REQUIRE(e.find('/', slash + 1) == std::string::npos);
  return glsl_double(e.substr(0, slash)) / glsl_double(e.substr(slash + 1));
}

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }
bool same_bits(float a, float b) { return std::memcmp(&a, &b, sizeof a) == 0; }

}  // namespace

TEST_CASE("exp_poly7: the GLSL include's coefficients equal the C++ ones bit for bit",
          "[exp_poly7][gpu_shaders]") {
  const std::string path = std::string(MESHSAL_SOURCE_DIR) + "/shaders/exp_poly7.glsl";
  INFO(path);
  const std::string text = read_text(path);
  std::map<int, double> found;
  std::istringstream lines(text);
  const std::string tag = "#define EXP_POLY7_C";
  for (std::string line; std::getline(lines, line);) {
    if (line.compare(0, tag.size(), tag) != 0) continue;
    const size_t sp = line.find(' ', tag.size());
    REQUIRE(sp != std::string::npos);
    const int k = std::atoi(line.substr(tag.size(), sp - tag.size()).c_str());
    REQUIRE(found.count(k) == 0);
    found[k] = glsl_constant(line.substr(sp + 1));
  }
  REQUIRE(found.size() == 8);
  for (int k = 0; k < 8; ++k) {
    INFO("coefficient of x^" << k << ": GLSL " << std::hexfloat << found[k] << ", C++ "
                              << kExpPoly7[k]);
    REQUIRE(found.count(k) == 1);
    CHECK(same_bits(found[k], kExpPoly7[k]));
  }
  // The same operations in the same order as exp_neg_poly7() in exp_poly7.h (Estrin's
  // scheme), every one precise.
  const char* steps[] = {"precise double x2 = x * x;",
                         "precise double x4 = x2 * x2;",
                         "precise double p01 = EXP_POLY7_C1 * x + EXP_POLY7_C0;",
                         "precise double p23 = EXP_POLY7_C3 * x + EXP_POLY7_C2;",
                         "precise double p45 = EXP_POLY7_C5 * x + EXP_POLY7_C4;",
                         "precise double p67 = EXP_POLY7_C7 * x + EXP_POLY7_C6;",
                         "precise double q03 = p23 * x2 + p01;",
                         "precise double q47 = p67 * x2 + p45;",
                         "precise double p = q47 * x4 + q03;"};
  size_t at = 0;
  for (const char* step : steps) {
    INFO("step " << step);
    at = text.find(step, at);
    REQUIRE(at != std::string::npos);
  }
  CHECK(text.find("fma(") == std::string::npos);
}

TEST_CASE("exp_poly7: the coefficients are (-1)^k / k!", "[exp_poly7]") {
  double factorial = 1;
  for (int k = 0; k < 8; ++k) {
    if (k > 0) factorial *= k;
    CHECK(same_bits(kExpPoly7[k], (k % 2 ? -1.0 : 1.0) / factorial));
  }
}

TEST_CASE("exp_poly7: measured error over the ranges it is used on", "[exp_poly7]") {
  // exp_neg_cutoff on [0, 2): the fast method's weights; the docs state 6.05e-7.
  double worst = 0, worst_at = 0;
  const int n = 1 << 20;
  for (int i = 0; i <= n; ++i) {
    const double x = i < n ? 2.0 * i / n : std::nextafter(2.0, 0.0);
    const double e = std::exp(-x);
    const double r = std::fabs(exp_neg_cutoff(x) - e) / e;
    if (r > worst) worst = r, worst_at = x;
  }
  INFO("exp_neg_cutoff: largest relative error " << worst << " at x = " << worst_at);
  CHECK(worst > 6.04e-7);
  CHECK(worst < 6.06e-7);
  CHECK(worst_at > 1.99);
  // exp_neg_poly7 on [0, 0.02]: the exact sweep's b = exp(-t/14400), exp to rounding.
  double small = 0;
  for (int i = 0; i <= n; ++i) {
    const double x = 0.02 * i / n, e = std::exp(-x);
    small = std::max(small, std::fabs(exp_neg_poly7(x) - e) / e);
  }
  INFO("exp_neg_poly7 on [0, 0.02]: largest relative error " << small);
  CHECK(small < 4e-16);
}

TEST_CASE("exp_poly7: the 4-wide evaluation equals the scalar one lane by lane", "[exp_poly7]") {
  for (int i = 0; i < 1000; ++i) {
    const v4d x = {0.002 * i, 0.002 * i + 5e-4, 0.002 * i + 1e-3, 0.002 * i + 1.5e-3};
    const v4d a = exp_neg_poly7(x), b = exp_neg_cutoff(x);
    for (int l = 0; l < 4; ++l) {
      CHECK(same_bits(a[l], exp_neg_poly7(double(x[l]))));
      CHECK(same_bits(b[l], exp_neg_cutoff(double(x[l]))));
    }
  }
}

TEST_CASE("exp_poly7: in float (the fast method's queries), error and 8 lanes", "[exp_poly7]") {
  // exp_neg_cutoff<float> on [0, 2): the coefficients and every step rounded to float.
  double worst = 0;
  const int n = 1 << 20;
  for (int i = 0; i < n; ++i) {
    const float x = float(2.0 * i / n);
    const double e = std::exp(-double(x));
    worst = std::max(worst, std::fabs(double(exp_neg_cutoff(x)) - e) / e);
  }
  INFO("exp_neg_cutoff<float>: largest relative error " << worst);
  CHECK(worst > 6e-7);  // at least the polynomial's own error
  CHECK(worst < 1.2e-6);  // 1.12e-6 measured, as exp_poly7.h states
  for (int i = 0; i < 1000; ++i) {
    v8f x;
    for (int l = 0; l < 8; ++l) x[l] = 0.00025f * float(8 * i + l);
    const v8f b = exp_neg_cutoff(x);
    for (int l = 0; l < 8; ++l) CHECK(same_bits(b[l], exp_neg_cutoff(float(x[l]))));
  }
}
