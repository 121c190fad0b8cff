// validate_args: walks one ObjectSchema of the table; every check is driven
// by the ArgSpec, none is specific to a command.
#include <cmath>
#include <cstdio>
#include <cstdint>
#include <limits>
#include <string>

#include <nlohmann/json.hpp>

#include "knoblab/control/schema.hpp"
#include "number_text.hpp"

namespace knoblab::control {

using nlohmann::json;

namespace {

std::string json_type_name(const json& j) {
  switch (j.type()) {
    case json::value_t::null: return "null";
    case json::value_t::boolean: return "a boolean";
    case json::value_t::number_integer:
    case json::value_t::number_unsigned: return "an integer";
    case json::value_t::number_float: return "a non-integer number";
    case json::value_t::string: return "a string";
    case json::value_t::array: return "an array";
    case json::value_t::object: return "an object";
    default: return "an unsupported value";
  }
}

std::string quoted_list(std::span<const std::string_view> names) {
  std::string out;
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (i > 0) out += i + 1 == names.size() ? " or " : ", ";
    out += '\'';
    out += names[i];
    out += '\'';
  }
  return out;
}

std::string range_text(Range r) {
  return "[" + detail::number_text(r.lo) + ", " + detail::number_text(r.hi) + "]";
}

bool in_range(double v, Range r) { return v >= r.lo && v <= r.hi; }

// Integers arrive as int64 or uint64; anything above int64 is out of every range.
std::optional<std::int64_t> as_int64(const json& j) {
  if (j.is_number_unsigned()) {
    const auto u = j.get<std::uint64_t>();
    if (u > static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max())) return std::nullopt;
    return static_cast<std::int64_t>(u);
  }
  return j.get<std::int64_t>();
}

bool is_choice(const json& j, std::span<const std::string_view> choices) {
  if (!j.is_string()) return false;
  const auto& s = j.get_ref<const std::string&>();
  for (const auto c : choices)
    if (c == s) return true;
  return false;
}

using Problem = std::optional<ArgProblem>;

Problem problem(const std::string& key, std::string text) { return ArgProblem{key, std::move(text)}; }

Problem check_integer(const std::string& key, const json& j, Range r, const char* what) {
  if (!j.is_number_integer()) return problem(key, std::string(what) + " must be an integer (got " + json_type_name(j) + ")");
  const auto v = as_int64(j);
  if (!v || !in_range(static_cast<double>(*v), r))
    return problem(key, std::string(what) + " must be in " + range_text(r) + " (got " + j.dump() + ")");
  return std::nullopt;
}

Problem check_size(const std::string& key, std::size_t n, Range r, const char* unit) {
  if (!in_range(static_cast<double>(n), r))
    return problem(key, std::string("must have ") + detail::number_text(r.lo) + " to " +
                            detail::number_text(r.hi) + " " + unit + " (got " + std::to_string(n) + ")");
  return std::nullopt;
}

Problem validate_object(const json& obj, const ObjectSchema& schema, const std::string& prefix);

// Every text the protocol takes is one line: it ends up in the store, in
// listings and in CSV metadata, where a tab or a newline would garble them.
// (The JSON parser has already refused invalid UTF-8.)
Problem check_text(const std::string& key, const std::string& s, Range size) {
  for (std::size_t i = 0; i < s.size(); ++i)
    if (const auto c = static_cast<unsigned char>(s[i]); c < 0x20 || c == 0x7f) {
      char hex[8];
      std::snprintf(hex, sizeof hex, "0x%02x", c);
      return problem(key, "must be one line of text: byte " + std::to_string(i + 1) + " is a control character (" +
                              hex + ")");
    }
  return check_size(key, s.size(), size, "bytes");
}

Problem validate_value(const std::string& key, const json& j, const ArgSpec& spec) {
  switch (spec.type) {
    case ArgType::integer: return check_integer(key, j, spec.range, "value");
    case ArgType::number:
      if (!j.is_number()) return problem(key, "must be a number (got " + json_type_name(j) + ")");
      if (const double v = j.get<double>(); !std::isfinite(v) || !in_range(v, spec.range))
        return problem(key, "must be in " + range_text(spec.range) +
                                (spec.unit.empty() ? "" : " " + std::string(spec.unit)) + " (got " + j.dump() + ")");
      return std::nullopt;
    case ArgType::string:
      if (!j.is_string()) return problem(key, "must be a string (got " + json_type_name(j) + ")");
      return check_text(key, j.get_ref<const std::string&>(), spec.size);
    case ArgType::boolean:
      if (!j.is_boolean()) return problem(key, "must be true or false (got " + json_type_name(j) + ")");
      return std::nullopt;
    case ArgType::choice:
      if (!is_choice(j, spec.choices)) return problem(key, "must be one of " + quoted_list(spec.choices));
      return std::nullopt;
    case ArgType::label:
      if (j.is_number_integer()) return check_integer(key, j, {-9.2e18, 9.2e18}, "value");
      if (!j.is_string()) return problem(key, "must be a string or an integer (got " + json_type_name(j) + ")");
      return check_text(key, j.get_ref<const std::string&>(), spec.size);
    case ArgType::integer_list:
      if (!j.is_array()) return problem(key, "must be an array of integers (got " + json_type_name(j) + ")");
      if (auto p = check_size(key, j.size(), spec.size, "elements")) return p;
      for (const auto& e : j)
        if (auto p = check_integer(key, e, spec.range, "every element")) return p;
      return std::nullopt;
    case ArgType::choice_list:
      if (!j.is_array()) return problem(key, "must be an array of strings (got " + json_type_name(j) + ")");
      if (auto p = check_size(key, j.size(), spec.size, "elements")) return p;
      for (const auto& e : j)
        if (!is_choice(e, spec.choices)) return problem(key, "every element must be one of " + quoted_list(spec.choices));
      return std::nullopt;
    case ArgType::number_list:
      if (!j.is_array()) return problem(key, "must be an array of numbers (got " + json_type_name(j) + ")");
      if (auto p = check_size(key, j.size(), spec.size, "elements")) return p;
      for (const auto& e : j) {
        if (!e.is_number()) return problem(key, "every element must be a number (got " + json_type_name(e) + ")");
        if (const double v = e.get<double>(); !std::isfinite(v) || !in_range(v, spec.range))
          return problem(key, "every element must be in " + range_text(spec.range) + " (got " + e.dump() + ")");
      }
      return std::nullopt;
    case ArgType::object:
      if (!j.is_object()) return problem(key, "must be an object (got " + json_type_name(j) + ")");
      return validate_object(j, *spec.object, key + ".");
    case ArgType::object_list:
      if (!j.is_array()) return problem(key, "must be an array of objects (got " + json_type_name(j) + ")");
      if (auto p = check_size(key, j.size(), spec.size, "elements")) return p;
      for (std::size_t i = 0; i < j.size(); ++i) {
        const std::string item = key + "[" + std::to_string(i) + "]";
        if (!j[i].is_object()) return problem(item, "must be an object (got " + json_type_name(j[i]) + ")");
        if (auto p = validate_object(j[i], *spec.object, item + ".")) return p;
      }
      return std::nullopt;
  }
  return problem(key, "has an unknown type in the schema");
}

const ArgSpec* find_spec(const ObjectSchema& schema, std::string_view key) {
  for (const auto& a : schema.args)
    if (a.key == key) return &a;
  return nullptr;
}

Problem check_group(const json& obj, const GroupRule& g, const std::string& prefix) {
  std::size_t present = 0;
  std::string_view first_missing, first_present;
  for (const auto k : g.keys) {
    if (obj.contains(k)) {
      ++present;
      if (first_present.empty()) first_present = k;
    } else if (first_missing.empty()) {
      first_missing = k;
    }
  }
  switch (g.kind) {
    case GroupRule::Kind::all_or_none:
      if (present != 0 && present != g.keys.size())
        return problem(prefix + std::string(first_missing),
                       "is required together with " + quoted_list(g.keys) + " (all or none)");
      break;
    case GroupRule::Kind::exactly_one:
      if (present != 1)
        return problem(prefix + std::string(present == 0 ? g.keys.front() : first_present),
                       "exactly one of " + quoted_list(g.keys) + " is required (got " + std::to_string(present) + ")");
      break;
    case GroupRule::Kind::at_least_one:
      if (present == 0)
        return problem(prefix + std::string(g.keys.front()), "at least one of " + quoted_list(g.keys) + " is required");
      break;
  }
  return std::nullopt;
}

Problem validate_object(const json& obj, const ObjectSchema& schema, const std::string& prefix) {
  // Unknown keys are refused: a typo must not be ignored silently.
  for (const auto& [k, v] : obj.items())
    if (!find_spec(schema, k)) return problem(prefix + k, "is not an argument of this command");
  for (const auto& spec : schema.args) {
    const auto it = obj.find(spec.key);
    if (it == obj.end()) {
      if (spec.required) return problem(prefix + std::string(spec.key), "is required");
      continue;
    }
    if (auto p = validate_value(prefix + std::string(spec.key), *it, spec)) return p;
  }
  for (const auto& g : schema.groups)
    if (auto p = check_group(obj, g, prefix)) return p;
  return std::nullopt;
}

}  // namespace

std::optional<ArgProblem> validate_args(const json& args, const ObjectSchema& schema) {
  if (!args.is_object()) return ArgProblem{"args", "must be an object (got " + json_type_name(args) + ")"};
  return validate_object(args, schema, "");
}

}  // namespace knoblab::control
