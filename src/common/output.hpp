#pragma once
// Writing results so that nothing is half-written: files appear complete or
// not at all (write to a temporary beside the target, then rename).

#include <nlohmann/json_fwd.hpp>

#include <string>

namespace sartor {

// Creates `directory` and its parents; throws InputError when it cannot.
void make_output_directory(const std::string& directory);

void write_file_atomically(const std::string& path, const std::string& content);
void write_json(const std::string& path, const nlohmann::json& value);

} // namespace sartor
