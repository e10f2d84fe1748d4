// The JSON reports of the pipelines, written once here for the command
// line's --report and Python's `report`: the option values under
// "parameters" come from the option-field tables (sharpmesh/option_fields.h),
// lengths are given in data units and as fractions of the input's diagonal.
#pragma once

#include <string>

#include "sharpmesh/compact.h"
#include "sharpmesh/features.h"
#include "sharpmesh/reconstruct.h"
#include "sharpmesh/stereo.h"
#include "sharpmesh/stereo_reconstruct.h"

namespace sharpmesh {

/// `sharpmesh reconstruct --report` without the command line's own keys
/// (command, input, output, seconds; its stage list adds read and write).
std::string reconstruct_report_json(const ReconstructResult& result, const ReconstructOptions& options);

/// reconstruct_normals(): the parameters, the normals stage's counts, the
/// features when extracted, the stages.
std::string normals_report_json(const NormalsResult& result, const ReconstructOptions& options);

/// `sharpmesh features --report` without the command line's own keys.
std::string feature_report_json(const FeatureResult& result, const FeatureOptions& options, double diagonal);

/// The counts of decimate() as `sharpmesh decimate --report` gives them (and
/// reconstruct's report under "decimation").
std::string decimation_report_json(const DecimationResult& result);

/// `sharpmesh stereo --report` without the command line's own keys; `model`
/// as reconstruct_stereo left it (its kept tracks).
std::string stereo_report_json(const StereoReconstruction& result, const StereoReconstructionOptions& options, const StereoModel& model);

}  // namespace sharpmesh
