// The influence-constants table and file: reading, writing, JSON and text. See
// influence_constants_file.h.
#include "app/influence_constants_file.h"

#include <stdexcept>

#include <fmt/format.h>

#include "app/toml_fields.h"
#include "core/contact/influence_constant_sets.h"

namespace railwear::app {

const char* const kInfluenceConstantsExpected =
    "{ c_f, c_z, c_s } (one set for both bodies) or { convex = { c_f, c_z, c_s }, concave = "
    "{ c_f, c_z, c_s } } (a set for each curvature sign)";

namespace {

constexpr const char* kConstantSetExpected = "a table { c_f, c_z, c_s }";

InfluenceConstantSet ReadConstantSet(const Fields& t) {
  t.AllowOnly({"c_f", "c_z", "c_s"});
  InfluenceConstantSet c;
  // Ranges the influence operator bears (1e-308 made its Cholesky factor fail); the fitted and
  // published constants are of order 1.
  c.c_f = t.Number("c_f", Positive(), Closed(1e-6, 1e3)).value_or(c.c_f);
  c.c_z = t.Number("c_z", Positive(), Closed(1e-6, 1e3)).value_or(c.c_z);
  c.c_s = t.Number("c_s", AnyFinite(), Closed(-1e3, 1e3)).value_or(c.c_s);
  return c;
}

}  // namespace

InfluenceConstants ReadInfluenceConstantsTable(const Fields& t) {
  t.AllowOnly({"c_f", "c_z", "c_s", "convex", "concave"});
  InfluenceConstants c;
  if (!t.Has("convex") && !t.Has("concave")) {
    const InfluenceConstantSet one = ReadConstantSet(t);
    c.c_f = one.c_f;
    c.c_z = one.c_z;
    c.c_s = one.c_s;
    return c;
  }
  for (const std::string_view key : {"c_f", "c_z", "c_s"}) {
    if (t.Has(key)) {
      t.Fail(key, std::string("either one set or convex and concave sets, not both: ") +
                      kInfluenceConstantsExpected);
    }
  }
  const auto convex = t.Table("convex", kConstantSetExpected);
  const auto concave = t.Table("concave", kConstantSetExpected);
  if (!convex) {
    t.FailMissing("convex", "the convex set too: " + std::string(kInfluenceConstantsExpected));
  }
  if (!concave) {
    t.FailMissing("concave", "the concave set too: " + std::string(kInfluenceConstantsExpected));
  }
  c.separate = SeparateInfluenceConstants{ReadConstantSet(*convex), ReadConstantSet(*concave)};
  return c;
}

InfluenceConstants ReadInfluenceConstantsFile(const std::string& path) {
  const std::string text = ReadInputFile(path, "influence constants file");
  const toml::table root = ParseToml(text, path);
  const Fields top(root, "", path);
  const auto t =
      top.Table("influence_constants", std::string("a table ") + kInfluenceConstantsExpected);
  if (!t) {
    top.FailMissing("influence_constants",
                    std::string("an [influence_constants] table ") + kInfluenceConstantsExpected);
  }
  return ReadInfluenceConstantsTable(*t);
}

std::string InfluenceConstantsFileText(const std::string& header, const InfluenceConstants& c) {
  auto set = [](const InfluenceConstantSet& v) {
    return fmt::format("c_f = {}\nc_z = {}\nc_s = {}\n", v.c_f, v.c_z, v.c_s);
  };
  std::string t = header;
  if (c.separate) {
    t += "\n[influence_constants.convex]\n" + set(c.separate->convex);
    t += "\n[influence_constants.concave]\n" + set(c.separate->concave);
  } else {
    t += "\n[influence_constants]\n" + set({c.c_f, c.c_z, c.c_s});
  }
  return t;
}

void WriteInfluenceConstantsFile(const std::string& path, const std::string& text,
                                 const InfluenceConstants& expected) {
  WriteOutputFile(path, text, "the influence constants file");
  const InfluenceConstants back = ReadInfluenceConstantsFile(path);
  if (InfluenceConstantsText(back) != InfluenceConstantsText(expected)) {
    throw std::runtime_error(fmt::format("{}: reads back as {}, not {}", path,
                                         InfluenceConstantsText(back),
                                         InfluenceConstantsText(expected)));
  }
}

nlohmann::json InfluenceConstantsJson(const InfluenceConstants& c) {
  auto set = [](double c_f, double c_z, double c_s) {
    return nlohmann::json{{"c_f", c_f}, {"c_z", c_z}, {"c_s", c_s}};
  };
  if (!c.separate) return set(c.c_f, c.c_z, c.c_s);
  const auto& s = *c.separate;
  return {{"convex", set(s.convex.c_f, s.convex.c_z, s.convex.c_s)},
          {"concave", set(s.concave.c_f, s.concave.c_z, s.concave.c_s)}};
}

std::string InfluenceConstantsText(const InfluenceConstants& c) {
  auto set = [](const InfluenceConstantSet& s) {
    return fmt::format("c_f {} c_z {} c_s {}", s.c_f, s.c_z, s.c_s);
  };
  if (!c.separate) return set({c.c_f, c.c_z, c.c_s});
  return fmt::format("convex {}, concave {}", set(c.separate->convex), set(c.separate->concave));
}

std::string ConstantsSetName(const InfluenceConstants& c) {
  const auto name = NameOf(c);
  return name ? std::string(ToString(*name)) : std::string("custom");
}

std::string InfluenceConstantsLine(const InfluenceConstants& c) {
  auto set = [](const InfluenceConstantSet& s) {
    return fmt::format("c_f {:.4g} c_z {:.4g} c_s {:.4g}", s.c_f, s.c_z, s.c_s);
  };
  const std::string values =
      c.separate ? fmt::format("convex {}, concave {}", set(c.separate->convex),
                               set(c.separate->concave))
                 : set({c.c_f, c.c_z, c.c_s});
  return fmt::format("constants {} ({})", ConstantsSetName(c), values);
}

}  // namespace railwear::app
