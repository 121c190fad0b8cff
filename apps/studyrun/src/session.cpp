#include "knoblab/studyrun/session.hpp"

#include <chrono>

#include "knoblab/studyrun/biometric_score.hpp"
#include "knoblab/studyrun/slider_tags.hpp"
#include "knoblab/studyrun/task.hpp"

namespace knoblab::studyrun {

namespace {

double unix_now() {
  return std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
}

// The knob every trace_period, times from the trial's start.
class Trace {
 public:
  explicit Trace(double period) : period_(period) {}
  void add(const KnobReading& r) {
    if (start_ < 0) start_ = r.t;
    if (next_ >= 0 && r.t < next_) return;
    next_ = (next_ < 0 ? r.t : next_) + period_;
    t_.push_back(r.t - start_);
    theta_.push_back(r.theta);
    omega_.push_back(r.omega);
    torque_.push_back(r.torque);
  }
  nlohmann::json json() const {
    return {{"period_s", period_}, {"start_s", start_}, {"t_s", t_}, {"theta_rad", theta_},
            {"omega_rad_s", omega_}, {"torque_Nm", torque_}};
  }

 private:
  double period_, start_ = -1, next_ = -1;
  std::vector<double> t_, theta_, omega_, torque_;
};

nlohmann::json condition_json(const study::Protocol& p, const study::Trial& t) {
  nlohmann::json c = nlohmann::json::object();
  for (std::size_t f = 0; f < p.factors.size(); ++f) c[p.factors[f].name] = study::trial_level(p, t, f).name;
  return c;
}

// The novices' familiarization, before their first trial: they explore each
// slider and label it (§3.4.1.3; experts were told the physics instead, so
// their labels would say nothing, Table 15). Only for a session that starts
// fresh: one resumed has had its familiarization, whether or not the
// participant had words to keep.
void familiarize(store::Store& store, const study::Protocol& protocol, const store::StudySession& session,
                 Participant& participant) {
  const auto* matching = std::get_if<study::MatchingSettings>(&protocol.settings);
  if (matching == nullptr || matching->group != study::MatchingSettings::Group::Novice) return;
  if (session.trials_committed > 0 || !session_slider_tags(store, session.session_id).empty()) return;
  const SliderTags tags = participant.slider_tags(matching->sliders);
  if (!tags.empty()) save_slider_tags(store, session.session_id, tags);
}

KnobReading next_reading(Apparatus& apparatus, const SessionOptions& o) {
  if (o.cancelled && o.cancelled()) throw Cancelled();
  return apparatus.next();
}

}  // namespace

std::uint64_t trial_seed(const study::Plan& plan, std::size_t index) {
  return plan.seed ^ (0x9E3779B97F4A7C15ull * (index + 1));
}

SessionResult run_session(store::Store& store, const study::Protocol& protocol, const std::string& protocol_json,
                          const std::string& code, std::size_t index, Apparatus& apparatus, Participant& participant,
                          const SessionOptions& o) {
  const study::Plan plan = study::plan(protocol, code, index);
  const store::StudySession session = store.open_study_session(
      {.study = protocol.study, .participant = code, .participant_index = index, .protocol_json = protocol_json,
       .plan_trials = plan.trials.size(), .simulated = o.simulated});
  SessionResult result{.session_id = session.session_id};
  const bool biometrics = protocol.biometrics.emg || protocol.biometrics.sc;
  std::optional<std::size_t> next = store.next_study_trial(session.session_id);
  result.resumed_at = next.value_or(0);
  familiarize(store, protocol, session, participant);
  while (next && (o.max_trials == 0 || result.trials_run < o.max_trials)) {
    const study::Trial& trial = plan.trials.at(*next - 1);
    if (o.on_trial_start) o.on_trial_start(trial, plan.trials.size());
    std::unique_ptr<Task> task = make_task(protocol, trial, trial_seed(plan, trial.index));
    participant.begin_trial(protocol, trial);
    Trace trace(o.trace_period_s);
    std::uint64_t shown = 0;
    auto show = [&](const Display& d) {
      if (o.on_display && d.version != shown) o.on_display(d);
      shown = d.version;
    };

    apparatus.render({});  // the bare knob until the condition's onset
    const double started_unix = unix_now();
    apparatus.start_trial({protocol.study, code, study::condition_label(protocol, trial)});
    KnobReading r = next_reading(apparatus, o);
    const double recording_start = r.t;
    // A quiet moment for the biometrics' baseline; the participant waits.
    if (biometrics)
      while (r.t - recording_start < o.baseline_s) {
        trace.add(r);
        r = next_reading(apparatus, o);
      }
    double onset = r.t;
    for (;;) {
      show(task->display());
      trace.add(r);
      const Action action = participant.act(task->display(), r);
      const Step step = task->feed(r, action);
      if (auto rendering = task->rendering_change()) apparatus.render(*rendering);
      if (step == Step::Onset) onset = r.t;
      if (step == Step::Done) break;
      r = next_reading(apparatus, o);
    }
    show(task->display());
    const double end = r.t;
    apparatus.render({});
    const TrialRecording recording = apparatus.stop_trial();
    const nlohmann::json measures = task->result();
    const nlohmann::json ratings = participant.rate(protocol.ratings, measures);

    // The markers from the recording's start, the clock its samples and the
    // box's are on once their first sample is subtracted.
    nlohmann::json bio{{"onset_s", onset - recording_start}, {"end_s", end - recording_start}};
    if (recording.capture_id && biometrics) {
      auto samples = store.load_biometrics(*recording.capture_id);
      const interchange::Capture capture = store.load_samples(*recording.capture_id);
      const double t0 = capture.t.empty() ? 0.0 : capture.t.front();
      for (store::BiometricSample& b : samples) b.t -= t0;
      bio["samples"] = samples.size();
      bio["score"] = to_json(score_biometrics(samples, onset - recording_start, end - recording_start, o.baseline_s));
    }
    store::StudyTrial row{.session_id = session.session_id,
                          .trial_index = trial.index,
                          .block = trial.block,
                          .stage = protocol.stages.at(trial.stage).name,
                          .practice = trial.practice,
                          .repetition = trial.repetition,
                          .condition_json = condition_json(protocol, trial).dump(),
                          .started_unix = started_unix,
                          .ended_unix = unix_now(),
                          .result_json = measures.dump(),
                          .ratings_json = ratings.dump(),
                          .biometrics_json = bio.dump(),
                          .trace_json = trace.json().dump(),
                          .capture_id = recording.capture_id};
    store.commit_study_trial(row);
    ++result.trials_run;
    if (o.on_trial_committed) o.on_trial_committed(row);
    next = store.next_study_trial(session.session_id);
  }
  if (!next) {
    if (!store.study_session(session.session_id)->finished_unix) store.finish_study_session(session.session_id);
    result.finished = true;
  }
  return result;
}

}  // namespace knoblab::studyrun
