// The field table of StereoReconstructionOptions (sharpmesh/option_fields.h):
// the flags of `sharpmesh stereo`, the keywords of sharpmesh.stereo, the
// "parameters" of its report.
#include "core/field_builders.h"
#include "sharpmesh/stereo_reconstruct.h"

namespace sharpmesh {
namespace {

using O = StereoReconstructionOptions;
using detail::member_field;
using detail::nested_field;

template <class Part>
void add(std::vector<OptionField<O>>& out, Part O::*part, const char* group, std::vector<OptionField<Part>> fields) {
  for (const OptionField<Part>& f : fields) out.push_back(nested_field(f, part, group));
}

std::vector<OptionField<O>> stereo_fields() {
  std::vector<OptionField<O>> f;
  using T = TrackPreprocessOptions;
  add<T>(f, &O::tracks, "Tracks (thesis 6.3.1)",
         {member_field("merge_distance", "t1: merge tracks closer than this (6.3.1)", "fraction of the tracks' half diagonal", &T::merge_distance),
          member_field("outlier_k", "k of the distance-to-neighbours 3-sigma filter (6.3.1)", "", &T::outlier_k),
          member_field("outlier_sigmas", "Remove tracks whose d_k is this many deviations above the mean (6.3.1)", "", &T::outlier_sigmas),
          member_field("outlier_relative",
                       "Compare each track's d_k with its k neighbours' (median), so regions that are only sparser are kept "
                       "(beyond the thesis; off: with the whole cloud's)",
                       "", &T::outlier_relative),
          member_field("min_cone_angle", "t2: remove tracks whose cameras span a narrower cone (6.3.1); 0: off, single-view tracks kept",
                       "radians", &T::min_cone_angle),
          member_field("cone_angle_on_fused",
                       "Apply t2 to fused depth-map points too (COLMAP fused.ply + .vis); by default they skip it, their views "
                       "being the depth maps that agree on a point",
                       "", &T::cone_angle_on_dense_points),
          member_field("smooth_k", "k of the Gaussian jet smoothing (6.3.1); 0: off", "", &T::smooth_k)});
  using P = TrackPhotoOptions;
  add<P>(f, &O::track_photo, "Tracks (thesis 6.3.1)",
         {member_field("track_photo", "Remove tracks whose image windows show no texture or disagree (beyond the thesis)", "", &P::enabled),
          member_field("track_ncc", "Lowest mean pairwise NCC of a track's windows", "", &P::min_ncc),
          member_field("track_half_window", "Half size of a track's windows", "pixels", &P::half_window),
          member_field("track_min_texture", "Lowest standard deviation of a window", "grey levels", &P::min_texture)});
  using D = DepthMapOptions;
  add<D>(f, &O::depth_maps, "Depth maps (thesis 6.3.2)",
         {member_field("canny_sigma", "Gaussian blur before Canny (6.3.2)", "pixels", &D::canny_sigma),
          member_field("canny_low", "Canny hysteresis low threshold (gradient magnitude, 8-bit scale)", "", &D::canny_low),
          member_field("canny_high", "Canny hysteresis high threshold", "", &D::canny_high),
          member_field("canny_adaptive",
                       "Scale the Canny thresholds by each image's contrast (99th-percentile gradient over 100; beyond the "
                       "thesis; off: as given)",
                       "", &D::canny_adaptive),
          member_field("contour_distance", "A track is a ctrack when it projects this close to a contour", "pixels", &D::contour_distance),
          member_field("gap_open", "o: gap opening penalty of the contour-edge score (6.3.2)", "", &D::gap_open),
          member_field("gap_extend", "e: gap extension penalty (6.3.2)", "", &D::gap_extend),
          member_field("overlap_angle", "Two contour edges at one ctrack closer than this overlap; the longer goes", "degrees",
                       &D::overlap_angle)});
  using S = SoupFilterOptions;
  add<S>(f, &O::filters, "Soup filters (thesis 6.3.2)",
         {member_field("max_crossings", "t3: remove soup triangles crossed by more lines of sight (6.3.2)", "", &S::max_crossings),
          member_field("sight_margin", "Lines of sight stop this far before their track", "average track spacings", &S::sight_margin),
          member_field("grazing_angle", "Lines of sight farther than this from a triangle's normal are grazing (6.3.2)", "degrees",
                       &S::grazing_angle),
          member_field("big_radius", "Triangles with a larger circumradius are big", "average track spacings", &S::big_radius),
          member_field("max_radius_edge", "Big triangles with a larger radius-edge ratio are removed (6.3.2)", "", &S::max_radius_edge),
          member_field("ncc", "Big regular triangles with a lower mean NCC are removed (6.3.2)", "", &S::ncc_threshold),
          member_field("photo", "The photo-consistency filter (6.3.2)", "", &S::photo_consistency),
          member_field("remove_occluded_tracks",
                       "Remove the triangles of tracks hidden behind the soup from most of their views (beyond the thesis)", "",
                       &S::remove_occluded_tracks)});
  using F = SoupFillOptions;
  add<F>(f, &O::fill, "Soup fill (beyond the thesis, 6.6)",
         {member_field("fill", "Where the soup is empty, fill it with the tracks' Poisson surface (off: the soup alone, the thesis)", "",
                       &F::enabled),
          member_field("fill_gap", "Fill only farther than this from every soup triangle", "size bounds l", &F::gap),
          member_field("fill_support", "Fill only this close to a track of the filtered soup", "average track spacings", &F::support),
          member_field("fill_bridge",
                       "Farther, fill where the soup's tracks within this many local spacings surround the facet; 0: off",
                       "local track spacings", &F::bridge),
          member_field("fill_resolution", "Protecting-ball spacing d' of the tracks' surface", "size bounds l", &F::resolution),
          member_field("fill_crossings", "Remove fill facets crossed by more lines of sight", "", &F::max_crossings)});
  using M = SoupMeshingOptions;
  add<M>(f, &O::meshing, "Meshing (thesis 6.3.3)",
         {member_field("angle", "alpha: minimum facet angle (6.2.1)", "degrees", &M::angle),
          member_field("size", "l: maximum surface Delaunay ball radius (6.5)", "fraction of the soup's half diagonal", &M::size),
          member_field("distance", "d: maximum facet-to-surface distance (6.5)", "fraction of the soup's half diagonal", &M::distance),
          member_field("initial_points", "Initial points of the refinement (centroids of random soup triangles)", "", &M::initial_points),
          member_field("seed_cells", "Also one initial point per occupied cell of a grid of seed_cell x l", "", &M::seed_cells),
          member_field("seed_cell", "Step of that grid", "size bounds l", &M::seed_cell),
          member_field("max_vertices", "Stop with an error past this many mesh vertices", "", &M::max_vertices),
          member_field("seed", "Seed of the refinement's initial points", "", &M::seed)});
  OptionField<O> hole = member_field("max_hole",
                                     "Fill the mesh's holes whose boundary is shorter than this; 0: off (beyond the thesis, its "
                                     "remedy of 6.6)",
                                     "fraction of the soup's half diagonal", &O::max_hole);
  hole.group = "Meshing (thesis 6.3.3)";
  f.push_back(hole);
  OptionField<O> manifold = member_field("manifold",
                                         "Make the mesh manifold and consistently oriented: the sheets meeting at an edge of more than "
                                         "two facets are separated (beyond the thesis)",
                                         "", &O::manifold);
  manifold.group = hole.group;
  f.push_back(manifold);
  f.push_back(member_field("threads", "Worker threads of this reconstruction (0: every core)", "", &O::threads));
  return f;
}

}  // namespace

const std::vector<OptionField<StereoReconstructionOptions>>& stereo_option_fields() {
  static const std::vector<OptionField<StereoReconstructionOptions>> fields = stereo_fields();
  return fields;
}

}  // namespace sharpmesh
