// Every option of a pipeline is declared once, here in the library, as a
// field table: name, one-line help with its thesis section, unit, group, and
// how to read and write it. The command-line flags, the Python keyword
// arguments and option classes, the JSON reports and the help texts are all
// generated from these tables (docs/architecture.md, "Options"), so adding an
// option is a change to one file: the table that declares it.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <variant>
#include <vector>

#include "sharpmesh/errors.h"

namespace sharpmesh {

/// One option value as a command line, Python and JSON see it.
using FieldValue = std::variant<bool, std::int64_t, double, std::string>;

/// Describes a value for an error message or a help text: "true", "3.5", "auto".
std::string format_field_value(const FieldValue& value);

template <class Options>
struct OptionField {
  /// snake_case, in the positive sense (`snapping`, not `no_snapping`): the
  /// Python keyword and the JSON key. The flag is `--name-with-dashes`, and
  /// `--no-name` for a switch that is on by default.
  std::string name;
  std::string help;   ///< one line, citing the thesis section or the design note
  std::string unit;   ///< "" for counts, switches and ratios
  std::string group;  ///< help-text heading; "" for the command's own options
  std::vector<std::string> choices;  ///< the allowed strings of a text option
  std::function<FieldValue(const Options&)> get;
  /// Converts numbers between integer and real where no digit is lost;
  /// throws InvalidArgument naming the field otherwise.
  std::function<void(Options&, const FieldValue&)> set;
};

/// The field of `name` in `fields`; throws InvalidArgument listing the names
/// when there is none.
template <class Options>
const OptionField<Options>& find_field(const std::vector<OptionField<Options>>& fields, const std::string& name) {
  std::string names;
  for (const OptionField<Options>& f : fields) {
    if (f.name == name) return f;
    names += (names.empty() ? "" : ", ") + f.name;
  }
  throw InvalidArgument("unknown option '" + name + "' (options: " + names + ")");
}

struct DecimationOptions;
struct FeatureOptions;
struct ReconstructOptions;
struct ReconstructTuning;
struct StereoReconstructionOptions;
struct TilingOptions;
struct WallOptions;

/// FeatureOptions (thesis 7.2).
const std::vector<OptionField<FeatureOptions>>& feature_option_fields();
/// ReconstructOptions (thesis 7.3, 7.4 and the repairs beyond it), the
/// feature options included under the group "Feature detection".
const std::vector<OptionField<ReconstructOptions>>& reconstruct_option_fields();
/// ReconstructTuning, the repairs' thresholds (part of the table above, under
/// the group "Tuning of the repairs").
const std::vector<OptionField<ReconstructTuning>>& tuning_option_fields();
/// DecimationOptions (sharpmesh/compact.h; part of the reconstruct table
/// under the group "Compaction").
const std::vector<OptionField<DecimationOptions>>& decimation_option_fields();
/// StereoReconstructionOptions (thesis Ch. 6 and the fill beyond it).
const std::vector<OptionField<StereoReconstructionOptions>>& stereo_option_fields();
/// WallOptions (sharpmesh/pointset.h: walls under roof edges of airborne scans;
/// part of the reconstruct table under the group "Airborne scans").
const std::vector<OptionField<WallOptions>>& wall_option_fields();
/// TilingOptions (sharpmesh/tiled.h: reconstruct in slabs).
const std::vector<OptionField<TilingOptions>>& tiling_option_fields();

}  // namespace sharpmesh
