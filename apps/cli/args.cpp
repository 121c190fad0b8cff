#include "args.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <sstream>

namespace knoblab::cli {

namespace {

// The same metavar for the same option in every command.
const std::map<std::string, std::string>& usual_metavars() {
  static const std::map<std::string, std::string> m = {
      {"db", "FILE.sqlite"},  {"input", "FILE.csv"},    {"heldout", "FILE.csv"},
      {"capture", "ID"},      {"heldout-capture", "ID"}, {"out", "FILE.csv"},
      {"json", "OUT.json|-"}, {"report", "DIR"},         {"render-model", "OUT.json"},
      {"seconds", "S"},       {"rate", "HZ"},            {"knob", "NAME"},
      {"params", "FIT.json"}, {"socket", "PATH"},        {"timeout", "S"}};
  return m;
}

std::size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diag = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diag = up;
    }
  }
  return row[b.size()];
}

// "unknown option --inptu for 'fit'; did you mean --input?" or the list of options.
std::string unknown_option(const CommandSpec& spec, const std::string& name) {
  std::string msg = "unknown option --" + name + " for '" + spec.name + "'";
  std::vector<std::string> names;
  if (spec.input_file) names.push_back("input");
  for (const auto& o : spec.options) names.push_back(o.name);
  // A close misspelling (two edits at most) or an unfinished name is worth a guess.
  const std::string* best = nullptr;
  std::size_t best_d = 3;
  for (const auto& n : names) {
    const std::size_t d = n.rfind(name, 0) == 0 && !name.empty() ? 1 : edit_distance(name, n);
    if (d < best_d) best = &n, best_d = d;
  }
  if (best) return msg + "; did you mean --" + *best + "?";
  if (names.empty()) return msg + "; it takes none";
  msg += "; it takes";
  for (const auto& n : names) msg += " --" + n;
  return msg;
}

bool all_digits(const std::string& s) {
  return !s.empty() && std::all_of(s.begin(), s.end(), [](unsigned char c) { return std::isdigit(c); });
}

bool takes(const CommandSpec& spec, const std::string& option) {
  return std::any_of(spec.options.begin(), spec.options.end(),
                     [&](const OptionSpec& o) { return o.name == option; });
}

}  // namespace

std::string metavar(const OptionSpec& option) {
  if (!option.metavar.empty()) return option.metavar;
  const auto& usual = usual_metavars();
  if (auto it = usual.find(option.name); it != usual.end()) return it->second;
  std::string upper = option.name;
  for (char& c : upper) c = c == '-' ? '_' : static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return upper;
}

Args::Args(const CommandSpec& spec, const std::vector<std::string>& argv) : spec_(spec) {
  std::optional<std::string> input_option;
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
    const bool input_alias = !opt && spec.input_file && name == "input";
    if (!opt && !input_alias) throw UsageError(unknown_option(spec, name));
    const bool wants_value = input_alias || opt->takes_value;
    if (wants_value && !inline_value) {
      if (i + 1 >= argv.size()) throw UsageError("option --" + name + " needs a value");
      value = argv[++i];
    } else if (!wants_value && inline_value) {
      throw UsageError("option --" + name + " takes no value");
    }
    if (input_alias) input_option = value;
    else values_[name] = value;
  }
  if (help_ || version_) return;
  if (input_option) {
    if (!positionals_.empty())
      throw UsageError("give the input file once: '" + positionals_[0] + "' or --input " + *input_option +
                       ", not both");
    positionals_.insert(positionals_.begin(), *input_option);
  }
  if (positionals_.size() < spec.min_positionals)
    throw UsageError("'" + spec.name + "' needs " + spec.synopsis);
  if (positionals_.size() > spec.max_positionals) {
    const std::string& extra = positionals_[spec.max_positionals];
    std::string msg = "unexpected argument '" + extra + "'";
    // The usual slips: a capture id without --capture, a file without --input.
    if (all_digits(extra) && takes(spec, "capture")) msg += "; a capture id goes after --capture";
    else if (spec.max_positionals == 0 && takes(spec, "input")) msg += "; a file goes after --input";
    throw UsageError(msg);
  }
  if (spec.input_file && !positionals_.empty() && all_digits(positionals_[0]) &&
      !std::filesystem::exists(positionals_[0]) && takes(spec, "capture") && !values_.count("capture"))
    throw UsageError("no file '" + positionals_[0] + "'; for capture " + positionals_[0] +
                     " in a store say --capture " + positionals_[0] + " --db FILE.sqlite");
}

long long parse_id(const std::string& what, const std::string& text, const std::string& noun) {
  long long id = 0;
  auto [p, ec] = std::from_chars(text.data(), text.data() + text.size(), id);
  if (ec != std::errc() || p != text.data() + text.size() || id <= 0)
    throw UsageError(what + " must be " + (noun.empty() ? "an" : "a " + noun) + " id (a positive integer), got '" +
                     text + "'");
  return id;
}

std::optional<std::string> Args::input() const {
  if (!spec_.input_file || positionals_.empty()) return std::nullopt;
  return positionals_[0];
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
  if (spec.input_file) os << "\nThe input file may also be given as --input FILE.\n";
  if (!spec.options.empty()) os << "\noptions:\n";
  const auto line = [&os](std::string flag, const std::string& help) {
    constexpr std::size_t kWidth = 26;  // a longer flag gets a line of its own
    if (flag.size() < kWidth) flag.resize(kWidth, ' ');
    else flag += "\n" + std::string(kWidth, ' ');
    os << flag << " " << help << "\n";
  };
  for (const auto& o : spec.options) line("  --" + o.name + (o.takes_value ? " " + metavar(o) : ""), o.help);
  line("  --help", "this text");
  line("  --version", "knoblab's version");
  if (!spec.examples.empty()) {
    os << "\nexample" << (spec.examples.size() > 1 ? "s" : "") << ":\n";
    for (const auto& e : spec.examples) os << "  " << e << "\n";
  }
  return os.str();
}

}  // namespace knoblab::cli
