// The field table of TilingOptions (sharpmesh/option_fields.h): the tile
// flags of `sharpmesh reconstruct`, the keywords of Python's reconstruct_tiled.
#include "core/field_builders.h"
#include "sharpmesh/option_fields.h"
#include "sharpmesh/tiled.h"

namespace sharpmesh {

const std::vector<OptionField<TilingOptions>>& tiling_option_fields() {
  using detail::member_field;
  using O = TilingOptions;
  static const std::vector<OptionField<O>> fields = {
      member_field("tiles",
                   "Mesh the cloud in this many slabs along its longest axis, one after the other, and weld them along the "
                   "cuts (1: one run; memory holds one slab's pipeline)",
                   "", &O::tiles),
      member_field("tile_margin", "Each slab also meshes its neighbours' points this far beyond its cuts", "d'", &O::margin),
      member_field("seam_snap", "Mesh vertices this close to a cut move onto it before the clip", "d'", &O::snap),
      member_field("seam_merge", "A seam vertex this close to one of the other side's becomes it (0: both sides' vertices kept)", "d'",
                   &O::seam_merge),
      member_field("seam_tolerance", "The two sides of a seam may lie this far apart and still be welded", "d'", &O::seam_tolerance),
  };
  return fields;
}

}  // namespace sharpmesh
