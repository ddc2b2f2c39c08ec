// meshsal CLI: one JSON object on one line, the form every command's --json output takes.
// Keys are snake_case; numbers print with 9 significant digits (%.9g), non-finite ones as null.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

namespace meshsal::cli {

class JsonObject {
 public:
  JsonObject& number(const std::string& key, double value);
  JsonObject& count(const std::string& key, uint64_t value);
  JsonObject& text(const std::string& key, const std::string& value);
  JsonObject& flag(const std::string& key, bool value);
  JsonObject& object(const std::string& key, const JsonObject& value);
  JsonObject& null(const std::string& key) { return raw(key, "null"); }
  // Arrays: of numbers (as number()) and of objects.
  JsonObject& numbers(const std::string& key, const std::vector<double>& values);
  JsonObject& strings(const std::string& key, const std::vector<std::string>& values);
  JsonObject& objects(const std::string& key, const std::vector<JsonObject>& values);
  // Already-formatted JSON (an array, null).
  JsonObject& raw(const std::string& key, const std::string& json);
  std::string str() const { return "{" + body_ + "}"; }
  // Prints str() and a newline on stdout, and flushes.
  void print() const;

 private:
  std::string body_;
};

// A name as a snake_case key: "gaussian sweep" -> "gaussian_sweep" (spaces and dashes to _).
std::string json_key(std::string name);

}  // namespace meshsal::cli
