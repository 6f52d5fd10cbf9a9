// The load-collective file: writer and reader (load_collective_file.h).
#include "app/load_collective_file.h"

#include <cmath>
#include <sstream>

#include <fmt/format.h>

#include "app/toml_fields.h"
#include "core/numerics/input_error.h"
#include "core/numerics/units.h"

namespace railwear::app {
namespace {

constexpr double kToMrad = 1e3;              // rad -> mrad
constexpr double kShareSumTolerance = 1e-6;  // 9-digit shares of up to ~1e3 bins sum to 1 +- 1e-6
constexpr std::string_view kAxleFromColumn = "column";
constexpr std::string_view kAxleFromLoad = "2Q/g";

// A number as the file prints it: 9 significant digits, TOML-valid ("1e-05", "88200").
std::string Num(double v) { return fmt::format("{:.9g}", v); }

std::string Quoted(const std::string& s) {
  std::ostringstream os;
  os << toml::value<std::string>(s);
  return os.str();
}

}  // namespace

std::string LoadCollectiveFileText(const LoadCollective& c, const std::string& version) {
  const LoadCollectiveBinWidths& w = c.widths;
  std::string t;
  t += fmt::format("# Load collective imported by `railwear traffic import`{}.\n",
                   version.empty() ? "" : fmt::format(" (railwear {})", version));
  t += fmt::format("# Source: {} ({} rows read, {} of weight 0 not binned).\n", c.source,
                   c.rows_read, c.rows_zero_weight);
  t += fmt::format("# Weight ({}): high rail {} in {} bins, low rail {} in {} bins.\n",
                   ToString(c.weight_unit), Num(c.total_weight_high),
                   EntryCount(c, RailSide::kHigh), Num(c.total_weight_low),
                   EntryCount(c, RailSide::kLow));
  t += fmt::format(
      "# Bin widths: y {} mm, yaw {} mrad, Q {} kN, V {} m/s, mu {}, xi {} (mu and xi only when "
      "the CSV has them).\n",
      Num(w.wheelset_y_m * kToMm), Num(w.yaw_rad * kToMrad), Num(w.vertical_force_N * 1e-3),
      Num(w.speed_m_s), Num(w.friction), Num(w.creepage_x));
  t += "# Each [[traffic]] entry is one bin: the weighted means of its rows; share = its weight /\n"
       "# its rail's total weight. Wheelset y, yaw and roll are in the track frame, positive\n"
       "# toward the high (outer, right) rail (docs/mbs_import.md).\n";
  if (!c.axle_load_from_column) {
    t += fmt::format(
        "# axle_load_t = 2 Q / {} / 1000 (the CSV has no axle_load_t column): an estimate that\n"
        "# assumes equal wheel loads.\n",
        Num(kAxleLoadGravity_m_s2));
  }
  t += "\n[collective]\n";
  t += fmt::format("source = {}\n", Quoted(c.source));
  t += fmt::format("rows_read = {}\n", c.rows_read);
  t += fmt::format("rows_zero_weight = {}\n", c.rows_zero_weight);
  t += fmt::format("weight_unit = \"{}\"\n", ToString(c.weight_unit));
  t += fmt::format("total_weight_high = {}\n", Num(c.total_weight_high));
  t += fmt::format("total_weight_low = {}\n", Num(c.total_weight_low));
  t += fmt::format("axle_load = \"{}\"\n",
                   c.axle_load_from_column ? kAxleFromColumn : kAxleFromLoad);
  std::string names;
  for (const std::string& n : c.mbs_names) {
    names += fmt::format("{}\"{}\"", names.empty() ? "" : ", ", n);
  }
  t += fmt::format("mbs = [{}]\n", names);
  t += fmt::format(
      "bin_widths = {{ y_mm = {}, yaw_mrad = {}, Q_N = {}, V_m_s = {}, mu = {}, xi = {} }}\n",
      Num(w.wheelset_y_m * kToMm), Num(w.yaw_rad * kToMrad), Num(w.vertical_force_N),
      Num(w.speed_m_s), Num(w.friction), Num(w.creepage_x));
  for (const LoadCollectiveEntry& e : c.entries) {
    t += "\n[[traffic]]\n";
    t += fmt::format("name = {}\n", Quoted(e.name));
    t += fmt::format("rail = \"{}\"\n", ToString(e.rail));
    t += fmt::format("wheelset_y_mm = {}\n", Num(e.wheelset_y_m * kToMm));
    t += fmt::format("yaw_mrad = {}\n", Num(e.yaw_rad * kToMrad));
    t += fmt::format("roll_mrad = {}\n", Num(e.roll_rad * kToMrad));
    t += fmt::format("vertical_N = {}\n", Num(e.vertical_force_N));
    t += fmt::format("speed_m_s = {}\n", Num(e.speed_m_s));
    if (e.friction) t += fmt::format("friction = {}\n", Num(*e.friction));
    if (e.creepage_x) t += fmt::format("creepage_x = {}\n", Num(*e.creepage_x));
    t += fmt::format("share = {}\n", Num(e.share));
    t += fmt::format("weight = {}\n", Num(e.weight));
    t += fmt::format("axle_load_t = {}\n", Num(e.axle_load_t));
    t += fmt::format("rows = {}\n", e.rows);
    if (!c.mbs_names.empty()) {
      std::string mbs;
      for (std::size_t k = 0; k < c.mbs_names.size(); ++k) {
        mbs += fmt::format("{}{} = {}", k == 0 ? "" : ", ", c.mbs_names[k], Num(e.mbs[k]));
      }
      t += fmt::format("mbs = {{ {} }}\n", mbs);
    }
  }
  return t;
}

LoadCollective ReadLoadCollective(const std::string& path) {
  const std::string text = ReadInputFile(path, "the load collective file");
  const toml::table root = ParseToml(text, path);
  const Fields top(root, "", path);
  top.AllowOnly({"collective", "traffic"});
  const auto head = top.Table("collective", "a [collective] table");
  if (!head) top.FailMissing("collective", "a [collective] table (written by traffic import)");
  head->AllowOnly({"source", "rows_read", "rows_zero_weight", "weight_unit", "total_weight_high",
                   "total_weight_low", "axle_load", "mbs", "bin_widths"});

  LoadCollective c;
  c.source = head->RequiredString("source", "the CSV's name");
  if (!head->Has("rows_read")) head->FailMissing("rows_read", "an integer >= 1");
  c.rows_read = *head->Integer("rows_read", IntegerAtLeast(1));
  c.rows_zero_weight = head->Integer("rows_zero_weight", IntegerAtLeast(0)).value_or(0);
  const std::vector<std::string_view> units = EnumChoices(kWeightUnitNames);
  const auto unit = head->Choice("weight_unit", units);
  if (!unit) head->FailMissing("weight_unit", JoinQuoted(units));
  c.weight_unit = *EnumFromString(kWeightUnitNames, *unit);
  c.total_weight_high = head->RequiredNumber("total_weight_high", AtLeast(0.0), Closed(0.0, 1e15));
  c.total_weight_low = head->RequiredNumber("total_weight_low", AtLeast(0.0), Closed(0.0, 1e15));
  const auto axle = head->Choice("axle_load", {kAxleFromColumn, kAxleFromLoad});
  if (!axle) head->FailMissing("axle_load", "'column' or '2Q/g'");
  c.axle_load_from_column = *axle == kAxleFromColumn;
  if (head->Has("mbs")) {
    const toml::array* names = head->Node("mbs")->as_array();
    if (names == nullptr) head->Fail("mbs", "an array of the mbs_ column names (strings)");
    for (const toml::node& n : *names) {
      const auto name = n.value_exact<std::string>();
      if (!name || name->empty()) head->Fail("mbs", "an array of non-empty strings");
      c.mbs_names.push_back(*name);
    }
  }
  const auto widths = head->Table("bin_widths", "an inline table of bin widths");
  if (!widths) {
    head->FailMissing("bin_widths", "{ y_mm, yaw_mrad, Q_N, V_m_s, mu, xi }");
  }
  widths->AllowOnly({"y_mm", "yaw_mrad", "Q_N", "V_m_s", "mu", "xi"});
  c.widths.wheelset_y_m = widths->RequiredNumber("y_mm", Positive()) * kMm;
  c.widths.yaw_rad = widths->RequiredNumber("yaw_mrad", Positive()) / kToMrad;
  c.widths.vertical_force_N = widths->RequiredNumber("Q_N", Positive());
  c.widths.speed_m_s = widths->RequiredNumber("V_m_s", Positive());
  c.widths.friction = widths->RequiredNumber("mu", Positive());
  c.widths.creepage_x = widths->RequiredNumber("xi", Positive());

  const std::vector<Fields> entries =
      ArrayOfTables(top, "traffic", "[[traffic]] tables, one per bin");
  if (entries.empty()) top.FailMissing("traffic", "at least one [[traffic]] entry");
  const std::vector<std::string_view> rails = EnumChoices(kRailSideNames);
  double share_sum[2] = {0.0, 0.0};
  for (const Fields& t : entries) {
    t.AllowOnly({"name", "rail", "wheelset_y_mm", "yaw_mrad", "roll_mrad", "vertical_N",
                 "speed_m_s", "friction", "creepage_x", "share", "weight", "axle_load_t", "rows",
                 "mbs"});
    LoadCollectiveEntry e;
    e.name = t.RequiredString("name", "a string");
    const auto rail = t.Choice("rail", rails);
    if (!rail) t.FailMissing("rail", JoinQuoted(rails));
    e.rail = *EnumFromString(kRailSideNames, *rail);
    // The ranges a scene's own keys have (docs/testing.md): a wheelset within 100 mm of the
    // track centre, roll within 0.5 rad, wheel loads up to 1 MN, speeds up to 150 m/s, mu in
    // (0, 2], xi in [-1, 1], axle loads in [0.1, 40] t; weights (passes, seconds or metres)
    // up to 1e15.
    e.wheelset_y_m = t.RequiredNumber("wheelset_y_mm", AnyFinite(), Closed(-100.0, 100.0)) * kMm;
    e.yaw_rad = t.RequiredNumber("yaw_mrad", InRange(-100.0, 100.0)) / kToMrad;
    e.roll_rad = t.Number("roll_mrad", AnyFinite(), Closed(-500.0, 500.0)).value_or(0.0) / kToMrad;
    e.vertical_force_N = t.RequiredNumber("vertical_N", AtLeast(0.0), Closed(0.0, 1e6));
    e.speed_m_s = t.RequiredNumber("speed_m_s", Positive(), OpenClosed(0.0, 150.0));
    e.friction = t.Number("friction", Positive(), OpenClosed(0.0, 2.0));
    e.creepage_x = t.Number("creepage_x", AnyFinite(), Closed(-1.0, 1.0));
    e.share = t.RequiredNumber("share", OpenClosed(0.0, 1.0));
    e.weight = t.RequiredNumber("weight", Positive(), OpenClosed(0.0, 1e15));
    e.axle_load_t = t.RequiredNumber("axle_load_t", Positive(), Closed(0.1, 40.0));
    e.rows = t.Integer("rows", IntegerAtLeast(1)).value_or(1);
    const auto mbs = t.Table("mbs", "an inline table of the [collective] mbs names");
    if (!c.mbs_names.empty() && !mbs) {
      t.FailMissing("mbs", "a table with the [collective] mbs names");
    }
    if (mbs) {
      std::vector<std::string_view> allowed(c.mbs_names.begin(), c.mbs_names.end());
      mbs->AllowOnly(allowed);
      for (const std::string& n : c.mbs_names) {
        e.mbs.push_back(mbs->RequiredNumber(n, AnyFinite()));
      }
    }
    share_sum[e.rail == RailSide::kHigh ? 0 : 1] += e.share;
    c.entries.push_back(std::move(e));
  }
  for (const RailSide r : {RailSide::kHigh, RailSide::kLow}) {
    const double sum = share_sum[r == RailSide::kHigh ? 0 : 1];
    if (EntryCount(c, r) > 0 && std::abs(sum - 1.0) > kShareSumTolerance) {
      throw InputError(
          fmt::format("{}: the shares of the {} rail's entries sum to {}: expected 1 "
                      "(within {})",
                      path, ToString(r), sum, kShareSumTolerance));
    }
  }
  return c;
}

}  // namespace railwear::app
