// The MCAP format's constants that its reader (rosbag/mcap_file) and writer (rosbag/mcap_writer)
// share: the magic that opens and closes a file and the record opcodes
// (https://mcap.dev/spec#records).
#pragma once

#include <cstddef>
#include <cstdint>

namespace fleetmerge::mcap {

constexpr char kMagic[] = "\x89MCAP0\r\n";
constexpr std::size_t kMagicSize = 8;

enum Op : std::uint8_t {
  kHeader = 0x01,
  kFooter = 0x02,
  kSchema = 0x03,
  kChannel = 0x04,
  kMessage = 0x05,
  kChunk = 0x06,
  kMessageIndex = 0x07,
  kChunkIndex = 0x08,
  kStatistics = 0x0b,
  kMetadata = 0x0c,
  kMetadataIndex = 0x0d,
  kSummaryOffset = 0x0e,
  kDataEnd = 0x0f,
};

}  // namespace fleetmerge::mcap
