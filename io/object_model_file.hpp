#pragma once
// Object model files (TOML) for the superquadric object detector (thesis ch. 5):
//
//   name = "mallet"
//   [[part]]
//   name = "head"
//   size = [30.0, 30.0, 56.0]   # a1 a2 a3, mm
//   shape = [0.1, 1.0]          # eps1 eps2, each in [0.1, 2]
//   taper = [0.0, 0.0]          # kx ky in [-1, 1], optional (default 0)
//   [[link]]                    # compound models only
//   parts = ["head", "shaft"]
//   angle_deg = 90.0            # angle between the two z-axes
//   distance = 170.0            # distance between the two centres, mm
//
// Every problem throws io::IoError ("<file>:<line>: field '<field>': <problem>"); unknown keys
// are errors.

#include <filesystem>
#include <string>
#include <string_view>

#include "detect/object/object_model.hpp"

namespace rangefit::io {

ObjectModel read_object_model(const std::filesystem::path& path);

// Parses text; `source` only names the file in error messages.
ObjectModel parse_object_model(std::string_view text, const std::filesystem::path& source);

// TOML text that parse_object_model reads back to the same model.
std::string format_object_model(const ObjectModel& model);

// Writes the model to `path` ("-": standard output) as format_object_model does, preceded by
// `comment` as "# " lines (how the model was learnt: residual, visible share; readers skip
// them). The file is written beside its destination and renamed over it, so a reader never sees
// half a model. Throws IoError when the model would not read back (no parts, an invalid part,
// a link to a missing part, a name with quotes, backslashes or control characters) or the file
// cannot be written.
void write_object_model(const std::filesystem::path& path, const ObjectModel& model,
                        std::string_view comment = {});

}  // namespace rangefit::io
