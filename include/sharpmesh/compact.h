// Compact meshes, beyond the thesis: its refinement gives one size d'
// everywhere (the limitation 7.5 names), so a flat face takes as many facets
// as a tight fillet. A fine protected mesh is collapsed edge by edge in
// the order of Garland and Heckbert's plane quadrics (SIGGRAPH 1997, CGAL's
// Surface_mesh_simplification) while its sharp edges stay where they are:
// a feature vertex moves only along its curve and a corner never moves.
#pragma once

#include <cstddef>
#include <vector>

#include "sharpmesh/progress.h"
#include "sharpmesh/types.h"

namespace sharpmesh {

/// Its field table (sharpmesh/option_fields.h) gives the flags of `sharpmesh
/// decimate` and of `reconstruct`'s compaction.
struct DecimationOptions {
  /// Stop at this many facets (0: no budget).
  std::size_t facets = 0;
  /// Refuse a collapse that takes the surface farther than this from the
  /// mesh it started from, as a fraction of that mesh's bounding-box
  /// diagonal (CGAL's polyhedral envelope: a guarantee, not an estimate; 0:
  /// no bound). Alone, the mesh is collapsed as far as it allows.
  double tolerance = 0;
  /// Besides the given feature curves, edges whose facets meet at more than
  /// this dihedral angle are kept as sharp edges [degrees] (0: the given
  /// curves only).
  double sharp_angle = 40;
  /// Refuse a collapse that turns any facet's normal by more than 90
  /// degrees (CGAL's Bounded_normal_change_filter): the folds that make a
  /// decimated mesh cross itself.
  bool bounded_normal_change = true;
  /// A budget or a tolerance is set: there is something to do.
  bool active() const { return facets > 0 || tolerance > 0; }
  /// Throws InvalidArgument naming a value out of its range.
  void check() const;
};

struct DecimationResult {
  std::size_t input_facets = 0;
  std::size_t output_facets = 0;
  std::size_t collapsed_edges = 0;
  std::size_t feature_edges = 0;    ///< sharp edges of the input kept as curves
  std::size_t corner_vertices = 0;  ///< feature vertices that never move (curve ends and junctions)
  /// The budget was not reached: every remaining collapse would move a
  /// corner, leave a curve, break the tolerance or fold a facet.
  bool budget_missed = false;
  /// Collapses run: a second and third one when facets crossed, with the
  /// vertices around the crossings frozen (kept where they are).
  int rounds = 0;
  std::size_t frozen_vertices = 0;
  std::size_t crossing_pairs = 0;  ///< facet pairs still crossing after the last round
};

/// Collapses edges of `mesh` until it has at most options.facets facets or
/// no collapse within options.tolerance is left (InvalidArgument when
/// neither is set; InvalidInput when the mesh is not manifold). `feature_curves`
/// are polylines through vertices of the mesh (as
/// ImplicitMeshingResult::feature_edges); their edges, the mesh's border
/// and the edges sharper than options.sharp_angle are the curves that
/// stay. The mesh keeps its topology (CGAL's link condition) and, with
/// bounded_normal_change, folds no facet over; where the collapse brought
/// facets across others (the two sides of a thin part), it is run again
/// with the vertices around the crossings frozen.
DecimationResult decimate(SurfaceMesh& mesh, const std::vector<Polyline>& feature_curves, const DecimationOptions& options,
                          const Progress& progress = {});

}  // namespace sharpmesh
