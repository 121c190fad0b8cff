// unique_ptr owners for libgpiod's C objects used at setup time.
#pragma once

#include <memory>

#include <gpiod.h>

namespace knoblab::hal::detail {

struct GpiodFree {
  void operator()(gpiod_chip* p) const { gpiod_chip_close(p); }
  void operator()(gpiod_chip_info* p) const { gpiod_chip_info_free(p); }
  void operator()(gpiod_line_info* p) const { gpiod_line_info_free(p); }
  void operator()(gpiod_line_settings* p) const { gpiod_line_settings_free(p); }
  void operator()(gpiod_line_config* p) const { gpiod_line_config_free(p); }
  void operator()(gpiod_request_config* p) const { gpiod_request_config_free(p); }
};

template <class T>
using GpiodPtr = std::unique_ptr<T, GpiodFree>;

}  // namespace knoblab::hal::detail
