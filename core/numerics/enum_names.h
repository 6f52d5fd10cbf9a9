// One name table per enum: a constexpr array of {value, "name"} written once beside the enum,
// from which ToString, FromString, the scene's choice lists and the CLI's option lists are all
// made, so each name is spelled in one place.
//
//   enum class Colour { kRed, kGreen };
//   inline constexpr std::array<EnumName<Colour>, 2> kColourNames = {{
//       {Colour::kRed, "red"}, {Colour::kGreen, "green"}}};
//   std::string_view ToString(Colour v) { return EnumToString(kColourNames, v); }
//
// An entry with selectable = false has a name for output only: FromString does not accept it and
// the choice lists leave it out (e.g. ModelKind::kCustom, which a scene reaches by setting the
// geometry or kernel explicitly, never by name).
#pragma once

#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace railwear {

template <typename E>
struct EnumName {
  E value;
  std::string_view name;
  bool selectable = true;  // accepted by EnumFromString and listed by EnumChoices
};

// The name of `value`; `unknown` when the table does not hold it.
template <typename E, std::size_t N>
constexpr std::string_view EnumToString(const std::array<EnumName<E>, N>& table, E value,
                                        std::string_view unknown = "?") {
  for (const auto& e : table) {
    if (e.value == value) return e.name;
  }
  return unknown;
}

// The value named `name` among the selectable entries; std::nullopt for any other name.
template <typename E, std::size_t N>
constexpr std::optional<E> EnumFromString(const std::array<EnumName<E>, N>& table,
                                          std::string_view name) {
  for (const auto& e : table) {
    if (e.selectable && e.name == name) return e.value;
  }
  return std::nullopt;
}

// The selectable names in table order (a scene key's choices).
template <typename E, std::size_t N>
std::vector<std::string_view> EnumChoices(const std::array<EnumName<E>, N>& table) {
  std::vector<std::string_view> out;
  for (const auto& e : table) {
    if (e.selectable) out.push_back(e.name);
  }
  return out;
}

// The same as strings (a command-line option's allowed values).
template <typename E, std::size_t N>
std::vector<std::string> EnumChoiceStrings(const std::array<EnumName<E>, N>& table) {
  std::vector<std::string> out;
  for (const auto& e : table) {
    if (e.selectable) out.emplace_back(e.name);
  }
  return out;
}

// The selectable names joined by `separator` ("draft, standard, reference, fine").
template <typename E, std::size_t N>
std::string JoinEnumChoices(const std::array<EnumName<E>, N>& table,
                            std::string_view separator = ", ") {
  std::string out;
  for (const auto& e : table) {
    if (!e.selectable) continue;
    if (!out.empty()) out += separator;
    out += e.name;
  }
  return out;
}

}  // namespace railwear
