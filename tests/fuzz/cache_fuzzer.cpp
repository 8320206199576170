// Fuzzes what a re-run reads back from its cache folder (io/cache_folder.hpp,
// pipeline/pair_cache.hpp), which a killed job, a full disk or a stray write may have left in any
// state. An input is an entry file's bytes (the seeds are entries that `merge --cache` wrote).
//   1. The file as found, under its own key's name, in a folder of its own version:
//      CacheFolder::Read checks its header, version, key and checksum, and must refuse it unless
//      it is the very entry Write makes of the payload it returns.
//   2. Its payload (the whole input when the header does not parse that far) written by
//      CacheFolder::Write and read back: the same bytes. The fuzzer thus gets past the checksum
//      to the payload parsers, ParsePairOutcome and ParsePreparation. A pair payload that parses
//      must be written back as the same bytes.
//   3. A preparation that parses is put to use as a map's (the cache keys it by the map's cells,
//      but trusts nothing): a small room prepared from it is paired with another, both ways.
// Anything but a clean run or a fleetmerge::Error is a finding.
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <optional>
#include <string>

#include "core/error.hpp"
#include "io/cache_folder.hpp"
#include "pipeline/pair_cache.hpp"
#include "pipeline/pair_merge.hpp"
#include "pipeline/prepared_map.hpp"
#include "tests/fuzz/fuzz_support.hpp"

namespace {

using namespace fleetmerge;

// A room of `width` x 40 cells of 5 cm, walls all round and three inner walls, cut from a
// 64-cell-wide floor at column `first_column`: two such cuts overlap where their columns do.
OccupancyGrid Room(int first_column, int width) {
  cv::Mat1b cells(40, width, static_cast<std::uint8_t>(CellState::kFree));
  const auto occupied = static_cast<std::uint8_t>(CellState::kOccupied);
  for (int r = 0; r < cells.rows; ++r) {
    for (int c = 0; c < width; ++c) {
      const int x = first_column + c;  // the floor's column
      const bool wall = r == 0 || r == 39 || x == 0 || x == 63 || (x == 20 && r < 28) ||
                        (x == 44 && r > 12) || (r == 20 && x > 44 && x < 58);
      if (wall) cells(r, c) = occupied;
    }
  }
  return OccupancyGrid(GridGeometry(0.05, Eigen::Array2i(width, 40)), cells);
}

// An entry file's version, key and payload (io/cache_folder.hpp's layout), or nullopt when its
// header does not parse that far.
struct EntryFields {
  std::string version;
  ContentDigest key{};
  std::string payload;
};
std::optional<EntryFields> FieldsOf(const std::string& entry) {
  EntryFields fields;
  std::size_t at = 16 + 4 + 4;  // magic, format, byte order
  std::uint32_t version_size = 0;
  if (entry.size() < at + sizeof version_size) return std::nullopt;
  std::memcpy(&version_size, entry.data() + at, sizeof version_size);
  at += sizeof version_size;
  if (entry.size() - at < std::size_t{version_size} + fields.key.size()) return std::nullopt;
  fields.version = entry.substr(at, version_size);
  at += version_size;
  std::memcpy(fields.key.data(), entry.data() + at, fields.key.size());
  at += fields.key.size();
  std::uint64_t payload_size = 0;
  if (entry.size() - at < sizeof payload_size) return std::nullopt;
  std::memcpy(&payload_size, entry.data() + at, sizeof payload_size);
  at += sizeof payload_size;
  if (entry.size() - at < payload_size) return std::nullopt;
  fields.payload = entry.substr(at, payload_size);
  return fields;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const OccupancyGrid room_a = Room(0, 48), room_b = Room(16, 48);
  static const PairOptions options;
  const std::string input(reinterpret_cast<const char*>(data), size);
  // The entry's own version and key where it has them, so that a seed (an entry of a real
  // cache) is trusted as found and its mutants fail one check at a time.
  const std::optional<EntryFields> fields = FieldsOf(input);
  const std::string version = fields ? fields->version : "fuzz";
  const ContentDigest key = fields ? fields->key : ContentHashOf("entry");
  const std::filesystem::path dir = fuzz::ScratchDir() / "cache";
  try {
    CacheFolder folder(dir, version, CacheFolderOptions{});
    fuzz::WriteBytes(folder.EntryPath(key), input.data(), input.size());
    if (const std::optional<std::string> found = folder.Read(key)) {
      // Only an entry this build writes is trusted: these very bytes for that payload.
      if (CacheEntryBytes(key, version, *found) != input) abort();
    }

    const std::string payload = fields ? fields->payload : input;
    folder.Write(key, payload);
    const std::optional<std::string> read = folder.Read(key);
    if (!read || *read != payload) abort();  // an entry this build wrote is read back whole

    if (const std::optional<PairOutcome> pair = ParsePairOutcome(payload)) {
      // Only payloads a search could have written parse, and they are written back bit for bit:
      // a cached pair is the computed one.
      if (PairOutcomePayload(*pair) != payload) abort();
    }
    if (std::optional<KeptPreparation> kept = ParsePreparation(payload)) {
      const PreparedMap a(room_a, options);
      const PreparedMap b(room_b, options, std::move(*kept));
      (void)RankedCellHypotheses(a, b, options);
      (void)RankedCellHypotheses(b, a, options);
    }
  } catch (const Error&) {
  }
  std::error_code ignored;  // one entry at a time: the folder does not grow with the run
  std::filesystem::remove(dir / (ToHex(key) + ".entry"), ignored);
  return 0;
}
