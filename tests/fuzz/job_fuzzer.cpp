// Fuzzes the job-file reader (LoadJobFile): the input is the job YAML, in a folder that also
// holds two valid maps a.yaml/a.pgm and b.yaml/b.pgm (the seeds name them). Anything but a
// clean load or a fleetmerge::Error is a finding.
#include "core/error.hpp"
#include "io/job_file.hpp"
#include "tests/fuzz/fuzz_support.hpp"

namespace {

void WriteMaps(const std::filesystem::path& dir) {
  static const std::string pgm = std::string("P5\n4 3\n255\n") + std::string(12, '\xfe');
  for (const char* name : {"a", "b"}) {
    const std::string yaml =
        std::string("image: ") + name + ".pgm\nresolution: 0.05\norigin: [0.0, 0.0, 0.0]\n";
    fleetmerge::fuzz::WriteBytes(dir / (std::string(name) + ".yaml"), yaml.data(), yaml.size());
    fleetmerge::fuzz::WriteBytes(dir / (std::string(name) + ".pgm"), pgm.data(), pgm.size());
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace fleetmerge;
  static const bool maps_written = (WriteMaps(fuzz::ScratchDir()), true);
  (void)maps_written;
  const std::filesystem::path job = fuzz::ScratchDir() / "job.yaml";
  fuzz::WriteBytes(job, reinterpret_cast<const char*>(data), size);
  try {
    for (const Job& j : LoadJobFile(job)) {
      if (j.maps.empty() || j.name.empty()) abort();  // validated jobs have maps and a name
    }
  } catch (const Error&) {
  }
  return 0;
}
