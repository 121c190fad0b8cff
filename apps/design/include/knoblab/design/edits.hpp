// Every change a designer can make to a design, one function each. An edit
// either applies whole or throws EditError (the design is then unchanged):
// the message is a sentence for the message bar (§5.4: notification, not
// dialogs). History (history.hpp) makes each of them undoable.
#pragma once

#include <cstddef>
#include <stdexcept>
#include <string>

#include "knoblab/design/design.hpp"

namespace knoblab::design {

class EditError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

// A placed tile in the pane.
struct TileRef {
  Channel channel = Channel::Position;
  std::size_t line = 0, index = 0;
  bool operator==(const TileRef&) const = default;
};

// An x interval of the editor's waveform (from < to).
struct Selection {
  double from = 0.0, to = 0.0;
};

// The waveform editor (§5.3.1).
void set_editor(Design& d, const Waveform& w, Channel drawn_for);  // a new or dragged-in waveform
void move_point(Design& d, std::size_t i, Point to);  // x stays strictly between its neighbours
void add_point(Design& d, Point p);                   // inserted in x order
void remove_point(Design& d, std::size_t i);          // at least 2 remain
// Scales the selected points away from a mirror line (Fig. 71): a
// horizontal line y = at stretches their y (amplitude), a vertical line
// x = at their x; factor may be negative (mirror), not 0.
enum class Mirror { Horizontal, Vertical };
void scale_selection(Design& d, Selection s, Mirror m, double at, double factor);
// The selected part of the editor's curve as a tile: the points inside and
// the curve's value at both ends.
Tile tile_from_selection(const Design& d, Selection s, const std::string& name);

// The tile palette (§5.3.1–5.3.2): tabs named by the designer.
void add_tab(Design& d, const std::string& name);
void rename_tab(Design& d, std::size_t tab, const std::string& name);
void remove_tab(Design& d, std::size_t tab);
void add_tile(Design& d, std::size_t tab, const Tile& t);
void rename_tile(Design& d, std::size_t tab, std::size_t index, const std::string& name);
void remove_tile(Design& d, std::size_t tab, std::size_t index);
void edit_tile(Design& d, std::size_t tab, std::size_t index);  // into the editor

// The tile pane (§5.3.2, Figs. 70, 72, 73). `line` may be one past the last
// line: the tile then starts a new line.
void place_tile(Design& d, Channel c, std::size_t line, const Tile& t, double from, double to);
void move_tile(Design& d, TileRef r, double from);  // same length
void resize_tile(Design& d, TileRef r, double from, double to);  // stretches the waveform
void remove_placed(Design& d, TileRef r);
// The sum of two tiles of one channel as one tile in a's place (b goes).
void superimpose(Design& d, TileRef a, TileRef b);
void add_line(Design& d, Channel c);
void remove_line(Design& d, Channel c, std::size_t line);
void set_line_active(Design& d, Channel c, std::size_t line, bool active);
void set_channel_play(Design& d, Channel c, bool play);
void set_time_loop(Design& d, bool loop);
void rename_design(Design& d, const std::string& name);

}  // namespace knoblab::design
