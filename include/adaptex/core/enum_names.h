#pragma once
/// \file enum_names.h
/// The names of the option enums, one table per enum declared beside the enum: the CLI, Python, the
/// studio and report.json all read and write an enum through its table. (AdaptMode's names are the
/// method registry's, adapt/method.h.)
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "adaptex/core/errors.h"

namespace adaptex {

/// One name of an enum value. An alias is accepted by parse_enum() but never written or listed.
template <class E>
struct EnumName {
  E value;
  const char* name;
  bool alias = false;
};

/// The table of E, canonical names first (specialized beside E, defined in its .cpp).
template <class E>
std::span<const EnumName<E>> enum_names();

/// The canonical name of \p value ("?" for a value outside the table).
template <class E>
const char* enum_name(E value) {
  for (const EnumName<E>& n : enum_names<E>())
    if (!n.alias && n.value == value) return n.name;
  return "?";
}

/// The canonical names of E, in table order (for help texts and choice lists).
template <class E>
std::vector<std::string> enum_choices() {
  std::vector<std::string> out;
  for (const EnumName<E>& n : enum_names<E>())
    if (!n.alias) out.emplace_back(n.name);
  return out;
}

/// \p names as "a, b or c".
std::string or_list(const std::vector<std::string>& names);

/// The value named \p name (canonical name or alias).
/// \throw InvalidInputError "unknown WHAT 'NAME' (expected a, b or c)"
template <class E>
E parse_enum(std::string_view name, std::string_view what) {
  for (const EnumName<E>& n : enum_names<E>())
    if (name == n.name) return n.value;
  throw InvalidInputError("unknown " + std::string(what) + " '" + std::string(name) + "' (expected " +
                          or_list(enum_choices<E>()) + ")");
}

}  // namespace adaptex
