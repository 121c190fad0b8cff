#include "knoblab/hal/gpio_chips.hpp"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <system_error>

#include "gpiod_handles.hpp"

namespace knoblab::hal {

namespace {

using detail::GpiodPtr;

// "gpiochip12" → 12; anything else → -1.
long chip_number(const std::string& filename) {
  constexpr std::string_view prefix = "gpiochip";
  if (filename.size() <= prefix.size() || filename.compare(0, prefix.size(), prefix) != 0) return -1;
  long n = 0;
  for (std::size_t i = prefix.size(); i < filename.size(); ++i) {
    if (filename[i] < '0' || filename[i] > '9') return -1;
    n = n * 10 + (filename[i] - '0');
  }
  return n;
}

std::string quoted(std::string_view s) { return "\"" + std::string(s) + "\""; }

GpiodPtr<gpiod_chip> open_chip(const std::string& path) {
  GpiodPtr<gpiod_chip> chip(gpiod_chip_open(path.c_str()));
  if (!chip) throw std::runtime_error(chip_open_error(path, errno));
  return chip;
}

std::string chip_label(gpiod_chip* chip) {
  GpiodPtr<gpiod_chip_info> info(gpiod_chip_get_info(chip));
  return info ? gpiod_chip_info_get_label(info.get()) : "?";
}

// Offset of `name` on `chip`, or -1 when the chip has no such line.
int find_offset(gpiod_chip* chip, const std::string& path, const std::string& name) {
  errno = 0;
  const int offset = gpiod_chip_get_line_offset_from_name(chip, name.c_str());
  if (offset < 0 && errno != ENOENT)
    throw std::runtime_error("cannot read line names of GPIO chip " + path + ": " + std::strerror(errno));
  return offset;
}

}  // namespace

std::string open_failure_reason(int err) {
  switch (err) {
    case ENOTTY:
    case ENODEV: return "not a GPIO chip character device";
    case EACCES:
    case EPERM:
      return std::string(std::strerror(err)) +
             " (give the daemon's user access, e.g. the group owning it or a udev rule)";
    default: return std::strerror(err);
  }
}

std::string chip_open_error(std::string_view path, int err) {
  return "cannot open GPIO chip " + std::string(path) + ": " + open_failure_reason(err);
}

std::vector<std::string> list_gpio_chips(const std::filesystem::path& dir) {
  std::vector<std::pair<long, std::string>> found;
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(dir, ec)) {
    const long n = chip_number(entry.path().filename().string());
    if (n >= 0) found.emplace_back(n, entry.path().string());
  }
  std::sort(found.begin(), found.end());
  std::vector<std::string> paths;
  for (auto& f : found) paths.push_back(std::move(f.second));
  return paths;
}

LineLocation locate_line(std::string_view chip, std::string_view name, std::string_view role,
                         const std::filesystem::path& dir) {
  const std::string line_name(name);
  const std::string what = "GPIO line " + quoted(name) + " (" + std::string(role) + ")";
  if (line_name.empty()) throw std::runtime_error(what + ": empty line name");

  if (chip != "auto") {
    const std::string path(chip);
    const auto handle = open_chip(path);
    const int offset = find_offset(handle.get(), path, line_name);
    if (offset < 0)
      throw std::runtime_error(what + " not found on " + path + " [" + chip_label(handle.get()) + "]");
    return {path, static_cast<unsigned>(offset)};
  }

  // "auto": every chip is searched, so a name on two chips is an error, not a guess.
  const std::vector<std::string> chips = list_gpio_chips(dir);
  if (chips.empty())
    throw std::runtime_error(what + " not found: no GPIO chips (gpiochip*) in " + dir.string());
  std::vector<LineLocation> hits;
  std::string searched;
  for (const std::string& path : chips) {
    searched += (searched.empty() ? "" : ", ") + path;
    GpiodPtr<gpiod_chip> handle(gpiod_chip_open(path.c_str()));
    if (!handle) {
      searched += " (cannot open: " + open_failure_reason(errno) + ")";
      continue;
    }
    searched += " [" + chip_label(handle.get()) + "]";
    const int offset = find_offset(handle.get(), path, line_name);
    if (offset >= 0) hits.push_back({path, static_cast<unsigned>(offset)});
  }
  if (hits.empty()) throw std::runtime_error(what + " not found; searched " + searched);
  if (hits.size() > 1)
    throw std::runtime_error(what + " exists on both " + hits[0].chip + " and " + hits[1].chip +
                             "; set \"chip\" to choose");
  return hits.front();
}

}  // namespace knoblab::hal
