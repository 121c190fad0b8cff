#include "knoblab/study/participant.hpp"

#include <stdexcept>
#include <string>

namespace knoblab::study {

namespace {

bool allowed(char c) {
  return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '-' || c == '_';
}

// Why the code is refused, or empty when it is fine.
std::string problem(std::string_view code) {
  if (code.empty()) return "is empty";
  if (code.size() > kMaxParticipantCodeLength)
    return "is longer than " + std::to_string(kMaxParticipantCodeLength) + " characters";
  bool digit = false;
  for (const char c : code) {
    if (!allowed(c)) return "may hold only letters, digits, '-' and '_'";
    digit = digit || (c >= '0' && c <= '9');
  }
  if (!digit) return "has no digit: use a pseudonymous code such as P01, never a name";
  return {};
}

}  // namespace

bool is_valid_participant_code(std::string_view code) { return problem(code).empty(); }

void check_participant_code(std::string_view code) {
  const std::string why = problem(code);
  if (!why.empty()) throw std::invalid_argument("participant code \"" + std::string(code) + "\" " + why);
}

}  // namespace knoblab::study
