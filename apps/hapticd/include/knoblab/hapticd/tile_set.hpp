// What the Haptic Icon Prototyper sends the renderer (thesis Ch. 5): position
// tiles (Eq. 19) and time tiles (Eq. 20, timed from when the set starts
// rendering), all summed on top of the render model. Built and checked by
// non-realtime code (tiles_from_json), handed to the loop whole.
#pragma once

#include <vector>

#include "knoblab/model/tiles.hpp"

namespace knoblab::hapticd {

struct TileSet {
  std::vector<model::PositionTile> position;
  std::vector<model::TimeTile> time;
};

}  // namespace knoblab::hapticd
