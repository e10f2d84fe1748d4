// The option-field tables: each field reads and writes its own member and
// no other, names are unique, and values are checked on the way in.
#include <gtest/gtest.h>

#include <set>

#include "sharpmesh/features.h"
#include "sharpmesh/option_fields.h"
#include "sharpmesh/reconstruct.h"

namespace sharpmesh {
namespace {

// A value of the field's kind that differs from `current`.
FieldValue another_value(const OptionField<ReconstructOptions>& field, const FieldValue& current) {
  if (const bool* b = std::get_if<bool>(&current)) return !*b;
  if (const std::int64_t* i = std::get_if<std::int64_t>(&current)) return *i + 3;
  if (const double* d = std::get_if<double>(&current)) return *d + 0.25;
  for (const std::string& choice : field.choices)
    if (choice != std::get<std::string>(current)) return choice;
  return std::get<std::string>(current) + "x";
}

TEST(OptionFields, EachFieldWritesItsOwnMemberOnly) {
  const auto& fields = reconstruct_option_fields();
  const ReconstructOptions defaults;
  for (const auto& field : fields) {
    ReconstructOptions changed;
    const FieldValue value = another_value(field, field.get(defaults));
    field.set(changed, value);
    EXPECT_EQ(field.get(changed), value) << field.name;
    for (const auto& other : fields) {
      if (other.name != field.name) {
        EXPECT_EQ(other.get(changed), other.get(defaults)) << field.name << " changed " << other.name;
      }
    }
  }
}

TEST(OptionFields, NamesAreUniqueAndEveryFieldHasHelp) {
  std::set<std::string> names;
  for (const auto& field : reconstruct_option_fields()) {
    EXPECT_TRUE(names.insert(field.name).second) << field.name;
    EXPECT_FALSE(field.help.empty()) << field.name;
    EXPECT_EQ(field.name.rfind("no_", 0), std::string::npos) << field.name << ": names are positive";
  }
  // The feature table is part of the reconstruction's.
  for (const auto& field : feature_option_fields()) EXPECT_EQ(names.count(field.name), 1u) << field.name;
}

TEST(OptionFields, ValuesAreCheckedOnTheWayIn) {
  ReconstructOptions o;
  const auto& fields = reconstruct_option_fields();
  find_field(fields, "delta").set(o, std::int64_t{5});  // an integer is a real without loss
  EXPECT_EQ(o.delta, 5.0);
  find_field(fields, "spacing_k").set(o, 8.0);  // and an integral real an integer
  EXPECT_EQ(o.spacing_k, 8);
  EXPECT_THROW(find_field(fields, "spacing_k").set(o, 8.5), InvalidArgument);
  EXPECT_THROW(find_field(fields, "seed").set(o, std::int64_t{-1}), InvalidArgument);
  EXPECT_THROW(find_field(fields, "seed").set(o, std::int64_t{1} << 40), InvalidArgument);
  EXPECT_THROW(find_field(fields, "snapping").set(o, std::int64_t{1}), InvalidArgument);
  EXPECT_THROW(find_field(fields, "normals").set(o, std::string("hough")), InvalidArgument);
  EXPECT_THROW(find_field(fields, "no_snapping"), InvalidArgument);
  find_field(fields, "normals").set(o, std::string("pca"));
  EXPECT_EQ(o.normal_source, NormalSource::Estimated);
  EXPECT_EQ(o.normals.method, NormalMethod::Pca);
  EXPECT_EQ(find_field(fields, "normals").get(o), FieldValue(std::string("pca")));
}

}  // namespace
}  // namespace sharpmesh
