// A fit as JSON: the format outside tools read (docs/fit.md). SI units.
//   {"model": "thesis6", ["axis": "linear",]     (only for a linear axis: m, N)
//    "params": {"M_acc": …, "C_vel_neg": …, …, "S_pos": …},
//    "ci95":   {"M_acc": [lo, hi], …},          (null for a held parameter)
//    "se": {…}, "held": ["A_pos", …],
//    "detents": {"present": true, "per_rev": 12.0, "power": …, "false_alarm": …},
//    "stick": {"dv": …, "D_neg": …, "D_pos": …} | null,
//    "rmse_Nm": …, "fit_percent": …, "bic": …, "ci95_torque_Nm": …,
//    "samples": …, "outliers": …, "iterations": …, "seconds": …}
// The "params" object (with "stick") is also a knob file `knoblab simulate
// --params` reads.
#pragma once

#include <string>

#include "knoblab/fit/knob_fit.hpp"

namespace knoblab::fit {

std::string to_json(const FitResult& r, int indent = 2);

// Just the model: {"model", "params", "stick"} — the knob file `knoblab
// simulate --params` reads, and the fits table's params column.
std::string knob_json(const FitResult& r);

}  // namespace knoblab::fit
