#include "io/yaml_errors.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>

#include "core/error.hpp"

namespace fleetmerge {
namespace fs = std::filesystem;

void YamlErrors::Fail(const std::string& what) const { throw Error(path_ + ": " + what); }

std::string YamlErrors::Message(const std::string& key, int line, const std::string& what) const {
  return path_ + ": line " + std::to_string(line) + ": key '" + key + "': " + what;
}

void YamlErrors::Fail(const std::string& key, int line, const std::string& what) const {
  throw Error(Message(key, line, what));
}

std::string Describe(const YAML::Node& node) {
  switch (node.Type()) {
    case YAML::NodeType::Scalar: {
      const std::string& text = node.Scalar();
      return "'" + (text.size() > 60 ? text.substr(0, 57) + "..." : text) + "'";
    }
    case YAML::NodeType::Sequence:
      return "a list of " + std::to_string(node.size()) +
             (node.size() == 1 ? " element" : " elements");
    case YAML::NodeType::Map:
      return "a mapping";
    default:
      return "an empty value";
  }
}

namespace {

// Map YAMLs and job files are a few kilobytes; anything this large is the wrong file.
constexpr std::uintmax_t kMaxYamlBytes = 16u << 20;

// Length of the well-formed UTF-8 sequence at text[i] (RFC 3629: no overlong forms, no
// surrogates, nothing above U+10FFFF), or 0.
std::size_t Utf8SequenceLength(const std::string& text, std::size_t i) {
  const auto byte = [&text](std::size_t k) { return static_cast<unsigned char>(text[k]); };
  const unsigned char b0 = byte(i);
  if (b0 < 0x80) return 1;
  std::size_t length = 0;
  unsigned char lo = 0x80, hi = 0xbf;  // allowed range of the second byte
  if (b0 >= 0xc2 && b0 <= 0xdf) {
    length = 2;
  } else if (b0 >= 0xe0 && b0 <= 0xef) {
    length = 3;
    if (b0 == 0xe0) lo = 0xa0;
    if (b0 == 0xed) hi = 0x9f;
  } else if (b0 >= 0xf0 && b0 <= 0xf4) {
    length = 4;
    if (b0 == 0xf0) lo = 0x90;
    if (b0 == 0xf4) hi = 0x8f;
  } else {
    return 0;
  }
  if (i + length > text.size() || byte(i + 1) < lo || byte(i + 1) > hi) return 0;
  for (std::size_t k = 2; k < length; ++k) {
    if (byte(i + k) < 0x80 || byte(i + k) > 0xbf) return 0;
  }
  return length;
}

// yaml-cpp passes invalid UTF-8 through into names and paths (and nlohmann::json then refuses
// to write report.json at the end of the job): refuse it here, naming the line and column.
void CheckUtf8(const std::string& text, const YamlErrors& errors) {
  int line = 1;
  std::size_t line_start = 0;
  for (std::size_t i = 0; i < text.size();) {
    const std::size_t length = Utf8SequenceLength(text, i);
    if (length == 0) {
      char hex[8];
      std::snprintf(hex, sizeof hex, "0x%02x", static_cast<unsigned char>(text[i]));
      errors.Fail("line " + std::to_string(line) + ", column " +
                  std::to_string(i - line_start + 1) + ": not valid UTF-8 text (byte " + hex +
                  "); save the file as UTF-8");
    }
    if (text[i] == '\n') {
      ++line;
      line_start = i + 1;
    }
    i += length;
  }
}

}  // namespace

std::string ReadYamlFileText(const fs::path& path, const std::string& kind,
                             const YamlErrors& errors) {
  std::error_code ec;
  if (fs::is_directory(path, ec)) errors.Fail("is a folder, expected a " + kind);
  const std::uintmax_t bytes = fs::file_size(path, ec);
  if (!ec && bytes > kMaxYamlBytes) {
    errors.Fail("is " + std::to_string(bytes) + " bytes, too large for a " + kind + " (at most " +
                std::to_string(kMaxYamlBytes) + "): is it the right file?");
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    const int error = errno;  // before anything else can change it
    errors.Fail("cannot open " + kind + ": " + std::strerror(error));
  }
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) {
    const int error = errno;
    errors.Fail("cannot read " + kind + ": " + std::strerror(error));
  }
  CheckUtf8(text.str(), errors);
  return text.str();
}

YAML::Node ParseYamlText(const std::string& text, const YamlErrors& errors) {
  try {
    return YAML::Load(text);
  } catch (const YAML::Exception& e) {
    if (e.mark.is_null()) errors.Fail("malformed YAML: " + e.msg);
    errors.Fail("line " + std::to_string(e.mark.line + 1) + ", column " +
                std::to_string(e.mark.column + 1) + ": malformed YAML: " + e.msg);
  }
}

std::map<std::string, YamlEntry> MappingEntries(const YAML::Node& mapping,
                                                const std::string& key_prefix,
                                                const YamlErrors& errors) {
  std::map<std::string, YamlEntry> entries;
  for (const auto& key_value : mapping) {
    if (!key_value.first.IsScalar()) continue;
    const YamlEntry entry{key_value.second, key_value.first.Mark().line + 1};
    const auto [it, inserted] = entries.emplace(key_value.first.Scalar(), entry);
    if (!inserted) {
      errors.Fail(key_prefix + it->first, entry,
                  "appears twice (first at line " + std::to_string(it->second.line) + ")");
    }
  }
  return entries;
}

}  // namespace fleetmerge
