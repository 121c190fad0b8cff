#include "knoblab/studyrun/export.hpp"

#include <algorithm>
#include <format>
#include <map>
#include <set>
#include <stdexcept>

#include <nlohmann/json.hpp>

namespace knoblab::studyrun {

namespace {

using nlohmann::json;

struct SessionTrials {
  store::StudySession session;
  std::vector<store::StudyTrial> trials;
};

std::vector<SessionTrials> load(store::Store& store, std::string_view study) {
  std::vector<SessionTrials> out;
  for (store::StudySession& s : store.study_sessions(study)) {
    auto trials = store.study_trials(s.session_id);
    out.push_back({std::move(s), std::move(trials)});
  }
  if (out.empty()) throw std::invalid_argument("the store has no session of study '" + std::string(study) + "'");
  for (const SessionTrials& s : out)
    if (s.session.protocol_sha256 != out.front().session.protocol_sha256)
      throw std::invalid_argument("the sessions of study '" + std::string(study) +
                                  "' ran different protocol files (participants " + out.front().session.participant +
                                  " and " + s.session.participant + "); export them apart");
  return out;
}

std::optional<double> micro(const json& score, const char* key) {
  if (!score.contains(key) || !score[key].is_number()) return std::nullopt;
  return score[key].get<double>() * 1e6;
}


std::string csv_number(double v) { return std::format("{}", v); }

std::string csv_field(const json& v) {
  if (v.is_null()) return "";
  if (v.is_boolean()) return v.get<bool>() ? "1" : "0";
  if (v.is_number_integer()) return std::to_string(v.get<long long>());
  if (v.is_number()) return csv_number(v.get<double>());
  std::string s = v.is_string() ? v.get<std::string>() : v.dump();
  if (s.find_first_of(",\"\n\r") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

}  // namespace

std::size_t rendering_factor(const study::Protocol& p) {
  const auto& s = std::get<study::PointingSettings>(p.settings);
  for (std::size_t f = 0; f < p.factors.size(); ++f)
    if (f != s.amplitude_factor && f != s.width_factor) return f;
  throw std::invalid_argument("the pointing protocol has no rendering factor besides amplitude and width");
}

study::Protocol stored_protocol(store::Store& store, std::string_view study) {
  return study::parse_protocol_text(load(store, study).front().session.protocol_json);
}

std::vector<study::PointingRow> pointing_rows(store::Store& store, std::string_view study) {
  const auto sessions = load(store, study);
  const study::Protocol p = study::parse_protocol_text(sessions.front().session.protocol_json);
  if (p.kind != study::Kind::Pointing)
    throw std::invalid_argument("study '" + std::string(study) + "' is a " + std::string(study::kind_name(p.kind)) +
                                " study, not pointing");
  const std::string rendering = p.factors[rendering_factor(p)].name;
  const std::string scale(study::scale_name(p.ratings.front().scale));
  std::vector<study::PointingRow> rows;
  for (const SessionTrials& s : sessions)
    for (const store::StudyTrial& t : s.trials) {
      const json condition = json::parse(t.condition_json);
      const json measures = json::parse(t.result_json);
      const json ratings = json::parse(t.ratings_json);
      const json bio = json::parse(t.biometrics_json);
      const json score = bio.value("score", json::object());
      for (const json& a : measures.at("acquisitions")) {
        if (!a.at("movement_time_s").is_number()) continue;  // never reached
        study::PointingRow r;
        r.participant = s.session.participant;
        r.session = 1;  // one session per participant and study
        r.block = static_cast<unsigned>(t.block);
        r.trial = static_cast<unsigned>(t.trial_index);
        r.practice = t.practice;
        r.stage = t.stage;
        r.rendering = condition.at(rendering).get<std::string>();
        r.amplitude_deg = a.at("amplitude_deg").get<double>();
        r.width_deg = a.at("width_deg").get<double>();
        r.acquisition = a.at("acquisition").get<unsigned>();
        r.direction = a.at("direction").get<int>();
        r.movement_time_s = a.at("movement_time_s").get<double>();
        r.endpoint_deg = a.at("endpoint_deg").get<double>();
        r.overshoot_deg = a.at("overshoot_deg").get<double>();
        r.rating = ratings.at(scale).get<int>();
        r.emg_uV = micro(score, "emg_V");
        r.sc_uS = micro(score, "sc_S");
        rows.push_back(std::move(r));
      }
    }
  return rows;
}

namespace {

// A trial's scalar measures and ratings flattened into named values, the
// names in the order they first appear: the CSV's columns and the report's
// keys. A measure that repeats a factor (the texture) has its column already.
struct Flat {
  const SessionTrials* session;
  const store::StudyTrial* trial;
  json measures = json::object(), ratings = json::object();
};

struct FlatTable {
  std::vector<Flat> rows;
  std::vector<std::string> measure_names, rating_names;
};

FlatTable flatten(const std::vector<SessionTrials>& sessions, const study::Protocol& p) {
  FlatTable t;
  auto put = [](json& values, std::vector<std::string>& names, const std::string& name, const json& v) {
    if (std::find(names.begin(), names.end(), name) == names.end()) names.push_back(name);
    values[name] = v;
  };
  for (const SessionTrials& s : sessions)
    for (const store::StudyTrial& tr : s.trials) {
      Flat& row = t.rows.emplace_back(Flat{&s, &tr});
      const json m = json::parse(tr.result_json);
      for (const auto& [k, v] : m.items())
        if (v.is_primitive() && !p.factor_index(k)) put(row.measures, t.measure_names, k, v);
      if (m.contains("sliders"))
        for (const auto& [k, v] : m["sliders"].items())
          if (v.is_primitive()) put(row.measures, t.measure_names, "slider_" + k, v);
      const json rated = json::parse(tr.ratings_json);
      for (const auto& [k, v] : rated.items()) {
        if (v.is_object())
          for (const auto& [axis, a] : v.items()) put(row.ratings, t.rating_names, k + "_" + axis, a);
        else
          put(row.ratings, t.rating_names, k, v);
      }
    }
  return t;
}

}  // namespace

std::vector<study::TrialRow> trial_rows(store::Store& store, std::string_view study) {
  const auto sessions = load(store, study);
  const study::Protocol p = study::parse_protocol_text(sessions.front().session.protocol_json);
  std::vector<study::TrialRow> out;
  for (const Flat& f : flatten(sessions, p).rows) {
    const store::StudyTrial& t = *f.trial;
    study::TrialRow r;
    r.participant = f.session->session.participant;
    r.block = static_cast<unsigned>(t.block);
    r.trial = static_cast<unsigned>(t.trial_index);
    r.practice = t.practice;
    const json condition = json::parse(t.condition_json);
    for (const study::Factor& factor : p.factors)
      if (condition.contains(factor.name) && condition[factor.name].is_string())
        r.levels[factor.name] = condition[factor.name].get<std::string>();
    // Booleans (timed_out, selected) are not quantities to average, and the
    // task's set-up (when the condition began, how long exploring lasts, the
    // list's start and target) is no outcome.
    static const std::set<std::string> set_up = {"onset_s", "exploration_s", "start_value", "target_value"};
    for (const auto& [k, v] : f.measures.items())
      if (v.is_number() && !set_up.contains(k)) r.measures[k] = v.get<double>();
    for (const auto& [k, v] : f.ratings.items())
      if (v.is_number()) r.ratings[k] = v.get<double>();
    const json score = json::parse(t.biometrics_json).value("score", json::object());
    r.emg_uV = micro(score, "emg_V");
    r.sc_uS = micro(score, "sc_S");
    out.push_back(std::move(r));
  }
  return out;
}

void write_trials_csv(std::ostream& out, store::Store& store, std::string_view study) {
  const auto sessions = load(store, study);
  const study::Protocol p = study::parse_protocol_text(sessions.front().session.protocol_json);
  const FlatTable table = flatten(sessions, p);
  out << "participant,session,block,trial,practice,stage";
  for (const study::Factor& f : p.factors) out << "," << f.name;
  out << ",started_unix,duration_s";
  for (const std::string& m : table.measure_names) out << "," << m;
  for (const std::string& r : table.rating_names) out << "," << r;
  out << ",emg_uV,sc_uS,capture_id\n";
  for (const Flat& row : table.rows) {
    const store::StudyTrial& t = *row.trial;
    const json condition = json::parse(t.condition_json);
    const json score = json::parse(t.biometrics_json).value("score", json::object());
    out << csv_field(row.session->session.participant) << ",1," << t.block << "," << t.trial_index << ","
        << (t.practice ? 1 : 0) << "," << csv_field(t.stage);
    for (const study::Factor& f : p.factors) out << "," << csv_field(condition.value(f.name, json()));
    out << "," << csv_number(t.started_unix) << "," << csv_number(t.ended_unix - t.started_unix);
    for (const std::string& k : table.measure_names) out << "," << csv_field(row.measures.value(k, json()));
    for (const std::string& k : table.rating_names) out << "," << csv_field(row.ratings.value(k, json()));
    const auto emg = micro(score, "emg_V"), sc = micro(score, "sc_S");
    out << "," << (emg ? csv_number(*emg) : "") << "," << (sc ? csv_number(*sc) : "") << ","
        << (t.capture_id ? std::to_string(*t.capture_id) : "") << "\n";
  }
}

}  // namespace knoblab::studyrun
