// Checks the one-way module graph: every #include "module/..." in a module's folder names the
// module itself or one it depends on (transitively), as declared once in CMakeLists.txt.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace {

using Graph = std::map<std::string, std::set<std::string>>;

// Parses "module: dep dep" lines (# comments allowed).
Graph read_graph(std::istream& in) {
  Graph graph;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    const auto colon = line.find(':');
    std::istringstream deps(line.substr(colon + 1));
    auto& entry = graph[line.substr(0, colon)];
    for (std::string dep; deps >> dep;) entry.insert(dep);
  }
  return graph;
}

// Each module with itself and everything it reaches.
Graph closure(const Graph& graph) {
  Graph result;
  for (const auto& [module, deps] : graph) {
    std::set<std::string> reached{module};
    std::vector<std::string> stack(deps.begin(), deps.end());
    while (!stack.empty()) {
      const std::string next = stack.back();
      stack.pop_back();
      if (!reached.insert(next).second) continue;
      const auto it = graph.find(next);
      if (it != graph.end()) stack.insert(stack.end(), it->second.begin(), it->second.end());
    }
    result[module] = reached;
  }
  return result;
}

// The folder named by each `#include "folder/..."` line of a text (a hand-written scan: GCC 12
// warns falsely inside std::regex under the sanitizers).
std::vector<std::pair<std::string, std::string>> quoted_includes(const std::string& text) {
  std::vector<std::pair<std::string, std::string>> found;
  std::istringstream lines(text);
  for (std::string line; std::getline(lines, line);) {
    std::size_t k = line.find_first_not_of(" \t");
    if (k == std::string::npos || line[k] != '#') continue;
    k = line.find_first_not_of(" \t", k + 1);
    if (k == std::string::npos || line.compare(k, 7, "include") != 0) continue;
    const std::size_t open = line.find('"', k + 7);
    if (open == std::string::npos) continue;
    const std::size_t slash = line.find('/', open + 1);
    const std::size_t close = line.find('"', open + 1);
    if (slash == std::string::npos || close == std::string::npos || slash > close) continue;
    found.emplace_back(line.substr(open + 1, slash - open - 1), line.substr(k - 1));
  }
  return found;
}

// The violations in one file's text: includes of another module that `module` may not use.
std::vector<std::string> violations(const Graph& allowed, const std::string& module, const std::string& file,
                                    const std::string& text) {
  std::vector<std::string> found;
  for (const auto& [target, line] : quoted_includes(text)) {
    if (!allowed.count(target)) continue;  // not a module (e.g. a system folder)
    if (!allowed.at(module).count(target)) found.push_back(file + " includes " + line);
  }
  return found;
}

TEST(ModuleGraph, CheckerFindsAForbiddenInclude) {
  std::istringstream text("core:\ncurves: core\nmeshes: core\nsurfaces: curves meshes\n");
  const Graph allowed = closure(read_graph(text));
  EXPECT_TRUE(violations(allowed, "surfaces", "a.cpp", "#include \"core/errors.h\"\n").empty());
  EXPECT_EQ(violations(allowed, "meshes", "m.h", "#include \"curves/bezier_curve.h\"\n").size(), 1u);
  EXPECT_EQ(violations(allowed, "meshes", "m.h", "# include \"surfaces/patch.h\"\n").size(), 1u);
  EXPECT_EQ(violations(allowed, "core", "c.h", "#include \"meshes/x.h\"\n#include <vector>\n").size(), 1u);
}

TEST(ModuleGraph, SourcesIncludeOnlyWhatTheGraphAllows) {
  std::ifstream graph_file(PATCHWORK_MODULE_GRAPH);
  ASSERT_TRUE(graph_file) << "cannot read " << PATCHWORK_MODULE_GRAPH;
  const Graph graph = read_graph(graph_file);
  ASSERT_TRUE(graph.count("meshes") && graph.count("curves") && graph.count("surfaces"));
  const Graph allowed = closure(graph);
  // The rule the design insists on, stated here as well: meshes knows nothing of Bezier.
  EXPECT_FALSE(allowed.at("meshes").count("curves"));
  EXPECT_FALSE(allowed.at("meshes").count("surfaces"));

  namespace fs = std::filesystem;
  std::vector<std::string> found;
  int files = 0;
  for (const auto& [module, reach] : allowed) {
    const fs::path folder = fs::path(PATCHWORK_SOURCE_DIR) / module;
    if (!fs::exists(folder)) continue;
    for (const auto& entry : fs::recursive_directory_iterator(folder)) {
      const auto extension = entry.path().extension();
      if (extension != ".h" && extension != ".cpp") continue;
      std::ifstream in(entry.path());
      std::stringstream text;
      text << in.rdbuf();
      const auto more = violations(allowed, module, entry.path().string(), text.str());
      found.insert(found.end(), more.begin(), more.end());
      ++files;
    }
  }
  EXPECT_GT(files, 10);
  for (const auto& violation : found) ADD_FAILURE() << violation;
}

}  // namespace
