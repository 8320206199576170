#include "io/map_yaml.hpp"

#include <yaml-cpp/yaml.h>

#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <map>
#include <sstream>

#include "io/yaml_errors.hpp"

namespace fleetmerge {
namespace fs = std::filesystem;
namespace {

using Entry = YamlEntry;

std::map<std::string, Entry> ParseEntries(const std::string& text, const YamlErrors& errors) {
  const YAML::Node root = ParseYamlText(text, errors);
  if (!root.IsMap()) {
    errors.Fail("expected a mapping with keys image, resolution, origin, ..., got " +
                Describe(root));
  }
  return MappingEntries(root, "", errors);  // keys that are not scalars: none map_server reads
}

const Entry* Find(const std::map<std::string, Entry>& entries, const std::string& key) {
  const auto it = entries.find(key);
  return it == entries.end() ? nullptr : &it->second;
}

const Entry& Require(const std::map<std::string, Entry>& entries, const std::string& key,
                     const std::string& expected, const YamlErrors& errors) {
  const Entry* entry = Find(entries, key);
  if (entry == nullptr) errors.Fail("missing required key '" + key + "' (" + expected + ")");
  return *entry;
}

// A finite number, or an error naming `key` (and `element`, for list members).
double ToNumber(const YAML::Node& node, const std::string& key, const Entry& entry,
                const YamlErrors& errors, const std::string& element = "") {
  double value = 0.0;
  if (!YAML::convert<double>::decode(node, value)) {
    errors.Fail(key, entry, element + "expected a number, got " + Describe(node));
  }
  if (!std::isfinite(value)) {
    errors.Fail(key, entry, element + "expected a finite number, got " + Describe(node));
  }
  return value;
}

fs::path ReadImagePath(const std::map<std::string, Entry>& entries, const fs::path& yaml_path,
                       const YamlErrors& errors) {
  // A job file handed over as a map (`merge --out DIR job.yaml`) would otherwise read as a map
  // with its image key forgotten.
  if (Find(entries, "image") == nullptr && Find(entries, "maps") != nullptr) {
    errors.Fail(
        "missing required key 'image' (the image file name): this file has a 'maps' key, as a "
        "job file does; run a job file as `fleetmerge merge FILE`, without --out");
  }
  const Entry& entry = Require(entries, "image", "the image file name", errors);
  if (!entry.value.IsScalar() || entry.value.Scalar().empty()) {
    errors.Fail("image", entry, "expected an image file name, got " + Describe(entry.value));
  }
  const fs::path image = entry.value.Scalar();
  const fs::path image_path = image.is_absolute() ? image : yaml_path.parent_path() / image;
  std::error_code ec;
  if (!fs::exists(image_path, ec)) {
    errors.Fail("image", entry, "image file '" + image_path.string() + "' does not exist");
  }
  if (fs::is_directory(image_path, ec)) {
    errors.Fail("image", entry, "'" + image_path.string() + "' is a folder, expected an image");
  }
  return image_path;
}

double ReadResolution(const std::map<std::string, Entry>& entries, const YamlErrors& errors) {
  const Entry& entry = Require(entries, "resolution", "metres per cell", errors);
  const double resolution_m = ToNumber(entry.value, "resolution", entry, errors);
  if (resolution_m <= 0.0) {
    errors.Fail("resolution", entry,
                "expected a number > 0 (metres per cell), got " + Describe(entry.value));
  }
  return resolution_m;
}

Pose2 ReadOrigin(const std::map<std::string, Entry>& entries, const YamlErrors& errors) {
  const Entry& entry = Require(entries, "origin", "[x, y, yaw]", errors);
  if (!entry.value.IsSequence() || entry.value.size() != 3) {
    errors.Fail("origin", entry,
                "expected a list of 3 numbers [x, y, yaw], got " + Describe(entry.value));
  }
  const std::array<const char*, 3> names = {"x", "y", "yaw"};
  std::array<double, 3> xyyaw{};
  for (std::size_t k = 0; k < 3; ++k) {
    xyyaw[k] = ToNumber(entry.value[k], "origin", entry, errors,
                        "element " + std::to_string(k + 1) + " (" + names[k] + "): ");
  }
  return Pose2(xyyaw[0], xyyaw[1], xyyaw[2]);
}

// map_server reads negate as an int; Nav2 also accepts a bool.
bool ReadNegate(const std::map<std::string, Entry>& entries, const YamlErrors& errors) {
  const Entry* entry = Find(entries, "negate");
  if (entry == nullptr) return false;
  int as_int = 0;
  bool as_bool = false;
  if (YAML::convert<int>::decode(entry->value, as_int) && (as_int == 0 || as_int == 1)) {
    return as_int == 1;
  }
  if (YAML::convert<bool>::decode(entry->value, as_bool)) return as_bool;
  errors.Fail("negate", *entry, "expected 0 or 1 (or false/true), got " + Describe(entry->value));
}

double ReadThreshold(const std::map<std::string, Entry>& entries, const std::string& key,
                     double default_value, const YamlErrors& errors) {
  const Entry* entry = Find(entries, key);
  if (entry == nullptr) return default_value;
  const double value = ToNumber(entry->value, key, *entry, errors);
  if (value < 0.0 || value > 1.0) {
    errors.Fail(key, *entry, "expected a number in [0, 1], got " + Describe(entry->value));
  }
  return value;
}

void CheckThresholdOrder(const MapMetadata& metadata, const std::map<std::string, Entry>& entries,
                         const YamlErrors& errors) {
  if (metadata.free_thresh < metadata.occupied_thresh) return;
  const char* key = Find(entries, "free_thresh") != nullptr ? "free_thresh" : "occupied_thresh";
  std::ostringstream what;
  what << "expected free_thresh < occupied_thresh, got free_thresh " << metadata.free_thresh
       << " and occupied_thresh " << metadata.occupied_thresh;
  errors.Fail(key, *Find(entries, key), what.str());
}

MapMode ReadMode(const std::map<std::string, Entry>& entries, const YamlErrors& errors) {
  const Entry* entry = Find(entries, "mode");
  if (entry == nullptr) return MapMode::kTrinary;
  const std::string text = entry->value.IsScalar() ? entry->value.Scalar() : "";
  if (text == "trinary") return MapMode::kTrinary;
  if (text == "scale") return MapMode::kScale;
  if (text == "raw") return MapMode::kRaw;
  errors.Fail("mode", *entry, "expected trinary, scale or raw, got " + Describe(entry->value));
}

std::string FormatNumber(double value) {
  std::array<char, 32> buffer{};
  const auto result = std::to_chars(buffer.data(), buffer.data() + buffer.size(), value);
  return std::string(buffer.data(), result.ptr);
}

// Plain YAML scalar when the name is made of safe characters, else a double-quoted one.
std::string FormatFileName(const std::string& name) {
  const bool plain = !name.empty() && std::isalnum(static_cast<unsigned char>(name[0])) != 0 &&
                     name.find_first_not_of(
                         "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                         "0123456789._-+") == std::string::npos;
  if (plain) return name;
  YAML::Emitter out;
  out << YAML::DoubleQuoted << name;
  return out.c_str();
}

}  // namespace

MapMetadata ReadMapYaml(const fs::path& yaml_path) {
  const YamlErrors errors(yaml_path);
  const std::map<std::string, Entry> entries =
      ParseEntries(ReadYamlFileText(yaml_path, "map YAML file", errors), errors);
  MapMetadata metadata;
  metadata.yaml_path = yaml_path;
  metadata.image_path = ReadImagePath(entries, yaml_path, errors);
  metadata.resolution_m = ReadResolution(entries, errors);
  metadata.origin = ReadOrigin(entries, errors);
  metadata.negate = ReadNegate(entries, errors);
  metadata.occupied_thresh = ReadThreshold(entries, "occupied_thresh", 0.65, errors);
  metadata.free_thresh = ReadThreshold(entries, "free_thresh", 0.196, errors);
  CheckThresholdOrder(metadata, entries, errors);
  metadata.mode = ReadMode(entries, errors);
  return metadata;
}

std::string FormatMapYaml(const GridGeometry& geometry, const std::string& image_name) {
  const Pose2& origin = geometry.T_map_grid();
  std::ostringstream out;
  out << "image: " << FormatFileName(image_name) << "\n"
      << "resolution: " << FormatNumber(geometry.resolution_m()) << "\n"
      << "origin: [" << FormatNumber(origin.x_m()) << ", " << FormatNumber(origin.y_m()) << ", "
      << FormatNumber(origin.yaw_rad()) << "]\n"
      << "negate: 0\n"
      << "occupied_thresh: 0.65\n"
      << "free_thresh: 0.196\n"
      << "mode: trinary\n";
  return out.str();
}

}  // namespace fleetmerge
