// The knoblab subcommands. Each returns the process exit code and throws
// UsageError (exit 2) or any std::exception (exit 1) with a clear message.
#pragma once

#include <string>
#include <vector>

#include "args.hpp"

namespace knoblab::cli {

struct Command {
  const CommandSpec& spec;
  int (*run)(const Args&);
};

const std::vector<Command>& commands();

extern const CommandSpec kSimulateSpec, kImportSpec, kExportSpec, kInspectSpec, kDemoSpec,
    kListSpec, kConvertSpec, kFitSpec, kFitsSpec, kFitExportSpec, kDiscrepancySpec, kCtlSpec, kCompareSpec,
    kResultsSpec, kStudySpec, kDesignSpec;
int run_simulate(const Args&);
int run_import(const Args&);
int run_export(const Args&);
int run_inspect(const Args&);
int run_demo(const Args&);
int run_list(const Args&);
int run_convert(const Args&);
int run_fit(const Args&);
int run_fits(const Args&);
int run_fit_export(const Args&);
int run_results(const Args&);
int run_discrepancy(const Args&);
int run_ctl(const Args&);
int run_compare(const Args&);
int run_study(const Args&);
int run_design(const Args&);

// hapticd's control socket: --socket, else $KNOBLAB_SOCKET, else /run/knoblab/hapticd.sock.
std::string hapticd_socket(const Args& args);

}  // namespace knoblab::cli
