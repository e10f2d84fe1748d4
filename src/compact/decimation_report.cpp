// The counts of a decimation (sharpmesh/report.h), written once for
// `sharpmesh decimate --report`, reconstruct's "decimation" section and
// Python's decimate().
#include <nlohmann/json.hpp>

#include "sharpmesh/compact.h"
#include "sharpmesh/report.h"

namespace sharpmesh {
namespace detail {

nlohmann::json decimation_report(const DecimationResult& r) {
  return {{"input_facets", r.input_facets},       {"output_facets", r.output_facets},
          {"collapsed_edges", r.collapsed_edges}, {"sharp_edges", r.feature_edges},
          {"corner_vertices", r.corner_vertices}, {"budget_missed", r.budget_missed},
          {"rounds", r.rounds},                   {"frozen_vertices", r.frozen_vertices},
          {"crossing_pairs", r.crossing_pairs}};
}

}  // namespace detail

std::string decimation_report_json(const DecimationResult& result) { return detail::decimation_report(result).dump(); }

}  // namespace sharpmesh
