// The house format of errors in the YAML files io/ reads (map YAML, job files):
//   "<file>: line L: key 'k': expected ..., got ..."
// (STYLE.md, "Errors"; lines are 1-based). Internal to io/: it exposes yaml-cpp types.
#pragma once

#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <map>
#include <string>

namespace fleetmerge {

// A value and the 1-based line of its key. Errors point at the key's line: for an empty value
// (`resolution:`) yaml-cpp marks the start of the next line instead.
struct YamlEntry {
  YAML::Node value;
  int line = 0;
};

// Formats every error as "<yaml path>: what" or "<yaml path>: line L: key 'k': what".
class YamlErrors {
 public:
  explicit YamlErrors(const std::filesystem::path& path) : path_(path.string()) {}

  [[noreturn]] void Fail(const std::string& what) const;
  // The message Fail(key, line, what) throws, for an error decided later.
  std::string Message(const std::string& key, int line, const std::string& what) const;
  [[noreturn]] void Fail(const std::string& key, int line, const std::string& what) const;
  [[noreturn]] void Fail(const std::string& key, const YamlEntry& entry,
                         const std::string& what) const {
    Fail(key, entry.line, what);
  }

 private:
  std::string path_;
};

// How a node appears in "got ..." (long scalars are shortened).
std::string Describe(const YAML::Node& node);

// The whole file; `kind` names it in errors ("map YAML file": "cannot open map YAML file: ...").
// Refuses files over 16 MiB (the wrong file) and text that is not UTF-8 (naming line, column).
std::string ReadYamlFileText(const std::filesystem::path& path, const std::string& kind,
                             const YamlErrors& errors);

// The parsed document; malformed YAML fails with the line and column yaml-cpp reports.
YAML::Node ParseYamlText(const std::string& text, const YamlErrors& errors);

// The entries of a mapping by key, with the lines of their keys. A repeated key fails as
// "key '<key_prefix><key>': appears twice (first at line N)". Keys that are not scalars are left
// out (compare the sizes to reject them).
std::map<std::string, YamlEntry> MappingEntries(const YAML::Node& mapping,
                                                const std::string& key_prefix,
                                                const YamlErrors& errors);

}  // namespace fleetmerge
