// Progress and cancellation through one callback, as CGAL does: the callback
// receives a stage name and a fraction in [0, 1] and returns false to cancel.
#pragma once

#include <functional>
#include <string>

namespace sharpmesh {

using Progress = std::function<bool(const std::string& stage, double fraction)>;

/// Calls `progress` if set; throws Cancelled when it returns false.
void report_progress(const Progress& progress, const std::string& stage, double fraction);

}  // namespace sharpmesh
