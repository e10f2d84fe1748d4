// The normals stage: CVCM normals (7.4) or estimated ones (A.7), oriented
// by the anchored tangent MST (A.8), with the orientation repairs beyond
// the thesis (patch votes, enclosed regions, crease-aware normals).
#include <algorithm>
#include <cmath>

#include "pipeline/stages.h"
#include "sharpmesh/features.h"

namespace sharpmesh::detail {
namespace {

/// CVCM normals (7.4) where the convolved VCM is anisotropic; elsewhere
/// (lambda0/lambda1 below `min_anisotropy`, 20: a fifth to a third of the
/// points of CAD models, near edges and in thin parts) a plane fit. In a wall
/// or flange thinner than the offset radius R the Voronoi cells are cut short
/// by the other side, the covariance turns isotropic and its main axis can
/// lie in the tangent plane, where the MST inverts whole flanges.
/// Those points lie next to creases, where any centred neighbourhood
/// straddles two faces and a jet normal is several degrees off. On clean to
/// moderately noisy clouds they take crease-aware normals from shifted
/// neighbourhoods instead (pointset.h), whose plane size grows with the
/// noise from 8 points when clean to 30 at 0.22 spacings (the crossovers
/// with jet normals, docs/design-notes.md, crease-aware normals). Clouds the
/// extraction had to denoise keep jet normals. Here those points get jet
/// normals, which turn smoothly enough for the MST; sharpen_normals
/// replaces them after orientation. Returns the points replaced.
std::vector<std::uint32_t> cvcm_normals(PointSet& cloud, const FeatureResult& features, const NormalEstimationOptions& estimation,
                                        double min_anisotropy) {
  cloud.normals.resize(cloud.size());
  std::vector<std::uint32_t> isotropic;
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    cloud.normals[i] = features.points[i].normal;
    if (!(features.points[i].ratio01 >= min_anisotropy)) isotropic.push_back(static_cast<std::uint32_t>(i));
  }
  NormalEstimationOptions jet = estimation;
  jet.method = NormalMethod::Jet;
  jet.k = std::min<int>(jet.k, static_cast<int>(cloud.size()) - 1);
  estimate_normals_at(cloud, isotropic, jet);
  return isotropic;
}

/// After orientation: the crease-aware normals at `ids` (see cvcm_normals),
/// each taking the sign of the oriented normal it replaces. They are not
/// oriented themselves: at a crease they turn by up to 90 degrees from one
/// point to the next and the MST loses the sign, which it keeps with the
/// smoothly turning jet normals.
/// Returns the number replaced (0 for denoised or noisier clouds).
std::size_t sharpen_normals(PointSet& oriented, const std::vector<std::uint32_t>& ids, const FeatureResult& features,
                            double max_noise) {
  const int last = static_cast<int>(oriented.size()) - 1;
  const double noise = features.average_spacing > 0 ? features.noise_estimate / features.average_spacing : 1.0;
  if (features.denoise_passes > 0 || !(noise < max_noise) || ids.empty()) return 0;
  ShiftedNormalOptions options;
  options.k = std::min(last, static_cast<int>(std::lround(std::clamp(8 + 100 * noise, 8.0, 30.0))));
  options.candidates = std::min(last, std::max(18, 3 * options.k / 2));
  estimate_shifted_normals_at(oriented, ids, options);  // signed like the oriented jet normals
  return ids.size();
}

}  // namespace

/// Signs for the tangent MST to grow from (exterior_votes.cpp), so that no
/// knife edge (a conical roof's rim) inverts the face behind it: the sheet
/// parity where it decides (thin plates and bars included), else the
/// occupancy (cells of one spacing resolve thin roofs; where a sparse
/// random sampling's gaps let the outside in, cells of 1.5 spacings still
/// wall it off); none where the two disagree. Then only the
/// votes their same-sheet neighbours confirm (vote_consensus.cpp). All zero
/// on open clouds.
std::vector<signed char> occupancy_anchors(const PointSet& cloud, double average_spacing, double noise, int k) {
  std::vector<signed char> occupancy;
  // The free cells must lie within a sheet's own band (its cell, one of
  // dilation and the noise): a line that crosses more occupied cells on
  // one side has crossed another sheet there, as from the inner face of a
  // hollow part's wall thinner than four cells, whose outside lies beyond
  // the outer face; the sheet parity decides those.
  for (double cell : {average_spacing, 1.5 * average_spacing}) {
    occupancy = exterior_side_votes(cloud, cell, 2.5 * cell + 4 * noise);
    if (std::any_of(occupancy.begin(), occupancy.end(), [](signed char v) { return v != 0; })) break;
  }
  std::vector<signed char> votes = sheet_parity_votes(cloud, average_spacing, noise);
  for (std::size_t i = 0; i < votes.size(); ++i) {
    if (votes[i] == 0) votes[i] = occupancy[i];
    else if (occupancy[i] != 0 && occupancy[i] != votes[i]) votes[i] = 0;
  }
  return neighbour_confirmed_votes(cloud, votes, k);
}

PointSet oriented_normals(const PipelineInput& in, bool from_cvcm, ReconstructResult& result) {
  const ReconstructOptions& options = in.options;
  PointSet oriented = in.points;
  std::vector<std::uint32_t> isotropic;
  if (from_cvcm) {
    // Automatic normals replace the isotropic CVCM ones; --normals cvcm is the thesis's 7.4 throughout.
    const double min_anisotropy = options.normal_source == NormalSource::Automatic ? options.tuning.min_cvcm_anisotropy : 0.0;
    isotropic = cvcm_normals(oriented, result.features, options.normals, min_anisotropy);
    result.normals.isotropic_cvcm_normals = isotropic.size();
  } else {
    estimate_normals(oriented, options.normals, in.progress);
  }
  const bool automatic = options.normal_source == NormalSource::Automatic && options.feature_mode == FeatureMode::Extract;
  // Tangent-aware MST (orientation.cpp): no flips across thin walls.
  // Automatic normals: anchored by the occupancy (occupancy_anchors).
  std::vector<signed char> anchors;
  if (automatic && options.anchor_orientation) {
    anchors = occupancy_anchors(oriented, result.average_spacing, result.features.noise_estimate, options.orientation.k);
    result.normals.anchored_normals = static_cast<std::size_t>(std::count_if(anchors.begin(), anchors.end(), [](signed char v) { return v != 0; }));
  }
  orient_normals_tangent_mst(oriented, options.orientation.k, anchors, in.progress);
  // The crease points' jet normals carried the MST across the creases;
  // the anisotropic CVCM normals vote on it (patch_orientation.cpp).
  if (from_cvcm && automatic)
    result.normals.patch_flipped_normals =
        repair_inverted_patches(oriented, isotropic, result.average_spacing, options.orientation.k, anchors);
  // Regions the rest of the surface encloses on their outer side
  // (enclosed_orientation.cpp); not on the PIF baseline (--no-features).
  if (automatic && options.repair_enclosed_normals)
    result.normals.enclosed_flipped_normals = repair_enclosed_normals(oriented, result.average_spacing);
  if (from_cvcm && automatic) result.normals.sharpened_normals = sharpen_normals(oriented, isotropic, result.features, options.tuning.sharpen_max_noise);
  return oriented;
}

}  // namespace sharpmesh::detail
