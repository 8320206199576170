// builtin_interfaces/msg/Time from nanoseconds since the epoch (sec rounded down, so nanosec is
// in [0, 1e9) for times before 1970 too).
#pragma once

#include <cstdint>

namespace fleetmerge {

struct RosTime {
  std::int32_t sec = 0;
  std::uint32_t nanosec = 0;
};

inline RosTime RosTimeOf(std::int64_t ns) {
  std::int64_t sec = ns / 1'000'000'000;
  std::int64_t rest = ns % 1'000'000'000;
  if (rest < 0) {
    rest += 1'000'000'000;
    --sec;
  }
  return {static_cast<std::int32_t>(sec), static_cast<std::uint32_t>(rest)};
}

}  // namespace fleetmerge
