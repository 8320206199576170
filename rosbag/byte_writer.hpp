// Little-endian appending of binary records (MCAP, CDR payloads): the writing side of
// rosbag/byte_reader.hpp.
#pragma once

#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>
#include <utility>

static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__, "ByteWriter assumes a little-endian host");

namespace fleetmerge {

class ByteWriter {
 public:
  template <typename T>
  void Put(T value) {
    char raw[sizeof(T)];
    std::memcpy(raw, &value, sizeof(T));
    bytes_.append(raw, sizeof(T));
  }
  void Bytes(std::string_view bytes) { bytes_.append(bytes.data(), bytes.size()); }
  // A uint32 byte count, then the bytes (MCAP's strings and byte arrays).
  void Prefixed(std::string_view bytes) {
    Put(static_cast<std::uint32_t>(bytes.size()));
    Bytes(bytes);
  }
  std::size_t size() const { return bytes_.size(); }
  const std::string& bytes() const { return bytes_; }
  std::string& mutable_bytes() { return bytes_; }
  // Room for `total` bytes in all: a writer that knows its size (a map's cells) grows once.
  void Reserve(std::size_t total) { bytes_.reserve(total); }
  // The bytes, moved out: the writer's last use.
  std::string Release() { return std::move(bytes_); }

 private:
  std::string bytes_;
};

// ROS 2's CDR (XCDR1, little-endian): the 4-byte encapsulation header 00 01 00 00, then every
// primitive aligned to its size counted from the end of that header, strings as a uint32 length
// that counts the terminating NUL. The inverse of the CdrReader in rosbag/occupancy_grid_msg.cpp.
class CdrWriter {
 public:
  CdrWriter() { out_.Bytes(std::string_view("\x00\x01\x00\x00", 4)); }

  template <typename T>
  void Put(T value) {
    Align(sizeof(T));
    out_.Put(value);
  }
  void String(std::string_view text) {
    Put(static_cast<std::uint32_t>(text.size() + 1));
    out_.Bytes(text);
    out_.Put('\0');
  }
  // A sequence of bytes (int8[] / uint8[]): the element count, then the elements.
  void ByteSequence(std::string_view bytes) {
    Put(static_cast<std::uint32_t>(bytes.size()));
    out_.Bytes(bytes);
  }
  // ByteSequence of `count` elements that the caller writes into the returned bytes (valid
  // until the next write): a map's cells go into the message once, not through a copy.
  char* ByteSequenceToFill(std::size_t count) {
    Put(static_cast<std::uint32_t>(count));
    std::string& bytes = out_.mutable_bytes();
    const std::size_t at = bytes.size();
    bytes.resize(at + count);
    return bytes.data() + at;
  }
  void Reserve(std::size_t total) { out_.Reserve(total); }
  const std::string& bytes() const { return out_.bytes(); }
  std::string Release() { return out_.Release(); }

 private:
  void Align(std::size_t size) {
    const std::size_t offset = out_.size() - 4;
    for (std::size_t pad = (size - offset % size) % size; pad > 0; --pad) out_.Put('\0');
  }
  ByteWriter out_;
};

}  // namespace fleetmerge
