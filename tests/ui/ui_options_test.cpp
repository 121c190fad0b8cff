// knoblab-ui's command line.
#include <gtest/gtest.h>

#include <stdexcept>

#include "ui_options.hpp"

namespace knoblab::ui {
namespace {

TEST(UiOptions, APanelSizeAndAScreenAreTakenAsGiven) {
  const UiOptions o = parse_ui_options({"--size", "1024x600", "--screen", "system", "--socket", "/tmp/s.sock"});
  EXPECT_EQ(o.width, 1024);
  EXPECT_EQ(o.height, 600);
  EXPECT_EQ(o.screen, "system");
  EXPECT_EQ(o.socket, "/tmp/s.sock");
  EXPECT_TRUE(o.supervise);
}

TEST(UiOptions, AMalformedSizeIsRefusedWithWhatItMustBe) {
  for (const char* bad : {"1024", "1024x", "x600", "10x10", "1024x600x2", "big"}) {
    try {
      parse_ui_options({"--size", bad});
      ADD_FAILURE() << bad << " was accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("WIDTHxHEIGHT"), std::string::npos) << e.what();
    }
  }
}

TEST(UiOptions, AnUnknownOptionOrAMissingValueIsRefused) {
  EXPECT_THROW(parse_ui_options({"--frobnicate"}), std::invalid_argument);
  EXPECT_THROW(parse_ui_options({"--socket"}), std::invalid_argument);
  EXPECT_THROW(parse_ui_options({"--wait", "-1"}), std::invalid_argument);
}

}  // namespace
}  // namespace knoblab::ui
