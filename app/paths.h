// Path helpers: profile paths in a scene are relative to the scene file; a temporary directory
// for plot data and other intermediate files.
#pragma once

#include <filesystem>
#include <string>

namespace railwear::app {

// The directory that holds `file` ("." when it has none).
std::string DirectoryOf(const std::string& file);
// `path` unchanged when absolute, otherwise joined to base_dir.
std::string ResolveRelativeTo(const std::string& base_dir, const std::string& path);

// A new directory under the system's temp directory, named "<prefix>-XXXXXX", removed with
// everything in it when this object goes away. Throws std::runtime_error when it cannot be made.
class ScopedTempDir {
 public:
  explicit ScopedTempDir(const std::string& prefix = "railwear");
  ScopedTempDir(const ScopedTempDir&) = delete;
  ScopedTempDir& operator=(const ScopedTempDir&) = delete;
  ~ScopedTempDir();
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

}  // namespace railwear::app
