#include "sharpmesh/option_fields.h"

namespace sharpmesh {

std::string format_field_value(const FieldValue& value) {
  if (const bool* b = std::get_if<bool>(&value)) return *b ? "true" : "false";
  if (const std::int64_t* i = std::get_if<std::int64_t>(&value)) return std::to_string(*i);
  if (const double* d = std::get_if<double>(&value)) return format_number(*d);
  return std::get<std::string>(value);
}

}  // namespace sharpmesh
