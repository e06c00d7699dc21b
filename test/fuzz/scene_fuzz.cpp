// Scene files: a scene or a SceneError. Mesh paths resolve against a directory without meshes,
// so `type = "mesh"` exercises the error path only.
#include "sim/scene_loader.hpp"
#include "test/fuzz/fuzz_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    (void)rangefit::sim::parse_scene(rangefit::fuzz::input_text(data, size), "fuzz.toml",
                                     "/nonexistent");
  } catch (const rangefit::sim::SceneError&) {
  }
  return 0;
}
