#include "knoblab/jsonread/json_reader.hpp"

#include <algorithm>
#include <cmath>

namespace knoblab::jsonread {

namespace {

[[noreturn]] void type_error(const std::string& path, std::string_view expected, const nlohmann::json& v) {
  fail(path, "expected " + std::string(expected) + ", got " + v.dump());
}

}  // namespace

PathError::PathError(std::string path, std::string message)
    : PathError(path.empty() ? message : path + ": " + message, path, message) {}

PathError::PathError(const std::string& what, std::string path, std::string message)
    : std::invalid_argument(what), path_(std::move(path)), message_(std::move(message)) {}

PathError PathError::in_file(const std::string& file) const { return PathError(file + ": " + what(), path_, message_); }

void fail(const std::string& path, const std::string& message) { throw PathError(path, message); }

std::string member_path(const std::string& path, std::string_view key) {
  return path.empty() ? std::string(key) : path + "." + std::string(key);
}

std::string element_path(const std::string& path, std::size_t index) {
  return path + "[" + std::to_string(index) + "]";
}

double as_number(const nlohmann::json& v, const std::string& path) {
  if (!v.is_number()) type_error(path, "a number", v);
  const double x = v.get<double>();
  if (!std::isfinite(x)) type_error(path, "a finite number", v);
  return x;
}

std::uint64_t as_uint64(const nlohmann::json& v, const std::string& path) {
  // Parsed text gives non-negative integers as unsigned, C++-built json as signed.
  if (v.is_number_unsigned()) return v.get<std::uint64_t>();
  if (v.is_number_integer() && v.get<std::int64_t>() >= 0) return static_cast<std::uint64_t>(v.get<std::int64_t>());
  type_error(path, "a non-negative integer", v);
}

std::size_t as_count(const nlohmann::json& v, const std::string& path, std::size_t min, std::size_t max) {
  const std::uint64_t n = as_uint64(v, path);
  if (n < min || n > max)
    fail(path, "must be from " + std::to_string(min) + " to " + std::to_string(max) + ", got " + std::to_string(n));
  return static_cast<std::size_t>(n);
}

bool as_bool(const nlohmann::json& v, const std::string& path) {
  if (!v.is_boolean()) type_error(path, "true or false", v);
  return v.get<bool>();
}

std::string as_string(const nlohmann::json& v, const std::string& path) {
  if (!v.is_string()) type_error(path, "a string", v);
  std::string s = v.get<std::string>();
  if (s.empty()) fail(path, "must not be empty");
  return s;
}

void check_array(const nlohmann::json& v, const std::string& path, std::size_t min_size) {
  if (!v.is_array()) type_error(path, "an array", v);
  if (v.size() < min_size) fail(path, "needs at least " + std::to_string(min_size) + " entries");
}

std::size_t as_choice(const nlohmann::json& v, const std::string& path, const std::vector<std::string_view>& names) {
  const std::string s = as_string(v, path);
  for (std::size_t i = 0; i < names.size(); ++i)
    if (s == names[i]) return i;
  std::string list;
  for (const auto name : names) list += (list.empty() ? "" : ", ") + std::string(name);
  fail(path, "unknown value \"" + s + "\" (use " + list + ")");
}

ObjectReader::ObjectReader(const nlohmann::json& json, std::string path, std::string document)
    : json_(json), path_(std::move(path)) {
  if (!json_.is_object()) type_error(path_.empty() ? document : path_, "an object", json_);
}

const nlohmann::json* ObjectReader::find(std::string_view key) {
  known_.emplace_back(key);
  const auto it = json_.find(key);
  return it == json_.end() ? nullptr : &*it;
}

const nlohmann::json& ObjectReader::require(std::string_view key) {
  const nlohmann::json* v = find(key);
  if (v == nullptr) fail(path_of(key), "required key is missing");
  return *v;
}

std::string ObjectReader::string_or(std::string_view key, std::string fallback) {
  const nlohmann::json* v = find(key);
  return v ? as_string(*v, path_of(key)) : fallback;
}

bool ObjectReader::boolean_or(std::string_view key, bool fallback) {
  const nlohmann::json* v = find(key);
  return v ? as_bool(*v, path_of(key)) : fallback;
}

void ObjectReader::finish() const {
  for (const auto& [key, value] : json_.items()) {
    if (std::find(known_.begin(), known_.end(), key) != known_.end()) continue;
    std::vector<std::string> sorted = known_;
    std::sort(sorted.begin(), sorted.end());
    sorted.erase(std::unique(sorted.begin(), sorted.end()), sorted.end());
    std::string list;
    for (const auto& k : sorted) list += (list.empty() ? "" : ", ") + k;
    fail(path_of(key), "unknown key (known here: " + list + ")");
  }
}

}  // namespace knoblab::jsonread
