// Checked access to toml++ tables: every problem becomes an InputError naming file, line, key,
// value and what was expected.
#include "app/toml_fields.h"

#include <cmath>
#include <fstream>
#include <iostream>
#include <sstream>

#include <fmt/format.h>

#include "core/numerics/input_error.h"
#include "core/numerics/text_file.h"
#include "wear/rail_grade.h"

namespace railwear::app {

NumberRule AnyFinite() {
  return {[](double) { return true; }, "a finite number"};
}
NumberRule Positive() {
  return {[](double v) { return v > 0.0; }, "a number > 0"};
}
NumberRule AtLeast(double lo) {
  return {[lo](double v) { return v >= lo; }, fmt::format("a number >= {}", lo)};
}
NumberRule InRange(double lo, double hi) {
  return {[lo, hi](double v) { return v >= lo && v < hi; },
          fmt::format("a number in [{}, {})", lo, hi)};
}
NumberRule Closed(double lo, double hi) {
  return {[lo, hi](double v) { return v >= lo && v <= hi; },
          fmt::format("a number in [{}, {}]", lo, hi)};
}
NumberRule OpenClosed(double lo, double hi) {
  return {[lo, hi](double v) { return v > lo && v <= hi; },
          fmt::format("a number in ({}, {}]", lo, hi)};
}
NumberRule IntegerAtLeast(int lo) {
  return {[lo](double x) { return x >= lo && x == std::floor(x) && x < 1e6; },
          fmt::format("an integer >= {}", lo)};
}
NumberRule IntegerInRange(int lo, int hi) {
  return {[lo, hi](double x) { return x >= lo && x <= hi && x == std::floor(x); },
          fmt::format("an integer in [{}, {}]", lo, hi)};
}

int LineOf(const toml::node& node) {
  const int line = static_cast<int>(node.source().begin.line);
  return line > 0 ? line : 1;
}

namespace {

std::string Quoted(const std::string& s) {
  std::string out = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  return out + "\"";
}

// The value as a user would write it: strings in double quotes, numbers in their shortest form.
// `toml`: valid TOML also for floats whose shortest form reads as an integer (300 -> 300.0).
std::string Written(const toml::node& node, bool toml = false) {
  if (const auto s = node.value_exact<std::string>()) return Quoted(*s);
  if (const auto i = node.value_exact<int64_t>()) return fmt::format("{}", *i);
  if (const auto d = node.value_exact<double>()) {
    std::string text = fmt::format("{}", *d);
    if (toml && text.find_first_of(".eni") == std::string::npos) text += ".0";
    return text;
  }
  if (const auto b = node.value_exact<bool>()) return *b ? "true" : "false";
  if (const toml::array* a = node.as_array()) {
    std::string out;
    for (const auto& e : *a) {
      out += fmt::format("{}{}", out.empty() ? "" : ", ", Written(e, toml));
    }
    return fmt::format("[{}]", out);
  }
  if (const toml::table* t = node.as_table()) {
    std::string out;
    for (const auto& [k, v] : *t) {
      out += fmt::format("{}{} = {}", out.empty() ? "" : ", ", k.str(), Written(v, toml));
    }
    return fmt::format("{{ {} }}", out);
  }
  std::ostringstream os;  // dates and times
  node.visit([&os](const auto& v) { os << v; });
  return os.str();
}

}  // namespace

std::string TomlValueText(const toml::node& node) { return Written(node, true); }

std::string ValueText(const toml::node& node) {
  if (node.is_table() && !node.as_table()->is_inline()) return "(table)";
  if (node.is_array_of_tables()) return "(array of tables)";
  std::string text = Written(node);
  if (text.size() > 60) text = text.substr(0, 57) + "...";
  return text;
}

std::string FieldPrefix(const std::string& file, const toml::node& node, std::string_view key) {
  return fmt::format("{}:{}: key '{}' = {}", file, LineOf(node), key, ValueText(node));
}

std::string FieldError(const std::string& file, const toml::node& node, std::string_view key,
                       std::string_view expected) {
  return fmt::format("{}: expected {}", FieldPrefix(file, node, key), expected);
}

std::string JoinQuoted(const std::vector<std::string_view>& names) {
  std::string out;
  for (const auto& n : names) {
    if (!out.empty()) out += ", ";
    out += fmt::format("'{}'", n);
  }
  return out;
}

toml::table ParseToml(const std::string& text, const std::string& file) {
  try {
    return toml::parse(text, file);
  } catch (const toml::parse_error& e) {
    const auto& begin = e.source().begin;
    throw InputError(fmt::format("{}:{}:{}: TOML syntax error: {}", file, begin.line, begin.column,
                                 e.description()));
  }
}

std::string ReadInputFile(const std::string& path, std::string_view what) {
  std::optional<std::string> text = ReadTextFile(path);
  if (!text) throw InputError(fmt::format("{}: cannot open {}", path, what));
  return std::move(*text);
}

void WriteOutputFile(const std::string& path, std::string_view text, std::string_view what) {
  if (path == "-") {
    std::cout << text << std::flush;
    return;
  }
  if (!WriteTextFile(path, text)) throw InputError(fmt::format("{}: cannot write {}", path, what));
}

std::vector<Fields> ArrayOfTables(const Fields& top, std::string_view key,
                                  std::string_view expected) {
  std::vector<Fields> out;
  const toml::node* node = top.Node(key);
  if (node == nullptr) return out;
  if (!node->is_array_of_tables()) top.Fail(key, expected);
  int index = 0;
  for (const toml::node& entry : *node->as_array()) {
    out.emplace_back(*entry.as_table(), fmt::format("{}[{}]", key, index++), top.file());
  }
  return out;
}

namespace {

// E, nu and the hardness a rail or wheel grade presets (wear/rail_grade.h); true.
template <class Grade>
bool PresetFromGrade(const Grade& grade, Material* m) {
  m->youngs_modulus_Pa = grade.youngs_modulus_Pa;
  m->poisson_ratio = grade.poisson_ratio;
  m->hardness_Pa = grade.hardness_Pa;
  return true;
}

}  // namespace

Material ReadMaterial(const Fields& parent, std::string_view key, MaterialKeys keys) {
  constexpr double kMPa = 1e6;  // MPa -> Pa
  const auto t = parent.Table(key, "an inline table { E_MPa, nu }");
  if (!t) parent.FailMissing(key, "an inline table { E_MPa, nu }");
  if (keys == MaterialKeys::kWithDamage) {
    t->AllowOnly({"grade", "E_MPa", "nu", "hardness_MPa", "shear_yield_MPa"});
  } else if (keys == MaterialKeys::kWithHardness) {
    t->AllowOnly({"E_MPa", "nu", "hardness_MPa", "grade"});
  } else {
    t->AllowOnly({"E_MPa", "nu"});
  }
  Material m;
  // A rail or wheel grade (wear/rail_grade.h) presets every value; the keys given beside it
  // override.
  bool preset = false;
  if (keys == MaterialKeys::kWithDamage) {
    if (const auto name = t->Choice("grade", EnumChoices(kRailGradeNames))) {
      const RailGradeProperties grade = RailGradeOf(*RailGradeFromString(*name));
      preset = PresetFromGrade(grade, &m);
      m.shear_yield_Pa = grade.shear_yield_Pa;
    }
  } else if (keys == MaterialKeys::kWithHardness) {
    // A wheel grade (EN 13262): E, nu and the rim's minimum hardness.
    if (const auto name = t->Choice("grade", EnumChoices(kWheelGradeNames))) {
      preset = PresetFromGrade(WheelGradeOf(*WheelGradeFromString(*name)), &m);
    }
  }
  // Moduli from soft rubber (1 MPa) to beyond diamond (1e7 MPa): the contact modulus and the
  // approach of the solvers are bounded there (1e-308 MPa aborted the normal solver).
  if (!preset || t->Has("E_MPa")) {
    m.youngs_modulus_Pa = t->RequiredNumber("E_MPa", Positive(), Closed(1.0, 1e7)) * kMPa;
  }
  if (!preset || t->Has("nu")) m.poisson_ratio = t->RequiredNumber("nu", InRange(0.0, 0.5));
  if (const auto h = t->Number("hardness_MPa", Positive(), Closed(1.0, 1e6))) {
    m.hardness_Pa = *h * kMPa;
  }
  if (const auto y = t->Number("shear_yield_MPa", Positive(), Closed(1.0, 1e6))) {
    m.shear_yield_Pa = *y * kMPa;
  }
  return m;
}

Fields::Fields(const toml::table& table, std::string name, std::string file)
    : table_(table), name_(std::move(name)), file_(std::move(file)) {}

int Fields::Line() const { return LineOf(table_); }

std::string Fields::KeyName(std::string_view key) const {
  return name_.empty() ? std::string(key) : fmt::format("{}.{}", name_, key);
}

void Fields::Fail(std::string_view key, std::string_view expected) const {
  // A rule that relates keys may name one that is absent (kth_v2_m_s when only kth_v1_m_s is
  // given): say it is missing instead of dereferencing nothing.
  const toml::node* node = table_.get(key);
  if (node == nullptr) FailMissing(key, expected);
  throw InputError(FieldError(file_, *node, KeyName(key), expected));
}

void Fields::FailMissing(std::string_view key, std::string_view expected) const {
  throw InputError(fmt::format("{}:{}: key '{}' is missing: expected {}", file_, Line(),
                               KeyName(key), expected));
}

void Fields::AllowOnly(const std::vector<std::string_view>& allowed) const {
  for (const auto& [key, node] : table_) {
    bool known = false;
    for (const auto& a : allowed) known = known || key.str() == a;
    if (known) continue;
    const std::string where = name_.empty() ? "at the top level" : fmt::format("in [{}]", name_);
    throw InputError(fmt::format("{}:{}: key '{}' = {}: expected one of the keys allowed {}: {}",
                                 file_, LineOf(node), KeyName(key.str()), ValueText(node), where,
                                 JoinQuoted(allowed)));
  }
}

std::optional<double> Fields::Number(std::string_view key, const NumberRule& rule) const {
  const toml::node* node = table_.get(key);
  if (node == nullptr) return std::nullopt;
  double v = 0.0;
  if (const auto i = node->value_exact<int64_t>()) {
    v = static_cast<double>(*i);
  } else if (const auto d = node->value_exact<double>()) {
    v = *d;
  } else {
    Fail(key, rule.expected);
  }
  if (!std::isfinite(v) || !rule.ok(v)) Fail(key, rule.expected);
  return v;
}

double Fields::RequiredNumber(std::string_view key, const NumberRule& rule) const {
  const auto v = Number(key, rule);
  if (!v) FailMissing(key, rule.expected);
  return *v;
}

std::optional<double> Fields::Number(std::string_view key, const NumberRule& rule,
                                     const NumberRule& range) const {
  const auto v = Number(key, rule);
  if (v && !range.ok(*v)) Fail(key, range.expected + " (the range the numerics bear)");
  return v;
}

double Fields::RequiredNumber(std::string_view key, const NumberRule& rule,
                              const NumberRule& range) const {
  const auto v = Number(key, rule, range);
  if (!v) FailMissing(key, rule.expected);
  return *v;
}

std::optional<int> Fields::Integer(std::string_view key, const NumberRule& rule) const {
  const auto v = Number(key, rule);
  if (!v) return std::nullopt;
  return static_cast<int>(*v);
}

std::optional<int> Fields::Integer(std::string_view key, const NumberRule& number,
                                   const NumberRule& integer) const {
  const auto v = Number(key, number);
  if (!v) return std::nullopt;
  if (!integer.ok(*v)) Fail(key, integer.expected);
  return static_cast<int>(*v);
}

std::optional<std::array<double, 2>> Fields::NumberPair(std::string_view key,
                                                        std::string_view expected) const {
  const toml::node* node = table_.get(key);
  if (node == nullptr) return std::nullopt;
  const toml::array* a = node->as_array();
  if (a == nullptr || a->size() != 2) Fail(key, expected);
  std::array<double, 2> v{};
  for (size_t i = 0; i < 2; ++i) {
    const toml::node& n = *a->get(i);
    const auto x = n.value<double>();  // integers convert
    if (!n.is_number() || !x || !std::isfinite(*x)) Fail(key, expected);
    v[i] = *x;
  }
  return v;
}

std::optional<std::string> Fields::String(std::string_view key) const {
  const toml::node* node = table_.get(key);
  if (node == nullptr) return std::nullopt;
  const auto s = node->value_exact<std::string>();
  if (!s) Fail(key, "a string");
  return *s;
}

std::string Fields::RequiredString(std::string_view key, std::string_view expected) const {
  const toml::node* node = table_.get(key);
  if (node == nullptr) FailMissing(key, expected);
  const auto s = node->value_exact<std::string>();
  if (!s || s->empty()) Fail(key, expected);
  return *s;
}

std::optional<std::string> Fields::Choice(std::string_view key,
                                          const std::vector<std::string_view>& choices) const {
  const toml::node* node = table_.get(key);
  if (node == nullptr) return std::nullopt;
  const std::string expected = "one of " + JoinQuoted(choices);
  const auto s = node->value_exact<std::string>();
  if (!s) Fail(key, expected);
  for (const auto& c : choices) {
    if (*s == c) return *s;
  }
  Fail(key, expected);
}

std::optional<bool> Fields::Bool(std::string_view key) const {
  const toml::node* node = table_.get(key);
  if (node == nullptr) return std::nullopt;
  const auto b = node->value_exact<bool>();
  if (!b) Fail(key, "true or false");
  return *b;
}

std::optional<Fields> Fields::Table(std::string_view key, std::string_view expected) const {
  const toml::node* node = table_.get(key);
  if (node == nullptr) return std::nullopt;
  if (!node->is_table()) Fail(key, expected);
  return Fields(*node->as_table(), KeyName(key), file_);
}

}  // namespace railwear::app
