// Captures what C and C++ libraries write straight to the process's standard error while a
// function runs. OpenCV's imread prints its own line on a truncated ASCII PGM and libpng prints
// "libpng error: ..." on a corrupt PNG, beside our one clear message; capturing lets the loader
// fold that text into its fleetmerge::Error instead.
#pragma once

#include <functional>
#include <string>

namespace fleetmerge {

// Runs `fn` with file descriptor 2 redirected to an anonymous temporary file and returns the
// text written there. Calls are serialised by a process-wide mutex (the descriptor is process
// state), so a thread printing meanwhile is captured too: callers pass on what they do not
// consume. If the redirection cannot be set up, `fn` runs with stderr untouched and "" is
// returned. Exceptions from `fn` propagate after stderr is restored.
std::string CaptureNativeStderr(const std::function<void()>& fn);

}  // namespace fleetmerge
