// The words a participant gives each matching slider in the familiarization
// (thesis §3.4.1.3, Table 15: the novices' sticky notes, "weight",
// "pudding", "bump size", …), kept as the session's notes without a schema
// of their own: one note per slider, about the session (no trial), its text
// the participant's words, its tags ["slider", "<parameter>"]
// (docs/studies.md, "Slider tags"). A later note for the same slider
// replaces an earlier one, so a correction is a new note, never an edit.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <string_view>

#include "knoblab/store/store.hpp"

namespace knoblab::studyrun {

// Slider parameter (M_acc, B_vel, A_pos, detents_per_rev) → the words.
using SliderTags = std::map<std::string, std::string>;

// Keeps each slider's words as a note of the session, in the map's order.
// Words are trimmed; a slider whose words are blank is left out (nothing to
// keep). Throws std::invalid_argument for a parameter that is no slider's,
// before writing anything; store errors as they come (each note is its own
// transaction: a note written stays).
void save_slider_tags(store::Store& store, std::int64_t session_id, const SliderTags& tags);

// The slider a note gives words for, when it is a slider tag by the
// convention above; none for any other note.
std::optional<std::string> slider_tag_parameter(const store::StudyNote& note);

// A session's slider tags, the newest note per slider.
SliderTags session_slider_tags(store::Store& store, std::int64_t session_id);

// A study's slider tags: participant code → slider → words, over its
// sessions in the order they were opened.
std::map<std::string, SliderTags> slider_tags(store::Store& store, std::string_view study);

}  // namespace knoblab::studyrun
