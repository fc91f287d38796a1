#include "scanloc/common/output_folder.hpp"

#include <filesystem>
#include <stdexcept>

namespace scanloc {

void RefuseNonEmptyFolder(const std::string& dir, bool force) {
  namespace fs = std::filesystem;
  std::error_code error;
  const fs::file_status status = fs::status(dir, error);
  if (!fs::exists(status)) return;
  if (!fs::is_directory(status))
    throw std::runtime_error(dir + " exists and is not a folder; choose another --out");
  if (force) return;
  fs::directory_iterator entries(dir, error);
  if (error) throw std::runtime_error("cannot read the folder " + dir + ": " + error.message());
  std::size_t count = 0;
  std::string example;
  for (const fs::directory_entry& entry : entries) {
    if (count++ == 0) example = entry.path().filename().string();
  }
  if (count > 0)
    throw std::runtime_error(dir + " already exists and is not empty (" + std::to_string(count) +
                             (count == 1 ? " entry: " : " entries, e.g. ") + example +
                             "); give --force to write over it, or choose another --out");
}

void RefuseToReplace(const std::vector<std::string>& paths, bool force) {
  if (force) return;
  for (const std::string& path : paths) {
    std::error_code error;
    if (std::filesystem::exists(path, error))
      throw std::runtime_error(path + " already exists; give --force to replace it");
  }
}

}  // namespace scanloc
