#include "io/yaml_fields.hpp"

#include <algorithm>
#include <climits>
#include <cmath>
#include <sstream>

namespace fleetmerge {

std::string JoinWords(const std::vector<std::string>& words) {
  std::string text;
  for (const std::string& word : words) text += (text.empty() ? "" : ", ") + word;
  return text;
}

void FailExpected(const YamlField& field, const std::string& expected, const YamlErrors& errors) {
  double number = 0.0;
  bool boolean = false;
  const bool quoted = field.value.IsScalar() && field.value.Tag() == "!" &&
                      (YAML::convert<double>::decode(field.value, number) ||
                       YAML::convert<bool>::decode(field.value, boolean));
  errors.Fail(field.key, field.line,
              "expected " + expected + ", got " + Describe(field.value) +
                  (quoted ? " (quoted, so a string)" : ""));
}

YamlField ListElement(const YamlField& list, std::size_t index) {
  const YAML::Node value = list.value[index];
  // yaml-cpp marks an empty element at the start of the next line; a null mark: the list's.
  const int line = value.Mark().is_null() ? list.line : value.Mark().line + 1;
  return {value, list.key + "[" + std::to_string(index) + "]", line};
}

YamlMapping::YamlMapping(const YamlField& field, const std::vector<std::string>& allowed,
                         const std::string& what, const YamlErrors& errors)
    : field_(field), errors_(errors) {
  if (!field.value.IsMap()) FailExpected(field, what, errors);
  entries_ = MappingEntries(field.value, Prefix(), errors);
  if (entries_.size() != field.value.size()) {  // MappingEntries leaves such keys out
    errors.Fail(field.key, field.line, "expected plain key names, got a key that is a list");
  }
  for (const auto& [name, entry] : entries_) {
    if (std::find(allowed.begin(), allowed.end(), name) == allowed.end()) {
      errors.Fail(Prefix() + name, entry, "unknown key; allowed here: " + JoinWords(allowed));
    }
  }
}

std::optional<YamlField> YamlMapping::Find(const std::string& name) const {
  const auto it = entries_.find(name);
  if (it == entries_.end()) return std::nullopt;
  return YamlField{it->second.value, Prefix() + name, it->second.line};
}

YamlField YamlMapping::Require(const std::string& name, const std::string& expected) const {
  const std::optional<YamlField> child = Find(name);
  if (!child) errors_.Fail(Prefix() + name, field_.line, "missing: expected " + expected);
  return *child;
}

std::string ReadString(const YamlField& field, const std::string& expected,
                       const YamlErrors& errors) {
  if (!field.value.IsScalar() || field.value.Scalar().empty()) {
    FailExpected(field, expected, errors);
  }
  return field.value.Scalar();
}

long long ReadInteger(const YamlField& field, long long lo, long long hi,
                      const YamlErrors& errors) {
  const std::string expected =
      hi == INT_MAX || hi == LLONG_MAX
          ? "an integer >= " + std::to_string(lo)
          : "an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]";
  long long value = 0;
  if (!field.value.IsScalar() || field.value.Tag() == "!" ||
      !YAML::convert<long long>::decode(field.value, value) || value < lo || value > hi) {
    FailExpected(field, expected, errors);
  }
  return value;
}

double ReadNumber(const YamlField& field, double lo, double hi, bool lo_open,
                  const YamlErrors& errors) {
  std::ostringstream expected;
  expected << "a number ";
  if (std::isinf(hi)) {
    expected << (lo_open ? "> " : ">= ") << lo;
  } else {
    expected << "in " << (lo_open ? "(" : "[") << lo << ", " << hi << "]";
  }
  double value = 0.0;
  if (!field.value.IsScalar() || field.value.Tag() == "!" ||
      !YAML::convert<double>::decode(field.value, value) || !std::isfinite(value) ||
      (lo_open ? value <= lo : value < lo) || value > hi) {
    FailExpected(field, expected.str(), errors);
  }
  return value;
}

bool ReadBool(const YamlField& field, const YamlErrors& errors) {
  bool value = false;
  if (!field.value.IsScalar() || field.value.Tag() == "!" ||
      !YAML::convert<bool>::decode(field.value, value)) {
    FailExpected(field, "true or false", errors);
  }
  return value;
}

}  // namespace fleetmerge
