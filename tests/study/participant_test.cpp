// Participant codes are pseudonyms; anything that could be a name is refused.
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

#include "knoblab/study/participant.hpp"

namespace knoblab::study {
namespace {

TEST(ParticipantCodes, PseudonymousCodesAreAccepted) {
  for (const char* code : {"P01", "p1", "S3-P12", "novice_07", "9", "P0123456789ABCDE"})
    EXPECT_TRUE(is_valid_participant_code(code)) << code;
}

TEST(ParticipantCodes, NamesAndOddCharactersAreRefusedWithAReason) {
  for (const char* code : {"", "Alice", "JohnSmith", "P 01", "P01/2", "Zoë1", "P01.", "P0123456789ABCDEF"}) {
    EXPECT_FALSE(is_valid_participant_code(code)) << code;
    EXPECT_THROW(check_participant_code(code), std::invalid_argument) << code;
  }
  try {
    check_participant_code("Alice");
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("never a name"), std::string::npos) << e.what();
  }
}

TEST(ParticipantCodes, SixteenCharactersIsTheLongestCode) {
  EXPECT_TRUE(is_valid_participant_code(std::string(15, 'P') + "1"));
  EXPECT_FALSE(is_valid_participant_code(std::string(16, 'P') + "1"));
}

}  // namespace
}  // namespace knoblab::study
