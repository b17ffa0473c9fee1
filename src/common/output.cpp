#include "common/output.hpp"

#include "common/error.hpp"

#include <nlohmann/json.hpp>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <system_error>
#include <unistd.h>

namespace sartor {

void make_output_directory(const std::string& directory) {
  std::error_code error;
  std::filesystem::create_directories(directory, error);
  if (error) throw InputError(directory + ": cannot create output folder: " + error.message());
}

void write_file_atomically(const std::string& path, const std::string& content) {
  const std::string temporary = path + ".tmp." + std::to_string(::getpid());
  {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    out << content;
    out.flush();
    if (!out) {
      std::remove(temporary.c_str());
      throw InputError(path + ": cannot write file");
    }
  }
  std::error_code error;
  std::filesystem::rename(temporary, path, error);
  if (error) {
    std::remove(temporary.c_str());
    throw InputError(path + ": cannot write file: " + error.message());
  }
}

void write_json(const std::string& path, const nlohmann::json& value) {
  // Text from inputs (a fabric's or a file's name) need not be UTF-8, which
  // JSON requires: an invalid byte is written as U+FFFD rather than failing.
  write_file_atomically(path,
                        value.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n");
}

} // namespace sartor
