#include "api/backend.hpp"

namespace rangefit::api {

const char* to_string(Status s) {
  switch (s) {
    case Status::kOk:
      return "ok";
    case Status::kAccepted:
      return "accepted";
    case Status::kBadRequest:
      return "bad_request";
    case Status::kForbidden:
      return "forbidden";
    case Status::kNotFound:
      return "not_found";
    case Status::kTooLarge:
      return "too_large";
    case Status::kBusy:
      return "busy";
    case Status::kTimeout:
      return "timeout";
    case Status::kError:
      return "error";
  }
  return "error";
}

int http_status(Status s) {
  switch (s) {
    case Status::kOk:
      return 200;
    case Status::kAccepted:
      return 202;
    case Status::kBadRequest:
      return 400;
    case Status::kForbidden:
      return 403;
    case Status::kNotFound:
      return 404;
    case Status::kTooLarge:
      return 413;
    case Status::kBusy:
      return 503;
    case Status::kTimeout:
      return 504;
    case Status::kError:
      return 500;
  }
  return 500;
}

Answer error_answer(Status status, const std::string& message) {
  return {status, {{"error", message}}};
}

bool token_matches(const std::string& expected, const std::string& given) {
  if (expected.empty()) return false;
  // Compare every byte whatever the first difference, so the time taken tells nothing.
  unsigned diff = expected.size() == given.size() ? 0u : 1u;
  for (std::size_t i = 0; i < expected.size(); ++i) {
    diff |= static_cast<unsigned char>(expected[i]) ^
            static_cast<unsigned char>(i < given.size() ? given[i] : 0);
  }
  return diff == 0;
}

}  // namespace rangefit::api
