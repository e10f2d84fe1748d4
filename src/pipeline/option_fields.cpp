// The field table of ReconstructOptions (sharpmesh/option_fields.h): the
// flags of `sharpmesh reconstruct`, the keywords and the option class of
// sharpmesh.reconstruct, the "parameters" of its report.
#include "core/field_builders.h"
#include "sharpmesh/reconstruct.h"

namespace sharpmesh {
namespace {

using O = ReconstructOptions;

// NormalSource and NormalMethod as the one text option the user sees.
OptionField<O> normals_field() {
  OptionField<O> f;
  f.name = "normals";
  f.help =
      "Normals when the input has none: auto (with features: CVCM, 7.4; where the CVCM is isotropic, jet normals for the "
      "orientation, then crease-aware plane fits on clean clouds; else jet), cvcm (7.4 throughout), jet or pca (App. A.7)";
  f.choices = {"auto", "cvcm", "jet", "pca"};
  f.get = [](const O& o) -> FieldValue {
    if (o.normal_source == NormalSource::Automatic) return std::string("auto");
    if (o.normal_source == NormalSource::Cvcm) return std::string("cvcm");
    return std::string(o.normals.method == NormalMethod::Pca ? "pca" : "jet");
  };
  f.set = [](O& o, const FieldValue& v) {
    const std::string name = detail::from_field_value<std::string>(v, "normals");
    if (name == "auto") {
      o.normal_source = NormalSource::Automatic;
    } else if (name == "cvcm") {
      o.normal_source = NormalSource::Cvcm;
    } else if (name == "jet" || name == "pca") {
      o.normal_source = NormalSource::Estimated;
      o.normals.method = name == "pca" ? NormalMethod::Pca : NormalMethod::Jet;
    } else {
      throw InvalidArgument("option normals takes auto, cvcm, jet or pca (got " + name + ")");
    }
  };
  return f;
}

// The thresholds of the repairs (ReconstructTuning).
std::vector<OptionField<ReconstructTuning>> tuning_fields() {
  using detail::member_field;
  using T = ReconstructTuning;
  return {
      member_field("min_cvcm_anisotropy", "Automatic normals: a CVCM less anisotropic than this (largest over next eigenvalue) takes a jet normal",
                   "", &T::min_cvcm_anisotropy),
      member_field("min_normal_agreement", "Automatic normals: solve again from jet normals when Poisson agrees with fewer CVCM normals",
                   "fraction", &T::min_normal_agreement),
      member_field("input_normal_consensus", "Input normals agreeing in sign with an MST orientation on this share (or 1 - it) are used as given",
                   "fraction", &T::input_normal_consensus),
      member_field("sharpen_max_noise", "Crease-aware normals only on clouds less noisy than this", "average spacings", &T::sharpen_max_noise),
      member_field("noise_deviations", "Noise deviations allowed wherever a distance decides (data fit, snapping)", "", &T::noise_deviations),
      member_field("off_data_min", "A point is off the mesh beyond max(this, 0.6 d') + the noise allowance", "average spacings",
                   &T::off_data_min),
      member_field("repair_min_points", "The sign repair and the data-fit retry solve again for at least this many points", "",
                   &T::repair_min_points),
      member_field("repair_one_point_in", "Or one point in this many, when that is more", "", &T::repair_one_point_in),
      member_field("retry_reach", "Data-fit retry: also flip the points off the mesh this close to those against it", "average spacings",
                   &T::retry_reach),
      member_field("flatten_radius", "Flattening: fit face planes within min(ball radius, this)", "average spacings", &T::flatten_radius),
      member_field("flatten_max_move", "Flattening: move a vertex at most min(this x d', flatten_max_move_spacings)", "d'",
                   &T::flatten_max_move),
      member_field("flatten_max_move_spacings", "Flattening: the cap of a move in spacings", "average spacings", &T::flatten_max_move_spacings),
      member_field("flatten_max_residual", "Flattening: only onto planes fitting the data this closely", "d'", &T::flatten_max_residual),
      member_field("snap_max_move", "Snapping: move a vertex at most this + the noise allowance", "average spacings", &T::snap_max_move),
      member_field("snap_corner_distance", "Snapping: corners the mesh misses by more than this + the noise allowance take a vertex",
                   "average spacings", &T::snap_corner_distance),
      member_field("snap_data_distance", "Snapping: data points the mesh misses by more than this + the noise allowance take a vertex",
                   "average spacings", &T::snap_data_distance),
      member_field("snap_support_radius", "Snapping: a move may not take facets away from the points within this radius",
                   "average spacings", &T::snap_support_radius),
      member_field("thin_solid_max", "Thin shells: remove a separate closed solid thinner than this (or the noise allowance, when more)",
                   "average spacings", &T::thin_solid_max),
      member_field("thin_cavity_max", "Thin shells: remove a separate closed cavity (a bridged gap's air) thinner than this (or the noise allowance)",
                   "average spacings", &T::thin_cavity_max)};
}

std::vector<OptionField<O>> reconstruct_fields() {
  using detail::member_field;
  using detail::nested_field;
  std::vector<OptionField<O>> f = {
      member_field("delta", "Mesh size d' = delta x average spacing; facet angle 25 deg, edges <= 2d', distance <= 0.6d' (7.3.2)",
                   "average spacings", &O::delta),
      member_field("spacing_k", "The average spacing is the mean distance to this many nearest neighbours (7.3.2)", "", &O::spacing_k),
      member_field("average_spacing", "The average spacing when known (the tiles of one cloud share their whole cloud's; 0: measured)",
                   "data units", &O::average_spacing),
      member_field("ball_radius", "Protecting-ball radius (7.3.2)", "fraction of d'", &O::ball_radius),
      member_field("ball_growth", "Grow each protecting ball to reach the implicit surface (beyond the thesis; off: every ball at ball_radius)",
                   "", &O::adapt_balls_to_gap),
      member_field("trim",
                   "Remove facets farther than trim x d' + 2 avg from every input point, so open scans give open meshes (0: keep "
                   "the closed Poisson surface)",
                   "d'", &O::trim_distance),
      member_field("clip_boundary", "After the trim, cut the facets that overhang the data at the boundary about one spacing from it",
                   "", &O::clip_boundary),
      member_field("poisson_spacing", "Solve Poisson on a grid simplification with cells of this size (0: on every point)", "d'",
                   &O::poisson_spacing),
      member_field("poisson_thinning",
                   "Leave out of Poisson the points closer than this to an earlier point (0: keep all); near-coincident pairs "
                   "cost most of Poisson's time",
                   "average spacings", &O::poisson_thinning),
      member_field("poisson_screening",
                   "Pull of Poisson's function towards the points relative to its smoothness, lengths in average spacings: the "
                   "same surface in any unit (0: CGAL's own weight, which depends on the unit)",
                   "", &O::poisson_screening),
      member_field("poisson_screening_noisy", "The same on clouds the feature extraction finds noisy (denoised, or noise of 0.05 avg or more)",
                   "", &O::poisson_screening_noisy),
      member_field("seed_spacing",
                   "Before refinement, project one input point per cell of this size onto the implicit surface as a mesh "
                   "vertex, so parts thinner than the facets are not stepped over (0: none)",
                   "d'", &O::data_seed_spacing),
      member_field("flattening",
                   "Move the third vertices of the facets along protected edges onto the data's face planes (beyond the "
                   "thesis; off: they stay on the Poisson surface)",
                   "", &O::flatten_features),
      member_field("snapping",
                   "Move vertices onto the corners and data points the mesh misses (beyond the thesis; with extracted features "
                   "only; distances: --snap-*)",
                   "", &O::snap_vertices),
      member_field("intersection_repair",
                   "Cut the facets that cross others out with a ring of neighbours and fill the holes (beyond the thesis)", "",
                   &O::repair_self_intersections),
      normals_field(),
      nested_field(member_field("normal_k", "Neighbours for jet/pca normal estimation (App. A.7)", "", &NormalEstimationOptions::k),
                   &O::normals),
      nested_field(member_field("orient_k", "Neighbours for MST normal orientation (App. A.8)", "", &NormalOrientationOptions::k),
                   &O::orientation),
      member_field("recompute_normals", "Ignore the input's normals and estimate new ones", "", &O::recompute_normals),
      member_field("input_normal_check",
                   "Compare the input's normals with an MST orientation and re-orient them when their signs disagree (off: "
                   "their signs come from elsewhere, e.g. the cameras, and are used as given)",
                   "", &O::check_input_normals),
      member_field("sign_repair",
                   "Flip the normals the Poisson function contradicts and solve again, up to 3 times (beyond the thesis)", "",
                   &O::repair_normal_signs),
      member_field("winding_repair",
                   "Flip the regions whose outer side the rest of the cloud encloses, by its generalized winding number, before "
                   "Poisson (beyond the thesis; automatic normals with features only)",
                   "", &O::repair_enclosed_normals),
      member_field("orientation_anchors",
                   "Grow the normal orientation's MST from the signs the cloud's occupancy and sheet parity decide, not from "
                   "one seed per component (beyond the thesis; automatic normals with features only)",
                   "", &O::anchor_orientation),
      member_field("thin_vertices",
                   "Add Poisson vertices half-way across parts and gaps 1-6 avg thick, so the function is not flat inside a thin "
                   "plate (beyond the thesis)",
                   "", &O::thin_part_vertices),
      member_field("data_fit_retry",
                   "When input points lie off the mesh with normals against it, flip their normals, solve and mesh again, and "
                   "keep the new mesh when it leaves a quarter fewer such points, no more in all and none farther (beyond the "
                   "thesis)",
                   "", &O::refit_off_data),
      member_field("max_facets", "Refuse to start when the estimated facet count is above this (0: no limit)", "", &O::max_facets),
      member_field("protection_budget",
                   "Ball-size queries CGAL's protection may make per polyline point; past them the surface is meshed without "
                   "it and the report says so (0: no limit)",
                   "", &O::protection_budget),
      member_field("seed", "Seed of the refinement's initial points", "", &O::seed),
      member_field("threads", "Worker threads of this reconstruction (0: every core)", "", &O::threads),
  };
  for (const OptionField<FeatureOptions>& feature : feature_option_fields()) f.push_back(nested_field(feature, &O::features));
  for (const OptionField<WallOptions>& field : wall_option_fields()) f.push_back(nested_field(field, &O::walls));
  for (const OptionField<DecimationOptions>& field : decimation_option_fields())
    f.push_back(nested_field(field, &O::compaction, "Compaction (beyond the thesis)"));
  for (const OptionField<ReconstructTuning>& field : tuning_option_fields())
    f.push_back(nested_field(field, &O::tuning, "Tuning of the repairs (beyond the thesis)"));
  return f;
}

}  // namespace

const std::vector<OptionField<ReconstructTuning>>& tuning_option_fields() {
  static const std::vector<OptionField<ReconstructTuning>> fields = tuning_fields();
  return fields;
}

const std::vector<OptionField<ReconstructOptions>>& reconstruct_option_fields() {
  static const std::vector<OptionField<ReconstructOptions>> fields = reconstruct_fields();
  return fields;
}

}  // namespace sharpmesh
