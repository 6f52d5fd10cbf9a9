// Typed, checked access to the keys of a toml++ table, for scene files and the files they name,
// and the readers that the config dialects (scene, calibrate, fem-reference) share: integers,
// number pairs, arrays of enum names, arrays of tables, materials.
// Every failure throws InputError with "FILE:LINE: key 'section.key' = VALUE: expected WHAT".
#pragma once

#include <algorithm>
#include <array>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <toml++/toml.h>

#include "core/contact/contact_types.h"

namespace railwear::app {

// What a number must satisfy, and how to say it ("a number > 0").
struct NumberRule {
  std::function<bool(double)> ok;
  std::string expected;
};
NumberRule AnyFinite();
NumberRule Positive();
NumberRule AtLeast(double lo);
NumberRule InRange(double lo_inclusive, double hi_exclusive);     // [lo, hi)
NumberRule Closed(double lo_inclusive, double hi_inclusive);      // [lo, hi]
NumberRule OpenClosed(double lo_exclusive, double hi_inclusive);  // (lo, hi]
NumberRule IntegerAtLeast(int lo);  // "an integer >= lo" (and below 1e6)
NumberRule IntegerInRange(int lo_inclusive, int hi_inclusive);  // "an integer in [lo, hi]"

// A table of the scene with its dotted name ("load", "materials.rail") and file name.
class Fields {
 public:
  Fields(const toml::table& table, std::string name, std::string file);

  // Throws for the first key not in `allowed`, listing the allowed keys.
  void AllowOnly(const std::vector<std::string_view>& allowed) const;
  bool Has(std::string_view key) const { return table_.contains(key); }
  const toml::node* Node(std::string_view key) const { return table_.get(key); }

  std::optional<double> Number(std::string_view key, const NumberRule& rule) const;
  double RequiredNumber(std::string_view key, const NumberRule& rule) const;
  // The same, then `range` (the finite range the numerics bear, issue 17): a value that passes
  // `rule` but not `range` fails with "expected RANGE (the range the numerics bear)".
  std::optional<double> Number(std::string_view key, const NumberRule& rule,
                               const NumberRule& range) const;
  double RequiredNumber(std::string_view key, const NumberRule& rule,
                        const NumberRule& range) const;
  // An integer: `rule` must only accept whole numbers that fit an int (IntegerAtLeast,
  // IntegerInRange). The two-rule form checks `number` first (its message for values it
  // rejects) and then `integer` (its message for values that pass the first but are not one).
  std::optional<int> Integer(std::string_view key, const NumberRule& rule) const;
  std::optional<int> Integer(std::string_view key, const NumberRule& number,
                             const NumberRule& integer) const;
  // Two finite numbers [a, b] (integers convert); fails with `expected` for anything else.
  // Units are the caller's (the key's suffix, e.g. _mm).
  std::optional<std::array<double, 2>> NumberPair(std::string_view key,
                                                  std::string_view expected) const;
  std::optional<std::string> String(std::string_view key) const;
  std::string RequiredString(std::string_view key, std::string_view expected) const;
  // A string that must be one of `choices`.
  std::optional<std::string> Choice(std::string_view key,
                                    const std::vector<std::string_view>& choices) const;
  std::optional<bool> Bool(std::string_view key) const;
  // A sub-table (inline or not); nullopt when absent; throws when the key is not a table.
  std::optional<Fields> Table(std::string_view key, std::string_view expected) const;

  [[noreturn]] void Fail(std::string_view key, std::string_view expected) const;
  [[noreturn]] void FailMissing(std::string_view key, std::string_view expected) const;
  std::string KeyName(std::string_view key) const;
  const std::string& file() const { return file_; }
  int Line() const;

 private:
  const toml::table& table_;
  std::string name_;
  std::string file_;
};

// "FILE:LINE: key 'KEY' = VALUE: expected EXPECTED"
std::string FieldError(const std::string& file, const toml::node& node, std::string_view key,
                       std::string_view expected);
// "FILE:LINE: key 'KEY' = VALUE", for messages that go on differently.
std::string FieldPrefix(const std::string& file, const toml::node& node, std::string_view key);
// The node's value as written in TOML, shortened to about 60 characters.
std::string ValueText(const toml::node& node);
int LineOf(const toml::node& node);
// The value as TOML text in its shortest form, not shortened (strings in double quotes, floats
// always as floats: 300.0), for values written into a generated file (sweep plans).
std::string TomlValueText(const toml::node& node);
std::string JoinQuoted(const std::vector<std::string_view>& names);

// Parses TOML text; a syntax error becomes InputError "FILE:LINE:COLUMN: TOML syntax error: ...".
toml::table ParseToml(const std::string& text, const std::string& file);

// The whole text of an input file (a config or a file it names). Throws InputError
// "PATH: cannot open WHAT" when it cannot be opened (`what` as it reads there: "the
// calibration config").
std::string ReadInputFile(const std::string& path, std::string_view what);
// Writes `text` to `path` (replaced). Throws InputError "PATH: cannot write WHAT" when it fails.
// "-" writes to stdout.
void WriteOutputFile(const std::string& path, std::string_view text, std::string_view what);

// The [[KEY]] tables of `top`, named "KEY[0]", "KEY[1]", ...; none when the key is absent.
// Throws (with `expected`) when the key is not an array of tables.
std::vector<Fields> ArrayOfTables(const Fields& top, std::string_view key,
                                  std::string_view expected);

// A non-empty array of distinct names at `key`, each turned into an enum value by
// `from_string` (std::optional<Enum>(std::string_view), nullopt for an unknown name). Fails with
// `expected` when the key is not an array, is empty, or holds a non-string, an unknown name or a
// repeat. The key must be present (check Has first).
template <typename Enum, typename FromString>
std::vector<Enum> EnumArray(const Fields& t, std::string_view key, FromString from_string,
                            std::string_view expected) {
  const toml::array* a = t.Node(key)->as_array();
  if (a == nullptr || a->empty()) t.Fail(key, expected);
  std::vector<Enum> out;
  for (const toml::node& e : *a) {
    const auto name = e.value_exact<std::string>();
    const std::optional<Enum> value = name ? from_string(*name) : std::nullopt;
    if (!value || std::find(out.begin(), out.end(), *value) != out.end()) t.Fail(key, expected);
    out.push_back(*value);
  }
  return out;
}

// Which keys a material table accepts.
enum class MaterialKeys {
  kElastic,       // { E_MPa, nu }
  kWithDamage,    // { E_MPa, nu, hardness_MPa, shear_yield_MPa } (the rail of a scene)
  // { grade, E_MPa, nu, hardness_MPa } (the wheel of a scene: its pressure limit and, for wear
  // with co-evolution, its hardness; grade "R7" | "R8", wear/rail_grade.h, presets the others)
  kWithHardness,
};
// The material table at `key` of `parent` (inline or not; required): E_MPa in [1, 1e7] and nu
// in [0, 0.5) required, hardness_MPa and shear_yield_MPa (in [1, 1e6], optional) when `keys` allows
// them. Returns SI values (Pa); the optional properties stay NaN when absent.
Material ReadMaterial(const Fields& parent, std::string_view key, MaterialKeys keys);

}  // namespace railwear::app
