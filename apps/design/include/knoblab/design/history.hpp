// Undo and redo of every edit (§5.4: "the ability to cycle between previous
// states"). Designs are small, so each step keeps the whole design before
// the edit: undo can never disagree with what the edit did.
#pragma once

#include <cstddef>
#include <deque>
#include <string>
#include <utility>

#include "knoblab/design/design.hpp"

namespace knoblab::design {

class History {
 public:
  explicit History(Design d = {}) : design_(std::move(d)) {}

  const Design& design() const { return design_; }

  // Runs `edit` on a copy of the design; if it throws (EditError), nothing
  // changes and the error goes to the caller. Otherwise the copy becomes the
  // design, labelled for the message bar ("moved point 3"), and redo is cleared.
  template <class Edit>
  void apply(std::string label, Edit&& edit) {
    Design next = design_;
    std::forward<Edit>(edit)(next);
    if (next == design_) return;  // nothing changed: nothing to undo
    undo_.push_back({std::move(label), std::move(design_)});
    if (undo_.size() > kDepth) undo_.pop_front();
    redo_.clear();
    design_ = std::move(next);
  }

  bool can_undo() const { return !undo_.empty(); }
  bool can_redo() const { return !redo_.empty(); }
  const std::string& undo_label() const;  // "" when there is nothing to undo
  const std::string& redo_label() const;
  // The label of the step undone or redone; "" when there was none.
  std::string undo();
  std::string redo();

  // A design opened from a file: a fresh start, nothing to undo.
  void reset(Design d);
  // Whether the design differs from the one last saved (or opened).
  bool modified() const { return !(design_ == saved_); }
  void mark_saved() { saved_ = design_; }

  static constexpr std::size_t kDepth = 500;  // steps kept

 private:
  struct Step {
    std::string label;
    Design design;  // as it was on the other side of the step
  };
  Design design_;
  Design saved_;
  std::deque<Step> undo_, redo_;
};

}  // namespace knoblab::design
