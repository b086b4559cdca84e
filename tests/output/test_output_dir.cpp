// OutputDir: only folders that pcsim made are written, replaced or deleted;
// every outcome is the same on every rank (run on 1 and 2 ranks).
// pcsim-test-ranks: 1 2
#include <gtest/gtest.h>
#include <mpi.h>
#include <stdlib.h>

#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>

#include "pcsim/core/error.hpp"
#include "pcsim/output/output_dir.hpp"

namespace fs = std::filesystem;
using pcsim::InputError;
using pcsim::output::OutputDir;
using pcsim::output::OutputRequest;

namespace {

int rank() {
  int r = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &r);
  return r;
}

// A fresh folder for one test, the same path on every rank.
class OutputDirTest : public ::testing::Test {
 protected:
  void SetUp() override {
    std::string path;
    if (rank() == 0) {
      std::string templ = (fs::temp_directory_path() / "pcsim-outdir-XXXXXX").string();
      path = mkdtemp(templ.data());
    }
    int size = static_cast<int>(path.size());
    MPI_Bcast(&size, 1, MPI_INT, 0, MPI_COMM_WORLD);
    path.resize(size);
    MPI_Bcast(path.data(), size, MPI_CHAR, 0, MPI_COMM_WORLD);
    root_ = path;
  }
  void TearDown() override {
    MPI_Barrier(MPI_COMM_WORLD);
    if (rank() == 0) fs::remove_all(root_);
  }
  OutputRequest request(const std::string& name) const {
    return {(root_ / name).string(), "command line", "-o", "static", "scene.yaml", "scene"};
  }
  std::string path(const std::string& name) const { return (root_ / name).string(); }
  // Folder entries, sorted, as one string ("" when missing), seen by rank 0.
  std::string listing(const std::string& name) const {
    if (!fs::exists(path(name))) return "";
    std::set<std::string> names;
    for (const auto& e : fs::directory_iterator(path(name)))
      names.insert(e.path().filename().string());
    std::string out;
    for (const auto& n : names) out += n + " ";
    return out;
  }
  void write(const std::string& file, const std::string& text) const {
    if (rank() == 0) {
      fs::create_directories(fs::path(file).parent_path());
      std::ofstream(file) << text;
    }
    MPI_Barrier(MPI_COMM_WORLD);
  }
  static std::string read(const std::string& file) {
    std::ifstream in(file);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
  }
  fs::path root_;
};

// Every rank gets the InputError, naming the key and 'needle'.
#define EXPECT_REFUSED(statement, needle)                                           \
  do {                                                                              \
    try {                                                                           \
      statement;                                                                    \
      ADD_FAILURE() << "not refused: " #statement;                                  \
    } catch (const InputError& e) {                                                 \
      EXPECT_EQ(e.key(), "-o");                                                     \
      EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what(); \
    }                                                                               \
  } while (0)

TEST(FolderNames, OnlySingleFolderNamesAreAccepted) {
  for (const char* bad : {"", ".", "..", "a/b", "../../x", "a\\b", "/abs"})
    EXPECT_NE(pcsim::output::invalid_folder_name_reason(bad), "") << bad;
  for (const char* good : {"en50318-300", "run 1", "a..b", ".hidden"})
    EXPECT_EQ(pcsim::output::invalid_folder_name_reason(good), "") << good;
}

TEST_F(OutputDirTest, NewFolderIsMarkedLockedAndCommitted) {
  {
    OutputDir out(MPI_COMM_WORLD, request("a/b/result"));
    if (rank() == 0) {
      EXPECT_EQ(listing("a/b/result.partial"), ".pcsim-result ");
      EXPECT_NE(read(path("a/b/result.partial/.pcsim-result")).find("\"complete\": false"),
                std::string::npos);
      EXPECT_TRUE(fs::exists(path("a/b/result.pcsim-lock")));
      std::ofstream(out.file("data.txt")) << "new";
    }
    out.commit();
  }
  if (rank() == 0) {
    EXPECT_EQ(listing("a/b"), "result ");  // no partial folder, lock or old copy
    EXPECT_EQ(listing("a/b/result"), ".pcsim-result data.txt ");
    const std::string manifest = read(path("a/b/result/.pcsim-result"));
    for (const char* key : {"\"complete\": true", "\"command\": \"static\"",
                            "\"scene_file\": \"scene.yaml\"", "\"finished\""})
      EXPECT_NE(manifest.find(key), std::string::npos) << key << " in " << manifest;
  }
}

TEST_F(OutputDirTest, FailedRunRemovesWhatItMade) {
  { OutputDir out(MPI_COMM_WORLD, request("a/b/result")); }  // no commit: the run failed
  if (rank() == 0) EXPECT_EQ(listing(""), "");               // not even a/ is left
}

TEST_F(OutputDirTest, ForeignFolderIsRefusedOnEveryRankAndKept) {
  write(path("mine/notes.txt"), "user data");
  EXPECT_REFUSED(OutputDir(MPI_COMM_WORLD, request("mine")), "not written by pcsim");
  if (rank() == 0) {
    EXPECT_EQ(listing(""), "mine ");
    EXPECT_EQ(read(path("mine/notes.txt")), "user data");
  }
}

TEST_F(OutputDirTest, EarlierResultIsReplacedOnlyByACompleteOne) {
  for (const char* text : {"first", "second"}) {
    OutputDir out(MPI_COMM_WORLD, request("result"));
    if (rank() == 0) {
      if (std::string(text) == "second")  // the earlier result is intact while the run goes on
        EXPECT_EQ(read(path("result/data.txt")), "first");
      std::ofstream(out.file("data.txt")) << text;
    }
    out.commit();
  }
  if (rank() == 0) {
    EXPECT_EQ(listing(""), "result ");
    EXPECT_EQ(read(path("result/data.txt")), "second");
  }
}

TEST_F(OutputDirTest, CommitKeepsNewResultsWhenTheFolderBecameForeign) {
  OutputDir out(MPI_COMM_WORLD, request("result"));
  if (rank() == 0) std::ofstream(out.file("data.txt")) << "new";
  write(path("result/notes.txt"), "made by hand during the run");
  EXPECT_REFUSED(out.commit(), "the new results are kept in " + path("result.partial"));
  if (rank() == 0) {
    EXPECT_EQ(read(path("result/notes.txt")), "made by hand during the run");
    EXPECT_EQ(read(path("result.partial/data.txt")), "new");
  }
}

TEST_F(OutputDirTest, NewResultsOfAFailedCommitOutliveTheObject) {
  {
    OutputDir out(MPI_COMM_WORLD, request("result"));
    if (rank() == 0) std::ofstream(out.file("data.txt")) << "new";
    write(path("result/notes.txt"), "by hand");
    EXPECT_THROW(out.commit(), InputError);
  }
  if (rank() == 0) EXPECT_EQ(read(path("result.partial/data.txt")), "new");
}

TEST_F(OutputDirTest, SecondWriterIsRefusedAndTheFirstGoesOn) {
  OutputDir first(MPI_COMM_WORLD, request("result"));
  if (rank() == 0) std::ofstream(first.file("data.txt")) << "first";
  EXPECT_REFUSED(OutputDir(MPI_COMM_WORLD, request("result")), "another pcsim run");
  if (rank() == 0) EXPECT_EQ(read(path("result.partial/data.txt")), "first");
  first.commit();
  if (rank() == 0) EXPECT_EQ(read(path("result/data.txt")), "first");
}

TEST_F(OutputDirTest, LeftoverPartialWithDataIsKeptAndRefused) {
  // An interrupted run's partial folder: the manifest and some results.
  write(path("result.partial/.pcsim-result"),
        R"({"pcsim_result": 1, "command": "run", "scene_file": "s.yaml", "started": "T0"})");
  write(path("result.partial/results.h5"), "data");
  EXPECT_REFUSED(OutputDir(MPI_COMM_WORLD, request("result")), "interrupted pcsim run (run s.yaml");
  if (rank() == 0) EXPECT_EQ(listing("result.partial"), ".pcsim-result results.h5 ");
  // With the manifest alone it holds nothing: it is replaced.
  if (rank() == 0) fs::remove(path("result.partial/results.h5"));
  OutputDir out(MPI_COMM_WORLD, request("result"));
  out.commit();
  if (rank() == 0) EXPECT_EQ(listing(""), "result ");
}

TEST_F(OutputDirTest, UnwrittenPartialFolderIsReplaced) {
  // A run killed between making its partial folder and renaming its manifest
  // into it (a sweep's case under SIGKILL) leaves it empty or holding only
  // the manifest's temporary file: nothing of a result, so not refused.
  for (const char* left : {"", ".pcsim-result.tmp"}) {
    if (*left) {
      write(path(std::string("result.partial/") + left), R"({"pcsim_res)");
    } else {
      if (rank() == 0) fs::create_directories(path("result.partial"));
      MPI_Barrier(MPI_COMM_WORLD);
    }
    OutputDir out(MPI_COMM_WORLD, request("result"));
    out.commit();
    if (rank() == 0) EXPECT_EQ(listing(""), "result ") << "left: '" << left << "'";
    if (rank() == 0) EXPECT_EQ(listing("result"), ".pcsim-result ");
    if (rank() == 0) fs::remove_all(path("result"));
    MPI_Barrier(MPI_COMM_WORLD);
  }
}

TEST_F(OutputDirTest, ForeignPartialFolderIsRefused) {
  write(path("result.partial/mine.txt"), "user data");
  EXPECT_REFUSED(OutputDir(MPI_COMM_WORLD, request("result")), "not written by pcsim");
  if (rank() == 0) EXPECT_EQ(read(path("result.partial/mine.txt")), "user data");
}

}  // namespace
