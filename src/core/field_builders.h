// Builders of option-field tables (sharpmesh/option_fields.h): a field from a
// member, a field of a nested struct lifted into its parent, and the checked
// conversions between FieldValue and the member's own type.
#pragma once

#include <cmath>
#include <limits>
#include <type_traits>
#include <utility>

#include "sharpmesh/option_fields.h"

namespace sharpmesh::detail {

template <class T>
FieldValue to_field_value(const T& value) {
  if constexpr (std::is_same_v<T, bool>) {
    return value;
  } else if constexpr (std::is_integral_v<T>) {
    return static_cast<std::int64_t>(value);
  } else if constexpr (std::is_floating_point_v<T>) {
    return static_cast<double>(value);
  } else {
    return std::string(value);
  }
}

/// The value as a T, or InvalidArgument naming the option: a switch takes
/// true or false, a count an integer in its range, a length any finite or
/// infinite real, a text option a string.
template <class T>
T from_field_value(const FieldValue& value, const std::string& name) {
  const auto wrong = [&](const char* expected) {
    return InvalidArgument("option " + name + " takes " + expected + " (got " + format_field_value(value) + ")");
  };
  if constexpr (std::is_same_v<T, bool>) {
    if (const bool* b = std::get_if<bool>(&value)) return *b;
    throw wrong("true or false");
  } else if constexpr (std::is_integral_v<T>) {
    if (const std::int64_t* i = std::get_if<std::int64_t>(&value)) {
      const T narrowed = static_cast<T>(*i);
      if ((std::is_signed_v<T> || *i >= 0) && static_cast<std::int64_t>(narrowed) == *i) return narrowed;
    } else if (const double* d = std::get_if<double>(&value)) {
      if (std::isfinite(*d) && *d == std::floor(*d) && *d >= static_cast<double>(std::numeric_limits<T>::min()) &&
          *d <= static_cast<double>(std::numeric_limits<T>::max()))
        return static_cast<T>(*d);
    } else {
      throw wrong("an integer");
    }
    throw wrong(std::is_signed_v<T> ? "an integer in range" : "a non-negative integer in range");
  } else if constexpr (std::is_floating_point_v<T>) {
    if (const double* d = std::get_if<double>(&value)) return static_cast<T>(*d);
    if (const std::int64_t* i = std::get_if<std::int64_t>(&value)) return static_cast<T>(*i);
    throw wrong("a number");
  } else {
    if (const std::string* s = std::get_if<std::string>(&value)) return *s;
    throw wrong("a string");
  }
}

/// A field reading and writing `member` of Options.
template <class Options, class T>
OptionField<Options> member_field(std::string name, std::string help, std::string unit, T Options::*member) {
  OptionField<Options> f;
  f.name = std::move(name);
  f.help = std::move(help);
  f.unit = std::move(unit);
  f.get = [member](const Options& o) { return to_field_value(o.*member); };
  const std::string key = f.name;
  f.set = [member, key](Options& o, const FieldValue& v) { o.*member = from_field_value<T>(v, key); };
  return f;
}

/// The field of the nested struct `member` as a field of its parent.
template <class Parent, class Child>
OptionField<Parent> nested_field(const OptionField<Child>& child, Child Parent::*member, std::string group = {}) {
  OptionField<Parent> f;
  f.name = child.name;
  f.help = child.help;
  f.unit = child.unit;
  f.group = group.empty() ? child.group : std::move(group);
  f.choices = child.choices;
  f.get = [get = child.get, member](const Parent& o) { return get(o.*member); };
  f.set = [set = child.set, member](Parent& o, const FieldValue& v) { set(o.*member, v); };
  return f;
}

}  // namespace sharpmesh::detail
