// A polyline left out of the protection, as the report describes it.
#pragma once

#include "sharpmesh/meshing.h"

namespace sharpmesh::detail {

/// The whole of `line` as an unprotected stretch: its midpoint and length,
/// no measured gap; the caller says why it was left out.
UncoveredGap whole_polyline_gap(const Polyline& line);

}  // namespace sharpmesh::detail
