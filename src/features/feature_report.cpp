// The report of the feature extraction (sharpmesh/report.h).
#include "core/field_json.h"
#include "sharpmesh/report.h"

namespace sharpmesh {
namespace detail {

const char* junction_name(JunctionType type) {
  return type == JunctionType::Dart ? "dart" : type == JunctionType::Cusp ? "cusp" : "corner";
}

nlohmann::json feature_report(const FeatureResult& r, const FeatureOptions& o, double diagonal) {
  nlohmann::json junctions = nlohmann::json::array();
  std::size_t counts[3] = {0, 0, 0};
  for (const Junction& j : r.graph.junctions) {
    junctions.push_back({{"position", j.position}, {"type", junction_name(j.type)}, {"degree", j.degree}});
    ++counts[static_cast<int>(j.type)];
  }
  std::size_t closed = 0;
  for (const Polyline& p : r.graph.polylines) closed += p.size() > 2 && p.front() == p.back();
  return {{"parameters", options_json(o, feature_option_fields())},
          {"derived",
           {{"R", length_json(r.offset_radius, diagonal)}, {"r", length_json(r.convolution_radius, diagonal)},
            {"noise_estimate", length_json(r.noise_estimate, diagonal)},
            {"average_spacing", length_json(r.average_spacing, diagonal)}, {"denoise_k", r.denoise_k},
            {"denoise_passes", r.denoise_passes}}},
          {"counts",
           {{"points", r.points.size()}, {"edge_points", r.edge_points}, {"corner_points", r.corner_points},
            {"fitted_corner_points", r.fitted_corner_points}, {"unsharpened_edge_points", r.unsharpened_edge_points},
            {"clusters", r.clusters}, {"pruned_clusters", r.pruned_clusters}, {"off_data_polylines", r.off_data_polylines},
            {"polylines", r.graph.polylines.size()}, {"closed_polylines", closed}, {"darts", counts[0]}, {"cusps", counts[1]},
            {"corners", counts[2]}}},
          {"junctions", junctions},
          {"stages", stages_json(r.stages)}};
}

}  // namespace detail

std::string feature_report_json(const FeatureResult& result, const FeatureOptions& options, double diagonal) {
  return detail::feature_report(result, options, diagonal).dump();
}

}  // namespace sharpmesh
