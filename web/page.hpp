#pragma once
// rangefitd's browser page, compiled in (web/CMakeLists.txt): live state and diagnostics, the
// last results with their pictures, a 3D view of the last scan with the fitted models
// (three.js), and a form for bore and object requests. It talks to the HTTP interface only.

#include <string>
#include <string_view>
#include <vector>

namespace rangefit::web {

struct PageFile {
  std::string path;       // as served: "/index.html", "/app.js", ...
  std::string type;       // Content-Type
  std::string_view body;  // static storage
};

const std::vector<PageFile>& page_files();
// False when the build had no npm: page_files() is then one note saying so.
bool page_built();

}  // namespace rangefit::web
