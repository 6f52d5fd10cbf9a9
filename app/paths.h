// Path helpers for scene files: profile paths in a scene are relative to the scene file.
#pragma once

#include <string>

namespace railwear::app {

// The directory that holds `file` ("." when it has none).
std::string DirectoryOf(const std::string& file);
// `path` unchanged when absolute, otherwise joined to base_dir.
std::string ResolveRelativeTo(const std::string& base_dir, const std::string& path);

}  // namespace railwear::app
