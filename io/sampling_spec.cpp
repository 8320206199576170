#include "io/sampling_spec.hpp"

#include <stdexcept>

#include "core/error.hpp"

namespace fleetmerge {

std::optional<SamplingOptions> ParseSamplingSpec(const std::string& text) {
  SamplingOptions s;
  try {
    std::size_t used = 0;
    if (text == "all") return s;
    if (text.rfind("random:", 0) == 0) {
      s.mode = SamplingMode::kRandomFraction;
      s.fraction = std::stod(text.substr(7), &used);
      if (used != text.size() - 7 || !(s.fraction > 0.0 && s.fraction <= 1.0)) return std::nullopt;
      return s;
    }
    if (text.rfind("every:", 0) == 0) {
      s.mode = SamplingMode::kEveryKth;
      s.step = std::stoi(text.substr(6), &used);
      if (used != text.size() - 6 || s.step < 1) return std::nullopt;
      return s;
    }
  } catch (const std::logic_error&) {  // stod / stoi: not a number, out of range
  }
  return std::nullopt;
}

SamplingOptions ParseSampling(const std::string& option, const std::string& text) {
  const std::optional<SamplingOptions> sampling = ParseSamplingSpec(text);
  if (!sampling) {
    throw Error("option " + option + ": expected " + kSamplingSpecExpected + ", got '" + text +
                "'");
  }
  return *sampling;
}

}  // namespace fleetmerge
