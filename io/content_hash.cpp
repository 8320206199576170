#include "io/content_hash.hpp"

#include <cstring>

// Every xxHash function static inline in this file: no libxxhash.so at run time.
#define XXH_INLINE_ALL
#include <xxhash.h>

namespace fleetmerge {
namespace {

ContentDigest Canonical(XXH128_hash_t hash) {
  XXH128_canonical_t canonical;
  XXH128_canonicalFromHash(&canonical, hash);
  ContentDigest digest;
  static_assert(sizeof canonical.digest == sizeof(ContentDigest));
  std::memcpy(digest.data(), canonical.digest, digest.size());
  return digest;
}

}  // namespace

struct ContentHash::State {
  XXH3_state_t xxh;
};

ContentHash::ContentHash() : state_(std::make_unique<State>()) { XXH3_128bits_reset(&state_->xxh); }

ContentHash::~ContentHash() = default;

void ContentHash::Update(const void* data, std::size_t size) {
  XXH3_128bits_update(&state_->xxh, data, size);
}

ContentDigest ContentHash::Finish() const { return Canonical(XXH3_128bits_digest(&state_->xxh)); }

ContentDigest ContentHashOf(const std::string& bytes) {
  return Canonical(XXH3_128bits(bytes.data(), bytes.size()));
}

std::string ToHex(const ContentDigest& digest) {
  static constexpr char kDigits[] = "0123456789abcdef";
  std::string hex;
  hex.reserve(2 * digest.size());
  for (const std::uint8_t byte : digest) {
    hex += kDigits[byte >> 4];
    hex += kDigits[byte & 15];
  }
  return hex;
}

}  // namespace fleetmerge
