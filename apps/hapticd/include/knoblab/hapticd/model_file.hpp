// A model file as load_model's arguments (docs/protocol.md §7), for
// `hapticd --model FILE` and `knoblab ctl load_model FILE`:
//   {"model": "render4", "params": {…}}         knoblab fit --render-model
//   {"model": "thesis6", …, "render": {…},      knoblab discrepancy --model-out
//    "effects": [{"effect": ID, "params": {…}}, …]}   (docs/discrepancy.md)
// The render model's params become the arguments; the effects the renderer
// renders (model/effect_set.hpp) go into their "effects" under the same
// parameter names, the effect table's (model/effect_table.hpp), checked
// against it as simulate checks them (values derived beside a parameter,
// such as cycles_per_rev, are dropped). Effects it cannot render are refused, each named with
// why, as is a fit's result JSON (thesis6 with no "render"). The arguments
// are not checked here: the protocol's schema does that where they arrive.
#pragma once

#include <filesystem>
#include <stdexcept>
#include <string>

#include <nlohmann/json.hpp>

namespace knoblab::hapticd {

struct ModelFileError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// `source` names the file in messages. Throws ModelFileError.
nlohmann::json load_model_args(const nlohmann::json& file, const std::string& source);
nlohmann::json read_model_file_args(const std::filesystem::path& path);

}  // namespace knoblab::hapticd
