// `railwear history bands` and `railwear history life` (issue 19 points 4 and 5): an ensemble's
// percentile bands of a wear measure against MGT, and the traffic (and years) each run, each
// curve class and the line take to reach grinding or renewal limits.
//
// The ensemble. With --plan PLAN.toml (a sweep plan, app/sweep_plan.h) the runs are the plan's
// lines (runs named by their line ids, as `sweep --merge` stores them), grouped by curve class
// (SweepLine::group: the values of the axes that are not distributions); every line's run must
// be in the database and complete (InputError naming the missing lines otherwise). Without
// --plan every complete run of the database is one ensemble "(all runs)" (runs not complete are
// left out, said on stderr).
//
// A run's measure against MGT is read from its stored steps: W1/W2/W3 and the worn area from the
// steps table, rcf_damage as the largest value of the step's "rcf_damage" distribution. --rail
// low reads a two-rail run's low rail.
//
// Failed runs (issue 19): a run in state aborted with a recorded failure (schema 9; a sweep
// line whose run failed, merged by `sweep --merge`) is left out of the ensembles and named (run,
// class, the plan's values of its line, the error) in a "Failed runs" table after the text
// output, in "failed_runs" of the JSON, and in a warning on stderr (every format; the CSV stays
// a table of numbers). The exit code stays 0: the answer is over the complete runs and says
// which are missing (the sweep and the merge exited 3). A line with no run, or one started and
// not complete without a recorded failure, is still refused (it is work left to do).
//
// bands: on an MGT grid of --points values from 0 to the smallest final MGT of the class's runs
// (so every run covers it and nothing is extrapolated), each run's measure interpolated linearly
// between its stored steps, then percentiles over the runs (wear/ensemble.h
// ComputePercentileBands; GSL, linear between order statistics). A table, CSV or JSON on
// stdout; --plot PREFIX: PREFIX_bands.png (gnuplot), one panel per measure, the bands shaded.
//
// life: for each limit (the plan's [life] limits and --limit MEASURE=VALUE), each run's first
// MGT at the limit (wear/ensemble.h FirstCrossing: linear between the stored steps around it;
// "not reached" when no stored step reaches it), years = MGT / annual MGT (the plan's
// annual_mgt or --annual-mgt); per class the percentiles over its runs (a percentile that needs
// a run that never reached the limit is "not reached", i.e. beyond that run's final MGT); and,
// when the plan gives [[life.class]] lengths, the line summary: each run weighted by its class's
// length / the class's runs (a class without a [[life.class]] length weighs nothing there), the
// weighted quantile (wear/ensemble.h WeightedQuantile) = the
// traffic by which that share of the line's curve length reaches the limit.
// --rail both (life only): both rails of each two-rail run (the high and low rail of a curve);
// a run's life to a limit is the earlier of its two rails' (the rail is replaced when either
// reaches it), and the output names the governing rail per run and limit ("high", "low", "both"
// when they reach it at the same MGT) and counts them per class.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "app/history_command.h"

namespace CLI {
class App;
}

namespace railwear::app {

struct HistoryEnsembleOptions {
  std::string plan;  // the sweep plan; empty: every complete run of the database
  std::vector<double> percentiles = {5.0, 50.0, 95.0};
  std::string rail = "high";  // high or low; life also both
};

struct HistoryBandsOptions : HistoryEnsembleOptions {
  std::vector<std::string> measures = {"w1_mm", "w2_mm", "w3_mm", "worn_area_mm2"};
  int points = 11;              // MGT grid points, 0 to the smallest final MGT
  std::string format = "table";  // table, csv or json
  std::string plot;             // PNG prefix; empty: no plot
};

struct HistoryLifeOptions : HistoryEnsembleOptions {
  std::vector<std::string> limits;   // "MEASURE=VALUE", added to the plan's
  std::optional<double> annual_mgt;  // overrides the plan's
  bool json = false;
};

// Adds `bands` and `life` to `history` (`common` holds its --db).
void SetupHistoryEnsemble(CLI::App* history, const std::shared_ptr<HistoryOptions>& common);

// InputError (exit 2) for a bad option, plan, limit or ensemble (named); std::runtime_error when
// gnuplot is missing for --plot.
void RunHistoryBands(const HistoryOptions& options, const HistoryBandsOptions& bands);
void RunHistoryLife(const HistoryOptions& options, const HistoryLifeOptions& life);

}  // namespace railwear::app
