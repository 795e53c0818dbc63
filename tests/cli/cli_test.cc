// The taebp command-line program, run as a user would: theory and solve
// against the library, run's outputs and their determinism, bad input that
// leaves no half-written results, and --help.
#include "taebp/config/policies.h"
#include "taebp/persuasion/av_hv.h"
#include "taebp/persuasion/likelihood.h"
#include "taebp/persuasion/lp.h"
#include "taebp/persuasion/outcomes.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "cli_support.h"
#include "test_support.h"
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

namespace {

using ::testing::HasSubstr;
using json = nlohmann::json;
namespace per = taebp::persuasion;
namespace fs = std::filesystem;

const std::string kCli = TAEBP_CLI;
const std::string kSource = TAEBP_SOURCE_DIR;
const std::string kPaper = kSource + "/configs/paper.yaml";

constexpr int kExitConfig = 2;  // README: 2 bad configuration or argument
constexpr int kExitSumo = 3;    // README: 3 SUMO failed

using taebp::test::TempDir;

std::string ReadFile(const fs::path& p) { return taebp::test::ReadText(p); }

using taebp::test::CliResult;

// Runs the built taebp with `args` (no shell), capturing stdout and stderr.
CliResult RunCli(const std::vector<std::string>& args) {
  return taebp::test::RunProgram(kCli, args);
}

std::string Arg(double v) {
  std::ostringstream os;
  os.precision(17);
  os << v;
  return os.str();
}

// ------------------------------------------------------------------ theory

struct TheoryPoint {
  double prior, penalty, trust;
  std::optional<double> assumed;
};

// `taebp theory ... --json` against the library for the same inputs.
void ExpectTheoryMatchesLibrary(const TheoryPoint& p) {
  SCOPED_TRACE(testing::Message() << "lambda " << p.prior << " r " << p.penalty << " theta "
                                  << p.trust << " theta_hat " << p.assumed.value_or(-1));
  std::vector<std::string> args = {"theory", "--prior", Arg(p.prior), "--penalty",
                                   Arg(p.penalty), "--trust", Arg(p.trust), "--json"};
  if (p.assumed) {
    args.push_back("--assumed-trust");
    args.push_back(Arg(*p.assumed));
  }
  const CliResult r = RunCli(args);
  ASSERT_EQ(r.exit_code, 0) << r.Describe();
  const json j = json::parse(r.out);
  const per::AvHvParams params{p.prior, p.penalty};
  const per::LinearLikelihood lik(2.0);
  const double theta_hat = p.assumed.value_or(p.trust);
  const per::TaebpDesign d = per::DesignTaebp(params, theta_hat, lik);
  const per::PredictedOutcome o =
      per::PredictOutcome(per::Policy::kTaEbp, params, p.trust, lik, theta_hat);
  EXPECT_NEAR(j.at("p_star").get<double>(), d.p_star, 1e-12);
  EXPECT_NEAR(j.at("theta_star").get<double>(), d.theta_star, 1e-12);
  EXPECT_EQ(j.at("persuadable").get<bool>(), d.persuadable);
  EXPECT_NEAR(j.at("s_star").get<double>(), d.s_star, 1e-12);
  EXPECT_NEAR(j.at("a").get<double>(), d.a, 1e-12);
  EXPECT_NEAR(j.at("b").get<double>(), d.b, 1e-12);
  EXPECT_NEAR(j.at("p_nudge").get<double>(), d.p_nudge, 1e-12);
  EXPECT_NEAR(j.at("dc_rate").get<double>(), o.dc_rate, 1e-12);
  EXPECT_NEAR(j.at("collision_rate").get<double>(), o.collision_rate, 1e-12);
  EXPECT_NEAR(j.at("assumed_trust").get<double>(), theta_hat, 1e-12);
  for (per::Policy policy : {per::Policy::kNoEbp, per::Policy::kNoTrust, per::Policy::kTaEbp,
                             per::Policy::kFullReveal}) {
    const std::string name = taebp::PolicyName(policy);
    const per::PredictedOutcome po = per::PredictOutcome(policy, params, p.trust, lik, theta_hat);
    ASSERT_TRUE(j.at("policies").contains(name)) << name;
    EXPECT_NEAR(j["policies"][name].at("dc_rate").get<double>(), po.dc_rate, 1e-12) << name;
    EXPECT_NEAR(j["policies"][name].at("collision_rate").get<double>(), po.collision_rate, 1e-12)
        << name;
  }
}

TEST(CliTheory, PaperPointJsonMatchesLibraryAndHandDerivation) {
  ExpectTheoryMatchesLibrary({0.2, 3.0, 0.6, std::nullopt});
  const CliResult r = RunCli({"theory", "--prior", "0.2", "--penalty", "3", "--trust", "0.6",
                              "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.Describe();
  const json j = json::parse(r.out);
  // README: p* = 0.4, theta* = 0.25, s* = 64/39, b = 7/32, DC = 0.375.
  EXPECT_NEAR(j["p_star"].get<double>(), 0.4, 1e-12);
  EXPECT_NEAR(j["theta_star"].get<double>(), 0.25, 1e-12);
  EXPECT_NEAR(j["s_star"].get<double>(), 64.0 / 39.0, 1e-12);
  EXPECT_NEAR(j["b"].get<double>(), 7.0 / 32.0, 1e-12);
  EXPECT_NEAR(j["dc_rate"].get<double>(), 0.375, 1e-12);
  EXPECT_EQ(j["collision_rate"].get<double>(), 0.0);
}

TEST(CliTheory, AssumedTrustOneIsNoTrustsDesignAndCollides) {
  ExpectTheoryMatchesLibrary({0.2, 3.0, 0.6, 1.0});
  const CliResult r = RunCli({"theory", "--prior", "0.2", "--penalty", "3", "--trust", "0.6",
                              "--assumed-trust", "1", "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.Describe();
  const json j = json::parse(r.out);
  EXPECT_NEAR(j["collision_rate"].get<double>(), 0.2, 1e-12);
  EXPECT_NEAR(j["s_star"].get<double>(), 16.0 / 11.0, 1e-12);
  EXPECT_EQ(j["dc_rate"].get<double>(), 0.0);
}

TEST(CliTheory, GridIncludingNotPersuadableMatchesLibrary) {
  const std::vector<TheoryPoint> grid = {
      {0.3, 2.0, 0.8, std::nullopt}, {0.1, 5.0, 0.5, std::nullopt},
      {0.2, 3.0, 0.25, std::nullopt},  // exactly theta*
      {0.2, 3.0, 0.1, std::nullopt},   // below theta*: not persuadable
      {0.5, 1.0, 0.3, std::nullopt},   // lambda >= p*: no persuasion needed
      {0.2, 3.0, 0.6, 0.9},            // over-estimated trust
      {0.2, 3.0, 0.9, 0.6},            // under-estimated trust
  };
  for (const TheoryPoint& p : grid) ExpectTheoryMatchesLibrary(p);
  const CliResult r = RunCli({"theory", "--trust", "0.1", "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.Describe();
  const json j = json::parse(r.out);
  EXPECT_FALSE(j["persuadable"].get<bool>());
  EXPECT_EQ(j["s_star"].get<double>(), 0.0);
  EXPECT_EQ(j["dc_rate"].get<double>(), 0.0);
  EXPECT_EQ(j["collision_rate"].get<double>(), 0.0);
}

TEST(CliTheory, TableOutputShowsTheDesign) {
  const CliResult r = RunCli({"theory", "--prior", "0.2", "--penalty", "3", "--trust", "0.6"});
  ASSERT_EQ(r.exit_code, 0) << r.Describe();
  EXPECT_THAT(r.out, HasSubstr("1.641025641"));
  EXPECT_THAT(r.out, HasSubstr("0.21875"));
  EXPECT_THAT(r.out, HasSubstr("ta_ebp"));
}

TEST(CliTheory, BadInputExitsNonZeroNamingTheParameter) {
  struct Case {
    std::vector<std::string> args;
    std::vector<std::string> expected;
  };
  const std::vector<Case> cases = {
      {{"--trust", "1.3"}, {"trust", "1.3"}},
      {{"--trust", "-0.1"}, {"trust", "-0.1"}},
      {{"--prior", "0"}, {"prior", "0"}},
      {{"--prior", "1"}, {"prior", "1"}},
      {{"--penalty", "-1"}, {"penalty", "-1"}},
      {{"--assumed-trust", "2"}, {"trust", "2"}},
      {{"--likelihood", "cubic"}, {"likelihood", "cubic"}},
      {{"--s-max", "0"}, {"s_max", "0"}},
  };
  for (const Case& c : cases) {
    std::vector<std::string> args = {"theory"};
    args.insert(args.end(), c.args.begin(), c.args.end());
    args.push_back("--json");
    const CliResult r = RunCli(args);
    SCOPED_TRACE(c.args[0] + " " + c.args[1]);
    EXPECT_EQ(r.exit_code, kExitConfig) << r.Describe();
    for (const std::string& e : c.expected) EXPECT_THAT(r.err, HasSubstr(e)) << r.Describe();
    EXPECT_EQ(r.out, "");
  }
  // Not a number at all: CLI11 refuses it, also non-zero.
  const CliResult nan = RunCli({"theory", "--trust", "abc"});
  EXPECT_NE(nan.exit_code, 0);
  EXPECT_THAT(nan.err, HasSubstr("--trust"));
}

// ------------------------------------------------------------------ solve

per::Game Prosecutor() {
  per::Game g;
  g.states = {"guilty", "innocent"};
  g.actions = {"convict", "acquit"};
  g.prior = Eigen::Vector2d(0.3, 0.7);
  g.receiver_utility.resize(2, 2);
  g.receiver_utility << 1, 0, 0, 1;
  g.sender_utility.resize(2, 2);
  g.sender_utility << 1, 0, 1, 0;
  return g;
}

void ExpectSolveMatches(const json& j, const per::Game& game, double trust) {
  const per::LpResult lp = per::SolveTrustAwarePersuasion(game, trust);
  ASSERT_EQ(lp.status, per::LpResult::Status::kOptimal);
  EXPECT_EQ(j.at("status").get<std::string>(), per::ToString(lp.status));
  EXPECT_NEAR(j.at("sender_value").get<double>(), lp.sender_value, 1e-12);
  EXPECT_EQ(j.at("states").get<std::vector<std::string>>(), game.states);
  EXPECT_EQ(j.at("actions").get<std::vector<std::string>>(), game.actions);
  const json& scheme = j.at("scheme");
  ASSERT_EQ(scheme.size(), static_cast<std::size_t>(lp.scheme.rows()));
  for (Eigen::Index i = 0; i < lp.scheme.rows(); ++i) {
    ASSERT_EQ(scheme[i].size(), static_cast<std::size_t>(lp.scheme.cols()));
    for (Eigen::Index a = 0; a < lp.scheme.cols(); ++a)
      EXPECT_NEAR(scheme[i][a].get<double>(), lp.scheme(i, a), 1e-12) << i << "," << a;
  }
  const json& sig = j.at("signal_probability");
  ASSERT_EQ(sig.size(), static_cast<std::size_t>(lp.signal_probability.size()));
  for (Eigen::Index a = 0; a < lp.signal_probability.size(); ++a)
    EXPECT_NEAR(sig[a].get<double>(), lp.signal_probability(a), 1e-12);
}

TEST(CliSolve, ProsecutorMatchesLibraryAndTextbook) {
  const std::string problem = kSource + "/configs/problems/prosecutor.yaml";
  if (!fs::exists(problem)) GTEST_FAIL() << problem << " is missing";
  const CliResult r = RunCli({"solve", problem, "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.Describe();
  const json j = json::parse(r.out);
  // Kamenica & Gentzkow: value 0.6, convict the guilty always and the innocent
  // with probability 3/7.
  EXPECT_NEAR(j["sender_value"].get<double>(), 0.6, 1e-9);
  EXPECT_NEAR(j["scheme"][0][0].get<double>(), 1.0, 1e-9);
  EXPECT_NEAR(j["scheme"][1][0].get<double>(), 3.0 / 7.0, 1e-9);
  EXPECT_NEAR(j["scheme"][1][1].get<double>(), 4.0 / 7.0, 1e-9);
  EXPECT_NEAR(j["trust"].get<double>(), 1.0, 0);
  ExpectSolveMatches(j, Prosecutor(), 1.0);
  // The text output says the same.
  const CliResult text = RunCli({"solve", problem});
  ASSERT_EQ(text.exit_code, 0) << text.Describe();
  EXPECT_THAT(text.out, HasSubstr("sender value: 0.6"));
}

TEST(CliSolve, AvHvGameMatchesTheTaebpDesign) {
  const std::string problem = kSource + "/configs/problems/av_hv.yaml";
  if (!fs::exists(problem)) GTEST_FAIL() << problem << " is missing";
  const CliResult r = RunCli({"solve", problem, "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.Describe();
  const json j = json::parse(r.out);
  per::Game game = per::AvHvGame({0.2, 3.0});
  game.states = {"go", "stop"};
  ExpectSolveMatches(j, game, 0.6);
  // P(DC recommended) = lambda + (1 - lambda) b = 0.375; value 2 * 0.375 - 1.
  EXPECT_NEAR(j["signal_probability"][1].get<double>(), 0.375, 1e-9);
  EXPECT_NEAR(j["sender_value"].get<double>(), -0.25, 1e-9);
}

TEST(CliSolve, BadProblemFilesExitNonZeroNamingTheKey) {
  TempDir dir;
  const std::string good =
      "states: [a, b]\nactions: [x, y]\nprior: [0.3, 0.7]\n"
      "receiver_utility: [[1, 0], [0, 1]]\nsender_utility: [[1, 0], [1, 0]]\ntrust: 1\n";
  {
    const std::string path = dir.Write("unknown.yaml", good + "trsut: 0.5\n");
    const CliResult r = RunCli({"solve", path, "--json"});
    EXPECT_EQ(r.exit_code, kExitConfig) << r.Describe();
    EXPECT_THAT(r.err, HasSubstr("trsut"));
    EXPECT_THAT(r.err, HasSubstr(path));
    EXPECT_EQ(r.out, "");
  }
  {
    const std::string path = dir.Write("shape.yaml",
                                       "states: [a, b]\nactions: [x, y]\nprior: [0.3, 0.7]\n"
                                       "receiver_utility: [[1, 0]]\n"
                                       "sender_utility: [[1, 0], [1, 0]]\ntrust: 1\n");
    const CliResult r = RunCli({"solve", path});
    EXPECT_EQ(r.exit_code, kExitConfig) << r.Describe();
    EXPECT_THAT(r.err, HasSubstr("receiver_utility"));
  }
  {
    std::string bad = good;
    bad.replace(bad.find("trust: 1"), 8, "trust: 1.5");
    const CliResult r = RunCli({"solve", dir.Write("trust.yaml", bad)});
    EXPECT_EQ(r.exit_code, kExitConfig) << r.Describe();
    EXPECT_THAT(r.err, HasSubstr("trust"));
    EXPECT_THAT(r.err, HasSubstr("1.5"));
  }
  {
    const CliResult r = RunCli({"solve", (dir.path() / "missing.yaml").string()});
    EXPECT_EQ(r.exit_code, kExitConfig) << r.Describe();
    EXPECT_THAT(r.err, HasSubstr("missing.yaml"));
  }
}

// Numerics and limits of `solve` (each once aborted, misled or hung).
TEST(CliSolve, ExtremeAndLargeUtilitiesGiveTheRightAnswer) {
  TempDir dir;
  {
    // [1e308, -1e308] used to end in GLPK's abort() (SIGABRT, exit 134).
    const std::string path = dir.Write(
        "huge.yaml",
        "states: [a, b]\nactions: [x, y]\nprior: [0.5, 0.5]\n"
        "receiver_utility: [[1e308, -1e308], [0, 1]]\nsender_utility: [[1, 0], [1, 0]]\ntrust: 1\n");
    const CliResult r = RunCli({"solve", path, "--json"});
    ASSERT_EQ(r.exit_code, 0) << r.Describe();
    const json j = json::parse(r.out);
    EXPECT_EQ(j["status"], "optimal");
    EXPECT_NEAR(j["sender_value"].get<double>(), 1.0, 1e-9);
  }
  {
    // Both entries of state a at 1e17: the answer is -1 (x never obedient), not
    // the -0.5 of a disobedient scheme.
    const std::string path = dir.Write(
        "large.yaml",
        "states: [a, b]\nactions: [x, y]\nprior: [0.5, 0.5]\n"
        "receiver_utility: [[1e17, 1e17], [0, 1]]\nsender_utility: [[0, -1], [0, -1]]\ntrust: 0.5\n");
    const CliResult r = RunCli({"solve", path, "--json"});
    ASSERT_EQ(r.exit_code, 0) << r.Describe();
    const json j = json::parse(r.out);
    EXPECT_NEAR(j["sender_value"].get<double>(), -1.0, 1e-9);
    EXPECT_NEAR(j["scheme"][0][0].get<double>(), 0.0, 1e-9);
  }
}

TEST(CliSolve, DuplicateNamesAndOversizedGamesAreRefused) {
  TempDir dir;
  const std::string tail =
      "prior: [0.5, 0.5]\nreceiver_utility: [[1, 0], [0, 1]]\n"
      "sender_utility: [[1, 0], [1, 0]]\ntrust: 1\n";
  {
    const std::string path = dir.Write("states.yaml", "states: [go, go]\nactions: [x, y]\n" + tail);
    const CliResult r = RunCli({"solve", path});
    EXPECT_EQ(r.exit_code, kExitConfig) << r.Describe();
    EXPECT_THAT(r.err, HasSubstr(path));
    EXPECT_THAT(r.err, HasSubstr("states: the name 'go' appears twice"));
    EXPECT_EQ(r.out, "");
  }
  {
    const std::string path = dir.Write("actions.yaml", "states: [a, b]\nactions: [x, x]\n" + tail);
    const CliResult r = RunCli({"solve", path, "--json"});
    EXPECT_EQ(r.exit_code, kExitConfig) << r.Describe();
    EXPECT_THAT(r.err, HasSubstr(path));
    EXPECT_THAT(r.err, HasSubstr("actions: the name 'x' appears twice"));
    EXPECT_EQ(r.out, "");
  }
  {
    // 2 states x 4001 actions: 32 million obedience coefficients, refused at once.
    std::string actions, zeros;
    for (int a = 0; a < 4001; ++a) {
      actions += (a ? ", a" : "a") + std::to_string(a);
      zeros += a ? ", 0" : "0";
    }
    const std::string path = dir.Write(
        "big.yaml", "states: [a, b]\nactions: [" + actions + "]\nprior: [0.5, 0.5]\n" +
                        "receiver_utility: [[" + zeros + "], [" + zeros + "]]\n" +
                        "sender_utility: [[" + zeros + "], [" + zeros + "]]\ntrust: 1\n");
    const CliResult r = RunCli({"solve", path});
    EXPECT_EQ(r.exit_code, kExitConfig) << r.Describe();
    EXPECT_THAT(r.err, HasSubstr(path));
    EXPECT_THAT(r.err, HasSubstr("2 states and 4001 actions"));
    EXPECT_THAT(r.err, HasSubstr("above the LP's limits"));
  }
}

// ------------------------------------------------------------------ run

std::vector<std::string> CsvRows(const std::string& csv, std::string* header) {
  std::vector<std::string> rows;
  std::istringstream in(csv);
  bool seen_header = false;
  for (std::string line; std::getline(in, line);) {
    if (!line.empty() && line[0] == '#') continue;
    if (!seen_header) {
      *header = line;
      seen_header = true;
      continue;
    }
    rows.push_back(line);
  }
  return rows;
}

std::vector<std::string> Split(const std::string& line) {
  std::vector<std::string> out;
  std::istringstream in(line);
  for (std::string f; std::getline(in, f, ',');) out.push_back(f);
  return out;
}

// timing.json: the total, and per policy of the run where its time went
// (SUMO's start, SUMO's steps, the controller's steps), within the total.
void ExpectTimingWithinTheTotal(const fs::path& path) {
  const json timing = json::parse(ReadFile(path));
  const double total = timing.at("wall_seconds_total").get<double>();
  EXPECT_GT(total, 0);
  double parts = 0;
  for (const char* policy : {"no_ebp", "no_trust", "ta_ebp"}) {
    SCOPED_TRACE(policy);
    ASSERT_TRUE(timing.at("policies").contains(policy)) << timing.dump(2);
    const json& t = timing.at("policies").at(policy);
    EXPECT_GT(t.at("wall_seconds_start").get<double>(), 0);
    EXPECT_GT(t.at("wall_seconds_sumo_steps").get<double>(), 0);
    EXPECT_GT(t.at("wall_seconds_controller_steps").get<double>(), 0);
    parts += t.at("wall_seconds_start").get<double>() + t.at("wall_seconds_sumo_steps").get<double>() +
             t.at("wall_seconds_controller_steps").get<double>();
  }
  EXPECT_EQ(timing.at("policies").size(), 3u);
  EXPECT_LE(parts, total);
}

TEST(CliRun, WritesDocumentedOutputsDeterministically) {
  TempDir dir;
  const fs::path a = dir.path() / "a", b = dir.path() / "b";
  const CliResult ra = RunCli({"run", kPaper, "--set", "scenario.duration=120", "--out", a.string()});
  ASSERT_EQ(ra.exit_code, 0) << ra.Describe();
  const CliResult rb = RunCli({"run", kPaper, "--set", "scenario.duration=120", "--out", b.string(),
                               "--quiet"});
  ASSERT_EQ(rb.exit_code, 0) << rb.Describe();
  // The table on stdout.
  EXPECT_THAT(ra.out, HasSubstr("Collision Rate"));
  EXPECT_THAT(ra.out, HasSubstr("TA-EBP"));

  const std::string summary_a = ReadFile(a / "summary.json");
  const std::string csv_a = ReadFile(a / "encounters.csv");
  EXPECT_EQ(summary_a, ReadFile(b / "summary.json"));
  EXPECT_EQ(csv_a, ReadFile(b / "encounters.csv"));
  EXPECT_TRUE(fs::exists(a / "config.yaml"));
  ExpectTimingWithinTheTotal(a / "timing.json");
  // No temporary files left behind.
  for (const auto& entry : fs::directory_iterator(a))
    EXPECT_EQ(entry.path().filename().string().find(".tmp"), std::string::npos) << entry.path();

  const json s = json::parse(summary_a);
  const json& prov = s.at("provenance");
  EXPECT_EQ(prov.at("seed").get<long>(), 1);
  EXPECT_EQ(prov.at("config").at("scenario").at("duration").get<double>(), 120.0);
  EXPECT_EQ(prov.at("config").at("model").at("trust").get<double>(), 0.6);
  EXPECT_FALSE(prov.at("git_revision").get<std::string>().empty());
  EXPECT_THAT(prov.at("sumo_version").get<std::string>(), HasSubstr("SUMO"));

  std::string header;
  const std::vector<std::string> rows = CsvRows(csv_a, &header);
  EXPECT_EQ(header,
            "policy,time,junction,av,hv,av_movement,hv_movement,av_dir,hv_dir,intent,"
            "commanded_nudge,observed_displacement,hv_trust,hv_posterior,hv_action,av_action,"
            "collision");
  std::map<std::string, long> n, collisions, dc;
  for (const std::string& row : rows) {
    const std::vector<std::string> f = Split(row);
    ASSERT_EQ(f.size(), 17u) << row;
    ++n[f[0]];
    EXPECT_EQ(f[2], "C") << row;  // the figure-8's centre
    collisions[f[0]] += f[16] == "1";
    dc[f[0]] += f[14] == "DC";
  }

  const per::AvHvParams params{0.2, 3.0};
  const per::LinearLikelihood lik(2.0);
  const json& policies = s.at("policies");
  ASSERT_EQ(policies.size(), 3u);
  for (const std::string name : {"no_ebp", "no_trust", "ta_ebp"}) {
    SCOPED_TRACE(name);
    ASSERT_TRUE(policies.contains(name));
    const json& p = policies[name];
    const long encounters = p.at("encounters").get<long>();
    EXPECT_GT(encounters, 0);
    EXPECT_EQ(encounters, n[name]);
    EXPECT_EQ(p.at("collisions").get<long>(), collisions[name]);
    EXPECT_EQ(p.at("dc").get<long>(), dc[name]);
    EXPECT_DOUBLE_EQ(p.at("collision_rate").get<double>(),
                     static_cast<double>(collisions[name]) / encounters);
    EXPECT_DOUBLE_EQ(p.at("dc_rate").get<double>(), static_cast<double>(dc[name]) / encounters);
    const per::PredictedOutcome o =
        per::PredictOutcome(taebp::ParseGamePolicy(name), params, 0.6, lik);
    EXPECT_NEAR(p.at("theory_collision_rate").get<double>(), o.collision_rate, 1e-12);
    EXPECT_NEAR(p.at("theory_dc_rate").get<double>(), o.dc_rate, 1e-12);
    EXPECT_EQ(p.at("teleports").get<long>(), 0);
    EXPECT_EQ(p.at("other_collisions").get<long>(), 0);
  }
}

TEST(CliRun, BadInputExitsNonZeroAndLeavesTheOutputUntouched) {
  TempDir dir;
  const std::string garbage =
      dir.Write("garbage.net.xml", "<<< this is not a SUMO network\n\x01\x02\n");
  struct Case {
    std::string set;
    int exit_code;
    std::vector<std::string> expected;  // in stderr
  };
  const std::vector<Case> cases = {
      {"model.trust=1.3", kExitConfig, {"--set model.trust=1.3", "model.trust = 1.3"}},
      {"model.prior_go=0", kExitConfig, {"--set model.prior_go=0", "model.prior_go (lambda) = 0 is outside (0, 1)"}},
      {"scenario.duration=-1", kExitConfig, {"scenario.duration = -1"}},
      {"scenario.avs=-1", kExitConfig, {"scenario.avs = -1"}},
      {"scenario.avss=1", kExitConfig, {"--set scenario.avss=1", "scenario.avss"}},
      {"scenario.network=/nonexistent.net.xml", kExitConfig,
       {"scenario.network", "/nonexistent.net.xml"}},
      // Not a SUMO network: refused before SUMO starts, naming the key and file.
      {"scenario.network=" + garbage, kExitConfig, {"scenario.network", garbage}},
  };
  const std::string sentinel = "{\"sentinel\": true}\n";
  for (const Case& c : cases) {
    SCOPED_TRACE(c.set);
    // An existing result directory: unchanged afterwards.
    const fs::path out = dir.path() / "existing";
    fs::create_directories(out);
    std::ofstream(out / "summary.json", std::ios::binary) << sentinel;
    const CliResult r = RunCli({"run", kPaper, "--set", "scenario.duration=60", "--set", c.set,
                                "--out", out.string()});
    EXPECT_EQ(r.exit_code, c.exit_code) << r.Describe();
    for (const std::string& e : c.expected) EXPECT_THAT(r.err, HasSubstr(e)) << r.Describe();
    EXPECT_EQ(ReadFile(out / "summary.json"), sentinel);
    long files = 0;
    for (const auto& entry : fs::directory_iterator(out)) {
      (void)entry;
      ++files;
    }
    EXPECT_EQ(files, 1) << "files appeared in " << out;
    fs::remove_all(out);
    // A new result directory: never created.
    const fs::path fresh = dir.path() / "fresh";
    const CliResult r2 = RunCli({"run", kPaper, "--set", "scenario.duration=60", "--set", c.set,
                                 "--out", fresh.string()});
    EXPECT_EQ(r2.exit_code, c.exit_code) << r2.Describe();
    EXPECT_FALSE(fs::exists(fresh));
  }
}

TEST(CliRun, MissingConfigFileIsAConfigError) {
  TempDir dir;
  const std::string missing = (dir.path() / "nope.yaml").string();
  const CliResult r = RunCli({"run", missing, "--out", (dir.path() / "out").string()});
  EXPECT_EQ(r.exit_code, kExitConfig) << r.Describe();
  EXPECT_THAT(r.err, HasSubstr(missing));
  EXPECT_FALSE(fs::exists(dir.path() / "out"));
}

}  // namespace
