// knoblab study: the user studies from the command line — simulated
// participants run through hapticd, the sessions in a store, the tidy export
// and the analysis (docs/studies.md).
#include <algorithm>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <format>
#include <fstream>
#include <memory>
#include <optional>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "cancel.hpp"
#include "commands.hpp"
#include "progress.hpp"
#include "figure_args.hpp"
#include "knoblab/control/client.hpp"
#include "knoblab/hal/shared_hand_channel.hpp"
#include "knoblab/study/participant.hpp"
#include "knoblab/study/protocol.hpp"
#include "knoblab/study/shuffle.hpp"
#include "knoblab/study/pointing_plots.hpp"
#include "knoblab/study/pointing_report.hpp"
#include "knoblab/study/trial_plots.hpp"
#include "knoblab/study/trial_report.hpp"
#include "knoblab/studyrun/core_apparatus.hpp"
#include "knoblab/studyrun/export.hpp"
#include "knoblab/studyrun/hapticd_apparatus.hpp"
#include "knoblab/studyrun/reference_knob.hpp"
#include "knoblab/studyrun/session.hpp"
#include "knoblab/studyrun/simulated_participant.hpp"
#include "store_open.hpp"

namespace knoblab::cli {

const CommandSpec kStudySpec{
    "study",
    "simulate PROTOCOL.json --participants N --db FILE.sqlite [--socket PATH] [--hand NAME] |\n"
    "       sessions STUDY --db FILE.sqlite | export STUDY --db FILE.sqlite --out FILE.csv |\n"
    "       report STUDY --db FILE.sqlite --out DIR [--json FILE|-] [--format pdf,svg,png] |\n"
    "       withdraw STUDY PARTICIPANT --db FILE.sqlite [--yes]",
    "Run user studies with simulated participants; list, export and analyse them; withdraw a participant.\n"
    "simulate: each participant (codes SIM01, SIM02, …, or from --first) runs the\n"
    "protocol's whole plan through hapticd, which must run on the sim backend with\n"
    "a guided hand (daq config \"hand\": {\"channel\": NAME}); the simulated\n"
    "participant turns the knob through that hand. Every trial is committed to the\n"
    "store as it ends; run the same command again after an interruption and each\n"
    "session resumes at the trial that was running. The store must be hapticd's\n"
    "(trials refer to the captures it records). --in-process runs hapticd's core on\n"
    "the sim plant in simulated time instead, without a daemon, a box or captures:\n"
    "a dry run of a whole protocol with many participants in minutes.\n"
    "sessions: each participant's session of STUDY: trials committed of the plan.\n"
    "export: the committed trials as a tidy CSV (docs/studies.md): the pointing study\n"
    "one row per target acquisition, other kinds one row per trial.\n"
    "report: the analysis, printed, as JSON with --json, and as figures in DIR. The\n"
    "pointing study's (thesis §4.6.2): Fitts' law per rendering with effective widths,\n"
    "the repeated-measures ANOVA of movement time, the rating tests and correlations.\n"
    "Other kinds' over the levels of one factor (--factor; default the one with the\n"
    "most levels): ratings and measures per level, Friedman and Wilcoxon on each\n"
    "rating, its correlations with EMG and SC; matching, the settings against the\n"
    "reference knobs (thesis Tables 12–14).\n"
    "withdraw: the participant withdraws from STUDY and their data is deleted for\n"
    "good: their session, its trials and notes, and their trials' captures with\n"
    "samples, biometrics and results. Without --yes it only says what it would\n"
    "delete and exits non-zero.",
    with_figure_options({{"db", true, "the sqlite store (hapticd's)"},
     {"participants", true, "how many simulated participants (default 1)"},
     {"first", true, "the first participant's number (default 1: SIM01)"},
     {"max-trials", true, "stop each session after this many trials this run (default: all)"},
     {"socket", true, "hapticd's control socket (default $KNOBLAB_SOCKET, else /run/knoblab/hapticd.sock)"},
     {"hand", true, "the sim backend's hand channel (default /knoblab-sim-hand)"},
     {"in-process", false, "simulate: hapticd's core in simulated time, no daemon (no captures, no biometrics)"},
     {"out", true, "export: the CSV file; report: the directory for the figures"},
     {"json", true, "report: write the analysis as JSON; '-' for stdout"},
     {"factor", true, "report, not pointing: the factor whose levels are compared"},
     {"yes", false, "withdraw: delete the data (without it: only say what would be deleted)"},
     kQuietOption},
                        "out"),
    2, 3, false,
    {"knoblab study simulate examples/studies/pointing.json --participants 2 --db /var/lib/knoblab/knoblab.sqlite",
     "knoblab study sessions rotary-pointing --db /var/lib/knoblab/knoblab.sqlite",
     "knoblab study export rotary-pointing --db /var/lib/knoblab/knoblab.sqlite --out trials.csv",
     "knoblab study report rotary-pointing --db /var/lib/knoblab/knoblab.sqlite --out report/ --json report.json",
     "knoblab study report list-selection --factor knob --db /var/lib/knoblab/knoblab.sqlite --out report/",
     "knoblab study withdraw rotary-pointing P07 --db /var/lib/knoblab/knoblab.sqlite --yes"}};

namespace {

std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(path + ": cannot read");
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string simulated_code(long long n) { return std::format("SIM{:02}", n); }


// A simulated participant steers the knob through hapticd's sim backend's
// guided hand: without one (or on another channel) every trial would wait
// for a hand that never moves, so say so before anything is stored.
void refuse_unless_hapticd_guides(const std::string& socket, const std::string& hand_name) {
  nlohmann::json state;
  try {
    control::Client c(socket, std::chrono::seconds(5));
    c.hello();
    state = c.call("get_state");
  } catch (const std::exception& e) {
    throw std::runtime_error("cannot ask hapticd at " + socket + " for its state: " + e.what());
  }
  const auto& channel = state.contains("hand_channel") ? state["hand_channel"] : nlohmann::json();
  if (!channel.is_string())
    throw UsageError("hapticd at " + socket + " has no guided hand for a simulated participant: give its sim "
                     "backend one (\"daq\": {\"backend\": \"sim\", \"hand\": {\"channel\": \"" + hand_name +
                     "\"}}, docs/hal.md), or run the session in simulated time (--in-process)");
  if (channel.get<std::string>() != hand_name)
    throw UsageError("hapticd's guided hand listens on " + channel.get<std::string>() + ", not " + hand_name +
                     ": pass --hand " + channel.get<std::string>());
}

int simulate(const Args& args, const std::string& protocol_path) {
  const std::string text = read_text(protocol_path);
  const study::Protocol protocol = [&] {
    try {
      return study::parse_protocol_text(text);
    } catch (const study::ProtocolError& e) {
      throw e.in_file(protocol_path);
    }
  }();
  const long long participants = args.integer("participants", 1);
  const long long first = args.integer("first", 1);
  if (participants < 1 || participants > 999) throw UsageError("--participants must be 1 … 999");
  if (first < 1 || first + participants - 1 > 999) throw UsageError("--first must be 1 … 999");
  const long long max_trials = args.integer("max-trials", 0);
  if (max_trials < 0) throw UsageError("--max-trials must be ≥ 0");
  // Through hapticd the store is hapticd's (the trials refer to its
  // captures), so it must exist; a dry run may start a new one.
  store::Store db = args.has("in-process") ? store::Store::open(args.require("db")) : open_store_to_add(args.require("db"));
  // The knob's apparatus and the hand on it: hapticd and its sim backend's
  // shared hand channel, or hapticd's core here in simulated time.
  std::optional<hal::SharedHandChannel> shared_hand;
  std::unique_ptr<studyrun::Apparatus> apparatus;
  sim::HandChannel* hand = nullptr;
  if (args.has("in-process")) {
    auto core = std::make_unique<studyrun::CoreApparatus>();
    hand = &core->hand();
    apparatus = std::move(core);
  } else {
    const std::string hand_name = args.get("hand").value_or("/knoblab-sim-hand");
    refuse_unless_hapticd_guides(hapticd_socket(args), hand_name);
    shared_hand.emplace(hand_name);
    hand = &shared_hand->channel();
    apparatus = std::make_unique<studyrun::HapticdApparatus>(hapticd_socket(args));
  }
  CancelOnSignal on_signal;  // Ctrl-C stops at the next reading; the running trial is not committed
  Progress progress = Progress::on_stderr(args, "study simulate");
  for (long long n = first; n < first + participants; ++n) {
    const std::string code = simulated_code(n);
    const auto index = static_cast<std::size_t>(n - 1);
    studyrun::SimulatedParticipant participant(
        *hand, studyrun::ParticipantModel::draw(study::participant_seed(protocol.seed, code)),
        study::participant_seed(protocol.seed, code) ^ 0xA11CEull);
    studyrun::SessionOptions options;
    options.simulated = true;
    options.max_trials = static_cast<std::size_t>(max_trials);
    options.cancelled = cancel_requested;
    options.on_trial_committed = [&](const store::StudyTrial& t) {
      progress.show(code + ": trial " + std::to_string(t.trial_index) + " committed");
    };
    const studyrun::SessionResult r = studyrun::run_session(db, protocol, text, code, index, *apparatus, participant, options);
    participant.release();
    progress.clear();
    std::cout << code << ": session " << r.session_id << ", " << r.trials_run << " trials run"
              << (r.resumed_at > 1 ? " (resumed at trial " + std::to_string(r.resumed_at) + ")" : "")
              << (r.finished ? ", finished" : ", not finished") << "\n";
  }
  return 0;
}

int sessions(const Args& args, const std::string& study_id) {
  store::Store db = open_store_to_read(args.require("db"));
  const auto list = db.study_sessions(study_id);
  if (list.empty()) {
    std::cout << "no sessions of " << study_id << "\n";
    return 0;
  }
  std::cout << "session  participant  trials     state\n";
  for (const store::StudySession& s : list) {
    char line[128];
    std::snprintf(line, sizeof line, "%7lld  %-11s  %4zu/%-4zu  %s%s\n", static_cast<long long>(s.session_id),
                  s.participant.c_str(), s.trials_committed, s.plan_trials,
                  s.finished_unix ? "finished" : "open", s.simulated ? " (simulated)" : "");
    std::cout << line;
  }
  return 0;
}

// Written whole or not at all: a half-written CSV must not pass for an export.
void write_atomically(const std::string& path, const std::string& text) {
  const std::string tmp = path + ".part";
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!(out << text) || !out.flush()) throw std::runtime_error(path + ": cannot write");
  }
  std::filesystem::rename(tmp, path);
}

int export_trials(const Args& args, const std::string& study_id) {
  store::Store db = open_store_to_read(args.require("db"));
  const std::string path = args.require("out");
  std::ostringstream csv;
  const study::Protocol protocol = studyrun::stored_protocol(db, study_id);
  std::size_t rows = 0;
  if (protocol.kind == study::Kind::Pointing) {
    const auto table = studyrun::pointing_rows(db, study_id);
    study::write_pointing_csv(csv, table);
    rows = table.size();
  } else {
    studyrun::write_trials_csv(csv, db, study_id);
    const std::string text = csv.str();
    rows = static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n')) - 1;
  }
  write_atomically(path, csv.str());
  std::cout << path << ": " << rows << (protocol.kind == study::Kind::Pointing ? " acquisitions" : " trials") << "\n";
  return 0;
}

// The report's JSON to a file or stdout, its text to stdout unless the JSON
// went there.
void print_report(const Args& args, const nlohmann::json& json, const std::string& text,
                  const std::vector<std::filesystem::path>& files) {
  if (auto json_path = args.get("json")) {
    const std::string dumped = json.dump(2) + "\n";
    if (*json_path == "-")
      std::cout << dumped;
    else
      write_atomically(*json_path, dumped);
  }
  if (args.get("json").value_or("") != "-") {
    std::cout << text;
    for (const auto& f : files) std::cout << "wrote " << f.string() << "\n";
  }
}

int pointing_report(const Args& args, const study::Protocol& protocol, store::Store& db, const std::string& study_id) {
  if (args.get("factor"))
    throw UsageError("study report: --factor is for the per-trial studies; the pointing report compares renderings");
  const auto rows = studyrun::pointing_rows(db, study_id);
  study::PointingReportOptions options;
  for (const study::Level& l : protocol.factors[studyrun::rendering_factor(protocol)].levels)
    options.rendering_order.push_back(l.name);
  const study::PointingReport r = study::pointing_report(rows, options);
  const auto files = study::write_pointing_plots(r, rows, args.require("out"), figure_options(args, "out"));
  print_report(args, study::to_json(r), study::format_pointing_report(r), files);
  return 0;
}

// The factor compared: the one named, else the one with the most levels
// (the knob, the stimulus, the texture; the first of equals).
const study::Factor& compared_factor(const Args& args, const study::Protocol& protocol) {
  if (auto name = args.get("factor")) {
    if (const auto f = protocol.factor_index(*name)) return protocol.factors[*f];
    std::string names;
    for (const study::Factor& f : protocol.factors) names += (names.empty() ? "" : ", ") + f.name;
    throw UsageError("study report: the protocol has no factor '" + *name + "' (it has " + names + ")");
  }
  const study::Factor* best = &protocol.factors.front();
  for (const study::Factor& f : protocol.factors)
    if (f.levels.size() > best->levels.size()) best = &f;
  return *best;
}

int trial_report(const Args& args, const study::Protocol& protocol, store::Store& db, const std::string& study_id) {
  const study::Factor& factor = compared_factor(args, protocol);
  study::TrialReportOptions options;
  options.factor = factor.name;
  for (const study::Level& l : factor.levels) options.levels.push_back(l.name);
  if (&factor == &protocol.factors.front()) options.references = studyrun::matching_references(protocol);
  const auto rows = studyrun::trial_rows(db, study_id);
  const study::TrialReport r = study::trial_report(rows, options);
  const auto files = study::write_trial_plots(r, args.require("out"), figure_options(args, "out"));
  print_report(args, study::to_json(r), study::format_trial_report(r), files);
  return 0;
}

int report(const Args& args, const std::string& study_id) {
  store::Store db = open_store_to_read(args.require("db"));
  args.require("out");
  const study::Protocol protocol = studyrun::stored_protocol(db, study_id);
  if (protocol.kind == study::Kind::Pointing) return pointing_report(args, protocol, db, study_id);
  return trial_report(args, protocol, db, study_id);
}

// "1 234 567": the sample counts of a whole session run to millions.
std::string with_digit_groups(std::int64_t count) {
  std::string digits = std::to_string(count);
  for (auto i = static_cast<std::ptrdiff_t>(digits.size()) - 3; i > 0; i -= 3)
    digits.insert(static_cast<std::size_t>(i), " ");
  return digits;
}

std::string counted(std::size_t n, const std::string& noun) {
  return std::to_string(n) + " " + noun + (n == 1 ? "" : "s");
}

// "1 session, 112 trials, 3 notes, 112 captures (1 234 567 samples)".
std::string withdrawal_counts(const store::StudyWithdrawal& w) {
  return counted(w.sessions, "session") + ", " + counted(w.trials, "trial") + ", " + counted(w.notes, "note") +
         ", " + counted(w.captures, "capture") + " (" + with_digit_groups(w.samples) + " samples)";
}

std::string kept_captures(const store::StudyWithdrawal& w) {
  if (w.shared_captures == 0) return "";
  return "; " + counted(w.shared_captures, "capture") + " kept: other participants' trials refer to " +
         (w.shared_captures == 1 ? "it" : "them");
}

// Deleting is final, so it takes --yes; without it the same counts, as what
// would go, and a non-zero exit: a typo in a code or a study loses nothing.
int withdraw(const Args& args, const std::string& study_id, const std::string& participant) {
  const std::string who = participant + (args.has("yes") ? " withdrawn from " : " of ") + study_id + ": ";
  if (!args.has("yes")) {
    store::Store db = open_store_to_read(args.require("db"));
    const store::StudyWithdrawal w = db.study_withdrawal(study_id, participant);
    std::cout << who << "would delete " << withdrawal_counts(w) << kept_captures(w) << "\n";
    throw UsageError("withdraw deleted nothing: add --yes to delete " + participant + "'s data for good");
  }
  store::Store db = open_store_to_add(args.require("db"));
  const store::StudyWithdrawal w = db.withdraw_study_participant(study_id, participant);
  std::cout << who << withdrawal_counts(w) << " deleted" << kept_captures(w) << "\n";
  return 0;
}

// withdraw names a participant too; the others only their STUDY or file.
void check_positionals(const std::vector<std::string>& positionals) {
  const std::string& action = positionals.at(0);
  if (action != "simulate" && action != "sessions" && action != "export" && action != "report" && action != "withdraw")
    throw UsageError("study: unknown action '" + action + "' (simulate, sessions, export, report, withdraw)");
  if (action == "withdraw") {
    if (positionals.size() != 3) throw UsageError("study withdraw: give STUDY and PARTICIPANT (a code such as P07)");
    return;
  }
  if (positionals.size() > 2)
    throw UsageError("study " + action + ": unexpected '" + positionals[2] + "' (it takes one " +
                     (action == "simulate" ? "PROTOCOL.json" : "STUDY") + ")");
}

}  // namespace

int run_study(const Args& args) {
  check_positionals(args.positionals());
  const std::string& action = args.positionals().at(0);
  const std::string& target = args.positionals().at(1);
  if (action == "withdraw") return withdraw(args, target, args.positionals().at(2));
  if (action == "simulate") return simulate(args, target);
  if (action == "sessions") return sessions(args, target);
  if (action == "export") return export_trials(args, target);
  return report(args, target);
}

}  // namespace knoblab::cli
