// Values as their raw bytes, in this machine's byte order: what the cache's entries hold
// (io/cache_folder.hpp checks an entry's byte order, version and checksum before its payload is
// read, so a reader here only needs to stop at the end of the bytes).
#pragma once

#include <cstddef>
#include <cstring>
#include <string>
#include <type_traits>

namespace fleetmerge {

template <typename T>
void AppendRaw(std::string& bytes, const T& value) {
  static_assert(std::is_trivially_copyable_v<T>, "raw bytes of a trivially copyable type only");
  bytes.append(reinterpret_cast<const char*>(&value), sizeof value);
}

// `count` values from `values` as one block.
template <typename T>
void AppendRawArray(std::string& bytes, const T* values, std::size_t count) {
  static_assert(std::is_trivially_copyable_v<T>, "raw bytes of a trivially copyable type only");
  bytes.append(reinterpret_cast<const char*>(values), count * sizeof(T));
}

// Reads values in the order they were appended; a read past the end returns false.
class RawBytesReader {
 public:
  explicit RawBytesReader(const std::string& bytes) : bytes_(bytes) {}
  template <typename T>
  bool Read(T& value) {
    static_assert(std::is_trivially_copyable_v<T>, "raw bytes of a trivially copyable type only");
    if (bytes_.size() - offset_ < sizeof value) return false;
    std::memcpy(&value, bytes_.data() + offset_, sizeof value);
    offset_ += sizeof value;
    return true;
  }
  // `count` values into `values` (an array's bytes, appended as one block).
  template <typename T>
  bool ReadArray(T* values, std::size_t count) {
    static_assert(std::is_trivially_copyable_v<T>, "raw bytes of a trivially copyable type only");
    if (count > (bytes_.size() - offset_) / sizeof(T)) return false;
    std::memcpy(values, bytes_.data() + offset_, count * sizeof(T));
    offset_ += count * sizeof(T);
    return true;
  }
  // The next `size` bytes in place (valid while the bytes are), or nullptr past the end.
  const char* View(std::size_t size) {
    if (bytes_.size() - offset_ < size) return nullptr;
    const char* at = bytes_.data() + offset_;
    offset_ += size;
    return at;
  }
  bool ReadBytes(std::size_t size, std::string& out) {
    if (bytes_.size() - offset_ < size) return false;
    out.assign(bytes_, offset_, size);
    offset_ += size;
    return true;
  }
  std::size_t offset() const { return offset_; }
  std::size_t remaining() const { return bytes_.size() - offset_; }
  bool AtEnd() const { return offset_ == bytes_.size(); }

 private:
  const std::string& bytes_;
  std::size_t offset_ = 0;
};

}  // namespace fleetmerge
