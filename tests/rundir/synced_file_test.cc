// rundir/synced_file.h: the one writer every file taebp puts in place goes
// through (tests/layers checks that nothing else renames a file into place).
#include "taebp/rundir/synced_file.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <stdlib.h>

namespace taebp {
namespace {

namespace fs = std::filesystem;

std::string Read(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

class SyncedFile : public ::testing::Test {
 protected:
  void SetUp() override {
    char tmpl[] = "/tmp/taebp_synced_XXXXXX";
    ASSERT_NE(::mkdtemp(tmpl), nullptr);
    dir_ = tmpl;
  }
  void TearDown() override { fs::remove_all(dir_); }
  int Entries() const {
    int n = 0;
    for (const auto& e : fs::directory_iterator(dir_)) n += !e.path().empty();
    return n;
  }
  fs::path dir_;
};

TEST_F(SyncedFile, AStreamedFileIsInPlaceOnlyOnceCommitted) {
  const fs::path file = dir_ / "table.csv";
  std::ofstream(file) << "old\n";
  {
    SyncedWriter w(file.string());
    w.Stream() << "new,";
    w.Stream() << std::string(1 << 20, 'x') << "\n";  // larger than any buffer
    EXPECT_EQ(Read(file), "old\n");                   // not yet
    EXPECT_EQ(Entries(), 2);                           // the file and its temporary
    w.Commit();
  }
  EXPECT_EQ(Read(file).substr(0, 4), "new,");
  EXPECT_EQ(Read(file).size(), 4u + (1u << 20) + 1u);
  EXPECT_EQ(Entries(), 1);  // no temporary left
  // A scratch file (not synced: it is copied into a results folder synced).
  {
    SyncedWriter w(file.string(), /*sync=*/false);
    w.Stream() << "scratch\n";
    w.Commit();
  }
  EXPECT_EQ(Read(file), "scratch\n");
  EXPECT_EQ(Entries(), 1);
}

TEST_F(SyncedFile, AWriterLeftUncommittedLeavesTheFileAsItWas) {
  const fs::path file = dir_ / "table.csv";
  std::ofstream(file) << "old\n";
  {
    SyncedWriter w(file.string());
    w.Stream() << "half a table";
    std::string name;
    bool temporary = false;
    for (const auto& e : fs::directory_iterator(dir_))
      temporary = temporary || IsWriterTemporary(e.path().filename().string(), &name);
    EXPECT_TRUE(temporary);  // the sweep's and the run's clean-up knows the name
    EXPECT_EQ(name, "table.csv");
  }  // an exception unwinding past it, say
  EXPECT_EQ(Read(file), "old\n");
  EXPECT_EQ(Entries(), 1);
}

TEST_F(SyncedFile, AWriterIntoAMissingFolderSaysWhichFile) {
  const fs::path file = dir_ / "no" / "table.csv";
  try {
    SyncedWriter w(file.string());
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("cannot write " + file.string() + ": open: "),
              std::string::npos)
        << e.what();
  }
}

TEST_F(SyncedFile, PutInPlaceAndAFolderThatLostTheRace) {
  const fs::path picture = dir_ / "shot.png.part", out = dir_ / "shot.png";
  std::ofstream(picture) << "png";
  PutInPlace(picture.string(), out.string());
  EXPECT_EQ(Read(out), "png");
  EXPECT_FALSE(fs::exists(picture));
  // A folder generated twice (two processes filling the network cache): the
  // first is kept, the second removed.
  const fs::path a = dir_ / "a.tmp.1", b = dir_ / "a.tmp.2", cache = dir_ / "cache";
  fs::create_directories(a);
  fs::create_directories(b);
  std::ofstream(a / "net.xml") << "first";
  std::ofstream(b / "net.xml") << "second";
  EXPECT_TRUE(PutFolderInPlace(a.string(), cache.string()));
  EXPECT_FALSE(PutFolderInPlace(b.string(), cache.string()));
  EXPECT_EQ(Read(cache / "net.xml"), "first");
  EXPECT_FALSE(fs::exists(b));
}

}  // namespace
}  // namespace taebp
