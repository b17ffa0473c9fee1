#pragma once
// `sartor drape ... --wear-time S` (or `--analysis creep`): after the static
// drape, hours of wear with the garment's per-panel fabrics creeping, then
// take-off (solvers/wear.hpp): the options, the garment's held, hem and bagging
// vertices, and the outputs wear.csv, takeoff.csv, summary.json's "wear",
// wear/series.{h5,xmf} and takeoff/series.{h5,xmf}. docs/wear.md.

#include "app/cli.hpp"
#include "app/cloth_case.hpp"
#include "fem/cloth_output.hpp"
#include "solvers/wear.hpp"

#include <nlohmann/json_fwd.hpp>

#include <memory>
#include <string>
#include <vector>

namespace sartor {

// --wear-time, --take-off-times, --recovery-time, --hold-band, --hem-band,
// --bagging-box, --wear-first-step, --no-step-certificate.
const std::vector<OptionSpec>& wear_option_specs();

// Whether the options ask for wear (--wear-time given).
bool wear_requested(const Options& options);

// What a wear run did, filled by the hook.
struct WearRun {
  bool ran = false;
  std::string scheme;
  std::vector<std::string> fabrics;
  WearReport report;
  std::vector<int> held, hem;
  double cpu_seconds = 0.0;
  long checkpoints_written = 0;
  double resumed_time = -1.0; // s: the wear time resumed from (--restart); -1: none
};

// Sets cloth->after_statics so that the drape's solve goes on into the wear
// and take-off the options describe, writing the series into `directory`
// (rank 0) and the results into *run. Throws InputError for bad options.
void attach_wear(const Options& options, const std::string& directory,
                 const ClothOutputLabels& labels, CaseCloth* cloth,
                 const std::shared_ptr<WearRun>& run);

// summary["wear"].
void add_wear_summary(const WearRun& run, const ClothOutputLabels& labels, nlohmann::json& summary);

// The closing lines of the wear: steps, Newton iterations, and per take-off
// the hem drop, bagging height, largest permanent strain and certificate.
void print_wear(const WearRun& run);

// Rank 0: wear.csv (one row per accepted wear step) and takeoff.csv (one per
// take-off) in `directory`.
void write_wear_tables(const std::string& directory, const WearRun& run);

} // namespace sartor
