// The cache's content hash (io/content_hash.hpp) against XXH3-128 digests printed by xxHash's
// own command, `xxhsum -H2 FILE` (Debian package xxhash 0.8.1), for inputs at the edges of
// XXH3's size classes (0-16, 17-128, 129-240 bytes, then 64-byte stripes in 1024-byte blocks),
// and the same digest however the bytes are split.
#include "io/content_hash.hpp"

#include <gtest/gtest.h>

#include <string>

namespace fleetmerge {
namespace {

TEST(ContentHash, MatchesXxhsum) {
  EXPECT_EQ(ToHex(ContentHashOf("")), "99aa06d3014798d86001c324468d497f");
  EXPECT_EQ(ToHex(ContentHashOf("abc")), "06b05ab6733a618578af5f94892f3950");
  EXPECT_EQ(ToHex(ContentHashOf(std::string(16, 'a'))), "ff9f5054066830d0245750ddc4828d15");
  EXPECT_EQ(ToHex(ContentHashOf(std::string(17, 'a'))), "c77749c0e343aac52d27c0235c9dd6e1");
  EXPECT_EQ(ToHex(ContentHashOf(std::string(128, 'a'))), "134e2a91815f3105ef354c1b9e35d99d");
  EXPECT_EQ(ToHex(ContentHashOf(std::string(129, 'a'))), "a7758bdd09a0b20fd53a57a017f40a2f");
  EXPECT_EQ(ToHex(ContentHashOf(std::string(240, 'a'))), "0163721cdafde206ea57d24533760a39");
  EXPECT_EQ(ToHex(ContentHashOf(std::string(241, 'a'))), "3e7bebe4a2c07b0bf6cfef5c5aca1930");
  EXPECT_EQ(ToHex(ContentHashOf(std::string(1024, 'a'))), "52628c92ccb242754a5d6b09a9587a1c");
  EXPECT_EQ(ToHex(ContentHashOf(std::string(1000000, 'a'))), "a545df8e384a9579b1fd6fae5285c4eb");
}

TEST(ContentHash, TheSameDigestForAnySplitOfTheBytes) {
  std::string bytes;
  for (int i = 0; i < 5000; ++i) bytes += static_cast<char>(i * 37 + 11);
  const ContentDigest whole = ContentHashOf(bytes);
  for (const std::size_t piece : {1u, 3u, 63u, 64u, 65u, 200u, 1024u, 4999u}) {
    ContentHash hash;
    for (std::size_t at = 0; at < bytes.size(); at += piece) {
      hash.Update(bytes.substr(at, piece));
    }
    EXPECT_EQ(hash.Finish(), whole) << "pieces of " << piece;
  }
  bytes[2500] ^= 1;
  EXPECT_NE(ContentHashOf(bytes), whole);
}

}  // namespace
}  // namespace fleetmerge
