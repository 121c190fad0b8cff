// GpiodLines without GPIO hardware: chip discovery and every error path a
// technician can hit before a line is ever requested.
#include "knoblab/hal/gpiod_lines.hpp"

#include <cerrno>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "test_util.hpp"

namespace knoblab::hal {
namespace {

using test::error_of;
using test::TempDir;
using ::testing::AllOf;
using ::testing::ElementsAre;
using ::testing::HasSubstr;

TEST(GpioChips, ListsChipsInNumericOrderAndIgnoresOtherFiles) {
  TempDir dir;
  for (const char* name : {"gpiochip10", "gpiochip2", "gpiochip0", "gpiochipX", "gpiochip", "ttyS0"}) dir.touch(name);
  const auto p = [&](const char* name) { return (dir.path() / name).string(); };
  EXPECT_THAT(list_gpio_chips(dir.path()), ElementsAre(p("gpiochip0"), p("gpiochip2"), p("gpiochip10")));
}

TEST(GpioChips, AMissingDirectoryHasNoChips) {
  EXPECT_TRUE(list_gpio_chips("/nonexistent-knoblab-dir").empty());
}

TEST(GpioChips, AutoWithNoChipsSaysNoneWereFound) {
  TempDir dir;
  const std::string msg = error_of<std::runtime_error>([&] { locate_line("auto", "ESTOP_N", "estop", dir.path()); });
  EXPECT_THAT(msg, AllOf(HasSubstr("\"ESTOP_N\" (estop) not found"), HasSubstr("no GPIO chips"),
                         HasSubstr(dir.path().string())));
}

TEST(GpioChips, AutoListsEveryChipItSearched) {
  TempDir dir;
  dir.touch("gpiochip0");  // a regular file, not a character device
  const std::string msg = error_of<std::runtime_error>([&] { locate_line("auto", "FOOTSW", "capture_button", dir.path()); });
  EXPECT_THAT(msg, AllOf(HasSubstr("\"FOOTSW\" (capture_button) not found; searched"),
                         HasSubstr((dir.path() / "gpiochip0").string()),
                         HasSubstr("not a GPIO chip character device")));
}

TEST(GpioChips, AMissingChipPathIsNamed) {
  EXPECT_EQ(error_of<std::runtime_error>([] { locate_line("/dev/gpiochip99", "AMP_EN", "amp_enable"); }),
            "cannot open GPIO chip /dev/gpiochip99: No such file or directory");
}

TEST(GpioChips, ARegularFileIsNotAChip) {
  TempDir dir;
  const auto file = dir.touch("gpiochip0");
  EXPECT_EQ(error_of<std::runtime_error>([&] { locate_line(file.string(), "AMP_EN", "amp_enable"); }),
            "cannot open GPIO chip " + file.string() + ": not a GPIO chip character device");
}

TEST(GpioChips, PermissionDeniedComesWithAHint) {
  EXPECT_THAT(chip_open_error("/dev/gpiochip0", EACCES),
              AllOf(HasSubstr("cannot open GPIO chip /dev/gpiochip0: Permission denied"), HasSubstr("udev")));
}

TEST(GpiodLines, ANonexistentChipFailsConstructionWithItsPath) {
  GpiodLinesConfig c;
  c.chip = "/dev/gpiochip99";
  EXPECT_EQ(error_of<std::runtime_error>([&] { GpiodLines lines(c); }),
            "cannot open GPIO chip /dev/gpiochip99: No such file or directory");
}

TEST(GpiodLines, AutoWithNoChipsNamesTheFirstLineSought) {
  TempDir dir;
  GpiodLinesConfig c;
  c.device_dir = dir.path();
  EXPECT_THAT(error_of<std::runtime_error>([&] { GpiodLines lines(c); }),
              AllOf(HasSubstr("GPIO line \"AMP_EN\" (amp_enable) not found"), HasSubstr("no GPIO chips")));
}

}  // namespace
}  // namespace knoblab::hal
