#include "knoblab/design/history.hpp"

namespace knoblab::design {

namespace {
const std::string kNothing;
}  // namespace

const std::string& History::undo_label() const { return undo_.empty() ? kNothing : undo_.back().label; }
const std::string& History::redo_label() const { return redo_.empty() ? kNothing : redo_.back().label; }

std::string History::undo() {
  if (undo_.empty()) return {};
  Step step = std::move(undo_.back());
  undo_.pop_back();
  redo_.push_back({step.label, std::move(design_)});
  design_ = std::move(step.design);
  return step.label;
}

std::string History::redo() {
  if (redo_.empty()) return {};
  Step step = std::move(redo_.back());
  redo_.pop_back();
  undo_.push_back({step.label, std::move(design_)});
  design_ = std::move(step.design);
  return step.label;
}

void History::reset(Design d) {
  design_ = std::move(d);
  saved_ = design_;
  undo_.clear();
  redo_.clear();
}

}  // namespace knoblab::design
