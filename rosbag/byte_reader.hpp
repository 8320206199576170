// Bounds-checked little-endian reading of binary records (ROS 1 bags, MCAP, CDR). Every read past
// the end throws fleetmerge::Error naming what was being read and where, so a truncated or
// corrupt file is refused with a message instead of read out of bounds.
#pragma once

#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>
#include <utility>

#include "core/error.hpp"

static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__, "ByteReader assumes a little-endian host");

namespace fleetmerge {

class ByteReader {
 public:
  // `context` prefixes every error ("robot1.bag: chunk at byte 4117").
  ByteReader(std::string_view bytes, std::string context)
      : bytes_(bytes), context_(std::move(context)) {}

  std::size_t offset() const { return offset_; }
  std::size_t remaining() const { return bytes_.size() - offset_; }
  bool at_end() const { return offset_ >= bytes_.size(); }
  const std::string& context() const { return context_; }

  // The next n bytes, as a view into the buffer.
  std::string_view Bytes(std::size_t n, const char* what) {
    if (n > remaining()) {
      throw Error(context_ + ": " + what + " needs " + std::to_string(n) + " bytes at offset " +
                  std::to_string(offset_) + ", only " + std::to_string(remaining()) +
                  " remain (truncated or corrupt)");
    }
    const std::string_view out = bytes_.substr(offset_, n);
    offset_ += n;
    return out;
  }
  void Skip(std::size_t n, const char* what) { Bytes(n, what); }
  void Seek(std::size_t offset, const char* what) {
    if (offset > bytes_.size()) {
      throw Error(context_ + ": " + what + " at offset " + std::to_string(offset) +
                  " is past the end (" + std::to_string(bytes_.size()) + " bytes)");
    }
    offset_ = offset;
  }

  template <typename T>
  T Read(const char* what, bool big_endian = false) {
    const std::string_view raw = Bytes(sizeof(T), what);
    unsigned char b[sizeof(T)];
    std::memcpy(b, raw.data(), sizeof(T));
    if (big_endian) {
      for (std::size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(b[i], b[sizeof(T) - 1 - i]);
    }
    T value;
    std::memcpy(&value, b, sizeof(T));
    return value;
  }
  std::uint8_t U8(const char* what) { return Read<std::uint8_t>(what); }
  std::uint16_t U16(const char* what) { return Read<std::uint16_t>(what); }
  std::uint32_t U32(const char* what) { return Read<std::uint32_t>(what); }
  std::uint64_t U64(const char* what) { return Read<std::uint64_t>(what); }

 private:
  std::string_view bytes_;
  std::string context_;
  std::size_t offset_ = 0;
};

}  // namespace fleetmerge
