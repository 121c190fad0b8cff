// A small command-line parser: --name VALUE, --name=VALUE, --flag, and
// positionals. Each subcommand declares its options; anything else is an error.
// One grammar for every command: the main input file is the first positional or
// --input, every value option has a metavar, every --help ends with examples.
#pragma once

#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace knoblab::cli {

struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct OptionSpec {
  std::string name;  // without the leading dashes
  bool takes_value;
  std::string help;
  std::string metavar = {};  // shown after --name; empty: the usual one for the name
};

struct CommandSpec {
  std::string name;
  std::string synopsis;  // e.g. "FILE.csv --db FILE"
  std::string summary;   // first line: the one-sentence summary `knoblab --help` lists
  std::vector<OptionSpec> options;
  std::size_t min_positionals = 0, max_positionals = 0;
  // The command reads one input file, as its first positional or as --input.
  bool input_file = false;
  std::vector<std::string> examples = {};  // command lines, shown at the end of --help
};

class Args {
 public:
  Args(const CommandSpec& spec, const std::vector<std::string>& argv);

  bool help() const { return help_; }
  bool version() const { return version_; }  // --version: every command takes it
  bool has(const std::string& name) const { return values_.count(name) != 0; }
  std::optional<std::string> get(const std::string& name) const;
  std::string require(const std::string& name) const;
  double number(const std::string& name, double fallback) const;
  long long integer(const std::string& name, long long fallback) const;
  const std::vector<std::string>& positionals() const { return positionals_; }
  // The input file (first positional or --input) of a command that takes one.
  std::optional<std::string> input() const;

 private:
  const CommandSpec& spec_;
  bool help_ = false, version_ = false;
  std::map<std::string, std::string> values_;
  std::vector<std::string> positionals_;
};

// A store id (capture, fit, result): a positive integer, else a UsageError
// naming `what` ("--capture", "CAPTURE", …) and, when given, the kind of id
// ("must be a fit id").
long long parse_id(const std::string& what, const std::string& text, const std::string& noun = "");

// The metavar --help shows for an option: its own, else the usual one for its name.
std::string metavar(const OptionSpec& option);

std::string usage(const CommandSpec& spec);

}  // namespace knoblab::cli
