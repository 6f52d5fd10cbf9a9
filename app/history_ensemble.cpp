// `railwear history bands` and `history life`: ensembles of stored runs, their percentile bands
// and their traffic to wear limits.
#include "app/history_ensemble.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>

#include <fmt/format.h>
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "app/gnuplot.h"
#include "app/history_plot.h"
#include "app/number_format.h"
#include "app/stored_study.h"
#include "app/sweep_command.h"
#include "app/sweep_plan.h"
#include "core/numerics/input_error.h"
#include "profiles_db/profile_store.h"
#include "wear/ensemble.h"
#include "wear/traffic.h"

namespace railwear::app {
namespace fs = std::filesystem;
namespace {

// One ensemble: a curve class's runs.
struct EnsembleGroup {
  std::string label;
  std::vector<RunInfo> runs;
};

// A run that failed (state aborted, its failure recorded: schema 9): named, never banded.
struct FailedRun {
  std::string run;
  std::string label;   // its curve class
  std::string values;  // the plan's values of its line ("" without --plan)
  std::string message;
  std::string text;  // as printed: "line 3 (ID; values): message" or "run 'NAME': message"
};

// The ensembles of --plan (one per curve class, in manifest order), else every complete run.
// Runs that failed with a recorded failure go to `failed` (left out of every ensemble).
std::vector<EnsembleGroup> Ensembles(const ProfileStore& db, const std::string& plan_path,
                                     SweepPlan* plan_out, std::vector<FailedRun>* failed) {
  std::vector<EnsembleGroup> groups;
  if (plan_path.empty()) {
    EnsembleGroup all{"(all runs)", {}};
    std::vector<std::string> left_out;
    for (const RunInfo& run : db.Runs()) {
      if (run.state == RunState::kComplete) {
        all.runs.push_back(run);
      } else if (const std::optional<RunFailure> f =
                     run.state == RunState::kAborted ? db.FindRunFailure(run.id) : std::nullopt) {
        failed->push_back({run.name, all.label, "", f->message,
                           fmt::format("run '{}': {}", run.name, f->message)});
      } else {
        left_out.push_back(run.name);
      }
    }
    if (!left_out.empty()) {
      std::cerr << fmt::format("railwear: {} run(s) not complete, left out: {}\n",
                               left_out.size(), fmt::join(left_out, ", "));
    }
    if (all.runs.empty()) {
      throw InputError(fmt::format(
          "database '{}': no complete run; expected the complete runs of an ensemble (or --plan)",
          db.path()));
    }
    groups.push_back(std::move(all));
    return groups;
  }
  *plan_out = LoadSweepPlan(plan_path);
  std::vector<int> missing;
  for (const SweepLine& line : plan_out->lines) {
    const std::optional<RunInfo> run = db.FindRun(line.id);
    if (run && run->state == RunState::kAborted) {
      if (const std::optional<RunFailure> f = db.FindRunFailure(run->id)) {
        failed->push_back({line.id, line.group, line.Differences(), f->message,
                           FailedLineText(line, f->message)});
        continue;
      }
    }
    if (!run || run->state != RunState::kComplete) {
      missing.push_back(line.index);
      continue;
    }
    auto g = std::find_if(groups.begin(), groups.end(),
                          [&](const EnsembleGroup& e) { return e.label == line.group; });
    if (g == groups.end()) g = groups.insert(groups.end(), {line.group, {}});
    g->runs.push_back(*run);
  }
  if (!missing.empty()) {
    std::string lines;
    for (size_t i = 0; i < missing.size() && i < 10; ++i) {
      lines += fmt::format("{}{}", i ? ", " : "", missing[i]);
    }
    if (missing.size() > 10) lines += ", ...";
    throw InputError(fmt::format(
        "--plan {}: {} of {} line(s) have no complete run in database '{}' (lines {}); expected "
        "every line run and merged: `railwear sweep {}` then `railwear sweep {} --merge`",
        plan_path, missing.size(), plan_out->lines.size(), db.path(), lines, plan_path,
        plan_path));
  }
  if (groups.empty()) {
    throw InputError(fmt::format(
        "--plan {}: every one of its {} run(s) in database '{}' failed (first: {}); expected "
        "complete runs to band",
        plan_path, failed->size(), db.path(), failed->front().text));
  }
  return groups;
}

// The failed runs on stderr, as a warning (every format), and as a table for the text output.
void WarnOfFailedRuns(const std::vector<FailedRun>& failed, const std::string& left_out_of) {
  if (failed.empty()) return;
  std::vector<std::string> texts;
  for (const FailedRun& f : failed) texts.push_back(f.text);
  std::cerr << fmt::format("railwear: warning: {} run(s) failed and are left out of the {}: {}\n",
                           failed.size(), left_out_of, fmt::join(texts, "; "));
}

std::string FailedRunsTable(const std::vector<FailedRun>& failed) {
  std::vector<std::vector<std::string>> rows;
  for (const FailedRun& f : failed) {
    rows.push_back({f.run, f.label, f.values.empty() ? "-" : f.values, f.message});
  }
  return AlignedTable({"run", "class", "values", "error"}, rows);
}

nlohmann::json FailedRunsJson(const std::vector<FailedRun>& failed) {
  nlohmann::json out = nlohmann::json::array();
  for (const FailedRun& f : failed) {
    out.push_back({{"run", f.run}, {"class", f.label}, {"values", f.values}, {"error", f.message}});
  }
  return out;
}

// The run's `measure` against MGT, of the chosen rail.
MeasureSeries SeriesOf(const ProfileStore& db, const RunInfo& run, const std::string& measure,
                       RailSide rail) {
  std::vector<StepRecord> steps = db.Steps(run.id);
  const bool damage = measure == "rcf_damage";
  if (damage) {
    for (StepRecord& s : steps) s = db.LoadStep(run.id, s.step);
  }
  if (rail == RailSide::kLow) {
    steps = LowRailSteps(steps);
    if (steps.empty()) {
      throw InputError(fmt::format(
          "--rail low: run '{}' of database '{}' has one rail only; expected two-rail runs",
          run.name, db.path()));
    }
  }
  MeasureSeries out;
  for (const StepRecord& s : steps) {
    double v = 0.0;
    if (measure == "w1_mm") {
      v = s.w1_mm;
    } else if (measure == "w2_mm") {
      v = s.w2_mm;
    } else if (measure == "w3_mm") {
      v = s.w3_mm;
    } else if (measure == "worn_area_mm2") {
      v = s.worn_area_mm2;
    } else {
      const auto d = std::find_if(s.distributions.begin(), s.distributions.end(),
                                  [](const Distribution& x) { return x.kind == "rcf_damage"; });
      if (s.step == steps.front().step && d == s.distributions.end()) {
        v = 0.0;  // the unworn step 0 carries no damage
      } else if (d == s.distributions.end()) {
        throw InputError(fmt::format(
            "measure rcf_damage: run '{}' of database '{}' stores no RCF damage (step {}); "
            "expected runs with effect \"damage\"",
            run.name, db.path(), s.step));
      } else {
        v = d->value.empty() ? 0.0 : *std::max_element(d->value.begin(), d->value.end());
      }
    }
    out.mgt.push_back(s.mgt);
    out.value.push_back(v);
  }
  return out;
}

RailSide RailOf(const HistoryEnsembleOptions& o) {
  if (const auto side = RailSideFromString(o.rail)) return *side;
  throw InputError(
      fmt::format("--rail '{}': expected high or low (history life: also both)", o.rail));
}

void CheckPercentiles(const std::vector<double>& p) {
  if (p.empty()) throw InputError("--percentiles: expected at least one percentile in [0, 100]");
  for (size_t i = 0; i < p.size(); ++i) {
    if (!(p[i] >= 0.0 && p[i] <= 100.0) || (i > 0 && !(p[i] > p[i - 1]))) {
      throw InputError(fmt::format(
          "--percentiles {}: expected increasing numbers in [0, 100], e.g. 5,50,95",
          fmt::join(p, ",")));
    }
  }
}

void CheckMeasure(const std::string& m, const std::string& what) {
  if (std::find(kEnsembleMeasures.begin(), kEnsembleMeasures.end(), m) == kEnsembleMeasures.end()) {
    throw InputError(fmt::format("{} '{}': expected one of {}", what, m,
                                 fmt::join(kEnsembleMeasures, ", ")));
  }
}

// "p5", "p50", "p97.5".
std::string PercentileName(double p) { return fmt::format("p{}", p); }

// A measure's value as printed: mm and mm^2 with 4 decimals, damage with 4 significant digits.
std::string ValueCell(const std::string& measure, double v) {
  if (!std::isfinite(v)) return "NULL";
  return measure == "rcf_damage" ? fmt::format("{:.4g}", v) : FixedNoNegativeZero(v, 4);
}

nlohmann::json Finite(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(); }

struct GroupBands {
  std::string label;
  std::vector<std::string> runs;
  std::vector<std::pair<std::string, PercentileBands>> measures;
};

std::string BandsPlotScript(const std::vector<GroupBands>& groups,
                            const std::vector<double>& percentiles, const fs::path& dir,
                            const std::string& png) {
  const size_t n_measures = groups.front().measures.size();
  std::ostringstream g;
  g << GnuplotPngTerminal(900, 350 * static_cast<int>(n_measures) + 50) << "set output "
    << GnuplotQuote(png) << "\n";
  g << fmt::format("set multiplot layout {},1 title {}\n", n_measures,
                   GnuplotQuote(fmt::format("ensemble percentiles {}",
                                            fmt::join(percentiles, "/"))));
  g << "set grid\nset key top left\nset style fill transparent solid 0.25 noborder\n";
  const size_t np = percentiles.size();
  for (size_t m = 0; m < n_measures; ++m) {
    const std::string& measure = groups.front().measures[m].first;
    g << "set xlabel 'traffic [MGT]'\nset ylabel " << GnuplotQuote(measure) << "\n";
    std::vector<std::string> plots;
    for (size_t k = 0; k < groups.size(); ++k) {
      const PercentileBands& b = groups[k].measures[m].second;
      const fs::path file = dir / fmt::format("bands_{}_{}.dat", k, m);
      std::ofstream out(file);
      for (size_t j = 0; j < b.mgt.size(); ++j) {
        out << fmt::format("{:.9g}", b.mgt[j]);
        for (size_t p = 0; p < np; ++p) out << fmt::format(" {:.9g}", b.value[p][j]);
        out << "\n";
      }
      const std::string q = GnuplotQuote(file.string());
      // Nested bands: the outermost pair of percentiles first, each inner pair on top.
      for (size_t p = 0; p < np / 2; ++p) {
        plots.push_back(fmt::format(
            "{} using 1:{}:{} with filledcurves lc {} title {}", q, 2 + p, 2 + np - 1 - p, k + 1,
            GnuplotQuote(fmt::format("{} p{}-p{}", groups[k].label, percentiles[p],
                                     percentiles[np - 1 - p]))));
      }
      if (np % 2 == 1) {
        plots.push_back(fmt::format("{} using 1:{} with lines lw 2 lc {} title {}", q,
                                    2 + np / 2, k + 1,
                                    GnuplotQuote(fmt::format("{} p{}", groups[k].label,
                                                             percentiles[np / 2]))));
      }
    }
    g << "plot " << fmt::format("{}", fmt::join(plots, ", \\\n     ")) << "\n";
  }
  g << "unset multiplot\n";
  return g.str();
}

}  // namespace

void RunHistoryBands(const HistoryOptions& o, const HistoryBandsOptions& b) {
  CheckPercentiles(b.percentiles);
  if (b.measures.empty()) throw InputError("--measures: expected at least one measure");
  for (const std::string& m : b.measures) CheckMeasure(m, "--measures");
  if (b.points < 2) {
    throw InputError(fmt::format("--points {}: expected an integer >= 2", b.points));
  }
  if (b.format != "table" && b.format != "csv" && b.format != "json") {
    throw InputError(fmt::format("--format '{}': expected table, csv or json", b.format));
  }
  const RailSide rail = RailOf(b);
  if (!b.plot.empty()) {
    RequireGnuplotFor("history bands --plot", "leave out --plot for the numbers");
  }
  const ProfileStore db = OpenExistingStudy(o.db);
  SweepPlan plan;
  std::vector<FailedRun> failed;
  const std::vector<EnsembleGroup> groups = Ensembles(db, b.plan, &plan, &failed);

  std::vector<GroupBands> results;
  for (const EnsembleGroup& group : groups) {
    GroupBands r;
    r.label = group.label;
    for (const RunInfo& run : group.runs) r.runs.push_back(run.name);
    for (const std::string& measure : b.measures) {
      std::vector<MeasureSeries> series;
      double end = INFINITY;
      for (const RunInfo& run : group.runs) {
        series.push_back(SeriesOf(db, run, measure, rail));
        end = std::min(end, series.back().mgt.empty() ? 0.0 : series.back().mgt.back());
      }
      if (!(end > 0.0)) {
        throw InputError(fmt::format(
            "class '{}' of database '{}': a run without traffic (final MGT 0); expected runs "
            "with stored wear steps",
            group.label, db.path()));
      }
      std::vector<double> grid;
      for (int j = 0; j < b.points; ++j) grid.push_back(end * j / (b.points - 1));
      grid.back() = end;
      r.measures.emplace_back(measure, ComputePercentileBands(series, grid, b.percentiles));
    }
    results.push_back(std::move(r));
  }

  std::vector<std::string> columns = {"class", "measure", "MGT", "runs"};
  for (double p : b.percentiles) columns.push_back(PercentileName(p));
  if (b.format == "json") {
    nlohmann::json j = {{"database", db.path()},
                        {"rail", b.rail},
                        {"percentiles", b.percentiles},
                        {"classes", nlohmann::json::array()}};
    if (!b.plan.empty()) j["plan"] = b.plan;
    j["failed_runs"] = FailedRunsJson(failed);
    for (const GroupBands& r : results) {
      nlohmann::json c = {{"class", r.label}, {"runs", r.runs}, {"measures", nlohmann::json::object()}};
      for (const auto& [measure, bands] : r.measures) {
        nlohmann::json m = {{"mgt", bands.mgt}, {"runs", bands.runs}};
        for (size_t p = 0; p < bands.percentiles.size(); ++p) {
          nlohmann::json values = nlohmann::json::array();
          for (double v : bands.value[p]) values.push_back(Finite(v));
          m[PercentileName(bands.percentiles[p])] = std::move(values);
        }
        c["measures"][measure] = std::move(m);
      }
      j["classes"].push_back(std::move(c));
    }
    std::cout << j.dump(1) << "\n";
  } else {
    std::vector<std::vector<std::string>> rows;
    for (const GroupBands& r : results) {
      for (const auto& [measure, bands] : r.measures) {
        for (size_t k = 0; k < bands.mgt.size(); ++k) {
          std::vector<std::string> row = {r.label, measure,
                                          b.format == "csv" ? fmt::format("{}", bands.mgt[k])
                                                            : FixedNoNegativeZero(bands.mgt[k], 4),
                                          std::to_string(bands.runs[k])};
          for (size_t p = 0; p < bands.percentiles.size(); ++p) {
            const double v = bands.value[p][k];
            row.push_back(b.format == "csv" ? (std::isfinite(v) ? fmt::format("{}", v) : "")
                                            : ValueCell(measure, v));
          }
          rows.push_back(std::move(row));
        }
      }
    }
    if (b.format == "csv") {
      std::cout << fmt::format("{}\n", fmt::join(columns, ","));
      for (auto& row : rows) {
        if (row[0].find_first_of(",\"") != std::string::npos) {
          std::string quoted = "\"";
          for (char ch : row[0]) quoted += ch == '"' ? std::string("\"\"") : std::string(1, ch);
          row[0] = quoted + "\"";
        }
        std::cout << fmt::format("{}\n", fmt::join(row, ","));
      }
    } else {
      std::cout << AlignedTable(columns, rows);
      if (!failed.empty()) {
        std::cout << "\nFailed runs (left out of the bands)\n" << FailedRunsTable(failed);
      }
    }
  }
  WarnOfFailedRuns(failed, "bands");
  size_t runs = 0;
  for (const EnsembleGroup& g : groups) runs += g.runs.size();
  std::cerr << fmt::format("railwear: {} class(es), {} run(s), {} rail, in {}\n", groups.size(),
                           runs, b.rail, db.path());
  if (!b.plot.empty()) {
    const ScopedTempDir tmp("railwear-bands");
    const std::string png = fs::absolute(b.plot + "_bands.png").string();
    RunGnuplot(BandsPlotScript(results, b.percentiles, tmp.path(), png), tmp, {png});
    std::cerr << fmt::format("railwear: wrote {}_bands.png\n", b.plot);
  }
}

namespace {

// --limit MEASURE=VALUE.
LifeLimit ParseLimitOption(const std::string& text) {
  const size_t eq = text.find('=');
  const std::string measure = text.substr(0, eq);
  CheckMeasure(measure, fmt::format("--limit '{}': measure", text));
  char* end = nullptr;
  const std::string value = eq == std::string::npos ? "" : text.substr(eq + 1);
  const double v = std::strtod(value.c_str(), &end);
  if (value.empty() || *end != '\0' || !(v > 0.0) || !std::isfinite(v)) {
    throw InputError(fmt::format(
        "--limit '{}': expected MEASURE=VALUE with a value > 0 in the measure's unit, e.g. "
        "w2_mm=8",
        text));
  }
  return {fmt::format("{} {}", measure, v), measure, v, "--limit"};
}

// A life in MGT (and years) as printed: "not reached" for +inf.
std::string LifeCell(double mgt) {
  return std::isfinite(mgt) ? FixedNoNegativeZero(mgt, 3) : std::string("not_reached");
}

}  // namespace

void RunHistoryLife(const HistoryOptions& o, const HistoryLifeOptions& l) {
  CheckPercentiles(l.percentiles);
  // --rail both: the high and the low rail of each (two-rail) run, the life the earlier.
  const bool both = l.rail == "both";
  const RailSide rail = both ? RailSide::kHigh : RailOf(l);
  std::vector<LifeLimit> extra;
  for (const std::string& text : l.limits) extra.push_back(ParseLimitOption(text));
  if (l.annual_mgt && !(*l.annual_mgt > 0.0 && std::isfinite(*l.annual_mgt))) {
    throw InputError(fmt::format("--annual-mgt {}: expected a number > 0 (MGT per year)",
                                 *l.annual_mgt));
  }
  const ProfileStore db = OpenExistingStudy(o.db);
  SweepPlan plan;
  std::vector<FailedRun> failed;
  const std::vector<EnsembleGroup> groups = Ensembles(db, l.plan, &plan, &failed);
  std::vector<LifeLimit> limits = plan.life.limits;
  limits.insert(limits.end(), extra.begin(), extra.end());
  if (limits.empty()) {
    throw InputError(
        "no limits: expected [[life.limit]] tables in the plan's [life] (measure, value) or "
        "--limit MEASURE=VALUE");
  }
  const std::optional<double> annual = l.annual_mgt ? l.annual_mgt : plan.life.annual_mgt;
  // Every [[life.class]] names a class of the plan.
  for (const LifeClassLength& c : plan.life.classes) {
    if (std::none_of(groups.begin(), groups.end(),
                     [&](const EnsembleGroup& g) { return g.label == c.match; }) &&
        std::none_of(failed.begin(), failed.end(),
                     [&](const FailedRun& f) { return f.label == c.match; })) {
      std::vector<std::string> labels;
      for (const EnsembleGroup& g : groups) labels.push_back("\"" + g.label + "\"");
      throw InputError(fmt::format("{}: key 'match' = \"{}\": expected a curve class of the plan: {}",
                                   c.origin, c.match, fmt::join(labels, ", ")));
    }
  }

  // life[g][r][k]: MGT of group g's run r to limit k (+inf: not reached); final MGT per run;
  // with --rail both, governs[g][r][k]: the rail that reaches the limit first ("high", "low",
  // "both" at the same MGT, "" when neither does).
  std::vector<std::vector<std::vector<double>>> life(groups.size());
  std::vector<std::vector<std::vector<std::string>>> governs(groups.size());
  std::vector<std::vector<double>> final_mgt(groups.size());
  for (size_t g = 0; g < groups.size(); ++g) {
    for (const RunInfo& run : groups[g].runs) {
      std::map<std::pair<std::string, RailSide>, MeasureSeries> cache;
      const auto series = [&](const std::string& measure, RailSide side) -> const MeasureSeries& {
        auto it = cache.find({measure, side});
        if (it == cache.end()) {
          it = cache.emplace(std::make_pair(measure, side), SeriesOf(db, run, measure, side)).first;
        }
        return it->second;
      };
      std::vector<double> per_limit;
      std::vector<std::string> per_limit_rail;
      double last = 0.0;
      for (const LifeLimit& limit : limits) {
        const MeasureSeries& first = series(limit.measure, rail);
        last = first.mgt.empty() ? 0.0 : first.mgt.back();
        const double at = FirstCrossing(first, limit.value).value_or(INFINITY);
        if (!both) {
          per_limit.push_back(at);
          continue;
        }
        const double low =
            FirstCrossing(series(limit.measure, RailSide::kLow), limit.value).value_or(INFINITY);
        per_limit.push_back(std::min(at, low));
        per_limit_rail.push_back(!std::isfinite(std::min(at, low)) ? ""
                                 : at < low                        ? "high"
                                 : low < at                        ? "low"
                                                                   : "both");
      }
      life[g].push_back(std::move(per_limit));
      governs[g].push_back(std::move(per_limit_rail));
      final_mgt[g].push_back(last);
    }
  }
  // Per class and limit, with --rail both: how many runs each rail governs ("high 3, low 5").
  const auto governing_count = [&](size_t g, size_t k) {
    int high = 0, low = 0, tie = 0;
    for (const auto& run : governs[g]) {
      high += run[k] == "high" ? 1 : 0;
      low += run[k] == "low" ? 1 : 0;
      tie += run[k] == "both" ? 1 : 0;
    }
    return tie > 0 ? fmt::format("high {}, low {}, both {}", high, low, tie)
                   : fmt::format("high {}, low {}", high, low);
  };
  auto years = [&](double mgt) { return annual ? mgt / *annual : std::nan(""); };

  // Per class and limit: percentiles over the runs.
  std::vector<std::vector<std::vector<double>>> class_p(groups.size());  // [g][k][p]
  for (size_t g = 0; g < groups.size(); ++g) {
    for (size_t k = 0; k < limits.size(); ++k) {
      std::vector<double> values;
      for (const auto& run : life[g]) values.push_back(run[k]);
      std::vector<double> ps;
      for (double p : l.percentiles) ps.push_back(Percentile(values, p));
      class_p[g].push_back(std::move(ps));
    }
  }
  // The line: runs weighted by their class's length / runs.
  std::vector<std::vector<double>> line_p;  // [k][p]
  double line_km = 0.0;
  for (const LifeClassLength& c : plan.life.classes) line_km += c.length_km;
  if (!plan.life.classes.empty()) {
    for (size_t k = 0; k < limits.size(); ++k) {
      std::vector<double> values, weights;
      for (size_t g = 0; g < groups.size(); ++g) {
        double km = 0.0;
        for (const LifeClassLength& c : plan.life.classes) {
          if (c.match == groups[g].label) km += c.length_km;
        }
        for (const auto& run : life[g]) {
          values.push_back(run[k]);
          weights.push_back(km / static_cast<double>(life[g].size()));
        }
      }
      std::vector<double> ps;
      for (double p : l.percentiles) ps.push_back(WeightedQuantile(values, weights, p));
      line_p.push_back(std::move(ps));
    }
  }

  // Failed runs per class (the classes' percentiles are over their complete runs).
  std::vector<int> failed_in(groups.size(), 0);
  for (const FailedRun& f : failed) {
    for (size_t g = 0; g < groups.size(); ++g) failed_in[g] += groups[g].label == f.label ? 1 : 0;
  }
  if (l.json) {
    nlohmann::json j = {{"database", db.path()}, {"rail", l.rail}, {"percentiles", l.percentiles}};
    if (annual) j["annual_mgt"] = *annual;
    j["failed_runs"] = FailedRunsJson(failed);
    j["limits"] = nlohmann::json::array();
    for (const LifeLimit& limit : limits) {
      j["limits"].push_back({{"name", limit.name}, {"measure", limit.measure}, {"value", limit.value}});
    }
    j["runs"] = nlohmann::json::array();
    j["classes"] = nlohmann::json::array();
    for (size_t g = 0; g < groups.size(); ++g) {
      for (size_t r = 0; r < groups[g].runs.size(); ++r) {
        nlohmann::json run = {{"run", groups[g].runs[r].name},
                              {"class", groups[g].label},
                              {"final_mgt", final_mgt[g][r]},
                              {"mgt", nlohmann::json::array()}};
        for (double v : life[g][r]) run["mgt"].push_back(Finite(v));
        if (both) {
          run["governing_rail"] = nlohmann::json::array();
          for (const std::string& side : governs[g][r]) {
            run["governing_rail"].push_back(side.empty() ? nlohmann::json() : nlohmann::json(side));
          }
        }
        if (annual) {
          run["years"] = nlohmann::json::array();
          for (double v : life[g][r]) run["years"].push_back(Finite(years(v)));
        }
        j["runs"].push_back(std::move(run));
      }
      nlohmann::json c = {{"class", groups[g].label},
                          {"runs", groups[g].runs.size()},
                          {"failed", failed_in[g]},
                          {"mgt", nlohmann::json::array()}};
      for (const auto& ps : class_p[g]) {
        nlohmann::json row = nlohmann::json::object();
        for (size_t p = 0; p < ps.size(); ++p) row[PercentileName(l.percentiles[p])] = Finite(ps[p]);
        c["mgt"].push_back(std::move(row));
      }
      if (both) {
        c["governing_rail"] = nlohmann::json::array();
        for (size_t k = 0; k < limits.size(); ++k)
          c["governing_rail"].push_back(governing_count(g, k));
      }
      j["classes"].push_back(std::move(c));
    }
    if (!line_p.empty()) {
      j["line"] = {{"length_km", line_km}, {"mgt", nlohmann::json::array()}};
      for (const auto& ps : line_p) {
        nlohmann::json row = nlohmann::json::object();
        for (size_t p = 0; p < ps.size(); ++p) row[PercentileName(l.percentiles[p])] = Finite(ps[p]);
        j["line"]["mgt"].push_back(std::move(row));
      }
    }
    std::cout << j.dump(1) << "\n";
  } else {
    std::vector<std::vector<std::string>> rows;
    for (size_t g = 0; g < groups.size(); ++g) {
      for (size_t r = 0; r < groups[g].runs.size(); ++r) {
        for (size_t k = 0; k < limits.size(); ++k) {
          const double v = life[g][r][k];
          std::vector<std::string> row = {groups[g].runs[r].name, groups[g].label, limits[k].name,
                                          LifeCell(v)};
          if (annual) row.push_back(LifeCell(years(v)));
          if (both) row.push_back(governs[g][r][k].empty() ? "-" : governs[g][r][k]);
          row.push_back(FixedNoNegativeZero(final_mgt[g][r], 3));
          rows.push_back(std::move(row));
        }
      }
    }
    std::vector<std::string> columns = {"run", "class", "limit", "MGT"};
    if (annual) columns.push_back("years");
    if (both) columns.push_back("governing_rail");
    columns.push_back("final_MGT");
    std::cout << "Per run\n" << AlignedTable(columns, rows);

    auto percentile_rows = [&](const std::vector<double>& ps, std::vector<std::string> row) {
      for (double v : ps) row.push_back(LifeCell(v));
      if (annual) {
        for (double v : ps) row.push_back(LifeCell(years(v)));
      }
      return row;
    };
    std::vector<std::string> pcols;
    for (double p : l.percentiles) pcols.push_back(PercentileName(p) + "_MGT");
    if (annual) {
      for (double p : l.percentiles) pcols.push_back(PercentileName(p) + "_years");
    }
    rows.clear();
    for (size_t g = 0; g < groups.size(); ++g) {
      for (size_t k = 0; k < limits.size(); ++k) {
        int reached = 0;
        for (const auto& run : life[g]) reached += std::isfinite(run[k]) ? 1 : 0;
        rows.push_back(percentile_rows(
            class_p[g][k], {groups[g].label, limits[k].name, std::to_string(groups[g].runs.size()),
                            std::to_string(failed_in[g]), std::to_string(reached)}));
        if (both) rows.back().push_back(governing_count(g, k));
      }
    }
    columns = {"class", "limit", "runs", "failed", "reached"};
    columns.insert(columns.end(), pcols.begin(), pcols.end());
    if (both) columns.push_back("governing_rail");
    std::cout << "\nPer curve class (percentiles over its runs)\n" << AlignedTable(columns, rows);
    if (!line_p.empty()) {
      rows.clear();
      for (size_t k = 0; k < limits.size(); ++k) {
        rows.push_back(percentile_rows(line_p[k], {limits[k].name, FixedNoNegativeZero(line_km, 3)}));
      }
      columns = {"limit", "length_km"};
      columns.insert(columns.end(), pcols.begin(), pcols.end());
      std::cout << "\nLine (runs weighted by their class's length; pN: the traffic by which N % of "
                   "the length reaches the limit)\n"
                << AlignedTable(columns, rows);
    }
    if (!failed.empty()) {
      std::cout << "\nFailed runs (no life: left out of the percentiles)\n"
                << FailedRunsTable(failed);
    }
  }
  WarnOfFailedRuns(failed, "life percentiles");
  std::cerr << fmt::format("railwear: {} limit(s), {} class(es), {} rail, in {}{}\n",
                           limits.size(), groups.size(), l.rail, db.path(),
                           annual ? fmt::format(", {} MGT a year", *annual) : std::string());
}

void SetupHistoryEnsemble(CLI::App* history, const std::shared_ptr<HistoryOptions>& common) {
  auto bands = std::make_shared<HistoryBandsOptions>();
  CLI::App* b = history->add_subcommand(
      "bands",
      "Percentile bands of W1/W2/W3, worn area or RCF damage against MGT over an ensemble's runs "
      "(per curve class with --plan)");
  auto add_common = [](CLI::App* cmd, HistoryEnsembleOptions& e) {
    cmd->add_option("--plan", e.plan,
                    "The sweep plan: its lines' runs, grouped by curve class (default: every "
                    "complete run of the database)");
    cmd->add_option("--percentiles", e.percentiles, "Percentiles, increasing in [0, 100]")
        ->delimiter(',')
        ->capture_default_str();
    cmd->add_option("--rail", e.rail, "high or low: the rail of two-rail runs")
        ->capture_default_str();
  };
  add_common(b, *bands);
  b->add_option("--measures", bands->measures,
                "w1_mm, w2_mm, w3_mm, worn_area_mm2, rcf_damage (comma-separated)")
      ->delimiter(',')
      ->capture_default_str();
  b->add_option("--points", bands->points, "MGT grid points, 0 to the smallest final MGT")
      ->capture_default_str();
  b->add_option("--format", bands->format, "table, csv or json")->capture_default_str();
  b->add_option("--plot", bands->plot, "PNG prefix: PREFIX_bands.png (gnuplot)");
  b->callback([common, bands]() { RunHistoryBands(*common, *bands); });

  auto life = std::make_shared<HistoryLifeOptions>();
  CLI::App* l = history->add_subcommand(
      "life",
      "MGT (and years) to each wear limit per run, per curve class as percentiles, and for the "
      "line weighted by class length");
  add_common(l, *life);
  l->get_option("--rail")->description(
      "high, low, or both: the life of a two-rail run is then the earlier of its rails', and the "
      "output says which rail governs");
  l->add_option("--limit", life->limits,
                "MEASURE=VALUE, e.g. w2_mm=8 (repeatable; added to the plan's [life] limits)");
  l->add_option("--annual-mgt", life->annual_mgt, "Traffic per year [MGT] (default: the plan's)");
  l->add_flag("--json", life->json, "One JSON object on stdout");
  l->callback([common, life]() { RunHistoryLife(*common, *life); });
}

}  // namespace railwear::app
