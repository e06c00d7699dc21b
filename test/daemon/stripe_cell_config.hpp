#pragma once
// A rangefitd configuration of one simulated stripe cell for the object-service tests: the cell
// scans data/scenes/<scene> at time_scale 0 (sim seed 2), the object model data/models/<model> is
// copied beside the configuration and named in [[objects]], the tests' loopback DDS domain,
// spooling below `dir`. `extra` is TOML appended at the end (e.g. a [frames] table).
#include <filesystem>
#include <fstream>
#include <string>

#include "test/daemon/dds_test_env.hpp"

namespace rangefit::test {

inline std::filesystem::path write_stripe_cell_config(const std::filesystem::path& dir,
                                                      const std::string& scene,
                                                      const std::string& model,
                                                      bool pictures = true,
                                                      const std::string& extra = "") {
  const std::filesystem::path data = std::filesystem::path(RANGEFIT_SOURCE_DIR) / "data";
  std::filesystem::copy_file(data / "models" / model, dir / model);
  const std::filesystem::path config = dir / "rangefitd.toml";
  std::ofstream(config) << "[service]\nobject_sensor = \"stripe\"\n[dds]\ndomain_id = "
                        << dds_test_domain() << "\n[spool]\ndirectory = \""
                        << (dir / "spool").string() << "\"\n"
                        << (pictures ? "" : "pictures = false\n")
                        << "[sim]\ntime_scale = 0\nseed = 2\n"
                        << "[[devices]]\nname = \"stripe\"\nkind = \"stripe\"\nscene = \""
                        << (data / "scenes" / scene).string() << "\"\n"
                        << "[[objects]]\nmodel = \"" << model << "\"\n"
                        << extra;
  return config;
}

}  // namespace rangefit::test
