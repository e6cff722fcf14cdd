// The page's own CSS and JavaScript (io/report/web/), compiled into the library from those files
// at build time (cmake/EmbedWebAssets.cmake): a page written anywhere opens offline, and the
// sources stay readable files in the repository.
//
//   std::string_view script = WebAsset("page.js");
#pragma once

#include <string>
#include <string_view>

namespace comic::io {

// The text of io/report/web/<name>. Throws comic::Error(kNotFound) for another name.
std::string_view WebAsset(const std::string& name);

}  // namespace comic::io
