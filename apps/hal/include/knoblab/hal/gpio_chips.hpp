// Finding GPIO lines by name across /dev/gpiochip*. Setup time only
// (allocates, opens files); errors name the line and every chip searched.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace knoblab::hal {

struct LineLocation {
  std::string chip;  // device path
  unsigned offset = 0;
};

// The gpiochip* character devices in `dir`, in numeric order (2 before 10).
std::vector<std::string> list_gpio_chips(const std::filesystem::path& dir = "/dev");

// Finds line `name` on `chip`, or on each chip in `dir` when chip is "auto".
// `role` only labels the error. Throws std::runtime_error when the chip is
// missing, unreadable or not a GPIO chip, or no chip has the line.
LineLocation locate_line(std::string_view chip, std::string_view name, std::string_view role,
                         const std::filesystem::path& dir = "/dev");

// Why gpiod_chip_open failed, from its errno, with a hint for permissions.
std::string open_failure_reason(int err);
// "cannot open GPIO chip <path>: <reason>".
std::string chip_open_error(std::string_view path, int err);

}  // namespace knoblab::hal
