#include "io/map_names.hpp"

#include <algorithm>
#include <map>
#include <set>

#include "core/error.hpp"

namespace fleetmerge {
namespace fs = std::filesystem;

std::string TopicForName(const std::string& topic) {
  std::string out;
  for (const char c : topic) {
    if (c == '/') {
      if (!out.empty() && out.back() != '_') out += '_';
    } else {
      out += c;
    }
  }
  while (!out.empty() && out.back() == '_') out.pop_back();
  return out;
}

std::vector<std::string> UniqueMapNames(const std::vector<MapNameInput>& inputs,
                                        const std::vector<std::string>& taken) {
  const std::size_t n = inputs.size();
  const auto suffix = [&](std::size_t i) {
    return inputs[i].topic.empty() ? std::string() : "_" + TopicForName(inputs[i].topic);
  };
  std::vector<std::string> names(n);
  std::map<std::string, int> uses;
  for (const std::string& t : taken) ++uses[t];
  for (std::size_t i = 0; i < n; ++i) {
    names[i] = inputs[i].path.stem().string() + suffix(i);
    ++uses[names[i]];
  }
  // The folders above each colliding map, innermost first.
  std::map<std::string, std::vector<std::size_t>> groups;
  for (std::size_t i = 0; i < n; ++i) {
    if (uses[names[i]] > 1) groups[names[i]].push_back(i);
  }
  std::set<std::string> fixed;  // names that stay (unique ones and `taken`)
  for (const std::string& t : taken) fixed.insert(t);
  for (std::size_t i = 0; i < n; ++i) {
    if (uses[names[i]] == 1) fixed.insert(names[i]);
  }
  for (auto& [base, members] : groups) {
    std::vector<std::vector<std::string>> folders;
    std::size_t depth = 0;
    for (std::size_t i : members) {
      std::vector<std::string> parts;
      const fs::path parent = fs::absolute(inputs[i].path).lexically_normal().parent_path();
      for (const auto& part : parent) {
        if (part != parent.root_path() && !part.empty() && part != "/") parts.push_back(part);
      }
      std::reverse(parts.begin(), parts.end());
      depth = std::max(depth, parts.size());
      folders.push_back(parts);
    }
    bool done = false;
    for (std::size_t k = 1; k <= depth && !done; ++k) {
      std::vector<std::string> candidates;
      for (std::size_t m = 0; m < members.size(); ++m) {
        std::string name;
        for (std::size_t d = std::min(k, folders[m].size()); d-- > 0;) {
          name += (name.empty() ? "" : "/") + folders[m][d];
        }
        candidates.push_back((name.empty() ? inputs[members[m]].path.stem().string() : name) +
                             suffix(members[m]));
      }
      std::set<std::string> distinct(candidates.begin(), candidates.end());
      bool clash = distinct.size() != candidates.size();
      for (const auto& c : candidates) clash = clash || fixed.count(c) > 0;
      if (!clash) {
        for (std::size_t m = 0; m < members.size(); ++m) names[members[m]] = candidates[m];
        fixed.insert(candidates.begin(), candidates.end());
        done = true;
      }
    }
    if (!done) {  // same folders all the way up: only the file names differ (a.yaml vs a.pgm?)
      for (std::size_t m = 0; m < members.size(); ++m) {
        const std::size_t i = members[m];
        std::string name = fs::absolute(inputs[i].path).lexically_normal().generic_string();
        if (!name.empty() && name.front() == '/') name.erase(0, 1);
        name += suffix(i);
        if (fixed.count(name)) {
          throw Error(inputs[i].path.string() +
                      (inputs[i].topic.empty() ? "" : " topic " + inputs[i].topic) +
                      " is listed twice");
        }
        names[i] = name;
        fixed.insert(name);
      }
    }
  }
  return names;
}

}  // namespace fleetmerge
