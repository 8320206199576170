// The message of the fleetmerge::Error a call throws, for tests that assert on what an error
// names (a path, a key, a holder).
#pragma once

#include <functional>
#include <string>

#include "core/error.hpp"

namespace fleetmerge::testing {

// Empty when `fn` throws nothing; other exceptions pass through (the test fails on them).
inline std::string ErrorOf(const std::function<void()>& fn) {
  try {
    fn();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

}  // namespace fleetmerge::testing
