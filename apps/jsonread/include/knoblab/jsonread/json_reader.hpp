// Reading a JSON document (a study protocol, a prototyper design) with errors
// that name the value's full path, array indices included
// ("factors[1].levels[0].parameters.B_vel"): every problem is a PathError. An
// ObjectReader remembers the keys it was asked about; finish() rejects the
// rest, so a misspelt key is an error rather than a silent default.
#pragma once

#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

namespace knoblab::jsonread {

// A problem at one place in a document.
class PathError : public std::invalid_argument {
 public:
  // what() is "PATH: MESSAGE" (just MESSAGE for the document as a whole).
  PathError(std::string path, std::string message);
  // The same error, found in `file`: what() is "FILE: PATH: MESSAGE".
  PathError in_file(const std::string& file) const;

  const std::string& path() const { return path_; }        // e.g. "factors[1].levels[0].name"
  const std::string& message() const { return message_; }  // without the path

 private:
  PathError(const std::string& what, std::string path, std::string message);
  std::string path_;
  std::string message_;
};

[[noreturn]] void fail(const std::string& path, const std::string& message);  // throws PathError

std::string member_path(const std::string& path, std::string_view key);  // "a.b", or "b" at the top
std::string element_path(const std::string& path, std::size_t index);    // "a[3]"

double as_number(const nlohmann::json& v, const std::string& path);  // finite
std::uint64_t as_uint64(const nlohmann::json& v, const std::string& path);
std::size_t as_count(const nlohmann::json& v, const std::string& path, std::size_t min, std::size_t max);
bool as_bool(const nlohmann::json& v, const std::string& path);
std::string as_string(const nlohmann::json& v, const std::string& path);  // non-empty
void check_array(const nlohmann::json& v, const std::string& path, std::size_t min_size);

// One of `names`, as its position there; the message lists them.
std::size_t as_choice(const nlohmann::json& v, const std::string& path, const std::vector<std::string_view>& names);

class ObjectReader {
 public:
  // Fails unless an object; `document` names the whole (path "") in that message.
  ObjectReader(const nlohmann::json& json, std::string path, std::string document = "document");

  const nlohmann::json* find(std::string_view key);
  const nlohmann::json& require(std::string_view key);
  std::string path_of(std::string_view key) const { return member_path(path_, key); }
  const std::string& path() const { return path_; }

  std::string string(std::string_view key) { return as_string(require(key), path_of(key)); }
  std::string string_or(std::string_view key, std::string fallback);
  double number(std::string_view key) { return as_number(require(key), path_of(key)); }
  bool boolean(std::string_view key) { return as_bool(require(key), path_of(key)); }
  bool boolean_or(std::string_view key, bool fallback);

  // Fails on the first key of the object that nobody asked about.
  void finish() const;

 private:
  const nlohmann::json& json_;
  std::string path_;
  std::vector<std::string> known_;
};

}  // namespace knoblab::jsonread
