#pragma once
// A checksum of bytes: checkpoints' /checksum (fem/checkpoint.cpp) and the
// digest of the pattern a drape was made from (`sartor edit DRAPE_DIR`).

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace sartor {

// FNV-1a over bytes: each byte is xor-ed into the state, which is then
// multiplied by an odd number (a bijection modulo 2^64), so a change of any
// one byte, a flipped bit included, always changes the sum.
class Checksum {
public:
  void add(const void* data, std::size_t size) {
    const auto* bytes = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < size; ++i) {
      state_ ^= bytes[i];
      state_ *= 0x100000001b3ULL;
    }
  }
  void add(double value) { add(&value, sizeof value); }
  void add(const std::vector<double>& values) {
    const std::uint64_t count = values.size();
    add(&count, sizeof count);
    add(values.data(), values.size() * sizeof(double));
  }
  std::uint64_t value() const { return state_; }

private:
  std::uint64_t state_ = 0xcbf29ce484222325ULL;
};

// The checksum of a file's bytes as 16 hexadecimal digits. Throws
// InputError naming the file when it cannot be read.
std::string file_checksum(const std::string& path);

} // namespace sartor
