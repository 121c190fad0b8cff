// The command reference of docs/protocol.md, rendered from the table.
#include <string>

#include "knoblab/control/schema.hpp"
#include "number_text.hpp"

namespace knoblab::control {

namespace {

std::string choices_text(std::span<const std::string_view> choices) {
  std::string out;
  for (std::size_t i = 0; i < choices.size(); ++i) {
    if (i > 0) out += ", ";
    out += '`';
    out += choices[i];
    out += '`';
  }
  return out;
}

std::string range_text(Range r) {
  return detail::number_text(r.lo) + " … " + detail::number_text(r.hi);
}

std::string constraint_text(const ArgSpec& a) {
  switch (a.type) {
    case ArgType::integer:
    case ArgType::number: return range_text(a.range);
    case ArgType::string:
    case ArgType::label: return range_text(a.size) + " bytes, one line";
    case ArgType::boolean: return "";
    case ArgType::choice: return choices_text(a.choices);
    case ArgType::integer_list: return range_text(a.size) + " elements, each " + range_text(a.range);
    case ArgType::choice_list: return range_text(a.size) + " of " + choices_text(a.choices);
    case ArgType::number_list: return range_text(a.size) + " elements, each " + range_text(a.range);
    case ArgType::object: return "see below";
    case ArgType::object_list: return range_text(a.size) + " elements, each as below";
  }
  return "";
}

void rows(std::string& out, const ObjectSchema& schema, const std::string& prefix) {
  for (const auto& a : schema.args) {
    out += "| `" + prefix + std::string(a.key) + "` | " + std::string(to_string(a.type)) + " | " +
           (a.required ? "yes" : "no") + " | " + constraint_text(a) + " | " + std::string(a.unit) +
           " | " + std::string(a.doc) + " |\n";
    if (a.type == ArgType::object) rows(out, *a.object, prefix + std::string(a.key) + ".");
    if (a.type == ArgType::object_list) rows(out, *a.object, prefix + std::string(a.key) + "[].");
  }
}

void group_lines(std::string& out, const ObjectSchema& schema, const std::string& prefix) {
  for (const auto& g : schema.groups) {
    std::string keys;
    for (std::size_t i = 0; i < g.keys.size(); ++i) keys += (i ? ", `" : "`") + prefix + std::string(g.keys[i]) + "`";
    switch (g.kind) {
      case GroupRule::Kind::all_or_none: out += "- all or none of " + keys + "\n"; break;
      case GroupRule::Kind::exactly_one: out += "- exactly one of " + keys + "\n"; break;
      case GroupRule::Kind::at_least_one: out += "- at least one of " + keys + "\n"; break;
    }
  }
  for (const auto& a : schema.args) {
    if (a.type == ArgType::object) group_lines(out, *a.object, prefix + std::string(a.key) + ".");
    if (a.type == ArgType::object_list) group_lines(out, *a.object, prefix + std::string(a.key) + "[].");
  }
}

}  // namespace

std::string_view to_string(ArgType type) noexcept {
  switch (type) {
    case ArgType::integer: return "integer";
    case ArgType::number: return "number";
    case ArgType::string: return "string";
    case ArgType::boolean: return "boolean";
    case ArgType::choice: return "choice";
    case ArgType::label: return "label";
    case ArgType::integer_list: return "integer list";
    case ArgType::choice_list: return "choice list";
    case ArgType::number_list: return "number list";
    case ArgType::object: return "object";
    case ArgType::object_list: return "object list";
  }
  return "?";
}

std::string schema_markdown() {
  std::string out;
  for (const auto& c : command_table()) {
    out += "### `" + std::string(to_string(c.command)) + "`\n\n";
    out += std::string(c.summary) + " — answered by the " +
           (handled_by_server(c.command) ? "server itself" : "daemon (CommandHandler)") + ".\n\n";
    if (c.args.args.empty()) {
      out += "No arguments (`args` may be omitted or `{}`).\n\n";
    } else {
      out += "| key | type | required | range | unit | meaning |\n";
      out += "|---|---|---|---|---|---|\n";
      rows(out, c.args, "");
      out += "\n";
      std::string groups;
      group_lines(groups, c.args, "");
      if (!groups.empty()) out += "Rules across keys:\n\n" + groups + "\n";
    }
    out += "Example: `{\"v\":1,\"id\":1,\"cmd\":\"" + std::string(to_string(c.command)) +
           "\",\"args\":" + std::string(c.example_args) + "}`\n\n";
  }
  return out;
}

}  // namespace knoblab::control
