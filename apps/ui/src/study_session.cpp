#include "study_session.hpp"

#include <QDir>
#include <QFile>
#include <QFileInfo>
#include <QJsonDocument>
#include <QJsonObject>
#include <QPointer>

#include <algorithm>
#include <cmath>
#include <condition_variable>
#include <limits>
#include <mutex>
#include <numbers>
#include <optional>

#include <nlohmann/json.hpp>

#include "knoblab/store/store.hpp"
#include "knoblab/study/participant.hpp"
#include "knoblab/study/plan.hpp"
#include "knoblab/study/protocol.hpp"
#include "knoblab/study/slider_mapping.hpp"
#include "knoblab/studyrun/core_apparatus.hpp"
#include "knoblab/studyrun/hapticd_apparatus.hpp"
#include "knoblab/studyrun/session.hpp"
#include "knoblab/studyrun/simulated_participant.hpp"
#include "knoblab/studyrun/slider_tags.hpp"

namespace knoblab::ui {

namespace {

using nlohmann::json;

double deg(double rad) { return rad * 180.0 / std::numbers::pi; }

// A rendering term and how the screen shows it: SI × factor in unit.
struct Term {
  const char* parameter;
  const char* label;
  const char* unit;
  double factor;
  double study::Rendering::* field;
};
constexpr Term kTerms[] = {
    {"M_acc", "Inertia", "mN·m/(rad/s²)", 1e3, &study::Rendering::M_acc},
    {"B_vel", "Friction", "mN·m/(rad/s)", 1e3, &study::Rendering::B_vel},
    {"A_pos", "Detent strength", "mN·m", 1e3, &study::Rendering::A_pos},
    {"detents_per_rev", "Detents", "detents/rev", 1.0, &study::Rendering::detents_per_rev},
};

const Term* term(std::string_view parameter) {
  for (const Term& t : kTerms)
    if (parameter == t.parameter) return &t;
  return nullptr;
}

// The slider of `sliders` that sets term `t`, or none.
const study::Slider* slider_of(const std::vector<study::Slider>& sliders, const Term* t) {
  for (const study::Slider& s : sliders)
    if (t && s.parameter == t->parameter) return &s;
  return nullptr;
}

std::vector<study::Slider> offered_sliders(const study::Protocol& p, const study::Trial& trial) {
  std::vector<study::Slider> out;
  if (const auto* m = std::get_if<study::MatchingSettings>(&p.settings))
    for (std::size_t i : m->stage_sliders.at(trial.stage)) out.push_back(m->sliders.at(i));
  return out;
}

QString summary(const store::StudyTrial& t) {
  QStringList parts;
  const json ratings = json::parse(t.ratings_json, nullptr, false);
  if (ratings.is_object())
    for (const auto& [scale, value] : ratings.items()) {
      if (value.is_number()) parts << QStringLiteral("%1 %2").arg(QString::fromStdString(scale)).arg(value.get<int>());
      else if (value.is_object() && value.contains("valence") && value.contains("arousal"))
        parts << QStringLiteral("valence %1, arousal %2")
                     .arg(value["valence"].get<int>())
                     .arg(value["arousal"].get<int>());
    }
  const json result = json::parse(t.result_json, nullptr, false);
  if (result.is_object() && result.contains("acquisitions")) {
    double sum = 0;
    int n = 0;
    for (const json& a : result["acquisitions"])
      if (a.contains("movement_time_s") && a["movement_time_s"].is_number()) sum += a["movement_time_s"].get<double>(), ++n;
    if (n > 0) parts << QStringLiteral("MT %1 s").arg(sum / n, 0, 'f', 2);
  } else if (result.is_object() && result.contains("time_s") && result["time_s"].is_number()) {
    parts << QStringLiteral("%1 s").arg(result["time_s"].get<double>(), 0, 'f', 1);
  }
  return parts.join(QStringLiteral(" · "));
}

QString condition_text(const std::string& condition_json) {
  const json c = json::parse(condition_json, nullptr, false);
  QStringList parts;
  if (c.is_object())
    for (const auto& [factor, level] : c.items())
      if (level.is_string()) parts << QString::fromStdString(factor + "=" + level.get<std::string>());
  return parts.join(QStringLiteral(" "));
}

QVariantMap tags_map(const studyrun::SliderTags& tags) {
  QVariantMap out;
  for (const auto& [parameter, words] : tags) out.insert(QString::fromStdString(parameter), QString::fromStdString(words));
  return out;
}

QVariantMap trial_row(const store::StudyTrial& t) {
  return {{QStringLiteral("index"), static_cast<int>(t.trial_index)},
          {QStringLiteral("block"), static_cast<int>(t.block)},
          {QStringLiteral("stage"), QString::fromStdString(t.stage)},
          {QStringLiteral("practice"), t.practice},
          {QStringLiteral("condition"), condition_text(t.condition_json)},
          {QStringLiteral("summary"), summary(t)}};
}

}  // namespace

// The person at the participant view, as the runner sees them: act() hands
// over what the view set (slider moves, "done"), rate() waits for the view's
// ratings. With a stand-in (the simulated participant, for a dry run) the
// stand-in answers instead, and the session pauses where it was asked to.
class PersonParticipant final : public studyrun::Participant {
 public:
  std::function<void(double theta)> on_reading;
  std::function<void(const std::vector<study::Rating>&)> on_rating;
  std::function<void()> on_paused;
  studyrun::Participant* stand_in = nullptr;
  std::string pause_at;

  void begin_trial(const study::Protocol& protocol, const study::Trial& trial) override {
    if (stand_in) stand_in->begin_trial(protocol, trial);
    std::lock_guard lock(mutex_);
    done_ = dirty_ = false;
    sliders_.reset();
    ++trials_begun_;
    reads_ = 0;
    seen_version_ = 0;
  }

  studyrun::Action act(const studyrun::Display& d, const studyrun::KnobReading& r) override {
    if (on_reading) on_reading(r.theta);
    if (stand_in) {
      studyrun::Action a = stand_in->act(d, r);
      if (should_pause(d, r)) hold();
      return a;
    }
    std::lock_guard lock(mutex_);
    studyrun::Action a;
    if (!sliders_ && d.sliders) sliders_ = d.sliders;
    if (dirty_) a.sliders = sliders_, dirty_ = false;
    a.done = done_;
    done_ = false;
    return a;
  }

  // A person's words for the sliders are the experimenter's to type in
  // (saveSliderTags); a stand-in gives its own.
  std::map<std::string, std::string> slider_tags(const std::vector<study::Slider>& sliders) override {
    if (stand_in) return stand_in->slider_tags(sliders);
    return {};
  }

  json rate(const std::vector<study::Rating>& scales, const json& measures) override {
    if (stand_in && pause_at != "rating") return stand_in->rate(scales, measures);
    {
      std::lock_guard lock(mutex_);
      ratings_.reset();
    }
    if (on_rating) on_rating(scales);
    if (stand_in) hold();
    std::unique_lock lock(mutex_);
    cv_.wait(lock, [&] { return ratings_.has_value() || stopped_; });
    if (stopped_) throw studyrun::Cancelled();
    json out = *ratings_;
    ratings_.reset();
    return out;
  }

  void set_slider(std::string_view parameter, double si) {
    std::lock_guard lock(mutex_);
    const Term* t = term(parameter);
    if (!sliders_ || !t) return;
    (*sliders_).*(t->field) = si;
    dirty_ = true;
  }
  void set_done() {
    std::lock_guard lock(mutex_);
    done_ = true;
  }
  void submit(json ratings) {
    std::lock_guard lock(mutex_);
    ratings_ = std::move(ratings);
    cv_.notify_all();
  }
  void stop() {
    std::lock_guard lock(mutex_);
    stopped_ = true;
    cv_.notify_all();
  }

 private:
  // Waits, the screen showing what was asked for, until the session is stopped.
  void hold() {
    if (on_paused) on_paused();
    std::unique_lock lock(mutex_);
    cv_.wait(lock, [&] { return stopped_; });
    throw studyrun::Cancelled();
  }

  bool should_pause(const studyrun::Display& d, const studyrun::KnobReading& r) {
    ++reads_;
    if (d.version != seen_version_) {
      seen_version_ = d.version;
      shown_theta_ = r.theta;
    }
    if (pause_at == "target")  // a target shown, the needle halfway there
      return d.disk && d.instruction.starts_with("Move the needle onto") &&
             std::abs(r.theta - shown_theta_) >= 0.5 * std::abs(d.disk->centre_rad - shown_theta_) &&
             std::abs(r.theta - shown_theta_) > 0;
    if (pause_at == "counter")  // the counter on its way to the target
      return d.counter && d.target_value && *d.counter != *d.target_value &&
             std::abs(*d.counter - *d.target_value) * 2 <= std::abs(first_counter(d) - *d.target_value);
    if (pause_at == "freeform") return !d.counter && d.instruction == "Explore the knob" && reads_ > 1000;
    if (pause_at == "sliders") return d.sliders && d.version >= 6;
    if (pause_at == "texture") return !d.reference.empty() && reads_ > 500;
    if (pause_at.starts_with("trials:"))
      return trials_begun_ > std::stoul(pause_at.substr(7)) && reads_ > 300;
    return false;
  }
  long first_counter(const studyrun::Display& d) {
    if (!first_counter_ || first_target_ != *d.target_value) first_counter_ = *d.counter, first_target_ = *d.target_value;
    return *first_counter_;
  }

  std::mutex mutex_;
  std::condition_variable cv_;
  bool done_ = false, dirty_ = false, stopped_ = false;
  std::optional<study::Rendering> sliders_;
  std::optional<json> ratings_;
  std::size_t trials_begun_ = 0, reads_ = 0;
  std::uint64_t seen_version_ = 0;
  double shown_theta_ = 0;
  std::optional<long> first_counter_;
  long first_target_ = 0;
};

StudySession::StudySession(Options options, QObject* parent) : QObject(parent), options_(std::move(options)) {
  const QDir dir(options_.studiesDir);
  for (const QString& name : dir.entryList({QStringLiteral("*.json")}, QDir::Files, QDir::Name)) {
    const QString path = dir.filePath(name);
    try {
      const study::Protocol p = study::load_protocol(path.toStdString());
      protocols_.append(QVariantMap{{QStringLiteral("path"), path},
                                    {QStringLiteral("title"), QString::fromStdString(p.title)},
                                    {QStringLiteral("kind"), QString::fromStdString(std::string(study::kind_name(p.kind)))},
                                    {QStringLiteral("study"), QString::fromStdString(p.study)}});
    } catch (const std::exception&) {
      // Not a protocol this knoblab reads: not offered.
    }
  }
  notes_.setMaxThreadCount(1);
  needle_timer_.setInterval(33);
  connect(&needle_timer_, &QTimer::timeout, this, [this] {
    const double d = deg(theta_.load(std::memory_order_relaxed));
    if (std::abs(d - needle_deg_) < 0.05) return;
    needle_deg_ = d;
    emit needleChanged();
  });
}

StudySession::~StudySession() {
  join();
  notes_.waitForDone();
}

void StudySession::join() {
  cancel_ = true;
  if (person_) person_->stop();
  if (worker_.joinable()) worker_.join();
}

bool StudySession::settling() const {
  return options_.simulate && !options_.pause_at.isEmpty() && !paused_ &&
         (state_ == QLatin1String("running") || state_ == QLatin1String("rating"));
}

void StudySession::set_state(const QString& state, const QString& why) {
  state_ = state;
  message_ = why;
  if (state != QLatin1String("running") && state != QLatin1String("rating")) needle_timer_.stop();
  emit stateChanged();
}

QString StudySession::checkCode(const QString& code) const {
  try {
    study::check_participant_code(code.toStdString());
    return {};
  } catch (const std::exception& e) {
    return QString::fromUtf8(e.what());
  }
}

bool StudySession::start(const QString& protocolPath, const QString& code) {
  if (state_ == QLatin1String("running") || state_ == QLatin1String("rating")) {
    emit message(QStringLiteral("A session is running: stop it first"), QStringLiteral("warning"));
    return false;
  }
  if (const QString why = checkCode(code); !why.isEmpty()) {
    emit message(QStringLiteral("Participant code: ") + why, QStringLiteral("error"));
    return false;
  }
  QFile file(protocolPath);
  if (!file.open(QIODevice::ReadOnly)) {
    emit message(QStringLiteral("Cannot read the protocol %1").arg(protocolPath), QStringLiteral("error"));
    return false;
  }
  const QByteArray text = file.readAll();
  try {
    const study::Protocol p = study::parse_protocol_text(text.toStdString());
    title_ = QString::fromStdString(p.title);
    kind_ = QString::fromStdString(std::string(study::kind_name(p.kind)));
    trials_ = static_cast<int>(study::plan(p, code.toStdString(), 0).trials.size());
    protocol_sliders_.clear();
    if (const auto* m = std::get_if<study::MatchingSettings>(&p.settings))
      for (const study::Slider& s : m->sliders)
        if (const Term* t = term(s.parameter))
          protocol_sliders_ << QVariantMap{{QStringLiteral("parameter"), QString::fromLatin1(t->parameter)},
                                           {QStringLiteral("label"), QString::fromLatin1(t->label)}};
  } catch (const std::exception& e) {
    emit message(QFileInfo(protocolPath).fileName() + QStringLiteral(": ") + QString::fromUtf8(e.what()),
                 QStringLiteral("error"));
    return false;
  }
  if (worker_.joinable()) worker_.join();  // the last session's thread, finished
  participant_ = code;
  protocol_path_ = protocolPath;
  resumed_at_ = trial_ = committed_ = block_ = 0;
  stage_.clear(), condition_.clear(), recent_.clear(), rating_scales_.clear(), slider_tags_.clear();
  session_id_ = 0;
  cancel_ = false;
  paused_ = false;
  emit sessionChanged();
  emit trialChanged();
  emit sliderTagsChanged();
  set_state(QStringLiteral("running"));
  needle_timer_.start();
    auto person = std::make_shared<PersonParticipant>();
    person->pause_at = options_.pause_at.toStdString();
    auto post = [this](auto f) { QMetaObject::invokeMethod(this, std::move(f), Qt::QueuedConnection); };
    person->on_reading = [this](double theta) { theta_.store(theta, std::memory_order_relaxed); };
    person->on_paused = [this, post] {
      post([this] {
        paused_ = true;
        needle_deg_ = deg(theta_.load());
        emit needleChanged();
      });
    };
    person->on_rating = [this, post](const std::vector<study::Rating>& scales) {
      QVariantList list;
      for (const study::Rating& r : scales)
        list << QVariantMap{{QStringLiteral("scale"), QString::fromStdString(std::string(study::scale_name(r.scale)))},
                            {QStringLiteral("min"), r.min},
                            {QStringLiteral("max"), r.max},
                            {QStringLiteral("minIs"), r.min_is == study::ScaleEnd::Low ? QStringLiteral("low")
                                                                                       : QStringLiteral("high")},
                            {QStringLiteral("prompt"), QString::fromStdString(r.prompt)}};
      post([this, list] {
        rating_scales_ = list;
        emit ratingScalesChanged();
        set_state(QStringLiteral("rating"));
      });
    };
    person_ = person;
  worker_ = std::thread([this, path = options_.db, text, code] { run(path, text, code); });
  return true;
}

void StudySession::stop() {
  if (state_ != QLatin1String("running") && state_ != QLatin1String("rating")) return;
  cancel_ = true;
  if (person_) person_->stop();
}

void StudySession::submitRatings(const QVariantMap& ratings) {
  if (state_ != QLatin1String("rating") || !person_) return;
  const QByteArray text = QJsonDocument(QJsonObject::fromVariantMap(ratings)).toJson(QJsonDocument::Compact);
  person_->submit(json::parse(text.toStdString()));
  rating_scales_.clear();
  emit ratingScalesChanged();
  set_state(QStringLiteral("running"));
}

void StudySession::setSlider(const QString& parameter, double value) {
  const Term* t = term(parameter.toStdString());
  if (!person_ || !t) return;
  person_->set_slider(t->parameter, value / t->factor);
}

double StudySession::sliderValue(const QString& parameter, double position) const {
  const Term* t = term(parameter.toStdString());
  const study::Slider* s = slider_of(trial_sliders_, t);
  if (s == nullptr) return std::numeric_limits<double>::quiet_NaN();
  try {
    return study::slider_value(*s, position) * t->factor;
  } catch (const std::invalid_argument&) {
    return std::numeric_limits<double>::quiet_NaN();
  }
}

double StudySession::sliderPosition(const QString& parameter, double value) const {
  const Term* t = term(parameter.toStdString());
  const study::Slider* s = slider_of(trial_sliders_, t);
  if (s == nullptr) return std::numeric_limits<double>::quiet_NaN();
  try {
    return study::slider_position(*s, value / t->factor);
  } catch (const std::invalid_argument&) {
    return std::numeric_limits<double>::quiet_NaN();
  }
}

void StudySession::done() {
  if (person_) person_->set_done();
}

void StudySession::addNote(const QString& text, const QStringList& tags) {
  if (session_id_ == 0) {
    emit message(QStringLiteral("Start a session before taking notes"), QStringLiteral("warning"));
    return;
  }
  store::StudyNote note;
  note.session_id = session_id_;
  if (trial_ > 0) note.trial_index = static_cast<std::size_t>(trial_);
  note.text = text.trimmed().toStdString();
  json t = json::array();
  for (const QString& tag : tags)
    if (!tag.trimmed().isEmpty()) t.push_back(tag.trimmed().toStdString());
  note.tags_json = t.dump();
  // Off the UI thread: the store may be busy with another writer for a moment.
  QPointer<StudySession> self(this);
  notes_.start([self, note, db = options_.db] {
    QString said, level = QStringLiteral("info");
    try {
      store::Store s = store::Store::open(db.toStdString());
      s.add_study_note(note);
      said = note.trial_index ? QStringLiteral("Note kept with trial %1").arg(*note.trial_index)
                              : QStringLiteral("Note kept with the session");
    } catch (const std::exception& e) {
      said = QStringLiteral("The note was not kept: ") + QString::fromUtf8(e.what()), level = QStringLiteral("error");
    }
    if (StudySession* alive = self.data())
      QMetaObject::invokeMethod(
          alive, [self, said, level] { if (self) emit self->message(said, level); }, Qt::QueuedConnection);
  });
}

void StudySession::saveSliderTags(const QVariantMap& tags) {
  if (session_id_ == 0) {
    emit message(QStringLiteral("Start a session before keeping slider tags"), QStringLiteral("warning"));
    return;
  }
  studyrun::SliderTags changed;
  for (auto it = tags.cbegin(); it != tags.cend(); ++it) {
    const QString words = it.value().toString().trimmed();
    if (!words.isEmpty() && words != slider_tags_.value(it.key()).toString())
      changed[it.key().toStdString()] = words.toStdString();
  }
  if (changed.empty()) {
    emit message(QStringLiteral("No new slider tags to keep"), QStringLiteral("info"));
    return;
  }
  // Off the UI thread, as a note: the store may be busy with another writer for a moment.
  QPointer<StudySession> self(this);
  notes_.start([self, changed, id = session_id_, db = options_.db] {
    QString said, level = QStringLiteral("info");
    bool kept = false;
    try {
      store::Store s = store::Store::open(db.toStdString());
      studyrun::save_slider_tags(s, id, changed);
      said = QStringLiteral("Slider tags kept with the session (%1)").arg(changed.size());
      kept = true;
    } catch (const std::exception& e) {
      said = QStringLiteral("The slider tags were not kept: ") + QString::fromUtf8(e.what());
      level = QStringLiteral("error");
    }
    if (StudySession* alive = self.data())
      QMetaObject::invokeMethod(
          alive,
          [self, said, level, kept, id, words = tags_map(changed)] {
            if (!self) return;
            if (kept && self->session_id_ == id) {
              for (auto it = words.cbegin(); it != words.cend(); ++it) self->slider_tags_.insert(it.key(), it.value());
              emit self->sliderTagsChanged();
            }
            emit self->message(said, level);
          },
          Qt::QueuedConnection);
  });
}

void StudySession::run(QString db_path, QByteArray protocol_text, QString code_q) {
  auto post = [this](auto f) { QMetaObject::invokeMethod(this, std::move(f), Qt::QueuedConnection); };
  const std::string code = code_q.toStdString();
  try {
    const std::string text = protocol_text.toStdString();
    const study::Protocol protocol = study::parse_protocol_text(text);
    store::Store db = store::Store::open(db_path.toStdString());
    // The participant's index: theirs when they have a session, else the next.
    const auto sessions = db.study_sessions(protocol.study);
    std::size_t index = sessions.size();
    for (const auto& s : sessions)
      if (s.participant == code) index = s.participant_index;
    const study::Plan plan = study::plan(protocol, code, index);
    const store::StudySession session =
        db.open_study_session({.study = protocol.study, .participant = code, .participant_index = index,
                               .protocol_json = text, .plan_trials = plan.trials.size(),
                               .simulated = options_.simulate});
    const std::optional<std::size_t> next = db.next_study_trial(session.session_id);
    QVariantList recent;
    const auto done_trials = db.study_trials(session.session_id);
    for (auto it = done_trials.rbegin(); it != done_trials.rend() && recent.size() < 6; ++it) recent << trial_row(*it);
    const int committed = static_cast<int>(done_trials.size());
    post([this, id = session.session_id, at = static_cast<int>(next.value_or(0)), n = static_cast<int>(plan.trials.size()),
          recent, committed, tags = tags_map(studyrun::session_slider_tags(db, session.session_id))] {
      session_id_ = id;
      slider_tags_ = tags;
      emit sliderTagsChanged();
      resumed_at_ = at;
      trials_ = n;
      recent_ = recent;
      committed_ = committed;
      emit sessionChanged();
      emit trialChanged();
      if (at > 1) emit message(QStringLiteral("%1 resumes at trial %2 of %3").arg(participant_).arg(at).arg(n),
                               QStringLiteral("info"));
    });

    std::unique_ptr<studyrun::Apparatus> apparatus;
    std::unique_ptr<studyrun::SimulatedParticipant> stand_in;
    if (options_.simulate) {
      auto core = std::make_unique<studyrun::CoreApparatus>();
      const std::uint64_t seed = plan.seed;
      stand_in = std::make_unique<studyrun::SimulatedParticipant>(core->hand(), studyrun::ParticipantModel::draw(seed), seed);
      apparatus = std::move(core);
    } else {
      apparatus = std::make_unique<studyrun::HapticdApparatus>(options_.socket.toStdString());
    }
    person_->stand_in = stand_in.get();
    PersonParticipant& person = *person_;
    studyrun::SessionOptions o;
    o.simulated = options_.simulate;
    o.cancelled = [this] { return cancel_.load(std::memory_order_relaxed); };
    o.on_display = [this, post](const studyrun::Display& d) {
      post([this, d] {
        instruction_ = QString::fromStdString(d.instruction);
        has_disk_ = d.disk.has_value();
        disk_centre_deg_ = d.disk ? deg(d.disk->centre_rad) : 0;
        disk_width_deg_ = d.disk ? deg(d.disk->width_rad) : 0;
        needle_ = d.needle;
        has_counter_ = d.counter.has_value();
        counter_ = static_cast<int>(d.counter.value_or(0));
        has_target_ = d.target_value.has_value();
        target_value_ = static_cast<int>(d.target_value.value_or(0));
        QVariantMap s;
        if (d.sliders)
          for (const Term& t : kTerms) s.insert(QString::fromLatin1(t.parameter), (*d.sliders).*(t.field) * t.factor);
        sliders_ = s;
        reference_ = QString::fromStdString(d.reference);
        emit displayChanged();
      });
    };
    bool first_trial = true;
    o.on_trial_start = [this, post, &protocol, &db, &first_trial, id = session.session_id](const study::Trial& t,
                                                                                         std::size_t) {
      // A stand-in labels the sliders as the session begins (run_session's
      // familiarization): the experimenter view shows its words.
      if (first_trial && std::holds_alternative<study::MatchingSettings>(protocol.settings))
        post([this, tags = tags_map(studyrun::session_slider_tags(db, id))] {
          slider_tags_ = tags;
          emit sliderTagsChanged();
        });
      first_trial = false;
      QVariantList ranges;
      for (const study::Slider& s : offered_sliders(protocol, t))
        if (const Term* term_ = term(s.parameter))
          ranges << QVariantMap{{QStringLiteral("parameter"), QString::fromLatin1(term_->parameter)},
                                {QStringLiteral("label"), QString::fromLatin1(term_->label)},
                                {QStringLiteral("unit"), QString::fromUtf8(term_->unit)},
                                {QStringLiteral("min"), s.min * term_->factor},
                                {QStringLiteral("max"), s.max * term_->factor},
                                {QStringLiteral("exponent"), s.perceptual_exponent}};
      post([this, index = static_cast<int>(t.index), block = static_cast<int>(t.block),
            stage = QString::fromStdString(protocol.stages.at(t.stage).name), practice = t.practice,
            condition = QString::fromStdString(study::condition_label(protocol, t)), ranges,
            sliders = offered_sliders(protocol, t)] {
        trial_ = index;
        block_ = block;
        stage_ = stage;
        practice_ = practice;
        condition_ = condition;
        trial_sliders_ = sliders;
        slider_ranges_ = ranges;
        emit trialChanged();
      });
    };
    o.on_trial_committed = [this, post](const store::StudyTrial& row) {
      post([this, r = trial_row(row)] {
        recent_.prepend(r);
        while (recent_.size() > 6) recent_.removeLast();
        ++committed_;
        emit trialChanged();
      });
    };
    const studyrun::SessionResult result =
        studyrun::run_session(db, protocol, text, code, index, *apparatus, person, o);
    post([this, finished = result.finished] {
      set_state(finished ? QStringLiteral("finished") : QStringLiteral("stopped"),
                finished ? QStringLiteral("every trial is stored") : QString());
      if (finished) emit message(QStringLiteral("%1's session is complete").arg(participant_), QStringLiteral("info"));
    });
  } catch (const studyrun::Cancelled& e) {
    post([this, why = QString::fromUtf8(e.what())] {
      set_state(QStringLiteral("stopped"), why);
      emit message(QStringLiteral("Stopped: it resumes at trial %1").arg(trial_ > 0 ? trial_ : resumed_at_),
                   QStringLiteral("info"));
    });
  } catch (const std::exception& e) {
    post([this, why = QString::fromUtf8(e.what())] {
      set_state(QStringLiteral("error"), why);
      emit message(QStringLiteral("The session stopped: ") + why, QStringLiteral("error"));
    });
  }
}

}  // namespace knoblab::ui
