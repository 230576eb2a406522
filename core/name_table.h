#pragma once
// One table of (value, name) pairs per enum, read both ways: the single place where an
// enum's names are spelt (scenes, the tool, cache files and reports use them).
//
//   const std::pair<Motion, const char*> kMotions[] = {{Motion::translation, "translation"}, ...};
//   name_in(kMotions, Motion::six_dof)  -> "6dof"
//   value_in(kMotions, "6dof")          -> Motion::six_dof (none for an unknown name)
//   names_in(kMotions)                  -> "translation or 6dof" (for "expected ..." messages)
#include <cstddef>
#include <optional>
#include <string>
#include <utility>

namespace snapfit {

// A value's name, "?" for a value the table lacks.
template <typename T, std::size_t N>
const char* name_in(const std::pair<T, const char*> (&table)[N], T value) {
  for (const auto& [v, name] : table)
    if (v == value) return name;
  return "?";
}

// A name's value; none for an unknown name.
template <typename T, std::size_t N>
std::optional<T> value_in(const std::pair<T, const char*> (&table)[N], const std::string& name) {
  for (const auto& [v, text] : table)
    if (name == text) return v;
  return std::nullopt;
}

// Every name, "a, b or c".
template <typename T, std::size_t N>
std::string names_in(const std::pair<T, const char*> (&table)[N]) {
  std::string out;
  for (std::size_t i = 0; i < N; ++i) out += (i == 0 ? "" : i + 1 == N ? " or " : ", ") + std::string(table[i].second);
  return out;
}

}  // namespace snapfit
