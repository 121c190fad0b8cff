#include "compare_side.hpp"

#include <cctype>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>

#include "capture_input.hpp"
#include "fit_run.hpp"
#include "knob_file.hpp"
#include "knoblab/interchange/csv.hpp"
#include "store_open.hpp"

namespace knoblab::cli {

namespace {

using nlohmann::ordered_json;

std::string read_text(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot open " + path.string());
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

bool looks_like_json(const std::string& text) {
  for (const char c : text)
    if (!std::isspace(static_cast<unsigned char>(c))) return c == '{';
  return false;
}

bool is_id(const std::string& s) {
  if (s.empty()) return false;
  for (const char c : s)
    if (!std::isdigit(static_cast<unsigned char>(c))) return false;
  return true;
}

model::ThesisModel<double> thesis_of(const sim::KnobParams& k) {
  model::ThesisModel<double> m;
  m.inertia = k.inertia;
  m.friction = k.friction;
  m.detents = k.detents;
  return m;
}

// A fit result, render model or model file: its params as written, with
// the fit's intervals where it has them; the stick band (thesis6 keeps it
// beside the params); a model file's effects as "effect.param".
CompareSide from_json(const std::string& text, const std::string& source) {
  CompareSide side;
  side.model = thesis_of(parse_knob_json(text, source).knob);  // checks the params
  const ordered_json j = ordered_json::parse(text);
  const bool model_file = j.contains("render") || j.contains("effects");
  side.origin = model_file ? "model file" : j.contains("ci95") ? "fit result" : "render model";
  const ordered_json none = ordered_json::object();
  const ordered_json& ci = j.contains("ci95") && j.at("ci95").is_object() ? j.at("ci95") : none;
  for (const auto& [name, value] : j.at("params").items()) {
    SideParam p{name, value.get<double>(), std::nullopt};
    if (ci.contains(name) && ci.at(name).is_array() && ci.at(name).size() == 2)
      p.ci95 = std::array<double, 2>{ci.at(name)[0].get<double>(), ci.at(name)[1].get<double>()};
    side.params.push_back(p);
  }
  if (j.contains("stick") && j.at("stick").is_object())
    for (const char* key : {"dv", "D_neg", "D_pos"})
      if (j.at("stick").contains(key)) side.params.push_back({key, j.at("stick").at(key).get<double>(), std::nullopt});
  if (j.contains("effects") && j.at("effects").is_array())
    for (const auto& e : j.at("effects"))
      for (const auto& [name, value] : e.at("params").items())
        side.params.push_back({e.at("effect").get<std::string>() + "." + name, value.get<double>(), std::nullopt});
  return side;
}

// Eq. 6 (or 14) fitted to the capture: values, intervals and the stick band.
CompareSide from_fit(const fit::FitResult& r) {
  CompareSide side;
  side.origin = "fitted now";
  for (std::size_t k = 0; k < r.names.size(); ++k) {
    SideParam p{std::string(r.names[k]), r.params[k], std::nullopt};
    if (r.fitted[k]) p.ci95 = r.ci95[k];
    side.params.push_back(p);
  }
  if (r.stick) {
    side.params.push_back({"dv", r.stick->dv, std::nullopt});
    side.params.push_back({"D_neg", r.stick->D_neg, std::nullopt});
    side.params.push_back({"D_pos", r.stick->D_pos, std::nullopt});
  }
  side.model = fit::thesis_model(r);
  return side;
}

CompareSide from_capture(const interchange::Capture& capture, const Args& args) {
  const FitRun run = fit_capture(capture, prep_options(args), {});
  CompareSide side = from_fit(run.result);
  side.data = run.data;
  return side;
}

// A capture in the store: its latest thesis6 fit when it has one, else fitted now.
CompareSide from_store(std::int64_t id, const Args& args) {
  store::Store db = open_store_to_read(args.require("db"));
  const auto info = db.capture_info(id);
  if (!info) throw std::runtime_error("no capture " + std::to_string(id) + " in " + *args.get("db"));
  const interchange::Capture capture = db.load_samples(id);
  const std::string label = "capture " + std::to_string(id) + (info->knob.empty() ? "" : " (" + info->knob + ")");
  std::optional<store::FitInfo> stored;
  for (const store::FitInfo& f : db.list_fits(id))
    if (f.model == "thesis6") stored = f;
  CompareSide side;
  if (stored) {
    side = from_json(stored->result, label + ", stored fit " + std::to_string(stored->id));
    side.origin = "stored fit " + std::to_string(stored->id);
    side.data = fit::prepare(capture, prep_options(args));
  } else {
    side = from_capture(capture, args);
  }
  side.label = label;
  return side;
}

}  // namespace

CompareSide read_side(const std::string& operand, const Args& args) {
  const std::filesystem::path path(operand);
  if (args.has("db") && is_id(operand) && !std::filesystem::exists(path))
    return from_store(std::stoll(operand), args);
  if (!std::filesystem::exists(path))
    throw UsageError("'" + operand + "' is no file" +
                     (is_id(operand) ? std::string(" (a capture id needs --db FILE)") : std::string()));
  const std::string text = read_text(path);
  CompareSide side = looks_like_json(text) ? from_json(text, operand) : from_capture(interchange::read_csv(path), args);
  side.label = path.filename().string();
  return side;
}

}  // namespace knoblab::cli
