// Typed, checked access to the keys of a toml++ table, for scene files and the files they name.
// Every failure throws InputError with "FILE:LINE: key 'section.key' = VALUE: expected WHAT".
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <toml++/toml.h>

namespace railwear::app {

// What a number must satisfy, and how to say it ("a number > 0").
struct NumberRule {
  std::function<bool(double)> ok;
  std::string expected;
};
NumberRule AnyFinite();
NumberRule Positive();
NumberRule AtLeast(double lo);
NumberRule InRange(double lo_inclusive, double hi_exclusive);    // [lo, hi)
NumberRule OpenClosed(double lo_exclusive, double hi_inclusive);  // (lo, hi]

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
std::string JoinQuoted(const std::vector<std::string_view>& names);

// Parses TOML text; a syntax error becomes InputError "FILE:LINE:COLUMN: TOML syntax error: ...".
toml::table ParseToml(const std::string& text, const std::string& file);

}  // namespace railwear::app
