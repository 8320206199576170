// Replays files through a fuzz target's LLVMFuzzerTestOneInput without libFuzzer: every file in
// the folders given on the command line (seed corpus, kept crashing inputs). A crash, sanitizer
// report or stray exception fails the test; it prints how many inputs ran.
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);

int main(int argc, char** argv) {
  int inputs = 0;
  for (int a = 1; a < argc; ++a) {
    if (!std::filesystem::is_directory(argv[a])) {
      std::fprintf(stderr, "replay: %s is not a folder\n", argv[a]);
      return 2;
    }
    for (const auto& entry : std::filesystem::directory_iterator(argv[a])) {
      if (!entry.is_regular_file() || entry.path().filename().string()[0] == '.') continue;
      std::ifstream in(entry.path(), std::ios::binary);
      const std::string bytes((std::istreambuf_iterator<char>(in)),
                              std::istreambuf_iterator<char>());
      LLVMFuzzerTestOneInput(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
      ++inputs;
    }
  }
  std::printf("replay: %d inputs, no crash\n", inputs);
  return inputs > 0 ? 0 : 1;
}
