#include "knoblab/hal/config_reader.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "knoblab/hal/config_error.hpp"

namespace knoblab::hal::detail {

namespace {

[[noreturn]] void type_error(const std::string& path, std::string_view expected, const nlohmann::json& v) {
  throw ConfigError(path + ": expected " + std::string(expected) + ", got " + v.dump());
}

// Parsed text gives positive integers as unsigned, C++-built json as signed.
std::optional<std::uint64_t> non_negative(const nlohmann::json& v) {
  if (v.is_number_unsigned()) return v.get<std::uint64_t>();
  if (v.is_number_integer() && v.get<std::int64_t>() >= 0) return static_cast<std::uint64_t>(v.get<std::int64_t>());
  return std::nullopt;
}

}  // namespace

double as_number(const nlohmann::json& v, const std::string& path) {
  if (!v.is_number()) type_error(path, "a number", v);
  const double x = v.get<double>();
  if (!std::isfinite(x)) type_error(path, "a finite number", v);
  return x;
}

unsigned as_uint(const nlohmann::json& v, const std::string& path) {
  const auto n = non_negative(v);
  if (!n || *n > std::numeric_limits<unsigned>::max()) type_error(path, "a non-negative integer", v);
  return static_cast<unsigned>(*n);
}

std::string as_string(const nlohmann::json& v, const std::string& path) {
  if (!v.is_string()) type_error(path, "a string", v);
  return v.get<std::string>();
}

ConfigReader::ConfigReader(const nlohmann::json& json, std::string path) : json_(json), path_(std::move(path)) {
  if (!json_.is_object()) type_error(path_, "an object", json_);
}

std::string ConfigReader::path_of(std::string_view key) const { return path_ + "." + std::string(key); }

void ConfigReader::fail(std::string_view key, std::string_view message) const {
  throw ConfigError(path_of(key) + ": " + std::string(message));
}

const nlohmann::json* ConfigReader::find(std::string_view key) {
  known_.emplace_back(key);
  const auto it = json_.find(key);
  return it == json_.end() ? nullptr : &*it;
}

bool ConfigReader::has(std::string_view key) { return find(key) != nullptr; }

const nlohmann::json& ConfigReader::value(std::string_view key) {
  const nlohmann::json* v = find(key);
  if (v == nullptr) fail(key, "required key is missing");
  return *v;
}

std::string ConfigReader::string(std::string_view key) { return as_string(value(key), path_of(key)); }

std::string ConfigReader::string_or(std::string_view key, std::string fallback) {
  const nlohmann::json* v = find(key);
  return v ? as_string(*v, path_of(key)) : fallback;
}

double ConfigReader::number(std::string_view key) { return as_number(value(key), path_of(key)); }

double ConfigReader::number_or(std::string_view key, double fallback) {
  const nlohmann::json* v = find(key);
  return v ? as_number(*v, path_of(key)) : fallback;
}

unsigned ConfigReader::uint(std::string_view key) { return as_uint(value(key), path_of(key)); }

std::optional<unsigned> ConfigReader::optional_uint(std::string_view key) {
  const nlohmann::json* v = find(key);
  if (v == nullptr) return std::nullopt;
  return as_uint(*v, path_of(key));
}

std::uint64_t ConfigReader::uint64_or(std::string_view key, std::uint64_t fallback) {
  const nlohmann::json* v = find(key);
  if (v == nullptr) return fallback;
  const auto n = non_negative(*v);
  if (!n) type_error(path_of(key), "a non-negative integer", *v);
  return *n;
}

bool ConfigReader::boolean_or(std::string_view key, bool fallback) {
  const nlohmann::json* v = find(key);
  if (v == nullptr) return fallback;
  if (!v->is_boolean()) type_error(path_of(key), "true or false", *v);
  return v->get<bool>();
}

ConfigReader ConfigReader::object(std::string_view key) { return ConfigReader(value(key), path_of(key)); }

void ConfigReader::finish() const {
  for (const auto& [key, v] : json_.items()) {
    if (std::find(known_.begin(), known_.end(), key) != known_.end()) continue;
    std::vector<std::string> sorted = known_;
    std::sort(sorted.begin(), sorted.end());
    sorted.erase(std::unique(sorted.begin(), sorted.end()), sorted.end());
    std::string list;
    for (const auto& k : sorted) list += (list.empty() ? "" : ", ") + k;
    throw ConfigError(path_of(key) + ": unknown key (known here: " + list + ")");
  }
}

}  // namespace knoblab::hal::detail
