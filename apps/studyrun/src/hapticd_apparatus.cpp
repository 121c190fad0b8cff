#include "knoblab/studyrun/hapticd_apparatus.hpp"

#include <array>
#include <thread>

#include "render_terms.hpp"

namespace knoblab::studyrun {

namespace {

control::Client connect(const std::string& socket) {
  try {
    control::Client c(socket);
    control::HelloOptions hello;
    hello.client_name = "knoblab study";
    c.hello(hello);
    return c;
  } catch (const std::exception& e) {
    throw ApparatusError("hapticd at " + socket + ": " + e.what());
  }
}

}  // namespace

HapticdApparatus::HapticdApparatus(const std::string& socket, std::chrono::milliseconds silence_limit)
    : client_(connect(socket)), silence_limit_(silence_limit) {
  const nlohmann::json sub = call("subscribe", {{"events", {"trial", "fault_latched"}}, {"telemetry", true}});
  try {
    telemetry_ = std::make_unique<control::TelemetryReader>(sub.at("telemetry_shm").get<std::string>());
  } catch (const std::exception& e) {
    throw ApparatusError(std::string("hapticd's telemetry: ") + e.what());
  }
  last_record_ = last_poll_ = std::chrono::steady_clock::now();
}

HapticdApparatus::~HapticdApparatus() {
  if (!recording_) return;
  try {
    stop_trial();  // waits for hapticd to have stored it, so the next trial can start
  } catch (...) {
    // hapticd is gone or faulted: its recording ended with it (a destructor throws nothing).
  }
}

nlohmann::json HapticdApparatus::call(std::string_view cmd, nlohmann::json args) {
  try {
    return client_.call(cmd, std::move(args));
  } catch (const std::exception& e) {
    throw ApparatusError("hapticd " + std::string(cmd) + ": " + e.what());
  }
}

nlohmann::json HapticdApparatus::model_args(const study::Rendering& r) {
  const detail::RenderTerms t = detail::render_terms(r);
  return {{"M_acc", t.M_acc}, {"B_vel", t.B_vel}, {"A_pos", t.A_pos}, {"P_pos", t.P_pos}};
}

void HapticdApparatus::render(const study::Rendering& r) {
  if (rendered_ && *rendered_ == r && render_mode_) return;
  // A new model fades in over hapticd's ramp, so a slider drag changes the
  // feel smoothly, without a step in torque.
  call("load_model", model_args(r));
  rendered_ = r;
  if (!render_mode_) {
    call("set_mode", {{"mode", "render"}});
    render_mode_ = true;
  }
}

void HapticdApparatus::start_trial(const TrialLabel& label) {
  stopped_.reset();
  call("start_trial", {{"study", label.study}, {"participant", label.participant}, {"condition", label.condition}});
  recording_ = true;
  // The trial's readings start now: what the ring holds from before (the
  // rating, the commit) is history.
  pending_.clear();
  std::array<control::TelemetryRecord, 256> buf;
  while (telemetry_->read(buf).count == buf.size()) {
  }
}

void HapticdApparatus::take(const control::Event& e, bool fault_throws) {
  if (e.name == "fault_latched") {
    render_mode_ = false;  // a fault leaves hapticd idle; render is asked for again once cleared
    if (fault_throws)
      throw ApparatusError("hapticd latched a fault (" + e.data.value("faults", nlohmann::json::array()).dump() +
                           "): the motor is safe; clear it and resume the session");
  }
  if (e.name == "trial" && e.data.value("state", "") == "stopped") {
    TrialRecording rec;
    if (e.data.contains("capture_id") && e.data["capture_id"].is_number_integer())
      rec.capture_id = e.data["capture_id"].get<std::int64_t>();
    rec.complete = e.data.value("complete", false);
    rec.end_reason = e.data.value("end_reason", "");
    stopped_ = rec;
  }
}

std::optional<control::Event> HapticdApparatus::wait_event(std::chrono::milliseconds timeout) {
  try {
    return client_.wait_event(timeout);
  } catch (const std::exception& ex) {
    throw ApparatusError(std::string("hapticd lost: ") + ex.what());
  }
}

TrialRecording HapticdApparatus::stop_trial() {
  recording_ = false;  // asked once: a refusal means there is nothing left to stop
  call("stop_trial");
  // hapticd reports the recording once its last sample is committed; a fault
  // now ends the recording too, and the report still comes. Commits can
  // trail the recording by seconds (an SD card's or an emulated disk's
  // fsync, another process holding the store), so the wait goes on while
  // hapticd says it still holds samples to store, up to a few minutes; with
  // nothing left to store, 10 s without the report means it is not coming.
  constexpr auto kQuiet = std::chrono::seconds(10);
  constexpr auto kLongest = std::chrono::minutes(3);
  const auto asked = std::chrono::steady_clock::now();
  auto deadline = asked + kQuiet;
  while (!stopped_) {
    const auto now = std::chrono::steady_clock::now();
    if (now > deadline) {
      const nlohmann::json state = call("get_state");
      const auto buffered = state.value("/recorder/buffered"_json_pointer, std::uint64_t{0});
      if (buffered == 0 || now - asked > kLongest)
        throw ApparatusError("hapticd did not report the trial's recording within " +
                             std::to_string(std::chrono::duration_cast<std::chrono::seconds>(now - asked).count()) +
                             " s" + (buffered ? " (" + std::to_string(buffered) + " samples still waiting for the store)" : ""));
      deadline = now + kQuiet;
    }
    if (auto e = wait_event(std::chrono::milliseconds(100))) take(*e, false);
  }
  TrialRecording rec = *stopped_;
  stopped_.reset();
  return rec;
}

KnobReading HapticdApparatus::next() {
  while (pending_.empty()) {
    std::array<control::TelemetryRecord, 64> buf;
    const auto got = telemetry_->read(buf);
    const auto now = std::chrono::steady_clock::now();
    pending_.insert(pending_.end(), buf.begin(), buf.begin() + static_cast<std::ptrdiff_t>(got.count));
    if (got.count > 0) last_record_ = now;
    if (now - last_poll_ > std::chrono::milliseconds(50)) {
      while (auto e = wait_event(std::chrono::milliseconds(0))) take(*e, true);
      last_poll_ = now;
    }
    if (!pending_.empty()) break;
    if (telemetry_->writer_closed()) throw ApparatusError("hapticd stopped (its telemetry ring closed)");
    if (now - last_record_ > silence_limit_)
      throw ApparatusError("hapticd's telemetry has been silent for " + std::to_string(silence_limit_.count()) + " ms");
    std::this_thread::sleep_for(std::chrono::microseconds(500));
  }
  const control::TelemetryRecord rec = pending_.front();
  pending_.pop_front();
  return {rec.t, rec.theta, rec.omega, rec.torque};
}

}  // namespace knoblab::studyrun
