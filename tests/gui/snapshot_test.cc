// The visual side of the CLI, run as a user would: `taebp snapshot` writes a
// real picture of the figure-8 (re-executing itself under xvfb-run without a
// display), its errors are clear, and `taebp run --gui` (sumo-gui over
// libtraci) gives the same results as the in-process libsumo run.
// Skipped when sumo-gui or xvfb-run is not installed.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "test_support.h"

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

#include <sys/wait.h>
#include <unistd.h>

namespace {

using ::testing::HasSubstr;
namespace fs = std::filesystem;

const std::string kCli = TAEBP_CLI;
const std::string kSource = TAEBP_SOURCE_DIR;
const std::string kPaper = kSource + "/configs/paper.yaml";
const std::string kXvfb = "xvfb-run -a -s '-screen 0 1280x1024x24' ";

bool OnPath(const std::string& program) {
  return std::system(("command -v " + program + " >/dev/null 2>&1").c_str()) == 0;
}

// tools/setup.sh installs both: a missing program is a set-up bug, not a skip.
#define REQUIRE_GUI()                                                                     \
  do {                                                                                    \
    if (!OnPath("sumo-gui")) GTEST_FAIL() << "sumo-gui is missing (Debian package sumo)"; \
    if (!OnPath("xvfb-run")) GTEST_FAIL() << "xvfb-run is missing (Debian package xvfb)"; \
  } while (0)

using taebp::test::TempDir;

struct Result {
  int code = -1;
  std::string output;  // stdout and stderr
};

// Runs a shell command line; `env -u DISPLAY` in front exercises the xvfb path.
Result Shell(const std::string& command, const fs::path& log) {
  const int status = std::system((command + " >" + log.string() + " 2>&1").c_str());
  Result r;
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::ifstream in(log);
  r.output.assign(std::istreambuf_iterator<char>(in), {});
  return r;
}

std::string ReadFile(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

// encounters.csv without its provenance comment (git revision, wall times).
std::string Rows(const fs::path& csv) {
  std::istringstream in(ReadFile(csv));
  std::string line, out;
  while (std::getline(in, line))
    if (!line.empty() && line[0] != '#') out += line + "\n";
  return out;
}

unsigned Be32(const std::string& b, std::size_t at) {
  return (unsigned(static_cast<unsigned char>(b[at])) << 24) |
         (unsigned(static_cast<unsigned char>(b[at + 1])) << 16) |
         (unsigned(static_cast<unsigned char>(b[at + 2])) << 8) |
         unsigned(static_cast<unsigned char>(b[at + 3]));
}

TEST(Snapshot, WritesAPictureOfTheTrackWithoutADisplay) {
  REQUIRE_GUI();
  TempDir tmp;
  const fs::path png = tmp.path() / "pictures" / "figure8.png";
  const Result r = Shell("env -u DISPLAY " + kCli + " snapshot " + kPaper + " --out " +
                             png.string() + " --at 20",
                         tmp.path() / "log.txt");
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("snapshot of no_ebp at t = 20 s"));
  ASSERT_TRUE(fs::exists(png)) << r.output;

  const std::string b = ReadFile(png);
  ASSERT_GE(b.size(), 33u);
  EXPECT_EQ(b.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
  EXPECT_EQ(b.substr(12, 4), "IHDR");
  const unsigned width = Be32(b, 16), height = Be32(b, 20);
  // The snapshot window's view: about 1270 x 534, the figure-8's 2.4 : 1.
  EXPECT_GE(width, 640u);
  EXPECT_LE(width, 4096u);
  EXPECT_GE(height, 240u);
  EXPECT_LE(height, 4096u);
  EXPECT_GT(width, height);
  // A flat colour of that size compresses to a few KB; the track with sixteen
  // vehicles is over 15 KB (about 23 KB in SUMO 1.15).
  EXPECT_GT(b.size(), 15u * 1024) << "a nearly empty picture: is the view framed on the track?";
}

TEST(Snapshot, PolicyAndOverridesAreUsed) {
  REQUIRE_GUI();
  TempDir tmp;
  const fs::path png = tmp.path() / "ta.png";
  const Result r = Shell("env -u DISPLAY " + kCli + " snapshot " + kPaper + " --out " +
                             png.string() + " --at 5 --policy ta_ebp --set scenario.seed=7",
                         tmp.path() / "log.txt");
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("snapshot of ta_ebp at t = 5 s"));
  EXPECT_TRUE(fs::exists(png));
}

TEST(Snapshot, BadArgumentsAreClearErrors) {
  TempDir tmp;
  const fs::path png = tmp.path() / "x.png";
  for (const std::string at : {"0", "-3", "nan"}) {
    const Result r = Shell(kCli + " snapshot " + kPaper + " --out " + png.string() + " --at " + at,
                           tmp.path() / "log.txt");
    EXPECT_EQ(r.code, 2) << at << ": " << r.output;
    EXPECT_THAT(r.output, HasSubstr("--at")) << at;
  }
}

// Checked once sumo-gui is found (tools/setup.sh installs it: missing fails).
TEST(Snapshot, BadPolicyOrMissingOutIsAClearError) {
  if (!OnPath("sumo-gui")) GTEST_FAIL() << "sumo-gui is missing (Debian package sumo)";
  TempDir tmp;
  const fs::path png = tmp.path() / "x.png";
  Result r = Shell(kCli + " snapshot " + kPaper + " --out " + png.string() + " --policy bogus",
                   tmp.path() / "log.txt");
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_THAT(r.output, HasSubstr("bogus"));
  r = Shell(kCli + " snapshot " + kPaper, tmp.path() / "log.txt");  // --out is required
  EXPECT_NE(r.code, 0);
  EXPECT_THAT(r.output, HasSubstr("--out"));
  EXPECT_FALSE(fs::exists(png));
}

// Only PNG is written: another extension is refused before anything runs
// (sumo-gui used to leave a 0-byte file), and a failing run leaves an earlier
// picture at --out as it was, never an empty file.
TEST(Snapshot, OnlyPngAndNeverAnEmptyOrHalfWrittenFile) {
  REQUIRE_GUI();
  TempDir tmp;
  for (const std::string name : {"x.txt", "x", "x.PNG.bak", "x.jpg"}) {
    const fs::path out = tmp.path() / name;
    const Result r =
        Shell("env -u DISPLAY " + kCli + " snapshot " + kPaper + " --out " + out.string(),
              tmp.path() / "log.txt");
    EXPECT_EQ(r.code, 2) << name << ": " << r.output;
    EXPECT_THAT(r.output, HasSubstr(out.string())) << name;
    EXPECT_THAT(r.output, HasSubstr(".png")) << name;
    EXPECT_FALSE(fs::exists(out)) << name;
  }
  const fs::path png = tmp.path() / "earlier.png";
  std::ofstream(png, std::ios::binary) << "an earlier picture";
  // Well-formed XML that SUMO refuses (a lane speed that is not a number):
  // sumo-gui fails after the scenario was accepted.
  std::string net = ReadFile(fs::path(kCli).parent_path() / "sumo_net/figure8.net.xml");
  const std::size_t at = net.find("speed=\"");
  ASSERT_NE(at, std::string::npos);
  net.replace(at, net.find('"', at + 7) - at + 1, "speed=\"fast\"");
  const std::string bad = (tmp.path() / "bad_speed.net.xml").string();
  std::ofstream(bad) << net;
  const Result r = Shell("env -u DISPLAY " + kCli + " snapshot " + kPaper + " --out " +
                             png.string() + " --at 5 --set scenario.network=" + bad,
                         tmp.path() / "log.txt");
  EXPECT_EQ(r.code, 3) << r.output;
  EXPECT_EQ(ReadFile(png), "an earlier picture");
  for (const auto& e : fs::directory_iterator(tmp.path()))
    EXPECT_GT(fs::file_size(e.path()), 0u) << e.path() << " is empty";
}

// The RGB of one pixel of a PNG (python3-pil, which the legend needs too).
std::vector<int> Pixel(const fs::path& png, int x, int y, const fs::path& log) {
  const Result r = Shell("/usr/bin/python3 -c \"from PIL import Image; "
                         "print(*Image.open('" + png.string() + "').convert('RGB').getpixel((" +
                             std::to_string(x) + ", " + std::to_string(y) + ")))\"",
                         log);
  std::istringstream in(r.output);
  std::vector<int> rgb(3, -1);
  in >> rgb[0] >> rgb[1] >> rgb[2];
  return rgb;
}

// --junction frames one junction: the centre of the view is its crossing
// (road, dark), where the whole 4 x 4 grid's centre is the middle of a block
// (white background). On the whole grid the vehicles are drawn larger than
// life: the view is 550 m across (500 m of network, 5 % margin each side) in
// a 1270 x 535 px view, 535/550 px per metre, so a 5 m car takes 14 px at
// 14 / (5 * 535/550) = 2.9 times its size; the junction's 80 m need none.
TEST(Snapshot, FramesOneJunctionAndDrawsVehiclesReadably) {
  REQUIRE_GUI();
  TempDir tmp;
  const std::string grid = kSource + "/configs/grid_throughput.yaml";
  const std::string common = "env -u DISPLAY " + kCli + " snapshot " + grid +
                             " --policy ta_ebp --at 60 --out ";
  const fs::path junction = tmp.path() / "b1.png", whole = tmp.path() / "grid.png";
  Result r = Shell(common + junction.string() + " --junction B1", tmp.path() / "log.txt");
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_THAT(r.output, ::testing::Not(HasSubstr("vehicles drawn")));
  r = Shell(common + whole.string(), tmp.path() / "log.txt");
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("vehicles drawn 2.9x their size"));
  const std::vector<int> at_junction = Pixel(junction, 635, 267, tmp.path() / "p.txt");
  const std::vector<int> at_block = Pixel(whole, 635, 267, tmp.path() / "p.txt");
  ASSERT_GE(at_junction[0], 0) << "no pixel read";
  EXPECT_LT(at_junction[0] + at_junction[1] + at_junction[2], 3 * 100) << "not on the road";
  EXPECT_GT(at_block[0] + at_block[1] + at_block[2], 3 * 200) << "not the block between roads";
  // --zoom 4 on the junction: 20 m across, the crossing fills the view.
  const fs::path close = tmp.path() / "close.png";
  r = Shell(common + close.string() + " --junction B1 --zoom 4", tmp.path() / "log.txt");
  ASSERT_EQ(r.code, 0) << r.output;
  // 400 px west of the centre and 40 px below the lane divider (15 m, 1.5 m).
  const std::vector<int> corner = Pixel(close, 635 - 400, 267 + 40, tmp.path() / "p.txt");
  EXPECT_LT(corner[0] + corner[1] + corner[2], 3 * 100) << "zoomed in, 400 px off centre is road";
  const std::vector<int> corner_far = Pixel(junction, 635 - 400, 267 - 200, tmp.path() / "p.txt");
  EXPECT_GT(corner_far[0] + corner_far[1] + corner_far[2], 3 * 200) << "80 m across: a block";
  // Errors: an unknown junction names the network's own; a zoom that is not
  // a positive number.
  r = Shell(common + junction.string() + " --junction nowhere", tmp.path() / "log.txt");
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_THAT(r.output, HasSubstr("--junction nowhere: no such junction"));
  EXPECT_THAT(r.output, HasSubstr("B1"));
  for (const std::string zoom : {"0", "-1", "nan"}) {
    r = Shell(common + junction.string() + " --zoom " + zoom, tmp.path() / "log.txt");
    EXPECT_EQ(r.code, 2) << zoom << ": " << r.output;
    EXPECT_THAT(r.output, HasSubstr("--zoom")) << zoom;
  }
}

TEST(Snapshot, MissingProgramsAreNamed) {
  if (!OnPath("sumo-gui")) GTEST_FAIL() << "sumo-gui is missing (Debian package sumo)";
  TempDir tmp;
  const fs::path png = tmp.path() / "x.png";
  // No sumo-gui on PATH.
  Result r = Shell("env -u DISPLAY PATH=" + tmp.path().string() + " " + kCli + " snapshot " +
                       kPaper + " --out " + png.string(),
                   tmp.path() / "log.txt");
  EXPECT_NE(r.code, 0);
  EXPECT_THAT(r.output, HasSubstr("sumo-gui is not on PATH"));
  // sumo-gui but no xvfb-run, and no display.
  const fs::path bin = tmp.path() / "bin";
  fs::create_directories(bin);
  std::string sumo_gui;
  {
    FILE* p = popen("command -v sumo-gui", "r");
    char buf[4096] = {};
    if (p && std::fgets(buf, sizeof buf, p)) sumo_gui = buf;
    if (p) pclose(p);
    while (!sumo_gui.empty() && (sumo_gui.back() == '\n' || sumo_gui.back() == '\r')) sumo_gui.pop_back();
  }
  fs::create_symlink(sumo_gui, bin / "sumo-gui");
  r = Shell("env -u DISPLAY PATH=" + bin.string() + " " + kCli + " snapshot " + kPaper +
                " --out " + png.string(),
            tmp.path() / "log.txt");
  EXPECT_NE(r.code, 0);
  EXPECT_THAT(r.output, HasSubstr("xvfb-run is not installed"));
  // run --gui without a display.
  r = Shell("env -u DISPLAY " + kCli + " run " + kPaper + " --gui --out " +
                (tmp.path() / "out").string(),
            tmp.path() / "log.txt");
  EXPECT_NE(r.code, 0);
  EXPECT_THAT(r.output, HasSubstr("DISPLAY is not set"));
  EXPECT_FALSE(fs::exists(tmp.path() / "out"));
}

// sumo-gui (libtraci) and libsumo run the same engine: the same encounters,
// decisions and collisions, so `run --gui` results are the real results.
TEST(RunGui, SameResultsAsTheInProcessRun) {
  REQUIRE_GUI();
  TempDir tmp;
  const std::string common = " run " + kPaper +
                             " --quiet --set scenario.duration=150 --set policies=[no_trust,ta_ebp]";
  const Result plain = Shell(kCli + common + " --out " + (tmp.path() / "plain").string(),
                             tmp.path() / "plain.txt");
  ASSERT_EQ(plain.code, 0) << plain.output;
  const Result gui = Shell("env -u DISPLAY " + kXvfb + kCli + common + " --gui --out " +
                               (tmp.path() / "gui").string(),
                           tmp.path() / "gui.txt");
  ASSERT_EQ(gui.code, 0) << gui.output;
  const std::string rows = Rows(tmp.path() / "plain" / "encounters.csv");
  EXPECT_THAT(rows, HasSubstr("no_trust,"));
  EXPECT_THAT(rows, HasSubstr(",1\n")) << "expected at least one collision under no_trust";
  EXPECT_EQ(rows, Rows(tmp.path() / "gui" / "encounters.csv"));
  // The printed table (stdout) is the same too: sumo-gui's start-up chatter
  // does not end up in it.
  EXPECT_EQ(plain.output, gui.output);
}

}  // namespace

namespace {

// xvfb-run exits 5 when its clean-up cannot remove its temporary folder (seen
// once in CI: "problem while cleaning up temporary directory"), replacing the
// exit code of the command it ran. The snapshot's outcome must not depend on
// that: an xvfb-run that runs the real one and then always fails its clean-up.
TEST(Snapshot, TheOutcomeSurvivesAnXvfbRunWhoseCleanUpFails) {
  REQUIRE_GUI();
  TempDir tmp;
  const fs::path bin = tmp.path() / "bin";
  fs::create_directories(bin);
  const std::string real = "/usr/bin/xvfb-run";
  ASSERT_TRUE(fs::exists(real));
  {
    std::ofstream fake(bin / "xvfb-run");
    fake << "#!/bin/sh\n" << real << " \"$@\"\n"
         << "echo 'xvfb-run: error: problem while cleaning up temporary directory' >&2\nexit 5\n";
  }
  fs::permissions(bin / "xvfb-run", fs::perms::owner_all);
  const std::string env = "env -u DISPLAY PATH=" + bin.string() + ":\"$PATH\" ";
  // A network SUMO refuses: SUMO's failure (3), not xvfb-run's 5.
  std::string net = ReadFile(fs::path(kCli).parent_path() / "sumo_net/figure8.net.xml");
  const std::size_t at = net.find("speed=\"");
  ASSERT_NE(at, std::string::npos);
  net.replace(at, net.find('"', at + 7) - at + 1, "speed=\"fast\"");
  const std::string bad = (tmp.path() / "bad_speed.net.xml").string();
  std::ofstream(bad) << net;
  const fs::path png = tmp.path() / "x.png";
  Result r = Shell(env + kCli + " snapshot " + kPaper + " --out " + png.string() +
                       " --at 5 --set scenario.network=" + bad,
                   tmp.path() / "log.txt");
  EXPECT_THAT(r.output, HasSubstr("problem while cleaning up")) << "the fake xvfb-run was not used";
  EXPECT_EQ(r.code, 3) << r.output;
  EXPECT_FALSE(fs::exists(png));
  // A good snapshot: 0 and its picture.
  r = Shell(env + kCli + " snapshot " + kPaper + " --out " + png.string() + " --at 2",
            tmp.path() / "log.txt");
  EXPECT_EQ(r.code, 0) << r.output;
  EXPECT_GT(fs::exists(png) ? fs::file_size(png) : 0u, 0u) << r.output;
}

}  // namespace
