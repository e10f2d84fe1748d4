// Command-line flags generated from a library option-field table
// (sharpmesh/option_fields.h): `--name` for a value, `--no-name` for a switch
// that is on by default, `--name` for one that is off. The defaults shown are
// the values `options` holds when the flags are added.
#pragma once

#include <CLI/CLI.hpp>

#include <algorithm>
#include <string>
#include <vector>

#include "sharpmesh/option_fields.h"

namespace sharpmesh::cli {

inline std::string flag_name(const std::string& field_name) {
  std::string flag = field_name;
  std::replace(flag.begin(), flag.end(), '_', '-');
  return flag;
}

/// Adds a flag per field, except the fields named in `common`: those are
/// flags every command has (cli.h's CommonOptions), copied into the options
/// by the command itself.
template <class Options>
void add_option_fields(CLI::App& app, Options& options, const std::vector<OptionField<Options>>& fields,
                       const std::vector<std::string>& common = {}) {
  for (const OptionField<Options>& field : fields) {
    if (std::find(common.begin(), common.end(), field.name) != common.end()) continue;
    const FieldValue initial = field.get(options);
    const std::string flag = "--" + flag_name(field.name);
    const std::string help = field.help + (field.unit.empty() ? "" : " [" + field.unit + "]");
    CLI::Option* added = nullptr;
    if (const bool* on = std::get_if<bool>(&initial)) {
      const bool value = !*on;
      added = app.add_flag_function(*on ? "--no-" + flag_name(field.name) : flag,
                                    [&options, field, value](std::int64_t) { field.set(options, value); }, help);
    } else if (std::holds_alternative<std::int64_t>(initial)) {
      added = app.add_option_function<std::int64_t>(flag, [&options, field](const std::int64_t& v) { field.set(options, v); }, help);
    } else if (std::holds_alternative<double>(initial)) {
      added = app.add_option_function<double>(flag, [&options, field](const double& v) { field.set(options, v); }, help);
    } else {
      added = app.add_option_function<std::string>(flag, [&options, field](const std::string& v) { field.set(options, v); }, help);
      if (!field.choices.empty()) added->check(CLI::IsMember(field.choices));
    }
    if (!std::holds_alternative<bool>(initial)) added->default_str(format_field_value(initial));
    if (!field.group.empty()) added->group(field.group);
  }
}

}  // namespace sharpmesh::cli
