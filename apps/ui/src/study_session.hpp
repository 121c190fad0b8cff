// A participant's session of a user study, run from the screen: the
// experimenter view starts and stops it, the participant view shows what the
// participant's screen should (studyrun::Display) and takes their answers.
// The session runs on a thread of its own with studyrun::run_session, over
// hapticd (HapticdApparatus, a second connection to the control socket) and
// a PersonParticipant (the person at the participant view), committing each
// trial to the store as it ends; a session that exists resumes.
//
// For a dry run and the screenshot tests it runs instead in simulated time:
// hapticd's core on the sim plant (CoreApparatus) with the simulated
// participant's hand on it, pausing when the screen shows what was asked
// (`pauseAt`: a pointing target being reached, the counter with its target,
// moved sliders, the rating step, …), so a screenshot shows a real session.
#pragma once

#include <QObject>
#include <QString>
#include <QStringList>
#include <QThreadPool>
#include <QTimer>
#include <QVariantList>
#include <QVariantMap>
#include <QtQml/qqmlregistration.h>

#include <atomic>
#include <cstdint>
#include <memory>
#include <thread>
#include <vector>

namespace knoblab::study {
struct Slider;
}

namespace knoblab::ui {

class PersonParticipant;

class StudySession : public QObject {
  Q_OBJECT
  QML_ELEMENT
  QML_UNCREATABLE("knoblab-ui makes the one study session")
  // idle, running, rating, stopped, finished, error
  Q_PROPERTY(QString state READ state NOTIFY stateChanged)
  Q_PROPERTY(QString message READ message NOTIFY stateChanged)  // why it stopped or failed
  Q_PROPERTY(QVariantList protocols READ protocols CONSTANT)  // [{path, title, kind, study}]
  Q_PROPERTY(QString title READ title NOTIFY sessionChanged)
  Q_PROPERTY(QString kind READ kind NOTIFY sessionChanged)  // pointing, matching, list_selection, textures
  Q_PROPERTY(QString participant READ participant NOTIFY sessionChanged)
  Q_PROPERTY(bool simulated READ simulated CONSTANT)
  Q_PROPERTY(int resumedAt READ resumedAt NOTIFY sessionChanged)  // 1-based; 0 before it started
  // The trial running now (n of N) and its place in the plan.
  Q_PROPERTY(int trial READ trial NOTIFY trialChanged)
  Q_PROPERTY(int trials READ trials NOTIFY sessionChanged)
  Q_PROPERTY(int committed READ committed NOTIFY trialChanged)
  Q_PROPERTY(int block READ block NOTIFY trialChanged)
  Q_PROPERTY(QString stage READ stage NOTIFY trialChanged)
  Q_PROPERTY(bool practice READ practice NOTIFY trialChanged)
  Q_PROPERTY(QString condition READ condition NOTIFY trialChanged)
  // The matching sliders of this trial: [{parameter, label, unit, min, max,
  // exponent}] in presentation units (mN·m/(rad/s²), mN·m/(rad/s), mN·m,
  // detents/rev); exponent is the slider's perceptual_exponent β.
  Q_PROPERTY(QVariantList sliderRanges READ sliderRanges NOTIFY trialChanged)
  // A matching study's sliders, every one of the protocol (the
  // familiarization labels them all): [{parameter, label}]; empty for
  // another kind.
  Q_PROPERTY(QVariantList protocolSliders READ protocolSliders NOTIFY sessionChanged)
  // The session's slider tags as stored, the newest per slider: {parameter:
  // words} (studyrun/slider_tags.hpp: the novices' sticky notes, Table 15).
  Q_PROPERTY(QVariantMap sliderTags READ sliderTags NOTIFY sliderTagsChanged)
  // The participant's screen (studyrun::Display), angles in degrees.
  Q_PROPERTY(QString instruction READ instruction NOTIFY displayChanged)
  Q_PROPERTY(bool hasDisk READ hasDisk NOTIFY displayChanged)
  Q_PROPERTY(double diskCentreDeg READ diskCentreDeg NOTIFY displayChanged)
  Q_PROPERTY(double diskWidthDeg READ diskWidthDeg NOTIFY displayChanged)
  Q_PROPERTY(bool needle READ needle NOTIFY displayChanged)
  Q_PROPERTY(bool hasCounter READ hasCounter NOTIFY displayChanged)
  Q_PROPERTY(int counter READ counter NOTIFY displayChanged)
  Q_PROPERTY(bool hasTarget READ hasTarget NOTIFY displayChanged)
  Q_PROPERTY(int targetValue READ targetValue NOTIFY displayChanged)
  Q_PROPERTY(QVariantMap sliders READ sliders NOTIFY displayChanged)  // {parameter: presentation value}
  Q_PROPERTY(QString reference READ reference NOTIFY displayChanged)
  Q_PROPERTY(double needleDeg READ needleDeg NOTIFY needleChanged)  // the knob, from its readings
  // The rating step: [{scale, min, max, minIs, prompt}].
  Q_PROPERTY(QVariantList ratingScales READ ratingScales NOTIFY ratingScalesChanged)
  // The newest committed trials, newest first: [{index, block, stage, practice, condition, ratings, result}].
  Q_PROPERTY(QVariantList recentTrials READ recentTrials NOTIFY trialChanged)

 public:
  struct Options {
    QString db;         // the store (written: sessions, trials, notes)
    QString socket;     // hapticd's control socket
    QString studiesDir;  // the protocol files offered
    // Simulated time (CoreApparatus + SimulatedParticipant); pause_at: what
    // to stop at (target, counter, freeform, sliders, texture, rating,
    // trials:N); empty runs on.
    bool simulate = false;
    QString pause_at;
  };
  explicit StudySession(Options options, QObject* parent = nullptr);
  ~StudySession() override;

  QString state() const { return state_; }
  QString message() const { return message_; }
  QVariantList protocols() const { return protocols_; }
  QString title() const { return title_; }
  QString kind() const { return kind_; }
  QString participant() const { return participant_; }
  bool simulated() const { return options_.simulate; }
  int resumedAt() const { return resumed_at_; }
  int trial() const { return trial_; }
  int trials() const { return trials_; }
  int committed() const { return committed_; }
  int block() const { return block_; }
  QString stage() const { return stage_; }
  bool practice() const { return practice_; }
  QString condition() const { return condition_; }
  QVariantList sliderRanges() const { return slider_ranges_; }
  QVariantList protocolSliders() const { return protocol_sliders_; }
  QVariantMap sliderTags() const { return slider_tags_; }
  QString instruction() const { return instruction_; }
  bool hasDisk() const { return has_disk_; }
  double diskCentreDeg() const { return disk_centre_deg_; }
  double diskWidthDeg() const { return disk_width_deg_; }
  bool needle() const { return needle_; }
  bool hasCounter() const { return has_counter_; }
  int counter() const { return counter_; }
  bool hasTarget() const { return has_target_; }
  int targetValue() const { return target_value_; }
  QVariantMap sliders() const { return sliders_; }
  QString reference() const { return reference_; }
  double needleDeg() const { return needle_deg_; }
  QVariantList ratingScales() const { return rating_scales_; }
  QVariantList recentTrials() const { return recent_; }
  // A simulated session still on its way to where it pauses (the screenshot waits).
  bool settling() const;

  // "" when the code is a pseudonymous participant code, else why not.
  Q_INVOKABLE QString checkCode(const QString& code) const;
  // Starts (or resumes) the participant's session of the protocol file;
  // false with a message when it cannot.
  Q_INVOKABLE bool start(const QString& protocolPath, const QString& code);
  Q_INVOKABLE void stop();
  // The rating step's answers: {scale: value} or {"affect_grid": {valence, arousal}}.
  Q_INVOKABLE void submitRatings(const QVariantMap& ratings);
  // A matching slider, in presentation units.
  Q_INVOKABLE void setSlider(const QString& parameter, double value);
  // A matching slider of this trial: its value (presentation units) at a
  // position from 0 (bottom) to 1 (top), and back, by the protocol's power
  // law (study::slider_value, slider_position), so the participant view
  // moves its sliders in position and never maps values itself. NaN when
  // the trial has no such slider or the number is not finite.
  Q_INVOKABLE double sliderValue(const QString& parameter, double position) const;
  Q_INVOKABLE double sliderPosition(const QString& parameter, double value) const;
  Q_INVOKABLE void done();
  // A think-aloud note and free-text tags about the running trial.
  Q_INVOKABLE void addNote(const QString& text, const QStringList& tags);
  // The participant's words for each slider, {parameter: words}, kept with
  // the session as studyrun::save_slider_tags keeps them (one note per
  // slider); only words that differ from those stored are written, blank
  // ones never (a note is not taken back).
  Q_INVOKABLE void saveSliderTags(const QVariantMap& tags);

 signals:
  void stateChanged();
  void sessionChanged();
  void trialChanged();
  void displayChanged();
  void needleChanged();
  void ratingScalesChanged();
  void sliderTagsChanged();
  void message(const QString& text, const QString& level);

 private:
  void set_state(const QString& state, const QString& message = {});
  void run(QString path, QByteArray protocol_text, QString code);
  void join();

  Options options_;
  QVariantList protocols_;
  std::thread worker_;
  std::atomic<bool> cancel_{false};
  std::atomic<bool> paused_{false};
  std::atomic<double> theta_{0};
  std::shared_ptr<PersonParticipant> person_;
  QTimer needle_timer_;
  QThreadPool notes_;
  QString protocol_path_;
  std::int64_t session_id_ = 0;

  QString state_ = QStringLiteral("idle"), message_;
  QString title_, kind_, participant_;
  int resumed_at_ = 0, trial_ = 0, trials_ = 0, committed_ = 0, block_ = 0;
  QString stage_, condition_;
  bool practice_ = false;
  QVariantList slider_ranges_;
  std::vector<study::Slider> trial_sliders_;  // SI, as the protocol gives them
  QVariantList protocol_sliders_;
  QVariantMap slider_tags_;
  QString instruction_;
  bool has_disk_ = false, needle_ = false, has_counter_ = false, has_target_ = false;
  double disk_centre_deg_ = 0, disk_width_deg_ = 0, needle_deg_ = 0;
  int counter_ = 0, target_value_ = 0;
  QVariantMap sliders_;
  QString reference_;
  QVariantList rating_scales_;
  QVariantList recent_;
};

}  // namespace knoblab::ui
