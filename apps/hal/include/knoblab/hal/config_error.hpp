// Every configuration problem (bad JSON, unknown backend, missing or mistyped
// key) is a ConfigError whose message starts with the key's path, e.g.
// "daq.torque.channel: required key is missing".
#pragma once

#include <stdexcept>

namespace knoblab::hal {

class ConfigError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace knoblab::hal
