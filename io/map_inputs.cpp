#include "io/map_inputs.hpp"

#include "core/error.hpp"
#include "io/bag_maps.hpp"
#include "io/map_names.hpp"

namespace fleetmerge {
namespace fs = std::filesystem;
namespace {

fs::path Canonical(const fs::path& path) {
  std::error_code ec;
  fs::path canonical = fs::weakly_canonical(path, ec);
  if (ec) canonical = fs::absolute(path).lexically_normal();
  return canonical.has_filename() ? canonical : canonical.parent_path();
}

}  // namespace

fs::path NamingPath(const fs::path& path) {
  fs::path p = path.lexically_normal();
  if (!p.has_filename()) p = p.parent_path();
  std::error_code ec;
  if ((p.extension() == ".db3" || p.extension() == ".mcap") &&
      fs::is_regular_file(p.parent_path() / "metadata.yaml", ec)) {
    p = p.parent_path();
    if (p.empty()) p = fs::current_path();
  }
  if (p.filename() == "." || p.empty()) p = fs::absolute(p).lexically_normal().parent_path();
  return p;
}

std::vector<JobMap> ExpandMapInputs(const std::vector<MapInput>& inputs) {
  std::vector<JobMap> maps;
  std::vector<MapNameInput> unnamed;
  std::vector<std::size_t> unnamed_index;
  std::vector<std::string> taken;
  std::vector<fs::path> canonical;
  for (const MapInput& input : inputs) {
    std::vector<std::string> topics = {""};
    if (IsBagPath(input.path)) topics = BagMapTopics(input.path, input.topics);
    if (!input.name.empty() && topics.size() > 1) {
      throw Error(input.source.string() + ": the name '" + input.name + "' is given to a bag " +
                  "with " + std::to_string(topics.size()) + " map topics; pick one topic");
    }
    for (const std::string& topic : topics) {
      const fs::path c = Canonical(input.path);
      for (std::size_t m = 0; m < maps.size(); ++m) {
        if (canonical[m] == c && maps[m].topic == topic) {
          throw Error(input.source.string() + (topic.empty() ? "" : " topic " + topic) +
                      " is listed twice (the same file as " + maps[m].source.string() + ")");
        }
      }
      canonical.push_back(c);
      maps.push_back({input.name, input.source, input.path, topic, false, Pose2(), std::nullopt});
      if (input.name.empty()) {
        unnamed.push_back({NamingPath(input.path), topics.size() > 1 ? topic : ""});
        unnamed_index.push_back(maps.size() - 1);
      } else {
        taken.push_back(input.name);
      }
    }
  }
  const std::vector<std::string> names = UniqueMapNames(unnamed, taken);
  for (std::size_t k = 0; k < names.size(); ++k) maps[unnamed_index[k]].name = names[k];
  return maps;
}

LoadedMap LoadJobMap(const JobMap& map, std::int64_t max_cells) {
  if (!map.topic.empty()) return LoadBagMap(map.path, map.topic, max_cells);
  return LoadMap(map.path, max_cells);
}

}  // namespace fleetmerge
