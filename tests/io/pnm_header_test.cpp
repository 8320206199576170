#include "io/pnm_header.hpp"

#include <gtest/gtest.h>

#include "tests/io/io_test_util.hpp"
#include "tests/support/shared_data.hpp"

namespace fleetmerge {
namespace {

namespace fs = std::filesystem;
namespace ft = fleetmerge::testing;

std::optional<PnmHeader> HeaderOf(const std::string& bytes) {
  const fs::path path = ft::MakeTempDir("pnm_header") / "image.pnm";
  ft::WriteFile(path, bytes);
  return ReadPnmHeader(path);
}

TEST(PnmHeaderTest, ReadsBinaryAndAsciiHeadersWithComments) {
  const std::optional<PnmHeader> binary = HeaderOf("P5\n# made by hand\n640 480\n65535\n\x01\x02");
  ASSERT_TRUE(binary);
  EXPECT_EQ(binary->kind, '5');
  EXPECT_EQ(binary->width, 640);
  EXPECT_EQ(binary->height, 480);
  EXPECT_EQ(binary->maxval, 65535);
  const std::optional<PnmHeader> ascii = HeaderOf("P2 3#c\n2 100 1 2 3\n");
  ASSERT_TRUE(ascii);
  EXPECT_EQ(ascii->kind, '2');
  EXPECT_EQ(ascii->width, 3);
  EXPECT_EQ(ascii->height, 2);
  EXPECT_EQ(ascii->maxval, 100);
}

TEST(PnmHeaderTest, BitmapsHaveNoMaxval) {
  const std::optional<PnmHeader> bitmap = HeaderOf("P4\n8 2\n\xff\x00");
  ASSERT_TRUE(bitmap);
  EXPECT_EQ(bitmap->kind, '4');
  EXPECT_EQ(bitmap->maxval, 1);
}

TEST(PnmHeaderTest, RejectsWhatIsNotAHeader) {
  EXPECT_FALSE(HeaderOf(""));
  EXPECT_FALSE(HeaderOf("\x89PNG\r\n\x1a\n"));
  EXPECT_FALSE(HeaderOf("P7\n1 1\n255\n"));
  EXPECT_FALSE(HeaderOf("P5\n1 1\n"));                 // truncated before maxval
  EXPECT_FALSE(HeaderOf("P5\n-1 1\n255\n"));           // not a count
  EXPECT_FALSE(HeaderOf("P5\n99999999999 1\n255\n"));  // does not fit an int
  EXPECT_FALSE(ReadPnmHeader("/no/such/file.pgm"));
}

}  // namespace
}  // namespace fleetmerge
