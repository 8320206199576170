// Typed reads of a YAML document against a fixed schema, for files where every key is known
// (job files): each value is read with its key path ("jobs[2].hough.n_theta") and the line of its
// key, and every mistake fails in the house format of io/yaml_errors.hpp:
//   "<file>: line L: key 'jobs[2].hough.n_theta': expected an integer in [8, 3600], got 'abc'"
// Internal to io/: it exposes yaml-cpp types.
#pragma once

#include <yaml-cpp/yaml.h>

#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "io/yaml_errors.hpp"

namespace fleetmerge {

// A value, its key path and the 1-based line of its key ("" and the document's line for the
// root; list elements are "key[i]", 0-based, at their own line).
struct YamlField {
  YAML::Node value;
  std::string key;
  int line = 0;
};

// "a, b, c"
std::string JoinWords(const std::vector<std::string>& words);

// Fails with "expected <expected>, got <value>"; a quoted number or boolean is a string in
// YAML, and the message says so.
[[noreturn]] void FailExpected(const YamlField& field, const std::string& expected,
                               const YamlErrors& errors);

// Element `index` of a list field.
YamlField ListElement(const YamlField& list, std::size_t index);

// A mapping whose keys are checked when it is opened: `field` must be a mapping (else "expected
// <what>") whose keys are plain names from `allowed`, each once.
class YamlMapping {
 public:
  YamlMapping(const YamlField& field, const std::vector<std::string>& allowed,
              const std::string& what, const YamlErrors& errors);

  std::optional<YamlField> Find(const std::string& name) const;
  // Fails "missing: expected <expected>" at the mapping's line when `name` is absent.
  YamlField Require(const std::string& name, const std::string& expected) const;

 private:
  std::string Prefix() const { return field_.key.empty() ? "" : field_.key + "."; }

  YamlField field_;
  std::map<std::string, YamlEntry> entries_;
  const YamlErrors& errors_;
};

// A non-empty scalar, taken as text (`name: 2019` is the name "2019").
std::string ReadString(const YamlField& field, const std::string& expected,
                       const YamlErrors& errors);
// An unquoted integer in [lo, hi]; hi == INT_MAX reads "an integer >= lo" in messages.
long long ReadInteger(const YamlField& field, long long lo, long long hi, const YamlErrors& errors);
// An unquoted finite number in [lo, hi], or (lo, hi] when lo_open; hi may be infinity.
double ReadNumber(const YamlField& field, double lo, double hi, bool lo_open,
                  const YamlErrors& errors);
// An unquoted YAML boolean (true/false; yaml-cpp also takes yes/no, on/off), not 1/0.
bool ReadBool(const YamlField& field, const YamlErrors& errors);

// One of the listed names, exactly; fails "expected one of a, b, c".
template <typename Enum>
Enum ReadChoice(const YamlField& field, const std::vector<std::pair<std::string, Enum>>& choices,
                const YamlErrors& errors) {
  std::vector<std::string> names;
  for (const auto& [name, value] : choices) {
    if (field.value.IsScalar() && field.value.Scalar() == name) return value;
    names.push_back(name);
  }
  FailExpected(field, "one of " + JoinWords(names), errors);
}

}  // namespace fleetmerge
