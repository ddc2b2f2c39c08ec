// meshsal CLI: JsonObject (see json_object.h).
#include "json_object.h"

#include <cmath>
#include <cstdio>

#include "json_string.h"

namespace meshsal_cli {

JsonObject& JsonObject::raw(const std::string& key, const std::string& json) {
  if (!body_.empty()) body_ += ", ";
  body_ += json_string(key) + ": " + json;
  return *this;
}

JsonObject& JsonObject::number(const std::string& key, double value) {
  if (!std::isfinite(value)) return raw(key, "null");
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.9g", value);
  return raw(key, buf);
}

JsonObject& JsonObject::count(const std::string& key, uint64_t value) {
  return raw(key, std::to_string(value));
}

JsonObject& JsonObject::text(const std::string& key, const std::string& value) {
  return raw(key, json_string(value));
}

JsonObject& JsonObject::flag(const std::string& key, bool value) { return raw(key, value ? "true" : "false"); }

JsonObject& JsonObject::object(const std::string& key, const JsonObject& value) {
  return raw(key, value.str());
}

void JsonObject::print() const {
  std::printf("%s\n", str().c_str());
  std::fflush(stdout);
}

}  // namespace meshsal_cli
