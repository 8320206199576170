// Fuzzes the map reader (map YAML + PGM/PNG image, LoadMap). An input is the YAML text, the
// separator line "#IMAGE#", and the image bytes, written to map.yaml and image.pgm (the seeds'
// YAML names image.pgm; the image's format is found from its bytes). Anything but a clean load
// or a fleetmerge::Error (a crash, a sanitizer report, another exception) is a finding.
#include "core/error.hpp"
#include "io/map_io.hpp"
#include "tests/fuzz/fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace fleetmerge;
  const auto [yaml, image] = fuzz::Split(data, size, "\n#IMAGE#\n");
  const std::filesystem::path dir = fuzz::ScratchDir();
  fuzz::WriteBytes(dir / "map.yaml", yaml.data(), yaml.size());
  fuzz::WriteBytes(dir / "image.pgm", image.data(), image.size());
  try {
    // A small cell limit keeps each execution fast; the limit itself is what is fuzzed.
    const LoadedMap map = LoadMap(dir / "map.yaml", 1 << 20);
    if (map.grid.width() <= 0 || map.grid.height() <= 0) abort();  // loaded maps are not empty
  } catch (const Error&) {
  }
  return 0;
}
