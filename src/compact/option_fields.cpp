// The field table of DecimationOptions (sharpmesh/option_fields.h): the
// flags of `sharpmesh decimate` and of reconstruct's compaction, the
// keywords of sharpmesh.decimate and sharpmesh.reconstruct.
#include "core/field_builders.h"
#include "sharpmesh/compact.h"
#include "sharpmesh/option_fields.h"

namespace sharpmesh {

const std::vector<OptionField<DecimationOptions>>& decimation_option_fields() {
  using detail::member_field;
  using O = DecimationOptions;
  static const std::vector<OptionField<O>> fields = {
      member_field("facets",
                   "Collapse edges down to this many facets, sharp edges kept: few facets where the surface is flat, many "
                   "where it bends (0: no budget)",
                   "", &O::facets),
      member_field("tolerance",
                   "Keep the collapsed mesh within this distance of the mesh it started from; alone, collapse as far as it "
                   "allows (0: no bound)",
                   "fraction of the diagonal", &O::tolerance),
      member_field("sharp_angle", "Besides the protected feature curves, keep edges whose facets meet at more than this (0: none)",
                   "degrees", &O::sharp_angle),
      member_field("fold_filter", "Refuse collapses that turn a facet's normal by more than 90 degrees (CGAL's bounded normal change)",
                   "", &O::bounded_normal_change),
  };
  return fields;
}

}  // namespace sharpmesh
