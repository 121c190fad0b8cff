// The v1 command table: each command's arguments as data (key, type,
// required, range, unit). Validation, the docs' command reference and the
// tests all read this one table, so a new key is added in exactly one place.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include <nlohmann/json_fwd.hpp>

#include "knoblab/control/protocol.hpp"

namespace knoblab::control {

enum class ArgType : std::uint8_t {
  integer,       // JSON integer (1, not 1.0), value within `range`
  number,        // any JSON number, value within `range`
  string,        // byte length within `size`
  boolean,
  choice,        // one of `choices`
  label,         // opaque id: a string (byte length within `size`) or an integer
  integer_list,  // array, element count within `size`, each an integer within `range`
  choice_list,   // array, element count within `size`, each one of `choices`
  number_list,   // array, element count within `size`, each a number within `range`
  object,        // nested object validated against `object`
  object_list,   // array, element count within `size`, each validated against `object`
};

struct Range {
  double lo = 0.0, hi = 0.0;  // inclusive
};

struct ObjectSchema;

struct ArgSpec {
  std::string_view key;
  ArgType type = ArgType::number;
  bool required = false;
  Range range{};                                // integer, number, list elements
  Range size{};                                 // string, label, lists
  std::span<const std::string_view> choices{};  // choice, choice_list
  const ObjectSchema* object = nullptr;         // object, object_list elements
  std::string_view unit{};
  std::string_view doc{};
};

// Rules across keys of one object.
struct GroupRule {
  enum class Kind : std::uint8_t { all_or_none, exactly_one, at_least_one };
  Kind kind = Kind::all_or_none;
  std::span<const std::string_view> keys{};
};

struct ObjectSchema {
  std::span<const ArgSpec> args{};
  std::span<const GroupRule> groups{};
};

struct CommandSpec {
  Command command;
  ObjectSchema args;
  std::string_view summary;
  std::string_view example_args;  // JSON text of a valid "args" (tests, docs)
};

std::span<const CommandSpec> command_table() noexcept;
const CommandSpec& command_spec(Command command) noexcept;

std::string_view to_string(ArgType type) noexcept;

// Checks `args` against `schema`: no unknown keys, required keys present,
// types and ranges, then group rules. The first problem found, or nullopt.
struct ArgProblem {
  std::string key;      // path inside args, e.g. "pid.Kp" or "position[2].f_vel.x"
  std::string problem;  // e.g. "must be a number (got a string)"
};
std::optional<ArgProblem> validate_args(const nlohmann::json& args, const ObjectSchema& schema);

// The command reference section of docs/protocol.md, generated from the
// table (a test keeps the checked-in document in step).
std::string schema_markdown();

}  // namespace knoblab::control
