// Rotary pointing (thesis §4.6.1.3, Fig. 58): the participant aligns the
// needle on the home disk; the condition is rendered; then each target disk
// of the trial is shown in turn, and is acquired as soon as the needle is
// over it — the next appears at once, back the other way.
//
// Measures per acquisition (result()["acquisitions"]):
//   movement_time_s  from the disk's appearance to the needle entering it
//   endpoint_deg     where the movement ended — the furthest point before it
//                    first stopped or turned back for 40 ms after entering
//                    (a rendering's ringing does not end it) — from the
//                    disk's centre, along the
//                    movement's direction (+: past the centre)
//   overshoot_deg    how far that end went past the disk's far edge (≥ 0)
// Degrees at this edge, as the tidy export writes them.
#pragma once

#include <vector>

#include "knoblab/studyrun/task.hpp"

namespace knoblab::studyrun {

struct PointingTiming {
  double home_settle_s = 0.3;         // the needle rests on the home disk this long
  double rest_speed_rad_s = 0.05;     // slower than this counts as at rest
  double stop_s = 0.04;               // a movement has ended once this slow (or turned back) this long
  double home_timeout_s = 60;         // the home disk not reached by then ends the trial
  double acquisition_timeout_s = 20;  // a target not reached by then ends the trial
  double last_end_timeout_s = 1.5;    // the last movement's end is looked for this long
};

class PointingTask final : public Task {
 public:
  PointingTask(const study::Protocol& protocol, const study::Trial& trial, PointingTiming timing = {});
  const Display& display() const override { return display_; }
  Step feed(const KnobReading& reading, const Action& action) override;
  std::optional<study::Rendering> rendering_change() override;
  nlohmann::json result() const override;

 private:
  struct Acquisition {
    study::Target target;
    double shown_t = 0;
    double entered_t = -1;  // < 0 until entered
    double extreme = 0;     // furthest along the direction after entering (rad)
    double slow_since = -1; // when it last became slow (or turned back) after entering
    bool ended = false;
  };
  void show(std::size_t k, double t);
  void set_disk(std::optional<Disk> disk, std::string instruction);

  PointingTiming timing_;
  study::Rendering rendering_;
  Disk home_;
  std::vector<Acquisition> acq_;
  std::size_t current_ = 0;  // the acquisition whose disk is shown
  enum class Phase { Homing, Moving, Finishing, Done } phase_ = Phase::Homing;
  double settled_since_ = -1;
  double start_t_ = -1;
  double onset_t_ = 0;
  bool onset_pending_ = false;
  bool timed_out_ = false;
  Display display_;
};

}  // namespace knoblab::studyrun
