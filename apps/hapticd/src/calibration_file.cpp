#include "knoblab/hapticd/calibration_file.hpp"

#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "knoblab/interchange/atomic_file.hpp"

namespace knoblab::hapticd {

namespace {

using nlohmann::json;

double number(const json& obj, const char* key, const std::string& where) {
  if (!obj.contains(key)) throw std::runtime_error(where + ": \"" + key + "\" is missing");
  const json& v = obj.at(key);
  if (!v.is_number() || !std::isfinite(v.get<double>()))
    throw std::runtime_error(where + ": \"" + key + "\" must be a finite number");
  return v.get<double>();
}

void only_keys(const json& obj, std::initializer_list<const char*> known, const std::string& where) {
  for (const auto& [key, value] : obj.items()) {
    bool ok = false;
    for (const char* k : known) ok = ok || key == k;
    if (!ok) throw std::runtime_error(where + ": unknown key \"" + key + "\"");
  }
}

}  // namespace

CalibrationFile read_calibration_file(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read the calibration file " + path.string());
  std::stringstream text;
  text << in.rdbuf();
  const std::string where = path.string();
  const json j = json::parse(text.str(), nullptr, false);
  if (j.is_discarded()) throw std::runtime_error(where + ": not JSON");
  if (!j.is_object()) throw std::runtime_error(where + ": expected a JSON object");
  only_keys(j, {"counts_per_rev", "torque_Nm_per_V", "torque_offset_V", "C_cal", "gravity", "accepted"}, where);
  CalibrationFile f;
  capture::SensorCalibration& c = f.constants;
  c.counts_per_rev = number(j, "counts_per_rev", where);
  c.torque_Nm_per_V = number(j, "torque_Nm_per_V", where);
  c.torque_offset_V = number(j, "torque_offset_V", where);
  c.C_cal = number(j, "C_cal", where);
  if (!(c.counts_per_rev > 0.0)) throw std::runtime_error(where + ": \"counts_per_rev\" must be positive");
  if (!j.contains("gravity") || !j.at("gravity").is_object())
    throw std::runtime_error(where + ": \"gravity\" must be an object {\"A\", \"B\", \"C\", \"D\"}");
  const json& g = j.at("gravity");
  only_keys(g, {"A", "B", "C", "D"}, where + ": gravity");
  c.grav_A = number(g, "A", where + ": gravity");
  c.grav_B = number(g, "B", where + ": gravity");
  c.grav_C = number(g, "C", where + ": gravity");
  c.grav_D = number(g, "D", where + ": gravity");
  if (c.grav_B == 0.0) throw std::runtime_error(where + ": gravity \"B\" must not be 0 (Eq. 2 divides by it)");
  if (j.contains("accepted")) {
    if (!j.at("accepted").is_object()) throw std::runtime_error(where + ": \"accepted\" must be an object");
    f.accepted = j.at("accepted");
  }
  return f;
}

void write_calibration_file(const std::filesystem::path& path, const CalibrationFile& file) {
  json j = json::parse(file.constants.to_json());
  j["accepted"] = file.accepted;
  interchange::write_file_atomically(path, j.dump(2) + "\n");
}

}  // namespace knoblab::hapticd
