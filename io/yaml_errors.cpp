#include "io/yaml_errors.hpp"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>

#include "core/error.hpp"

namespace fleetmerge {
namespace fs = std::filesystem;

void YamlErrors::Fail(const std::string& what) const { throw Error(path_ + ": " + what); }

void YamlErrors::Fail(const std::string& key, int line, const std::string& what) const {
  Fail("line " + std::to_string(line) + ": key '" + key + "': " + what);
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

std::string ReadYamlFileText(const fs::path& path, const std::string& kind,
                             const YamlErrors& errors) {
  std::error_code ec;
  if (fs::is_directory(path, ec)) errors.Fail("is a folder, expected a " + kind);
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
