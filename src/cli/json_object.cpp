// meshsal CLI: JsonObject (see json_object.h).
#include "json_object.h"

#include <cmath>
#include <cstdio>

#include "json_string.h"

namespace meshsal::cli {

JsonObject& JsonObject::raw(const std::string& key, const std::string& json) {
  if (!body_.empty()) body_ += ", ";
  body_ += json_string(key) + ": " + json;
  return *this;
}

// %.9g, or null for NaN and infinities (JSON has no such numbers).
static std::string number_text(double value) {
  if (!std::isfinite(value)) return "null";
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.9g", value);
  return buf;
}

JsonObject& JsonObject::number(const std::string& key, double value) { return raw(key, number_text(value)); }

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

JsonObject& JsonObject::strings(const std::string& key, const std::vector<std::string>& values) {
  std::string a = "[";
  for (size_t i = 0; i < values.size(); ++i) a += (i ? ", " : "") + json_string(values[i]);
  return raw(key, a + "]");
}

JsonObject& JsonObject::numbers(const std::string& key, const std::vector<double>& values) {
  std::string list;
  for (double v : values) list += (list.empty() ? "" : ", ") + number_text(v);
  return raw(key, "[" + list + "]");
}

JsonObject& JsonObject::objects(const std::string& key, const std::vector<JsonObject>& values) {
  std::string list;
  for (const JsonObject& v : values) list += (list.empty() ? "" : ", ") + v.str();
  return raw(key, "[" + list + "]");
}

std::string json_key(std::string name) {
  for (char& c : name)
    if (c == ' ' || c == '-') c = '_';
  return name;
}

void JsonObject::print() const {
  std::printf("%s\n", str().c_str());
  std::fflush(stdout);
}

}  // namespace meshsal::cli
