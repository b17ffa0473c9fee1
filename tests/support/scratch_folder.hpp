#pragma once
// A folder of this test process' own under the system temporary folder,
// created on the first call and removed when the tests end. `name` says whose
// it is (e.g. "sartor_mesh_obj"); the process id keeps parallel runs apart.
// A process has one: later calls return the first call's folder.

#include <unistd.h>

#include <filesystem>
#include <string>
#include <system_error>

namespace sartor::test_support {

inline const std::filesystem::path& scratch_folder(const std::string& name) {
  struct Folder {
    std::filesystem::path path;
    explicit Folder(std::filesystem::path where) : path(std::move(where)) {
      std::filesystem::create_directories(path);
    }
    ~Folder() {
      std::error_code ignored;
      std::filesystem::remove_all(path, ignored);
    }
  };
  static const Folder folder(std::filesystem::temp_directory_path() /
                             (name + "_" + std::to_string(::getpid())));
  return folder.path;
}

} // namespace sartor::test_support
