// A polyline that turns back on itself (by more than 120 degrees) overlaps
// itself: a sharp edge never does, and CGAL's protection cannot take it
// (its ball removal crashes on such a curve).
#pragma once

#include <set>

#include "sharpmesh/types.h"

namespace sharpmesh::detail {

/// Drops each interior vertex where `line` turns back, unless it is in
/// `keep` (another polyline's end), until none is left; a vertex that the
/// removal makes coincide with its successor goes too.
inline void remove_fold_backs(Polyline& line, const std::set<Vec3>& keep = {}) {
  for (bool removed = true; removed && line.size() >= 3;) {
    removed = false;
    for (std::size_t i = 1; i + 1 < line.size(); ++i) {
      const Vec3 in = line[i] - line[i - 1], out = line[i + 1] - line[i];
      if (dot(in, out) < -0.5 * norm(in) * norm(out) && !keep.count(line[i])) {
        line.erase(line.begin() + static_cast<std::ptrdiff_t>(i));
        if (line[i - 1] == line[i]) line.erase(line.begin() + static_cast<std::ptrdiff_t>(i));
        removed = true;
        break;
      }
    }
  }
}

}  // namespace sharpmesh::detail
