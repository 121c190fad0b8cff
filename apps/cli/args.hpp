// A small command-line parser: --name VALUE, --name=VALUE, --flag, and
// positionals. Each subcommand declares its options; anything else is an error.
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
};

struct CommandSpec {
  std::string name;
  std::string synopsis;  // e.g. "FILE.csv --db FILE"
  std::string summary;
  std::vector<OptionSpec> options;
  std::size_t min_positionals = 0, max_positionals = 0;
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

 private:
  const CommandSpec& spec_;
  bool help_ = false, version_ = false;
  std::map<std::string, std::string> values_;
  std::vector<std::string> positionals_;
};

std::string usage(const CommandSpec& spec);

}  // namespace knoblab::cli
