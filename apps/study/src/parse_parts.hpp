// The parts of parse_protocol that live in their own files: the factors and
// their levels (factors.cpp) and each kind's settings (kind_settings.cpp).
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "knoblab/study/protocol.hpp"

namespace knoblab::study::detail {

// Names that end up in file names, logs and the store: letters, digits,
// '-', '_' and '.', at most 64 characters.
void check_name(const std::string& name, const std::string& path);

// A finite number in [min, max], with the unit named in the message.
double in_range(const nlohmann::json& v, const std::string& path, double min, double max, std::string_view unit);

// The `factors` array. Throws ProtocolError.
std::vector<Factor> parse_factors(const nlohmann::json& v, const std::string& path);

// A factor named by a string value.
std::size_t factor_named(const Protocol& protocol, const nlohmann::json& v, const std::string& path);

// The section named after the protocol's kind; factors and stages are read.
KindSettings parse_kind_settings(const nlohmann::json& v, const std::string& path, const Protocol& protocol);

}  // namespace knoblab::study::detail
