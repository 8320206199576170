// The project's one exception type. Its message names the file, the key or line, and what was
// expected, so a user can fix the input without reading code (see STYLE.md, "Errors").
#pragma once

#include <stdexcept>
#include <string>

namespace fleetmerge {

class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& message) : std::runtime_error(message) {}
};

}  // namespace fleetmerge
