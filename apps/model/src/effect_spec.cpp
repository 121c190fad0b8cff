// Effect specs checked against the table (effect_table.hpp): from
// simulate's text, from a params object as discrepancy reports it, and
// reported values named by the table.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <stdexcept>

#include "knoblab/model/effect_table.hpp"

namespace knoblab::model {

namespace {

std::string joined(const std::vector<std::string_view>& names) {
  std::string out;
  for (const std::string_view n : names) out += (out.empty() ? "" : ", ") + std::string(n);
  return out;
}

[[noreturn]] void refuse(const EffectRow& r, const std::string& why) {
  throw std::invalid_argument("effect '" + std::string(r.id) + "'" + why);
}

// Where the values come from: a user's text asks for exactly what it names;
// a report carries derived values beside the parameters they come from.
enum class Source { Text, Report };

EffectSpec checked(const EffectRow& r, const NamedValues& given, Source source) {
  EffectSpec s;
  s.effect = r.effect;
  for (const auto& [name, v] : given) {
    const EffectParam* p = r.param(name);
    if (!p)
      refuse(r, " has no parameter '" + name + "' (its parameters: " + joined(r.settable_names()) + ")");
    if (!p->settable()) {
      if (source == Source::Report) continue;
      refuse(r, ": " + name + " is reported, not set (" + std::string(p->meaning) + ")" +
                    (p->other.empty() ? "" : "; give " + std::string(p->other)));
    }
    if (s.has(name)) refuse(r, ": " + name + " is given twice");
    if (!std::isfinite(v)) refuse(r, ": " + name + " is not a finite number");
    s.params.emplace_back(name, v);
  }
  // In the table's order, so that text() reads the same whatever order came in.
  const auto order = [&](const std::string& n) { return r.param(n) - r.params.data(); };
  std::sort(s.params.begin(), s.params.end(),
            [&](const auto& a, const auto& b) { return order(a.first) < order(b.first); });
  // A report's alternative beside its parameter only restates it.
  if (source == Source::Report) {
    for (const EffectParam& p : r.params) {
      if (p.role == Role::Alternative && s.has(p.other))
        std::erase_if(s.params, [&](const auto& kv) { return kv.first == p.name; });
    }
  }
  // Ranges first: their sentences are the more specific ones.
  for (const auto& [name, v] : s.params) {
    const EffectParam& p = *r.param(name);
    if (!p.in_range(v))
      refuse(r, ": " + name + " must be " + p.range_text() + (p.why.empty() ? "" : " (" + std::string(p.why) + ")") +
                    ", not " + shortest_number(v));
  }
  for (const EffectParam& p : r.params) {
    if (p.role == Role::Alternative && s.has(p.name) && s.has(p.other))
      refuse(r, ": give " + std::string(p.other) + " or " + std::string(p.name) + ", not both");
  }
  std::vector<std::string_view> sizes;
  bool sized = false;
  for (const EffectParam& p : r.params) {
    const bool gives_size = p.role == Role::Size || (p.role == Role::Alternative && r.param(p.other)->role == Role::Size);
    if (!gives_size) continue;
    sizes.push_back(p.name);
    sized = sized || s.has(p.name);
  }
  if (!sizes.empty() && !sized) {
    const bool one = sizes.size() == 1;
    refuse(r, " needs " + std::string(one ? "" : "one of ") + joined(sizes) + ": without " + (one ? "it" : "any") +
                  " the effect is zero (its parameters: " + joined(r.settable_names()) + "; e.g. '" +
                  std::string(r.id) + ":" + std::string(sizes.front()) + "=…')");
  }
  for (const EffectParam& p : r.params) {
    if (p.role == Role::Required && !s.has(p.name))
      refuse(r, " needs " + std::string(p.name) + " (" + std::string(p.meaning) + ")");
  }
  return s;
}

}  // namespace

bool EffectSpec::has(std::string_view name) const {
  return std::any_of(params.begin(), params.end(), [&](const auto& kv) { return kv.first == name; });
}

double EffectSpec::value(std::string_view name) const {
  const EffectParam* p = row().param(name);
  if (!p) throw std::logic_error("effect '" + std::string(id()) + "' has no parameter '" + std::string(name) + "'");
  for (const auto& [n, v] : params)
    if (n == name) return v;
  return p->fallback;
}

std::string EffectSpec::text() const {
  std::string out(id());
  char sep = ':';
  for (const auto& [k, v] : params) {
    out += sep + k + "=" + shortest_number(v);
    sep = ',';
  }
  return out;
}

EffectSpec parse_effect_spec(std::string_view one) {
  const std::size_t colon = one.find(':');
  const std::string id(one.substr(0, colon));
  const EffectRow* r = find_effect(id);
  if (!r) throw std::invalid_argument("unknown effect '" + id + "' (known: " + known_effect_ids() + ")");
  NamedValues given;
  std::string_view rest = colon == std::string_view::npos ? "" : one.substr(colon + 1);
  while (!rest.empty()) {
    const std::size_t comma = std::min(rest.find(','), rest.size());
    const std::string_view kv = rest.substr(0, comma);
    rest = comma < rest.size() ? rest.substr(comma + 1) : "";
    const std::size_t eq = kv.find('=');
    if (eq == std::string_view::npos) refuse(*r, ": expected name=value, got '" + std::string(kv) + "'");
    const std::string name(kv.substr(0, eq)), value(kv.substr(eq + 1));
    char* stop = nullptr;
    const double v = std::strtod(value.c_str(), &stop);
    if (value.empty() || *stop != '\0' || !std::isfinite(v))
      refuse(*r, ": '" + name + "' is not a number: '" + value + "'");
    given.emplace_back(name, v);
  }
  return checked(*r, given, Source::Text);
}

std::vector<EffectSpec> parse_effect_specs(std::string_view text) {
  std::vector<EffectSpec> out;
  std::size_t at = 0;
  while (at < text.size()) {
    const std::size_t end = std::min(text.find(';', at), text.size());
    const std::string_view one = text.substr(at, end - at);
    at = end + 1;
    if (!one.empty()) out.push_back(parse_effect_spec(one));
  }
  return out;
}

EffectSpec effect_from_params(std::string_view id, const NamedValues& params) {
  const EffectRow* r = find_effect(id);
  if (!r) throw std::invalid_argument("unknown effect '" + std::string(id) + "' (known: " + known_effect_ids() + ")");
  return checked(*r, params, Source::Report);
}

NamedValues reported_values(Effect e, const std::vector<double>& values) {
  const EffectRow& r = effect_row(e);
  NamedValues out;
  for (const EffectParam& p : r.params)
    if (p.reported) out.emplace_back(std::string(p.name), 0.0);
  if (out.size() != values.size())
    throw std::logic_error("effect '" + std::string(r.id) + "' reports " + std::to_string(out.size()) +
                           " values, not " + std::to_string(values.size()));
  for (std::size_t k = 0; k < out.size(); ++k) out[k].second = values[k];
  return out;
}

}  // namespace knoblab::model
