// The retry policy around CGAL's Mesh_3 refinement, in plain C++: what
// happens after a refinement ran away, stalled, failed inside CGAL or ran
// past its protection budget. implicit_mesher.cpp runs the refinements;
// this policy decides which protected polylines go before the next one.
// CGAL's Mesh_3 (5.5, CGAL issue #9102) can fail next to protected curves
// that come close to each other or to another sheet of the surface.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "sharpmesh/meshing.h"

namespace sharpmesh::detail {

/// How one refinement ended, as the mesher reports it.
struct RefinementRun {
  enum class Status {
    Finished,           ///< a mesh, possibly stopped as running away or stalled (flags in `result`)
    CgalFailure,        ///< CGAL threw; `cgal_message` says why
    ProtectionStopped,  ///< the feature protection ran past its query budget
  };
  Status status = Status::Finished;
  ImplicitMeshingResult result;
  /// Where a run-away refinement piled its vertices, when its check knew.
  std::optional<Vec3> runaway_pile;
  std::string cgal_message;
};

/// One refinement with `attempt`'s options. `rescue_stalled`: points where
/// the function is too flat for Newton's search may be protected; `stalled`
/// receives them.
using RefineOnce = std::function<RefinementRun(const ImplicitMeshingOptions& attempt, bool rescue_stalled, std::vector<Vec3>& stalled)>;

/// Refines with `refine` until a mesh comes out: after a runaway, a stall
/// or a CGAL failure at a known point, the polylines near that spot are
/// dropped (and reported as uncovered gaps); after a failure nowhere in
/// particular, first the rescued flat points go, then every polyline; a
/// protection past its budget runs again without protection. At most
/// `max_retries` refinements after the first; the last one's CGAL failure
/// is thrown as a NumericalFailure.
ImplicitMeshingResult refine_with_retries(const ImplicitMeshingOptions& options, const RefineOnce& refine,
                                          const Progress& progress, int max_retries = 4);

/// The point of CGAL's "(x y z w) is already inserted on surface." error.
bool failure_point(const std::string& message, Vec3& p);

/// Where a runaway refinement was working: the centre of the densest cell
/// (of the edge length bound) of mesh edges shorter than 1% of that bound.
bool runaway_spot(const SurfaceMesh& mesh, double edge_length, Vec3& spot);

/// Positions shared by two or more output vertices: non-manifold vertices
/// of the complex, which facets_in_complex_3_to_triangle_mesh splits (the
/// facets around them touch, and count as self-intersecting).
std::vector<Vec3> pinched_vertices(const SurfaceMesh& mesh);

/// Removes every polyline that passes within `reach` of p, and reports
/// each as refused by the mesher. False when no polyline comes that close.
bool drop_protection_near(std::vector<Polyline>& polylines, const Vec3& p, double reach, std::vector<UncoveredGap>& dropped);

}  // namespace sharpmesh::detail
