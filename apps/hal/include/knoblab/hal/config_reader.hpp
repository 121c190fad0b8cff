// Reading one JSON object of configuration with errors that name the key's
// full path ("daq.torque.channel: …"). Keys nobody asked about are rejected
// by finish(), so a typo ("chanel") fails loudly instead of using a default.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

namespace knoblab::hal::detail {

class ConfigReader {
 public:
  // Throws ConfigError unless `json` is an object.
  ConfigReader(const nlohmann::json& json, std::string path);

  bool has(std::string_view key);
  const nlohmann::json& value(std::string_view key);  // required
  const nlohmann::json* find(std::string_view key);   // optional

  std::string string(std::string_view key);
  std::string string_or(std::string_view key, std::string fallback);
  double number(std::string_view key);
  double number_or(std::string_view key, double fallback);
  unsigned uint(std::string_view key);
  std::optional<unsigned> optional_uint(std::string_view key);
  std::uint64_t uint64_or(std::string_view key, std::uint64_t fallback);
  bool boolean_or(std::string_view key, bool fallback);
  ConfigReader object(std::string_view key);

  std::string path_of(std::string_view key) const;
  const std::string& path() const { return path_; }
  [[noreturn]] void fail(std::string_view key, std::string_view message) const;
  // Throws ConfigError for any key not asked about, listing the known ones.
  void finish() const;

 private:
  const nlohmann::json& json_;
  std::string path_;
  std::vector<std::string> known_;
};

// Type checks for a value found elsewhere (array elements, string-or-object).
double as_number(const nlohmann::json& v, const std::string& path);
unsigned as_uint(const nlohmann::json& v, const std::string& path);
std::string as_string(const nlohmann::json& v, const std::string& path);

}  // namespace knoblab::hal::detail
