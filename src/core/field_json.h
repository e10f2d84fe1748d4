// Option values and lengths as JSON, for the reports (sharpmesh/report.h).
#pragma once

#include <nlohmann/json.hpp>

#include <variant>
#include <vector>

#include "sharpmesh/option_fields.h"
#include "sharpmesh/timing.h"

namespace sharpmesh::detail {

inline nlohmann::json field_json(const FieldValue& value) {
  return std::visit([](const auto& v) { return nlohmann::json(v); }, value);
}

/// {name: value} for every field of the table.
template <class Options>
nlohmann::json options_json(const Options& options, const std::vector<OptionField<Options>>& fields) {
  nlohmann::json out = nlohmann::json::object();
  for (const OptionField<Options>& f : fields) out[f.name] = field_json(f.get(options));
  return out;
}

/// A length in data units and as a fraction of the diagonal.
inline nlohmann::json length_json(double value, double diagonal) {
  return {{"value", value}, {"fraction_of_diagonal", diagonal > 0 ? value / diagonal : 0.0}};
}

inline nlohmann::json stages_json(const std::vector<StageTiming>& stages) {
  nlohmann::json out = nlohmann::json::array();
  for (const StageTiming& s : stages)
    out.push_back({{"name", s.name}, {"seconds", s.seconds}, {"peak_memory_mib", s.peak_rss_bytes / (1024.0 * 1024.0)}});
  return out;
}

}  // namespace sharpmesh::detail
