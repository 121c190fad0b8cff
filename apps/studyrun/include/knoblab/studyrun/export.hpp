// A study's committed trials out of the store as tidy tables
// (docs/studies.md, "Exporting"): the pointing study as one row per target
// acquisition (study/tidy.hpp, what its report reads), every other kind as
// one row per trial with a column per factor, per measure and per rating.
#pragma once

#include <ostream>
#include <string_view>
#include <vector>

#include "knoblab/store/store.hpp"
#include "knoblab/study/protocol.hpp"
#include "knoblab/study/tidy.hpp"
#include "knoblab/study/trial_report.hpp"

namespace knoblab::studyrun {

// The protocol the study's sessions ran (the first session's; all must
// agree). Throws std::invalid_argument when the store has no session of the
// study or its sessions ran different protocols.
study::Protocol stored_protocol(store::Store& store, std::string_view study);

// A pointing protocol's rendering factor: the one that is neither its
// amplitude nor its width factor (its levels are the report's renderings).
std::size_t rendering_factor(const study::Protocol& protocol);

// Every committed trial of a pointing study, practice included (marked), one
// row per acquisition; acquisitions never made (a trial that timed out) are
// left out. The rating is the protocol's first scale.
std::vector<study::PointingRow> pointing_rows(store::Store& store, std::string_view study);

// Any study's committed trials, practice included (marked), as the per-trial
// report reads them: each factor's level, the ratings and the numeric
// measures flattened as write_trials_csv names its columns, the biometric
// scores in µV and µS.
std::vector<study::TrialRow> trial_rows(store::Store& store, std::string_view study);

// Any study, one row per trial: participant, session, block, trial,
// practice, stage, a column per factor (its level), started_unix,
// duration_s, a column per scalar measure the task recorded that is not
// already a factor's column (the matching
// sliders as slider_<parameter>, SI), a column per rating (the affect grid
// as affect_grid_valence, affect_grid_arousal), emg_uV, sc_uS, capture_id.
// Missing values are empty (NA in R and pandas).
void write_trials_csv(std::ostream& out, store::Store& store, std::string_view study);

}  // namespace knoblab::studyrun
