#include "knoblab/studyrun/slider_tags.hpp"

#include <stdexcept>

#include <nlohmann/json.hpp>

namespace knoblab::studyrun {

namespace {

constexpr const char* kTag = "slider";

// The four terms a matching slider can set (protocol.hpp's Slider).
bool is_slider_parameter(std::string_view p) {
  return p == "M_acc" || p == "B_vel" || p == "A_pos" || p == "detents_per_rev";
}

std::string trimmed(const std::string& s) {
  const auto first = s.find_first_not_of(" \t\r\n");
  if (first == std::string::npos) return {};
  return s.substr(first, s.find_last_not_of(" \t\r\n") - first + 1);
}

}  // namespace

void save_slider_tags(store::Store& store, std::int64_t session_id, const SliderTags& tags) {
  for (const auto& [parameter, words] : tags)
    if (!is_slider_parameter(parameter))
      throw std::invalid_argument("slider tags: \"" + parameter +
                                  "\" is no slider (M_acc, B_vel, A_pos, detents_per_rev)");
  for (const auto& [parameter, words] : tags) {
    const std::string text = trimmed(words);
    if (text.empty()) continue;
    store.add_study_note({.session_id = session_id,
                          .trial_index = std::nullopt,
                          .text = text,
                          .tags_json = nlohmann::json::array({kTag, parameter}).dump()});
  }
}

std::optional<std::string> slider_tag_parameter(const store::StudyNote& note) {
  if (note.trial_index) return std::nullopt;  // about a trial: an ordinary note
  const nlohmann::json tags = nlohmann::json::parse(note.tags_json, nullptr, false);
  if (!tags.is_array() || tags.size() != 2 || tags[0] != kTag || !tags[1].is_string()) return std::nullopt;
  const std::string parameter = tags[1].get<std::string>();
  if (!is_slider_parameter(parameter)) return std::nullopt;
  return parameter;
}

SliderTags session_slider_tags(store::Store& store, std::int64_t session_id) {
  SliderTags out;
  for (const store::StudyNote& note : store.study_notes(session_id))  // by note_id: the newest last
    if (const auto parameter = slider_tag_parameter(note)) out[*parameter] = note.text;
  return out;
}

std::map<std::string, SliderTags> slider_tags(store::Store& store, std::string_view study) {
  std::map<std::string, SliderTags> out;
  for (const store::StudySession& session : store.study_sessions(study)) {
    SliderTags tags = session_slider_tags(store, session.session_id);
    if (tags.empty()) continue;
    for (auto& [parameter, words] : tags) out[session.participant][parameter] = std::move(words);
  }
  return out;
}

}  // namespace knoblab::studyrun
