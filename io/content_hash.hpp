// The re-run cache's content hash (pipeline/pair_cache.hpp, io/cache_folder.hpp): XXH3-128 of
// xxHash (Debian's libxxhash-dev, compiled in from its header, so no library is loaded at
// start-up). Entries are named by the hash of everything they depend on (maps' cells, options,
// version) and carry one of their own bytes. 128 bits make an accidental match of two different
// maps as unlikely as with a cryptographic hash (a collision is expected only after ~2^64
// contents); the cache guards against accidents (truncated, corrupt, stale or foreign files),
// not against someone who can write into its folder, who could write any entry anyway.
// It hashes a job's maps about 100 times as fast as SHA-256 did (fleet_benchmark's BM_MapDigest;
// docs/speed.md).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>

namespace fleetmerge {

// Big-endian, as `xxhsum -H2` prints it.
using ContentDigest = std::array<std::uint8_t, 16>;

class ContentHash {
 public:
  ContentHash();
  ~ContentHash();
  ContentHash(const ContentHash&) = delete;
  ContentHash& operator=(const ContentHash&) = delete;

  void Update(const void* data, std::size_t size);
  void Update(const std::string& bytes) { Update(bytes.data(), bytes.size()); }
  // The digest of everything given to Update so far.
  ContentDigest Finish() const;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

ContentDigest ContentHashOf(const std::string& bytes);

// 32 lower-case hexadecimal digits.
std::string ToHex(const ContentDigest& digest);

}  // namespace fleetmerge
