// The field table of WallOptions (sharpmesh/option_fields.h): the airborne
// flags of `reconstruct` and `features`, their Python keywords and report keys.
#include "core/field_builders.h"
#include "sharpmesh/pointset.h"

namespace sharpmesh {

const std::vector<OptionField<WallOptions>>& wall_option_fields() {
  using detail::member_field;
  using O = WallOptions;
  static const std::vector<OptionField<O>> fields = [] {
    OptionField<O> mode;
    mode.name = "walls";
    mode.help =
        "Add vertical walls from roof edges down to the ground where a scan from above saw none: auto (on for clouds one "
        "layer thick and wide rather than high, as airborne scans are), on, off (beyond the thesis)";
    mode.choices = {"auto", "on", "off"};
    mode.get = [](const O& o) -> FieldValue {
      return std::string(o.mode == WallMode::Automatic ? "auto" : o.mode == WallMode::On ? "on" : "off");
    };
    mode.set = [](O& o, const FieldValue& v) {
      const std::string name = detail::from_field_value<std::string>(v, "walls");
      if (name == "auto") o.mode = WallMode::Automatic;
      else if (name == "on") o.mode = WallMode::On;
      else if (name == "off") o.mode = WallMode::Off;
      else throw InvalidArgument("option walls takes auto, on or off (got " + name + ")");
    };
    std::vector<OptionField<O>> f = {
        mode,
        member_field("wall_min_drop", "A wall starts where a point has another this much lower within the wall reach",
                     "average spacings", &O::min_drop),
        member_field("wall_reach", "Horizontal distance within which a drop counts",
                     "average spacings", &O::reach),
        member_field("wall_max_flatness",
                     "Only points whose 12 nearest points are this flat start a wall: smallest over largest eigenvalue of "
                     "their covariance (a roof, not a tree crown)",
                     "", &O::max_flatness),
    };
    for (OptionField<O>& field : f) field.group = "Airborne scans (beyond the thesis)";
    return f;
  }();
  return fields;
}

}  // namespace sharpmesh
