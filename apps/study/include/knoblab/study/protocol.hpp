// A user study's protocol, read from its JSON file (docs/studies.md): the
// factors and their levels, how trials are blocked, repeated, practised and
// ordered, the rating scales asked after each trial, the biometrics
// recorded, and the settings of its kind (thesis §3.4 matching; ch. 4
// textures, list selection, rotary pointing).
//
// Values are SI inside. The file may give angles only as fields named
// *_deg (amplitude_deg, width_deg, home_width_deg), which are converted to
// radians here, at the edge.
//
// Every problem in a file is a ProtocolError naming the key's path, e.g.
// "factors[1].levels[0].parameters.B_vel: must be at most 0.045 …"; keys
// nobody reads are rejected, so a typo fails loudly instead of being
// ignored.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include <nlohmann/json.hpp>

#include "knoblab/jsonread/json_reader.hpp"

namespace knoblab::study {

// what() is "PATH: MESSAGE"; in_file() prefixes the file (apps/jsonread).
using ProtocolError = jsonread::PathError;

enum class Kind { Matching, Pointing, ListSelection, Textures };
std::string_view kind_name(Kind kind);  // "matching", "pointing", …

// Eq. 14 / Eqs. 15–17 as the appliance renders them, SI:
//   τ = M_acc·θ̈ + B_vel·θ̇ + A_pos·sin(detents_per_rev·θ)
// A term the file leaves out is zero.
struct Rendering {
  double M_acc = 0;            // kg·m² (N·m per rad/s²)
  double B_vel = 0;            // N·m·s/rad
  double A_pos = 0;            // N·m
  double detents_per_rev = 0;  // 1/rev; 0 only without detents (A_pos = 0)
  bool operator==(const Rendering&) const = default;
};

// The haptic knob's continuous limits (thesis Table 9, in SI) that every
// rendering and slider range must stay within, and a bound on detent count.
inline constexpr Rendering kRenderingLimits{1.5e-3, 45e-3, 0.18, 360};

struct Level {
  std::string name;
  std::string description;  // empty when the file gives none
  std::string preset;       // a `knoblab simulate` preset id, or empty
  std::optional<Rendering> rendering;
  std::optional<double> amplitude_rad;  // a pointing target's distance
  std::optional<double> width_rad;      // a pointing target's width
};

struct Factor {
  std::string name;
  std::vector<Level> levels;
  std::optional<std::size_t> level_index(std::string_view level) const;
};

// A part of the study run as a whole before the next (thesis: novices matched
// the knobs without detents before those with; Study 2 ran freeform
// exploration before target finding). allowed[f] lists the levels of factor f
// the stage takes, in the factor's order. A file without stages has one,
// "all", taking every level.
struct Stage {
  std::string name;
  std::vector<std::vector<std::size_t>> allowed;
};

// Practice that is run but not analysed: either the first `blocks` blocks
// (thesis Study 3: the first of four blocks, participants not told), or
// `trials` trials at the start of each stage of the first block (Study 1: a
// full pass over the textures; Study 2: two trials per context).
struct Practice {
  std::size_t blocks = 0;
  std::size_t trials = 0;
};

enum class OrderScheme { Random, LatinSquare, Fixed };
struct Order {
  OrderScheme scheme = OrderScheme::Random;
  std::size_t factor = 0;  // the latin square's factor (LatinSquare only)
};

enum class Scale { SamValence, SamArousal, AffectGrid, Satisfaction, Appropriateness };
std::string_view scale_name(Scale scale);

// Which end of the construct the scale's lowest value stands for. The thesis
// used both: Studies 1–2 put low valence at 1, Study 3 and the matching
// study's satisfaction put the favourable end at 1.
enum class ScaleEnd { Low, High };

struct Rating {
  Scale scale = Scale::SamValence;
  int min = 1;
  int max = 9;
  ScaleEnd min_is = ScaleEnd::Low;  // for the affect grid: both of its axes
  std::string prompt;               // the question as put, or empty
};

struct Biometrics {
  bool emg = false;  // facial EMG (valence)
  bool sc = false;   // skin conductance (arousal)
};

// Matching (§3.4.1): the participant sets a rendered knob's sliders until it
// feels like a mechanical test knob.
struct Slider {
  std::string parameter;  // a Rendering field: M_acc, B_vel, A_pos, detents_per_rev
  double min = 0;         // SI, as that field
  double max = 0;
  // β of Stevens' power law ψ ∝ φ^β for what the slider sets: equal steps of
  // the slider are equal steps of ψ (slider_mapping.hpp). 1: linear, as the
  // thesis' sliders were, which an expert felt were not linear (§3.4.3.3).
  double perceptual_exponent = 1;
};
struct MatchingSettings {
  enum class Group { Novice, Expert };
  Group group = Group::Novice;
  bool think_aloud = false;      // experts verbalised their strategies
  bool explain_physics = false;  // the experimenter named each slider's physics
  std::vector<Slider> sliders;
  std::vector<std::vector<std::size_t>> stage_sliders;  // per stage: indices into sliders
};

// Rotary pointing (§4.6): each trial is `acquisitions` movements, back and
// forth between the home position and a target `amplitude` away.
enum class Direction { Positive, Negative, Alternate, Random };
struct PointingSettings {
  unsigned acquisitions = 3;
  std::size_t amplitude_factor = 0;  // whose levels carry amplitude_rad
  std::size_t width_factor = 0;      // whose levels carry width_rad
  Direction first_direction = Direction::Random;
  double home_width_rad = 0;  // the start disk
};

// List selection (§4.5): a counter moved by the knob to a target value, or
// freeform exploration with the display off.
struct ListSelectionSettings {
  unsigned list_length = 0;
  double items_per_rev = 0;  // counter steps per knob revolution
  std::size_t context_factor = 0;
  std::size_t freeform_level = 0;  // its level with the display off, no target
  double exploration_s = 0;
  double rating_s = 0;
  double rest_s = 0;
};

// Textures (§4.4): the participant strokes a real surface, blindfolded.
struct TexturesSettings {
  std::size_t factor = 0;  // whose levels are the textures
  double stroke_min_s = 0;
  double stroke_max_s = 0;
  bool blindfold = true;
};

using KindSettings = std::variant<MatchingSettings, PointingSettings, ListSelectionSettings, TexturesSettings>;

struct Protocol {
  std::string study;  // id: letters, digits, '-', '_', '.'
  Kind kind = Kind::Matching;
  std::string title;
  std::string source;               // where in the thesis, or empty
  std::vector<std::string> notes;   // e.g. readings of ambiguous text
  std::vector<Factor> factors;
  std::vector<Stage> stages;        // never empty
  std::size_t blocks = 1;
  std::size_t repetitions = 1;      // complete passes per stage per block
  Practice practice;
  Order order;
  std::uint64_t seed = 0;
  std::vector<Rating> ratings;
  Biometrics biometrics;
  KindSettings settings;

  std::optional<std::size_t> factor_index(std::string_view name) const;
};

// Throws ProtocolError.
Protocol parse_protocol(const nlohmann::json& file);
Protocol parse_protocol_text(std::string_view text);
Protocol load_protocol(const std::filesystem::path& path);

}  // namespace knoblab::study
