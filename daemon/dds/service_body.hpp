#pragma once
// A ROS 2 service sample as rmw_cyclonedds frames it is the call's header (the client's 64-bit
// request-writer id and the sequence number) followed by the fields of our topic type, in the
// same order and of the same types: Detect_Request_ is DetectRequest_ after the header, and
// Detect_Response_ is Detection_ after it (msg_idl_agreement_test checks the two IDL files field
// by field). Their generated C structs therefore lay the body out the same way, so the body is
// copied as one block instead of field by field, where a field added to both IDL files could be
// forgotten. A field added to one file only changes the size and fails to compile here.
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <type_traits>

namespace rangefit::daemon {

// Bytes of the call header at the start of a service sample (uint64 + int64).
inline constexpr std::size_t kServiceHeaderBytes = 16;

template <class Service, class Topic>
constexpr bool same_body() {
  return std::is_trivially_copyable_v<Service> && std::is_trivially_copyable_v<Topic> &&
         sizeof(Service) == kServiceHeaderBytes + sizeof(Topic) && alignof(Topic) <= 8 &&
         offsetof(Service, rmw_sequence_number) + sizeof(std::int64_t) == kServiceHeaderBytes;
}

// The topic sample carried by a service sample (pointers are shared, not duplicated).
template <class Topic, class Service>
Topic service_body(const Service& sample) {
  static_assert(same_body<Service, Topic>(), "service and topic types differ after the header");
  Topic body;
  std::memcpy(static_cast<void*>(&body),
              reinterpret_cast<const unsigned char*>(&sample) + kServiceHeaderBytes, sizeof body);
  return body;
}

// A service sample with the call header and the topic sample's fields (pointers shared).
template <class Service, class Topic>
Service service_sample(std::uint64_t client, std::int64_t sequence, const Topic& body) {
  static_assert(same_body<Service, Topic>(), "service and topic types differ after the header");
  Service sample{};
  sample.rmw_client_guid = client;
  sample.rmw_sequence_number = sequence;
  std::memcpy(reinterpret_cast<unsigned char*>(&sample) + kServiceHeaderBytes,
              static_cast<const void*>(&body), sizeof body);
  return sample;
}

}  // namespace rangefit::daemon
