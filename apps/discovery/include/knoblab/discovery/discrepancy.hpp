// Discrepancy discovery: where a recording and the fitted thesis model
// disagree, which physics from the effect library explains it, fitted and
// checked on data the fit did not see (docs/discrepancy.md).
//
//   FitData d = fit::prepare(capture);
//   DiscrepancyResult r = discover(d);
//   r.findings[0].effect, r.findings[0].explanation, r.final_model.heldout_rmse_Nm
//
// The recording is cut into contiguous time blocks; even blocks train, odd
// blocks are held out (or a second recording is held out whole). The base model (Eq. 6, fit_knob's start and stick
// band) is fitted on the training blocks. Every candidate effect is then
// fitted jointly with the base parameters (Ceres, autodiff through
// knoblab/model/effects.hpp) and scored on the held-out blocks. A candidate
// passes when it lowers the held-out RMS by at least min_heldout_gain,
// consistently across the held-out blocks (block_drop.hpp: the t or the
// signed-rank z of the per-block mean-square drops ≥ min_t) and lowers the
// BIC; the passing one with the largest held-out gain is kept, and the
// search repeats with it in the model, until nothing passes. The findings
// are reported only when together they cut the held-out RMS by at least
// min_reported_gain; below that bar they are tentative: shown, not adopted.
#pragma once

#include <limits>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "knoblab/discovery/effects.hpp"
#include "knoblab/fit/fit_data.hpp"
#include "knoblab/fit/knob_fit.hpp"
#include "knoblab/fit/run_hooks.hpp"

namespace knoblab::discovery {

using Params = std::vector<std::pair<std::string, double>>;

// The final model as a knob a simulator or renderer takes: Eq. 6 with the
// base fit's stick band, and each kept effect with the parameters a finding
// reports, under the effect table's names (model/effect_table.hpp), without
// the values derived beside them: what `knoblab simulate --effects` takes. Detents with a
// negative amplitude are turned by half a period (A > 0, S + π, odd
// harmonics negated): the same torque, and |A| as Eq. 14 renders it.
struct EffectTerm {
  EffectId effect{};
  Params params;
};
struct FinalKnob {
  std::vector<double> params;  // Eq. 6, fit order (model::kThesisParamNames)
  bool detents = false;        // the detent term is fitted (else A = 0)
  std::optional<fit::StickBand> stick;
  std::vector<EffectTerm> effects;
  // A render model's knob (Eq. 14 has no detent phase): the phase is the
  // recording's, fitted to it even where the rest is held.
  bool detent_phase_unknown = false;
};

struct DiscrepancyOptions {
  std::size_t blocks = 32;          // contiguous time blocks, odd ones held out
  std::size_t max_rows = 6000;      // training / held-out rows used, evenly strided
  double min_heldout_gain = 0.02;   // held-out RMS must fall by ≥ 2 %
  double min_t = 3.0;               // … in most held-out blocks (drop_consistency)
  // Two candidates explain the same residual when the torques they add
  // correlate (≥ 0.5 on the training rows). Then the one with fewer
  // parameters is named unless the richer one's held-out RMS is lower by at
  // least this much (relative); the finding's sentence names the runner-up
  // and the margin.
  double parsimony_margin = 0.02;
  // A finding is a claim that the model left physics out; it is made only
  // when the terms found cut the held-out RMS (base → final) by ≥ 20 % where
  // they act (the held-out rows in any finding's support). A smaller,
  // consistent improvement is real evidence but too weak to act on: it is
  // reported as tentative and the final model stays the base. A candidate
  // that cuts the held-out RMS by this much on its own support (at least
  // min_support_rows rows there) is significant even when that is under
  // min_heldout_gain over all rows: an effect on 2 % of the rows is not
  // hidden by the other 98 %.
  double min_reported_gain = 0.20;
  std::size_t min_support_rows = 50;
  std::size_t max_findings = 4;
  std::vector<EffectId> effects;    // candidates; empty: every implemented one
  // Progress ("fitting the base model", "trying candidates, round N" k of
  // n, "residual tests") and cancellation, checked in the base fit's Ceres
  // iterations and between candidates: discover() throws fit::Cancelled.
  fit::RunHooks hooks;
  // The base from a given model (knoblab discrepancy --model: a fit's JSON,
  // a render model or a model file, e.g. the simulation the user trusts)
  // instead of a fit of Eq. 6: its terms, stick band and effects are held as
  // given unless refit_base, and the search finds what the recording has
  // that the model lacks.
  std::optional<FinalKnob> base_model;
  bool refit_base = false;
};

struct Finding {
  EffectId effect{};
  double confidence = 0.0;   // 0…1
  std::string where;         // where the residual was structured
  std::string explanation;   // what it is, then its held-out figures
  Params params;             // the effect's parameters (SI; the effect table's names)
  // Before and after the effect, over the rows the base and every finding's
  // model describe, so that they chain: one finding's after is the next one's
  // before (a delay or a coupling's twist leaves some rows undescribed).
  double rmse_before_Nm = 0.0, rmse_after_Nm = 0.0;                  // training rows
  double heldout_rmse_before_Nm = 0.0, heldout_rmse_after_Nm = 0.0;  // held-out rows
  double bic_before = 0.0, bic_after = 0.0;
  std::size_t heldout_rows = 0;  // the held-out rows those figures are over
  // Where it acts: the held-out rows where the effect changes the model's
  // torque by at least a tenth of its largest change (99th percentile over
  // the training rows), and the held-out RMS there before and after. An
  // effect near zero speed or after reversals is judged there.
  std::size_t support_rows = 0;
  double support_heldout_rmse_before_Nm = 0.0, support_heldout_rmse_after_Nm = 0.0;
  double t_stat = 0.0;       // held-out blocks' mean-square drops: drop_consistency
};

struct ModelSummary {
  Params params;             // Eq. 6 names, then "<effect>.<name>"
  double rmse_Nm = 0.0;      // training rows
  double heldout_rmse_Nm = 0.0;
  double bic = 0.0;
  // The held-out rows the model describes, which heldout_rmse_Nm is over: a
  // delay moves some rows' motion into the stick band, a coupling's twist
  // leaves out the rows where its knob creeps.
  std::size_t heldout_rows = 0;
  // From the residual trace (whiteness.hpp): held-out rows when there are
  // enough. fit % as MATLAB's compare; p of the Ljung–Box whiteness test and
  // of the independence from ω test (NaN: too few rows).
  double fit_percent = 0.0;
  double whiteness_p = 0.0;
  double independence_p = 0.0;
  // The forward view: the model driven by the measured torque over 20 ms
  // windows from the measured state, on the held-out data; RMS of the
  // simulated − measured angle (NaN: no positive inertia to integrate).
  double forward_rmse_rad = 0.0;
};

struct CandidateScore {      // every candidate of every round, for the report
  int round = 0;
  EffectId effect{};
  double heldout_gain = 0.0;  // 1 − RMS_after / RMS_before on held-out rows
  double t_stat = 0.0;
  bool kept = false;
};

// The rows the analysis used, with the base model's and the final model's
// residual (measured − model torque), for plots and whiteness tests.
// Training rows first, then held-out rows, each in time order.
struct ResidualTrace {
  std::vector<double> t, theta, omega, torque;
  std::vector<double> before, after;  // N·m
  std::vector<char> heldout;          // 1: a held-out row
  std::size_t size() const { return t.size(); }
};

struct DiscrepancyResult {
  // The recording's (FitData::axis): the sentences' and the report's units;
  // the figures stay SI, in the channel's own units (m and N when linear).
  fit::Axis axis = fit::Axis::Rotary;
  ModelSummary base, final_model;
  FinalKnob final_knob;  // final_model's terms
  std::vector<Finding> findings;  // empty: nothing is missing
  // Found, but together under min_reported_gain: not in the final model;
  // the held-out RMS with them added (NaN when there are none).
  std::vector<Finding> tentative;
  double tentative_heldout_rmse_Nm = std::numeric_limits<double>::quiet_NaN();
  double min_reported_gain = 0.0;  // the bar this result was judged by
  std::vector<CandidateScore> candidates;
  std::size_t train_rows = 0, heldout_rows = 0;
  // The rows slower than this (rad/s; m/s on a linear axis) were left out:
  // the base's stick band, and at least 2 % of the 95th-percentile speed.
  double slow_speed = 0.0;
  // Time blocks the recording was cut into: opt.blocks, or more for a
  // recording that passes each angle once (discover.cpp, blocks_for); 0 with
  // a held-out recording.
  std::size_t blocks = 0;
  // Base → final on the held-out rows both describe (NaN without findings):
  // their count, and each model's held-out RMS there.
  struct SameRows {
    std::size_t rows = 0;
    double base_Nm = 0.0, final_Nm = 0.0;
  } same_rows;
  bool heldout_recording = false;  // held out: another recording, not time blocks
  bool base_given = false;         // the base is DiscrepancyOptions::base_model
  bool base_held = false;          // … held as given (not refitted)
  ResidualTrace trace;
  double seconds = 0.0;
};

// The effects discover() can fit today.
std::vector<EffectId> implemented_effects();
// … those that apply to an axis, discover()'s candidates when
// DiscrepancyOptions::effects is empty: a linear axis has no gravity (a sine
// of the position in metres; its carriage's weight is a constant force,
// which `offset` is).
std::vector<EffectId> implemented_effects(fit::Axis axis);

// Throws fit::FitDataError when the data cannot identify the base model,
// fit::Cancelled when opt.hooks says so.
DiscrepancyResult discover(const fit::FitData& data, const DiscrepancyOptions& opt = {});

// The same, trained on the whole of `data` and scored on another recording
// of the same knob (its time blocks give the held-out t): for recordings
// that pass each position once, where held-out time blocks would be
// positions the training never saw.
DiscrepancyResult discover(const fit::FitData& data, const fit::FitData& heldout,
                           const DiscrepancyOptions& opt = {});

// {"base": …, "findings": […], "final": …} with the names docs/discrepancy.md fixes;
// "axis": "linear" first for a linear axis (SI: read rad as m, N·m as N).
std::string to_json(const DiscrepancyResult& r, int indent = 2);

// The final model as a model file (docs/discrepancy.md, "Model file"):
// thesis6 params and stick, "effects", and "render", the base reduced to
// Eq. 14 over the captured velocities `omega` as knoblab fit
// --render-model reduces a fit. `input` names the capture in "source".
std::string model_file_json(const DiscrepancyResult& r, std::span<const double> omega, const std::string& input);

// When the base and the final model do not describe the same held-out rows,
// one sentence giving both held-out RMS on the rows both describe;
// otherwise empty.
std::string same_rows_sentence(const DiscrepancyResult& r);

}  // namespace knoblab::discovery
