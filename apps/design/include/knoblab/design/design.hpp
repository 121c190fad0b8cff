// A Haptic Icon Prototyper design (thesis Ch. 5): the waveform in the
// editor, the tile palette and the tile pane, as one value that can be
// compared, copied for undo and saved (docs/designs.md).
//
// A tile is a waveform — a cubic spline through control points — and a name;
// it has no channel until it is placed (§5.3.2). The channel it is placed in
// says what its waveform means, as the thesis sketched "torque waveforms
// based on the user's hand position, velocity and acceleration" (§5.3.1):
//
//   channel       the tile spans      its waveform is            stretched?
//   position      θ from…to (rad)     torque over θ (N·m)        x onto the span
//   velocity      θ from…to (rad)     torque over θ̇ (N·m)        no: x is θ̇ (rad/s)
//   acceleration  θ from…to (rad)     mass over θ (kg·m²)        x onto the span
//   time          t from…to (s)       torque over t (N·m)        x onto the span
//
// So a constant-damping tile is a line through 0 whose slope is the damping,
// and resizing a position or time tile changes its frequency (Fig. 72).
// Each channel holds lines of placed tiles; every active line is summed.
#pragma once

#include <array>
#include <string>
#include <string_view>
#include <vector>

namespace knoblab::design {

enum class Channel { Position, Velocity, Acceleration, Time };
inline constexpr std::array<Channel, 4> kChannels{Channel::Position, Channel::Velocity, Channel::Acceleration,
                                                  Channel::Time};
std::string_view channel_name(Channel c);  // "position", …

struct Point {
  double x = 0.0, y = 0.0;
  bool operator==(const Point&) const = default;
};

// Control points with strictly increasing x (at least 2 once in a tile).
struct Waveform {
  std::vector<Point> points;
  bool periodic = false;  // the spline repeats; the first and last y are equal
  bool operator==(const Waveform&) const = default;

  double x_min() const { return points.empty() ? 0.0 : points.front().x; }
  double x_max() const { return points.empty() ? 0.0 : points.back().x; }
};

struct Tile {
  std::string name;
  Waveform waveform;
  // What the waveform was drawn as (the editor's axes); not a channel: the
  // tile can be placed in any.
  Channel drawn_for = Channel::Position;
  bool operator==(const Tile&) const = default;
};

struct PaletteTab {
  std::string name;
  std::vector<Tile> tiles;
  bool operator==(const PaletteTab&) const = default;
};

struct PlacedTile {
  Tile tile;
  double from = 0.0, to = 0.0;  // rad, or s in the time channel; from < to
  bool operator==(const PlacedTile&) const = default;
};

struct Line {
  std::vector<PlacedTile> tiles;
  bool active = true;  // summed into what plays
  bool operator==(const Line&) const = default;
};

struct ChannelLines {
  std::vector<Line> lines;
  bool play = true;   // felt when the design plays (§5.3.2: any channels at once)
  bool operator==(const ChannelLines&) const = default;
};

struct Editor {
  Waveform waveform;
  Channel drawn_for = Channel::Position;
  bool operator==(const Editor&) const = default;
};

struct Design {
  std::string name;
  Editor editor;
  std::vector<PaletteTab> palette;
  std::array<ChannelLines, 4> channels{};  // indexed by Channel
  bool time_loop = false;                   // the time channel repeats after its last tile
  bool operator==(const Design&) const = default;

  ChannelLines& lines(Channel c) { return channels[static_cast<std::size_t>(c)]; }
  const ChannelLines& lines(Channel c) const { return channels[static_cast<std::size_t>(c)]; }
};

// Units of a channel's tile waveforms, for labels: x then y.
std::string_view x_unit(Channel c);  // "rad", "rad/s", "rad", "s"
std::string_view y_unit(Channel c);  // "N·m", "N·m", "kg·m²", "N·m"

}  // namespace knoblab::design
