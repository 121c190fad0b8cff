// Designs as documented JSON files (docs/designs.md), plain enough for other
// tools (Matlab, pandas) to read and write, as the thesis kept its tiles in
// "a text file format that is easily read and written by other software".
// Reading is strict: every problem is a jsonread::PathError naming the key
// ("channels.position.lines[0].tiles[2].to: …"), unknown keys included.
#pragma once

#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "knoblab/design/design.hpp"
#include "knoblab/jsonread/json_reader.hpp"

namespace knoblab::design {

inline constexpr const char* kDesignFormat = "knoblab-design";
inline constexpr int kDesignVersion = 1;

nlohmann::json to_json(const Design& d);

// A waveform as the file and hapticd's load_tiles both write a curve:
// {"x": [...], "y": [...], "periodic": true?}. Reading refuses, at `path`,
// anything that is not such a function; `noun` names it in the sentence
// ("the waveform", "the curve").
nlohmann::json waveform_json(const Waveform& w);
Waveform read_waveform(const nlohmann::json& v, const std::string& path, const std::string& noun = "the waveform");
Design design_from_json(const nlohmann::json& j);  // throws jsonread::PathError

// Files: read_design throws PathError with the file's name in front (also for
// a file that is missing or not JSON); write_design replaces the file whole
// (a temporary beside it, renamed), so a crash never leaves half a design.
Design read_design(const std::filesystem::path& file);
void write_design(const std::filesystem::path& file, const Design& d);

}  // namespace knoblab::design
