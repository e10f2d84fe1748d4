// The report of the Chapter 6 pipeline (sharpmesh/report.h).
#include "core/field_json.h"
#include "sharpmesh/report.h"

namespace sharpmesh {

std::string stereo_report_json(const StereoReconstruction& r, const StereoReconstructionOptions& o, const StereoModel& model) {
  using detail::options_json;
  const TrackPreprocessStats& ts = r.tracks;
  const SoupFilterStats& fs = r.filters;
  const nlohmann::json report = {
      {"units", "lengths in data units; merge distance as a fraction of the input tracks' half diagonal (of their 1-99% extent per axis), size, distance and max_hole of "
                "the filtered soup's (derived.soup_half_diagonal)"},
      {"parameters", options_json(o, stereo_option_fields())},
      {"derived", {{"half_diagonal", ts.half_diagonal}, {"raw_half_diagonal", ts.raw_half_diagonal}, {"soup_half_diagonal", r.meshing.half_diagonal}}},
      {"counts",
       {{"views", model.cameras.size()},
        {"tracks", {{"input", ts.input}, {"far", ts.far_tracks}, {"merged", ts.merged}, {"removed_distance", ts.removed_distance},
                    {"removed_cone_angle", ts.removed_cone}, {"cone_filter_skipped_fused", ts.cone_filter_skipped},
                    {"removed_photo", r.removed_track_photo}, {"kept", model.tracks.size()}}},
        {"depth_maps", {{"contour_tracks", r.contour_tracks}, {"contour_edges", r.contour_edges}}},
        {"soup", {{"lifted", r.soup_triangles}, {"unique", r.soup_unique}, {"removed_visibility", fs.removed_visibility},
                  {"removed_grazing", fs.removed_grazing}, {"occluded_tracks", fs.occluded_tracks},
                  {"removed_occluded", fs.removed_occluded}, {"removed_anamorphic", fs.removed_anamorphic},
                  {"photo_tested", fs.photo_tested}, {"removed_photo", fs.removed_photo}, {"kept", fs.output}}},
        {"fill", {{"tracks", r.fill.tracks}, {"surface_facets", r.fill.surface_facets}, {"removed_near_soup", r.fill.removed_near_soup},
                  {"removed_far", r.fill.removed_far}, {"removed_visibility", r.fill.removed_visibility}, {"added", r.fill.added},
                  {"skipped", r.fill.skipped}}},
        {"mesh", {{"vertices", r.meshing.mesh.vertices.size()}, {"facets", r.meshing.mesh.faces.size()}, {"refinement_steps", r.meshing.steps}}},
        {"holes", {{"boundary_cycles", r.holes.holes}, {"filled", r.holes.filled}, {"added_facets", r.holes.added_facets},
                   {"unfaired", r.holes.unfaired}, {"failed", r.holes.failed}}},
        {"manifold", {{"non_manifold_edges", r.manifold.non_manifold_edges}, {"duplicated_vertices", r.manifold.duplicated_vertices},
                      {"flipped_facets", r.manifold.flipped_facets}}}}},
      {"stages", detail::stages_json(r.stages)}};
  return report.dump();
}

}  // namespace sharpmesh
