#include "daemon/service/result_outcome.hpp"

#include "daemon/service/calibrate_request.hpp"
#include "detect/bore/bore_result.hpp"
#include "detect/learn/model_learning.hpp"
#include "detect/object/object_detector.hpp"

namespace rangefit::daemon {

bool is_not_found_reason(std::string_view reason) {
  // Bad priors, models and options are the caller's error, never "not found".
  for (const BoreReason r :
       {BoreReason::kEmptyRoi, BoreReason::kDegenerateNormals, BoreReason::kNoPlane,
        BoreReason::kTooFewWallPoints, BoreReason::kFitFailed, BoreReason::kAxisParallelToPlane,
        BoreReason::kShapeFitFailed}) {
    if (reason == to_string(r)) return true;
  }
  for (const DetectReason r : {DetectReason::kEmptyCloud, DetectReason::kNoHypothesis,
                               DetectReason::kNotConfirmed, DetectReason::kNotLinked}) {
    if (reason == to_string(r)) return true;
  }
  for (const LearnReason r : {LearnReason::kEmptyCloud, LearnReason::kNoObject,
                              LearnReason::kTooFewPoints, LearnReason::kSecondPartNotSeen}) {
    if (reason == to_string(r)) return true;
  }
  // The scan did not show the calibration body well enough (calib/ says why after the prefix).
  return reason.starts_with(kNotCalibrated);
}

Outcome outcome_of(const DetectionResult& result) {
  if (result.found) return Outcome::kFound;
  return is_not_found_reason(result.reason) ? Outcome::kNotFound : Outcome::kError;
}

int exit_code_of(const DetectionResult& result) {
  switch (outcome_of(result)) {
    case Outcome::kFound:
      return 0;
    case Outcome::kNotFound:
      return 2;
    case Outcome::kError:
      return 1;
  }
  return 1;
}

}  // namespace rangefit::daemon
