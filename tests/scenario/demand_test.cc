// Generated fringe demand (scenario/demand.h) on netgenerate grids: the
// fringe, determinism, the Poisson arrivals and uniform exits against their
// distributions (99.9% intervals), begin/end, and a routes file SUMO runs.
#include "taebp/scenario/demand.h"

#include "taebp/config/config.h"
#include "taebp/report/report.h"  // kZ999
#include "taebp/controller/sumo_adapter.h"
#include "taebp/scenario/scenario.h"

#include <boost/math/distributions/chi_squared.hpp>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "net_support.h"
#include "test_support.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <tuple>
#include <set>
#include <string>
#include <vector>

namespace taebp {
namespace {

using ::testing::HasSubstr;
using test::ErrorOf;
using test::TempDir;


double Chi2Quantile(double df, double p) {
  return boost::math::quantile(boost::math::chi_squared(df), p);
}

// A 4x4 all-way stop grid with 100 m fringe edges (16 entries, 16 exits).
class DemandOnGrid : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new TempDir("taebp_demand");
    net_ = new net::NetFile(
        net::NetFile::Load(test::Netgenerate(*dir_, "grid", 4, "allway_stop", 100)));
  }
  static void TearDownTestSuite() {
    delete net_;
    delete dir_;
  }
  static TempDir* dir_;
  static net::NetFile* net_;
};
TempDir* DemandOnGrid::dir_ = nullptr;
net::NetFile* DemandOnGrid::net_ = nullptr;

TEST_F(DemandOnGrid, FringeIsTheEdgesFromAndToDeadEnds) {
  const FringeEdges f = FindFringe(*net_);
  EXPECT_EQ(f.entries.size(), 16u);
  EXPECT_EQ(f.exits.size(), 16u);
  std::set<std::string> from_dead, to_dead;
  for (const std::string& e : f.entries) {
    const net::Edge* edge = net_->FindEdge(e);
    ASSERT_NE(edge, nullptr);
    EXPECT_EQ(net_->FindJunction(edge->from)->type, "dead_end") << e;
    EXPECT_EQ(net_->FindJunction(edge->to)->type, "allway_stop") << e;
    from_dead.insert(edge->from);
  }
  for (const std::string& e : f.exits) {
    const net::Edge* edge = net_->FindEdge(e);
    EXPECT_EQ(net_->FindJunction(edge->to)->type, "dead_end") << e;
    to_dead.insert(edge->to);
  }
  EXPECT_EQ(from_dead.size(), 16u);  // one entry and one exit per dead end
  EXPECT_EQ(from_dead, to_dead);
  // No fringe without dead ends: a grid without fringe edges, the figure-8.
  TempDir dir("taebp_demand");
  const net::NetFile bare = net::NetFile::Load(test::Netgenerate(dir, "bare", 3, "allway_stop"));
  EXPECT_TRUE(FindFringe(bare).entries.empty());
  const std::string msg =
      ErrorOf<std::invalid_argument>([&] { DemandTrips(bare, DemandSpec{}); });
  EXPECT_THAT(msg, HasSubstr(bare.path()));
  EXPECT_THAT(msg, HasSubstr("fringe"));
  const net::NetFile fig8 = net::NetFile::Load(DefaultNetworkPath());
  EXPECT_THROW(DemandTrips(fig8, DemandSpec{}), std::invalid_argument);
  // Through the writer: a ConfigError naming the key.
  const std::string out = (dir.path() / "x.rou.xml").string();
  EXPECT_THAT(ErrorOf<ConfigError>([&] { WriteDemand(bare, DemandSpec{}, out); }),
              HasSubstr("scenario.demand"));
}

// The fringe by topology (issue 26): with its turnarounds (netgenerate's
// default) netgenerate types a grid's dead ends with --default-junction-type
// too; the entries and exits are still the edges from and to the junctions
// with one neighbour where traffic can only turn around. The figure-8's loop
// ends (one neighbour, traffic goes on) are no fringe.
TEST(DemandFringe, IsFoundByTopologyWhateverTypeTheDeadEndsHave) {
  TempDir dir("taebp_demand");
  const std::string path = (dir.path() / "stops.net.xml").string();
  ASSERT_EQ(test::Shell("netgenerate --grid --grid.number 3 --grid.attach-length 100 "
                        "--default-junction-type priority_stop --tls.guess false "
                        "--xml-validation never --output-file " + path,
                        (dir.path() / "stops.log").string()),
            0);
  const net::NetFile net = net::NetFile::Load(path);
  const FringeEdges f = FindFringe(net);
  EXPECT_EQ(f.entries.size(), 12u);
  EXPECT_EQ(f.exits.size(), 12u);
  std::set<std::string> ends;
  for (const std::string& e : f.entries) {
    const net::Edge* edge = net.FindEdge(e);
    ASSERT_NE(edge, nullptr);
    EXPECT_EQ(net.FindJunction(edge->from)->type, "priority_stop") << e;
    EXPECT_EQ(net.CarNeighbours().at(edge->from).size(), 1u) << e;
    ends.insert(edge->from);
  }
  for (const std::string& e : f.exits) EXPECT_EQ(ends.count(net.FindEdge(e)->to), 1u) << e;
  EXPECT_EQ(ends.size(), 12u);
  EXPECT_EQ(net.FringeJunctions(), std::vector<std::string>(ends.begin(), ends.end()));
  // Demand on it: every trip enters and leaves there.
  const std::vector<Trip> trips = DemandTrips(net, DemandSpec{});
  ASSERT_FALSE(trips.empty());
  for (const Trip& t : trips) {
    EXPECT_EQ(ends.count(net.FindEdge(t.from)->from), 1u) << t.id;
    EXPECT_EQ(ends.count(net.FindEdge(t.to)->to), 1u) << t.id;
  }
  EXPECT_TRUE(net::NetFile::Load(DefaultNetworkPath()).FringeJunctions().empty());
}

bool SameTrips(const std::vector<Trip>& a, const std::vector<Trip>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (a[i].id != b[i].id || a[i].depart != b[i].depart || a[i].from != b[i].from ||
        a[i].to != b[i].to)
      return false;
  return true;
}

TEST_F(DemandOnGrid, TripsAreDeterministicSortedNamedAndNeverUTurns) {
  DemandSpec spec;
  spec.flow = 600;
  spec.end = 3600;
  spec.seed = 1;
  const std::vector<Trip> a = DemandTrips(*net_, spec);
  EXPECT_TRUE(SameTrips(a, DemandTrips(*net_, spec)));
  spec.seed = 2;
  const std::vector<Trip> b = DemandTrips(*net_, spec);
  EXPECT_FALSE(SameTrips(a, b));
  ASSERT_GT(a.size(), 1000u);

  const FringeEdges f = FindFringe(*net_);
  const std::set<std::string> entries(f.entries.begin(), f.entries.end());
  const std::set<std::string> exits(f.exits.begin(), f.exits.end());
  for (std::size_t i = 0; i < a.size(); ++i) {
    const Trip& t = a[i];
    EXPECT_EQ(t.id, "d" + std::to_string(i));
    if (i > 0) {
      EXPECT_LE(a[i - 1].depart, t.depart);
    }
    EXPECT_GE(t.depart, 0.0);
    EXPECT_LT(t.depart, 3600.0);
    EXPECT_TRUE(entries.count(t.from)) << t.from;
    EXPECT_TRUE(exits.count(t.to)) << t.to;
    EXPECT_NE(net_->FindEdge(t.to)->to, net_->FindEdge(t.from)->from)
        << t.id << ": back to where it came from";
  }
  // A longer horizon continues each entry's stream: the first hour is unchanged.
  spec.seed = 1;
  spec.end = 7200;
  std::vector<Trip> longer = DemandTrips(*net_, spec);
  longer.erase(std::remove_if(longer.begin(), longer.end(),
                              [](const Trip& t) { return t.depart >= 3600; }),
               longer.end());
  EXPECT_TRUE(SameTrips(a, longer));
}

TEST_F(DemandOnGrid, ArrivalsArePoissonAtTheFlowAndExitsUniform) {
  DemandSpec spec;
  spec.flow = 300;            // veh/h per entry
  spec.end = 100 * 3600.0;    // 100 h: 30000 expected per entry
  spec.seed = 7;
  const std::vector<Trip> trips = DemandTrips(*net_, spec);
  const FringeEdges f = FindFringe(*net_);
  const double expected = spec.flow * spec.end / 3600.0;
  const double bin = 60.0;  // s
  const int bins = static_cast<int>(spec.end / bin);
  std::map<std::string, std::vector<long>> per_bin;
  std::map<std::string, std::map<std::string, long>> exits_of;
  std::map<std::string, long> count;
  for (const Trip& t : trips) {
    ++count[t.from];
    auto& v = per_bin[t.from];
    v.resize(bins);
    ++v[static_cast<int>(t.depart / bin)];
    ++exits_of[t.from][t.to];
  }
  for (const std::string& entry : f.entries) {
    SCOPED_TRACE(entry);
    // The count over the horizon: Poisson(expected), 99.9% interval.
    const double n = static_cast<double>(count[entry]);
    EXPECT_LE(std::abs(n - expected), kZ999 * std::sqrt(expected)) << n << " vs " << expected;
    // Poisson, not merely the right mean: counts per minute have variance =
    // mean (index of dispersion ~ chi-square with bins-1 degrees of freedom).
    const std::vector<long>& v = per_bin[entry];
    double mean = 0;
    for (long c : v) mean += c;
    mean /= bins;
    double d = 0;
    for (long c : v) d += (c - mean) * (c - mean) / mean;
    EXPECT_GE(d, Chi2Quantile(bins - 1, 0.0005));
    EXPECT_LE(d, Chi2Quantile(bins - 1, 0.9995));
    // Exits: uniform over the fringe exits other than the way back.
    const std::map<std::string, long>& ex = exits_of[entry];
    EXPECT_EQ(ex.size(), f.exits.size() - 1);
    double chi2 = 0;
    const double e = n / (f.exits.size() - 1);
    for (const auto& [exit, k] : ex) chi2 += (k - e) * (k - e) / e;
    EXPECT_LE(chi2, Chi2Quantile(static_cast<double>(ex.size() - 1), 0.999));
  }
}

TEST_F(DemandOnGrid, BeginAndEndAreHonoured) {
  DemandSpec spec;
  spec.flow = 400;
  spec.begin = 1800;
  spec.end = 2700;
  const std::vector<Trip> trips = DemandTrips(*net_, spec);
  ASSERT_FALSE(trips.empty());
  for (const Trip& t : trips) {
    EXPECT_GT(t.depart, 1800.0);
    EXPECT_LT(t.depart, 2700.0);
  }
  // 16 entries x 400 veh/h x 0.25 h = 1600 expected.
  const double expected = 16 * 400 * 0.25;
  EXPECT_LE(std::abs(static_cast<double>(trips.size()) - expected), kZ999 * std::sqrt(expected));
  // An empty window gives no trips.
  spec.end = spec.begin;
  EXPECT_TRUE(DemandTrips(*net_, spec).empty());
}

TEST_F(DemandOnGrid, TheRoutesFileRunsInSumo) {
  DemandSpec spec;
  spec.flow = 300;
  spec.end = 600;
  spec.seed = 3;
  spec.length = 4.5;
  spec.max_speed = 10;
  const std::string routes = (dir_->path() / "demand.rou.xml").string();
  const long written = WriteDemand(*net_, spec, routes);
  const std::vector<Trip> trips = DemandTrips(*net_, spec);
  ASSERT_EQ(written, static_cast<long>(trips.size()));
  const std::string text = test::ReadText(routes);
  long lines = 0;
  for (std::size_t p = text.find("<trip "); p != std::string::npos; p = text.find("<trip ", p + 1))
    ++lines;
  EXPECT_EQ(lines, written);

  Sumo().Start({"sumo", "-n", net_->path(), "-r", routes, "--no-step-log", "true",
               "--xml-validation", "never", "--step-length", "0.5"});
  std::map<std::string, double> departed;  // id -> time
  std::map<std::string, const Trip*> by_id;
  for (const Trip& t : trips) by_id[t.id] = &t;
  while (Sumo().Time() < 300) {
    Sumo().Step();
    for (const std::string& id : Sumo().DepartedIDs()) {
      departed[id] = Sumo().Time();
      ASSERT_TRUE(by_id.count(id)) << id;
      const std::vector<std::string> route = Sumo().Route(id);
      ASSERT_FALSE(route.empty());
      EXPECT_EQ(route.front(), by_id[id]->from) << id;
      EXPECT_EQ(route.back(), by_id[id]->to) << id;
      EXPECT_EQ(Sumo().TypeID(id), "car");
      EXPECT_DOUBLE_EQ(Sumo().Length(id), 4.5);
    }
  }
  Sumo().Close();
  // Every trip due by 240 s departed by 300 s, none before its time.
  long due = 0;
  for (const Trip& t : trips) {
    if (t.depart > 240) continue;
    ++due;
    ASSERT_TRUE(departed.count(t.id)) << t.id << " (depart " << t.depart << ") never departed";
    EXPECT_GE(departed[t.id] + 1e-9, std::floor(t.depart * 100) / 100) << t.id;
  }
  EXPECT_GT(due, 100);
  // Unwritable output: a ConfigError naming the key and the path.
  const std::string bad = (dir_->path() / "no" / "such" / "dir.rou.xml").string();
  const std::string msg = ErrorOf<ConfigError>([&] { WriteDemand(*net_, spec, bad); });
  EXPECT_THAT(msg, HasSubstr("scenario.demand"));
  EXPECT_THAT(msg, HasSubstr(bad));
}


// An OpenStreetMap-like fringe: the north arm is a footway (pedestrians
// only), the east arm one-way into the crossing, and the west-to-south turn
// is not a connection. Trips use only edges open to cars, and only exits a
// car can reach from their entry; SUMO departs every one of them.
TEST(DemandOnAnImport, OnlyCarEdgesAndReachableExits) {
  TempDir dir("taebp_demand_osm");
  // No turn from W to S: a car entering at W can reach no exit (no U-turns).
  const std::string con = dir.Write("osmlike.con.xml",
                                    "<connections>\n  <delete from=\"WC\" to=\"CS\"/>\n"
                                    "</connections>\n");
  const std::string net_path = test::Netconvert(
      dir, "osmlike2",
      "  <node id=\"C\" x=\"0\" y=\"0\" type=\"priority\"/>\n"
      "  <node id=\"N\" x=\"0\" y=\"100\" type=\"dead_end\"/>\n"
      "  <node id=\"S\" x=\"0\" y=\"-100\" type=\"dead_end\"/>\n"
      "  <node id=\"E\" x=\"100\" y=\"0\" type=\"dead_end\"/>\n"
      "  <node id=\"W\" x=\"-100\" y=\"0\" type=\"dead_end\"/>\n",
      "  <edge id=\"WC\" from=\"W\" to=\"C\" numLanes=\"1\"/>\n"
      "  <edge id=\"CW\" from=\"C\" to=\"W\" numLanes=\"1\"/>\n"
      "  <edge id=\"EC\" from=\"E\" to=\"C\" numLanes=\"1\"/>\n"
      "  <edge id=\"SC\" from=\"S\" to=\"C\" numLanes=\"1\"/>\n"
      "  <edge id=\"CS\" from=\"C\" to=\"S\" numLanes=\"1\"/>\n"
      "  <edge id=\"NC\" from=\"N\" to=\"C\" numLanes=\"1\" allow=\"pedestrian\"/>\n"
      "  <edge id=\"CN\" from=\"C\" to=\"N\" numLanes=\"1\" allow=\"pedestrian\"/>\n",
      "--connection-files " + con);
  const net::NetFile net = net::NetFile::Load(net_path);
  ASSERT_NE(net.FindLane("NC_0"), nullptr);
  EXPECT_FALSE(net.FindLane("NC_0")->passenger);
  EXPECT_TRUE(net.FindLane("WC_0")->passenger);

  const FringeEdges f = FindFringe(net);
  EXPECT_EQ(std::set<std::string>(f.entries.begin(), f.entries.end()),
            (std::set<std::string>{"WC", "EC", "SC"}));
  EXPECT_EQ(std::set<std::string>(f.exits.begin(), f.exits.end()),
            (std::set<std::string>{"CW", "CS"}));

  DemandSpec spec;
  spec.flow = 600;
  spec.end = 600;
  spec.seed = 5;
  const std::vector<Trip> trips = DemandTrips(net, spec);
  std::map<std::string, std::set<std::string>> pairs;
  for (const Trip& t : trips) pairs[t.from].insert(t.to);
  // E reaches both exits, S only W (its way back excluded), W none (turn deleted, no U-turn).
  EXPECT_EQ(pairs["EC"], (std::set<std::string>{"CW", "CS"}));
  EXPECT_EQ(pairs["SC"], (std::set<std::string>{"CW"}));
  EXPECT_EQ(pairs.count("WC"), 0u);

  const std::string routes = (dir.path() / "demand.rou.xml").string();
  ASSERT_GT(WriteDemand(net, spec, routes), 0);
  Sumo().Start({"sumo", "-n", net_path, "-r", routes, "--no-step-log", "true", "--xml-validation",
               "never", "--step-length", "0.5", "--end", "700"});
  long departed = 0;
  while (Sumo().Time() < 700) {
    Sumo().Step();
    departed += static_cast<long>(Sumo().DepartedIDs().size());
  }
  Sumo().Close();
  EXPECT_EQ(departed, static_cast<long>(trips.size()));
}

// origins: minor_roads. On a priority crossing whose east-west road has the
// right of way, the minor roads are exactly the north and south approaches;
// at an all-way stop every approach stops. A junction not given has none.
TEST(DemandOnMinorRoads, TheMinorApproachesOfTheGivenJunctions) {
  TempDir dir("taebp_demand_minor");
  const net::NetFile two_way = net::NetFile::Load(test::FourWay(dir, "tw", "priority"));
  const FringeEdges f = FindMinorRoads(two_way, {"C"});
  EXPECT_EQ(f.entries, (std::vector<std::string>{"NC", "SC"}));
  // Destinations: the minor roads and the way out of the city.
  EXPECT_EQ(f.exits, (std::vector<std::string>{"CE", "CN", "CS", "CW", "NC", "SC"}));
  EXPECT_TRUE(FindMinorRoads(two_way, {}).entries.empty());
  // The major approaches' left turns yield ('m'), their straight links have
  // the right of way ('M'): not minor roads.
  for (const std::string id : {"EC", "WC"}) {
    bool left_yields = false, straight_major = false;
    for (int k : two_way.LinksFrom(id + "_0")) {
      const net::Link& l = two_way.links()[static_cast<std::size_t>(k)];
      left_yields = left_yields || (l.dir == 'l' && l.state == 'm');
      straight_major = straight_major || (l.dir == 's' && l.state == 'M');
    }
    EXPECT_TRUE(left_yields && straight_major) << id;
  }
  // A T's stem turns only (no straight link): minor; with sidewalks too,
  // whose links to the walking areas go straight on with 'M' (OSM imports).
  for (const std::string extra : {"", "--sidewalks.guess true"}) {
    const net::NetFile t =
        net::NetFile::Load(test::TJunction(dir, extra.empty() ? "t" : "tsw", "priority", extra));
    EXPECT_EQ(FindMinorRoads(t, {"C"}).entries, (std::vector<std::string>{"SC"})) << extra;
    if (!extra.empty()) {
      ASSERT_NE(t.FindLane("SC_1"), nullptr) << "no sidewalk guessed";
      EXPECT_FALSE(t.FindLane("SC_0")->passenger);
    }
  }
  const net::NetFile all_way = net::NetFile::Load(test::FourWay(dir, "aw", "allway_stop"));
  EXPECT_EQ(FindMinorRoads(all_way, {"C"}).entries,
            (std::vector<std::string>{"EC", "NC", "SC", "WC"}));
}

// Trips from the minor roads: every one starts on a minor road, ends on a
// destination it can reach other than another approach of its own junction,
// at the flow per origin; a network without minor roads is an error naming
// the key.
TEST(DemandOnMinorRoads, TripsStartOnMinorRoadsAtTheFlow) {
  TempDir dir("taebp_demand_minor2");
  const net::NetFile net = net::NetFile::Load(test::FourWay(dir, "tw", "priority"));
  DemandSpec spec;
  spec.origins = DemandOrigins::kMinorRoads;
  spec.junctions = {"C"};
  spec.flow = 360;
  spec.end = 100 * 3600.0;
  spec.seed = 3;
  const std::vector<Trip> trips = DemandTrips(net, spec);
  std::map<std::string, std::map<std::string, long>> n;
  for (const Trip& t : trips) ++n[t.from][t.to];
  ASSERT_EQ(n.size(), 2u);
  for (const auto& [from, to] : n) {
    EXPECT_TRUE(from == "NC" || from == "SC") << from;
    // Not the other minor approach of C, not the way back: the three exits.
    std::set<std::string> dest;
    long total = 0;
    for (const auto& [x, k] : to) {
      dest.insert(x);
      total += k;
    }
    const std::string straight = from == "NC" ? "CS" : "CN";
    EXPECT_EQ(dest, (std::set<std::string>{"CE", "CW", straight})) << from;
    // 36000 expected per origin over 100 h (Poisson: sd 190): 99.9 %.
    EXPECT_NEAR(static_cast<double>(total), 36000.0, kZ999 * std::sqrt(36000.0)) << from;
  }
  spec.junctions = {};
  EXPECT_THAT(ErrorOf<std::invalid_argument>([&] { DemandTrips(net, spec); }),
              HasSubstr("has no minor road"));
  const std::string out = (dir.path() / "x.rou.xml").string();
  EXPECT_THAT(ErrorOf<ConfigError>([&] { WriteDemand(net, spec, out); }),
              HasSubstr("scenario.demand"));
}

// The major roads' own traffic (major_flow): trips from the major approaches
// of the junctions, at the flow per approach, to the minor roads' destinations
// (not back through their own junction); the origins' trips are those
// without it, renumbered; a network without a major approach is an error.
TEST(DemandOnMajorRoads, TripsStartOnTheMajorApproachesAtTheFlowOnTopOfTheOrigins) {
  TempDir dir("taebp_demand_major");
  const net::NetFile net = net::NetFile::Load(test::FourWay(dir, "tw", "priority"));
  const FringeEdges m = FindMajorRoads(net, {"C"});
  EXPECT_EQ(m.entries, (std::vector<std::string>{"EC", "WC"}));
  EXPECT_EQ(m.exits, FindMinorRoads(net, {"C"}).exits);
  EXPECT_TRUE(FindMajorRoads(net, {}).entries.empty());

  DemandSpec spec;
  spec.origins = DemandOrigins::kMinorRoads;
  spec.junctions = {"C"};
  spec.flow = 90;
  spec.end = 100 * 3600.0;
  spec.seed = 5;
  const std::vector<Trip> minor_only = DemandTrips(net, spec);
  spec.major_flow = 360;
  const std::vector<Trip> trips = DemandTrips(net, spec);
  std::map<std::string, std::map<std::string, long>> n;
  std::vector<std::tuple<double, std::string, std::string>> from_minor, expected_minor;
  for (const Trip& t : trips) {
    ++n[t.from][t.to];
    if (t.from == "NC" || t.from == "SC") from_minor.emplace_back(t.depart, t.from, t.to);
  }
  for (const Trip& t : minor_only) expected_minor.emplace_back(t.depart, t.from, t.to);
  EXPECT_EQ(from_minor, expected_minor);
  for (std::size_t i = 0; i < trips.size(); ++i) {
    EXPECT_EQ(trips[i].id, "d" + std::to_string(i));
    if (i > 0) {
      EXPECT_LE(trips[i - 1].depart, trips[i].depart);
    }
  }
  ASSERT_EQ(n.size(), 4u);
  for (const std::string from : {"EC", "WC"}) {
    std::set<std::string> dest;
    long total = 0;
    for (const auto& [x, k] : n[from]) {
      dest.insert(x);
      total += k;
    }
    // Straight on, left or right: not the way back (no U-turn at C), not
    // C's own minor approaches.
    const std::string straight = from == "EC" ? "CW" : "CE";
    EXPECT_EQ(dest, (std::set<std::string>{"CN", "CS", straight})) << from;
    // 36000 expected per approach over 100 h: 99.9 %.
    EXPECT_NEAR(static_cast<double>(total), 36000.0, kZ999 * std::sqrt(36000.0)) << from;
  }
  // On the fringe demand too; an all-way stop has no major approach.
  spec.origins = DemandOrigins::kFringe;
  spec.end = 3600;
  const std::size_t with_major = DemandTrips(net, spec).size();
  spec.major_flow = 0;
  const std::size_t without = DemandTrips(net, spec).size();
  // 2 approaches x 360 veh/h more.
  EXPECT_NEAR(static_cast<double>(with_major - without), 720.0, kZ999 * std::sqrt(720.0));
  spec.major_flow = 360;
  const net::NetFile all_way = net::NetFile::Load(test::FourWay(dir, "aw", "allway_stop"));
  spec.origins = DemandOrigins::kMinorRoads;
  EXPECT_THAT(ErrorOf<std::invalid_argument>([&] { DemandTrips(all_way, spec); }),
              HasSubstr("has no major road"));
  EXPECT_THAT(ErrorOf<std::invalid_argument>([&] { DemandTrips(all_way, spec); }),
              HasSubstr("for major_flow = 360 veh/h; set it to 0"));
}

}  // namespace
}  // namespace taebp
