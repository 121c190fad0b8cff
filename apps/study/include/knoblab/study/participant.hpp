// Participants are known to the appliance only by a pseudonymous code such
// as "P01": it seeds their plan and labels their trials, and a name must
// never take its place.
#pragma once

#include <cstddef>
#include <string_view>

namespace knoblab::study {

inline constexpr std::size_t kMaxParticipantCodeLength = 16;

// A code is 1–16 letters, digits, '-' or '_', with at least one digit: names
// have none, so a name typed where the code belongs is refused.
bool is_valid_participant_code(std::string_view code);

// Throws std::invalid_argument saying what is wrong with the code.
void check_participant_code(std::string_view code);

}  // namespace knoblab::study
