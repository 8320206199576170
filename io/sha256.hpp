// SHA-256 (FIPS 180-4), written out here because the project has no cryptography dependency.
// The re-run cache (pipeline/pair_cache.hpp) names its entries by the SHA-256 of what they
// depend on (maps' cells, options, version) and checks each entry's bytes with one: a content
// hash that two different maps cannot share by accident, unlike a 32- or 64-bit checksum.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>

namespace fleetmerge {

using Sha256Digest = std::array<std::uint8_t, 32>;

class Sha256 {
 public:
  Sha256();
  void Update(const void* data, std::size_t size);
  void Update(const std::string& bytes) { Update(bytes.data(), bytes.size()); }
  // The digest of everything given to Update; the object is not to be used afterwards.
  Sha256Digest Finish();

 private:
  void Block(const std::uint8_t* block);
  std::array<std::uint32_t, 8> state_;
  std::array<std::uint8_t, 64> buffer_{};
  std::size_t buffered_ = 0;
  std::uint64_t total_bytes_ = 0;
};

Sha256Digest Sha256Of(const std::string& bytes);

// 64 lower-case hexadecimal digits.
std::string ToHex(const Sha256Digest& digest);

}  // namespace fleetmerge
