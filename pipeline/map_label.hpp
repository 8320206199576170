// How notes and errors of a fleet merge name a map: by its name when the caller gave the names
// (FleetOptions::map_names: a job's maps, the API's), else by its number in job order, from 1.
#pragma once

#include <string>
#include <vector>

namespace fleetmerge {

// "map 'run3'", or "map 3" without names.
inline std::string MapLabel(const std::vector<std::string>& names, int m) {
  if (static_cast<std::size_t>(m) < names.size()) return "map '" + names[m] + "'";
  return "map " + std::to_string(m + 1);
}

// "'run3', 'run4'", or "3, 4" without names.
inline std::string MapList(const std::vector<std::string>& names, const std::vector<int>& maps) {
  std::string text;
  for (const int m : maps) {
    text += text.empty() ? "" : ", ";
    text +=
        static_cast<std::size_t>(m) < names.size() ? "'" + names[m] + "'" : std::to_string(m + 1);
  }
  return text;
}

// " (in job order)" when maps are numbered, for errors that name a map by MapLabel.
inline const char* JobOrderNote(const std::vector<std::string>& names) {
  return names.empty() ? " (in job order)" : "";
}

}  // namespace fleetmerge
