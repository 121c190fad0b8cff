// Which axis a capture is (fit_data.hpp): from its metadata, as a CSV gives
// it (`# axis: linear`) or as the store keeps an imported CSV's comments
// (one `metadata` JSON object; a key given twice is an array).
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "knoblab/fit/fit_data.hpp"

namespace knoblab::fit {

namespace {

constexpr const char* kExpected = "expected rotary or linear";

// Every value the metadata gives `axis`, in order.
std::vector<std::string> axis_values(const interchange::Capture& c) {
  std::vector<std::string> out;
  for (const auto& [key, value] : c.metadata) {
    if (key == "axis") out.push_back(value);
    if (key != "metadata") continue;
    const nlohmann::json doc = nlohmann::json::parse(value, nullptr, false);
    if (!doc.is_object() || !doc.contains("axis")) continue;
    const nlohmann::json& a = doc.at("axis");
    for (const nlohmann::json& v : a.is_array() ? a : nlohmann::json::array({a})) {
      if (!v.is_string()) throw FitDataError("metadata 'axis' is " + v.dump() + ": " + kExpected);
      out.push_back(v.get<std::string>());
    }
  }
  return out;
}

}  // namespace

std::optional<Axis> capture_axis(const interchange::Capture& capture) {
  std::optional<Axis> axis;
  for (const std::string& value : axis_values(capture)) {
    const std::optional<Axis> a = parse_axis(value);
    if (!a) throw FitDataError("metadata 'axis' is '" + value + "': " + kExpected);
    if (axis && *axis != *a) throw FitDataError("metadata 'axis' is given as both rotary and linear");
    axis = a;
  }
  return axis;
}

Axis resolve_axis(const interchange::Capture& capture, std::optional<Axis> given) {
  const std::optional<Axis> said = capture_axis(capture);
  if (said && given && *said != *given) {
    throw FitDataError("the capture's metadata says 'axis: " + std::string(axis_name(*said)) + "', not " +
                       std::string(axis_name(*given)));
  }
  return said ? *said : given.value_or(Axis::Rotary);
}

}  // namespace knoblab::fit
