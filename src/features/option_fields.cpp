// The field table of FeatureOptions (sharpmesh/option_fields.h): the flags of
// `sharpmesh features` and `reconstruct`, the keywords of extract_features().
#include "core/field_builders.h"
#include "sharpmesh/features.h"

namespace sharpmesh {

const std::vector<OptionField<FeatureOptions>>& feature_option_fields() {
  using detail::member_field;
  using O = FeatureOptions;
  static const std::vector<OptionField<O>> fields = [] {
    std::vector<OptionField<O>> f = {
        member_field("offset_radius", "Voronoi offset radius R (7.2.1)", "fraction of the bounding-sphere radius", &O::offset_radius),
        member_field("max_offset_radius",
                     "R at most this (beyond the thesis: a scene's bounding sphere is no measure of its buildings); -1: "
                     "automatic, 24 spacings on clouds that look airborne, no bound on objects; 0: no bound",
                     "average spacings", &O::max_offset_radius),
        member_field("convolution_radius", "Convolution radius r (7.2.1); 0: automatic, R/10 widened to 4 estimated noise deviations",
                     "fraction of R", &O::convolution_radius),
        member_field("t1", "Smooth if lambda0/lambda1 > t1 (Algorithm 1)", "", &O::t1),
        member_field("t2", "Edge if lambda1/lambda2 >= t2, else corner (Algorithm 1)", "", &O::t2),
        member_field("cluster_k", "Neighbours of rho_k for close pairs (Algorithm 2)", "", &O::cluster_k),
        member_field("cluster_angle", "theta: largest angle between edge directions and a close pair (7.2.2)", "degrees", &O::cluster_angle),
        member_field("min_cluster_size", "Clusters with fewer points are pruned (7.2.2)", "", &O::min_cluster_size),
        member_field("successor_k", "r_p = rho_k(p) of the successor procedure (7.2.3)", "", &O::successor_k),
        member_field("junction_factor", "r_junc = factor x spacing of a polyline's last four points (7.2.3)", "", &O::junction_factor),
        member_field("min_dihedral_angle",
                     "An edge point must see two surface patches at least this far apart to be kept, and moves onto their "
                     "intersection (beyond the thesis)",
                     "degrees", &O::min_dihedral_angle),
        member_field("denoise_k",
                     "Jet-smooth over k neighbours before the VCM (App. A.6); -1: automatic, when the noise exceeds half the "
                     "spacing; 0: never",
                     "", &O::denoise_k),
        member_field("fit_corner_points",
                     "Corner points (Algorithm 1) on the line of two faces 45+ degrees apart become edge points, so polylines "
                     "reach their corners (beyond the thesis; off: the thesis's Algorithm 1)",
                     "", &O::fit_corner_points),
    };
    for (OptionField<O>& field : f) field.group = "Feature detection (thesis 7.2)";
    return f;
  }();
  return fields;
}

}  // namespace sharpmesh
