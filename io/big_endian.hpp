// 16-bit image samples as the files store them, most significant byte first (binary PGM with a
// maxval above 255, PNG), whatever the host's byte order.
#pragma once

#include <cstddef>
#include <cstdint>

namespace fleetmerge {

inline void StoreBigEndian16(const std::uint16_t* samples, std::size_t count, std::uint8_t* out) {
  for (std::size_t k = 0; k < count; ++k) {
    out[2 * k] = static_cast<std::uint8_t>(samples[k] >> 8);
    out[2 * k + 1] = static_cast<std::uint8_t>(samples[k] & 0xff);
  }
}

}  // namespace fleetmerge
