// Python option classes and keyword arguments generated from the library's
// option-field tables (sharpmesh/option_fields.h), as pycolmap does: the
// class's defaults and help are read from C++, and a function takes either
// an options object, keywords, or both (keywords win).
#pragma once

#include <string>
#include <vector>

#include "convert.h"
#include "sharpmesh/option_fields.h"

namespace sharpmesh::python {

inline py::object to_python(const FieldValue& value) {
  if (const bool* b = std::get_if<bool>(&value)) return py::bool_(*b);
  if (const std::int64_t* i = std::get_if<std::int64_t>(&value)) return py::int_(*i);
  if (const double* d = std::get_if<double>(&value)) return py::float_(*d);
  return py::str(std::get<std::string>(value));
}

/// A Python value as the field's kind; InvalidArgument naming the field for another type.
inline FieldValue from_python(const py::handle& value, const std::string& name) {
  if (py::isinstance<py::bool_>(value)) return value.cast<bool>();
  if (py::isinstance<py::int_>(value)) return value.cast<std::int64_t>();
  if (py::isinstance<py::float_>(value)) return value.cast<double>();
  if (py::isinstance<py::str>(value)) return value.cast<std::string>();
  throw InvalidArgument("option " + name + " takes a number, a bool or a string (got " + py::str(py::type::of(value)).cast<std::string>() + ")");
}

/// Sets one keyword. `no_NAME=True` is accepted for a switch NAME that is on
/// by default, as the command line's `--no-name` is.
template <class Options>
void set_keyword(Options& options, const std::vector<OptionField<Options>>& fields, const std::string& key, const py::handle& value) {
  if (key.rfind("no_", 0) == 0) {
    for (const OptionField<Options>& f : fields)
      if (f.name == key.substr(3) && std::holds_alternative<bool>(f.get(Options{})) && std::get<bool>(f.get(Options{}))) {
        f.set(options, !std::get<bool>(from_python(value, key)));
        return;
      }
  }
  const OptionField<Options>& field = find_field(fields, key);
  field.set(options, from_python(value, key));
}

/// `options` (None or an Options object) with the keywords applied.
template <class Options>
Options options_from(const py::object& options, const py::kwargs& keywords, const std::vector<OptionField<Options>>& fields) {
  Options out = options.is_none() ? Options{} : options.cast<Options>();
  for (const auto& [key, value] : keywords) set_keyword(out, fields, key.template cast<std::string>(), value);
  return out;
}

/// The help lines of the keywords: `name = default [unit]: help`.
template <class Options>
std::string keyword_help(const std::vector<OptionField<Options>>& fields) {
  const Options defaults;
  std::string text;
  for (const OptionField<Options>& f : fields)
    text += "  " + f.name + " = " + format_field_value(f.get(defaults)) + (f.unit.empty() ? "" : " [" + f.unit + "]") + ": " + f.help + "\n";
  return text;
}

/// The class `name` with one property per field and keyword construction.
template <class Options>
void bind_option_class(py::module_& m, const char* name, const std::vector<OptionField<Options>>& fields, const std::string& doc) {
  py::class_<Options> cls(m, name, (doc + "\n\nKeywords and properties:\n" + keyword_help(fields)).c_str());
  cls.def(py::init([&fields](const py::kwargs& keywords) { return options_from<Options>(py::none(), keywords, fields); }));
  for (const OptionField<Options>& f : fields) {
    cls.def_property(
        f.name.c_str(), [&f](const Options& o) { return to_python(f.get(o)); },
        [&f](Options& o, const py::object& value) { f.set(o, from_python(value, f.name)); }, f.help.c_str());
  }
  cls.def("to_dict", [&fields](const Options& o) {
    py::dict d;
    for (const OptionField<Options>& f : fields) d[py::str(f.name)] = to_python(f.get(o));
    return d;
  });
  cls.def("__repr__", [&fields, name = std::string(name)](const Options& o) {
    std::string text = name + "(";
    const Options defaults;
    bool first = true;
    for (const OptionField<Options>& f : fields) {
      if (f.get(o) == f.get(defaults)) continue;
      text += (first ? "" : ", ") + f.name + "=" + py::repr(to_python(f.get(o))).template cast<std::string>();
      first = false;
    }
    return text + ")";
  });
}

}  // namespace sharpmesh::python
