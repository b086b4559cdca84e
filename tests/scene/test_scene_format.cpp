// docs/scene-format.md lists exactly the keys the scene readers accept.
//
// The readers record the allowed keys of every map they check
// (InputNode::allow_only -> scene::allowed_keys_seen()). This test reads the
// complete examples of the page ("# example: <kind>" blocks) and every scene
// in runs/, so that every map of every scene kind is checked at least once,
// then compares the recorded key paths with the keys of the page's tables:
// a key a reader accepts must be documented, a documented key must be one
// a reader accepts (and was reached, so the examples cover it).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>

#include "pcsim/scene/catenary_scene.hpp"
#include "pcsim/scene/composition.hpp"
#include "pcsim/scene/pantograph_scene.hpp"
#include "pcsim/scene/run_scene.hpp"

namespace fs = std::filesystem;
using pcsim::scene::InputNode;

namespace {

const std::string kDoc = std::string(PCSIM_SOURCE_DIR) + "/docs/scene-format.md";

struct Page {
  std::set<std::string> keys;                                 // documented key paths
  std::vector<std::pair<std::string, std::string>> examples;  // (kind, YAML text)
  std::string text;
};

Page read_page() {
  Page page;
  std::ifstream in(kDoc);
  std::string line, block;
  bool in_key_table = false, in_yaml = false;
  const std::regex backticked("`([^`]+)`");
  while (std::getline(in, line)) {
    page.text += line + "\n";
    if (in_yaml) {
      if (line == "```") {
        in_yaml = false;
        std::smatch m;
        if (std::regex_search(block, m, std::regex("^# example: (\\w+)")))
          page.examples.emplace_back(m[1], block);
      } else {
        block += line + "\n";
      }
      continue;
    }
    if (line == "```yaml") {
      in_yaml = true;
      block.clear();
      continue;
    }
    if (line.rfind("| key |", 0) == 0) in_key_table = true;
    if (line.empty() || line[0] != '|') in_key_table = false;
    if (!in_key_table || line.rfind("| `", 0) != 0) continue;
    const std::string first_cell = line.substr(1, line.find('|', 1) - 1);
    for (std::sregex_iterator it(first_cell.begin(), first_cell.end(), backticked), end; it != end;
         ++it)
      page.keys.insert((*it)[1]);
  }
  return page;
}

// Reads a scene with the reader of its kind ("run", "modes", "pantograph").
void read_scene(const InputNode& scene, const std::string& kind) {
  if (kind == "run") {
    pcsim::scene::load_run_scene(scene);
  } else if (kind == "pantograph") {
    pcsim::scene::load_pantograph_study_scene(scene);
  } else {
    pcsim::scene::load_catenary_scene(scene);
    pcsim::scene::load_modes_section(scene);
  }
}

std::string kind_of(const InputNode& scene) {
  if (scene.has("study")) return "pantograph";
  return scene.has("pantographs") ? "run" : "modes";
}

// Every scene in runs/ (not the designs, models and data they use).
std::vector<std::string> repository_scenes() {
  std::vector<std::string> out;
  for (const auto& e : fs::recursive_directory_iterator(std::string(PCSIM_SOURCE_DIR) + "/runs")) {
    const std::string path = e.path().string();
    if (e.path().extension() != ".yaml" || path.find("/designs/") != std::string::npos ||
        path.find("/models/") != std::string::npos)
      continue;
    out.push_back(path);
  }
  return out;
}

// The key paths the readers allowed in the given files: "a.b" for key b of map a.
std::set<std::string> allowed_keys(const std::set<std::string>& files) {
  std::set<std::string> out;
  for (const auto& [file, maps] : pcsim::scene::allowed_keys_seen()) {
    if (!files.count(file)) continue;
    for (const auto& [path, keys] : maps)
      for (const auto& key : keys) out.insert(path.empty() ? key : path + "." + key);
  }
  return out;
}

std::string list(const std::set<std::string>& keys) {
  std::string s;
  for (const auto& k : keys) s += "  " + k + "\n";
  return s;
}

}  // namespace

TEST(SceneFormat, ExamplesAndRepositoryScenesAreReadable) {
  const Page page = read_page();
  std::set<std::string> kinds;
  for (std::size_t i = 0; i < page.examples.size(); ++i) {
    const auto& [kind, text] = page.examples[i];
    const std::string file =
        std::string(PCSIM_SOURCE_DIR) + "/runs/scene-format-example-" + std::to_string(i) + ".yaml";
    SCOPED_TRACE("example " + std::to_string(i) + " (" + kind + ") of docs/scene-format.md");
    EXPECT_NO_THROW(read_scene(pcsim::scene::load_composed_text(text, file), kind));
    kinds.insert(kind);
  }
  EXPECT_EQ(kinds, (std::set<std::string>{"modes", "run", "pantograph"}));
  const auto scenes = repository_scenes();
  EXPECT_GE(scenes.size(), 25u);
  for (const auto& path : scenes) {
    SCOPED_TRACE(path);
    EXPECT_NO_THROW({
      const auto scene = pcsim::scene::load_composed(path);
      read_scene(scene, kind_of(scene));
    });
  }
}

TEST(SceneFormat, DocumentedKeysAreTheKeysTheReadersAccept) {
  const Page page = read_page();
  std::set<std::string> files;
  for (std::size_t i = 0; i < page.examples.size(); ++i) {
    const std::string file =
        std::string(PCSIM_SOURCE_DIR) + "/runs/scene-format-example-" + std::to_string(i) + ".yaml";
    read_scene(pcsim::scene::load_composed_text(page.examples[i].second, file), page.examples[i].first);
    files.insert(file);
  }
  for (const auto& path : repository_scenes()) {
    const auto scene = pcsim::scene::load_composed(path);
    read_scene(scene, kind_of(scene));
    files.insert(path);
  }
  const auto allowed = allowed_keys(files);
  ASSERT_GT(allowed.size(), 50u);
  std::set<std::string> undocumented, unknown;
  for (const auto& k : allowed)
    if (!page.keys.count(k)) undocumented.insert(k);
  for (const auto& k : page.keys)
    if (!allowed.count(k)) unknown.insert(k);
  EXPECT_TRUE(undocumented.empty()) << "accepted by the readers, missing in docs/scene-format.md:\n"
                                    << list(undocumented);
  EXPECT_TRUE(unknown.empty()) << "in docs/scene-format.md, not accepted by any reader (or not "
                                  "reached by the examples):\n"
                               << list(unknown);
  // The composition keys are the composer's, not a reader's: documented in prose.
  EXPECT_NE(page.text.find("`base: FILE`"), std::string::npos);
  EXPECT_NE(page.text.find("`set: {PATH: VALUE, ...}`"), std::string::npos);
}
