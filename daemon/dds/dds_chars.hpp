#pragma once
// Cyclone's generated message structs hold strings as char*; writing a message only reads them.

#include <string>

namespace rangefit::daemon {

// The string's characters for a message field the writer only reads.
inline char* dds_chars(const std::string& s) { return const_cast<char*>(s.c_str()); }

}  // namespace rangefit::daemon
