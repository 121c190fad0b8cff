#include "args.hpp"

#include <charconv>
#include <cmath>
#include <sstream>

namespace knoblab::cli {

Args::Args(const CommandSpec& spec, const std::vector<std::string>& argv) : spec_(spec) {
  for (std::size_t i = 0; i < argv.size(); ++i) {
    const std::string& a = argv[i];
    if (a == "--help" || a == "-h") {
      help_ = true;
      continue;
    }
    if (a == "--version") {
      version_ = true;
      continue;
    }
    if (a.rfind("--", 0) != 0 || a.size() == 2) {
      positionals_.push_back(a);
      continue;
    }
    std::string name = a.substr(2), value;
    const auto eq = name.find('=');
    const bool inline_value = eq != std::string::npos;
    if (inline_value) {
      value = name.substr(eq + 1);
      name = name.substr(0, eq);
    }
    const OptionSpec* opt = nullptr;
    for (const auto& o : spec.options)
      if (o.name == name) opt = &o;
    if (!opt) throw UsageError("unknown option --" + name + " for '" + spec.name + "'");
    if (opt->takes_value && !inline_value) {
      if (i + 1 >= argv.size()) throw UsageError("option --" + name + " needs a value");
      value = argv[++i];
    } else if (!opt->takes_value && inline_value) {
      throw UsageError("option --" + name + " takes no value");
    }
    values_[name] = value;
  }
  if (help_ || version_) return;
  if (positionals_.size() < spec.min_positionals)
    throw UsageError("'" + spec.name + "' needs " + spec.synopsis);
  if (positionals_.size() > spec.max_positionals)
    throw UsageError("unexpected argument '" + positionals_[spec.max_positionals] + "'");
}

std::optional<std::string> Args::get(const std::string& name) const {
  auto it = values_.find(name);
  if (it == values_.end()) return std::nullopt;
  return it->second;
}

std::string Args::require(const std::string& name) const {
  auto v = get(name);
  if (!v) throw UsageError("'" + spec_.name + "' needs --" + name);
  return *v;
}

double Args::number(const std::string& name, double fallback) const {
  auto v = get(name);
  if (!v) return fallback;
  double x = 0;
  auto [p, ec] = std::from_chars(v->data(), v->data() + v->size(), x);
  if (ec != std::errc() || p != v->data() + v->size() || !std::isfinite(x))
    throw UsageError("--" + name + ": not a number: '" + *v + "'");
  return x;
}

long long Args::integer(const std::string& name, long long fallback) const {
  auto v = get(name);
  if (!v) return fallback;
  long long x = 0;
  auto [p, ec] = std::from_chars(v->data(), v->data() + v->size(), x);
  if (ec != std::errc() || p != v->data() + v->size())
    throw UsageError("--" + name + ": not an integer: '" + *v + "'");
  return x;
}

std::string usage(const CommandSpec& spec) {
  std::ostringstream os;
  os << "usage: knoblab " << spec.name << (spec.synopsis.empty() ? "" : " ") << spec.synopsis
     << "\n\n" << spec.summary << "\n";
  if (!spec.options.empty()) os << "\noptions:\n";
  for (const auto& o : spec.options) {
    std::string flag = "  --" + o.name + (o.takes_value ? " VALUE" : "");
    if (flag.size() < 24) flag.resize(24, ' ');
    os << flag << " " << o.help << "\n";
  }
  os << "  --help                 this text\n";
  os << "  --version              knoblab's version\n";
  return os.str();
}

}  // namespace knoblab::cli
