// net::NetFile on real SUMO networks built by the test (netconvert from
// plain-XML nodes and edges, netgenerate grids) and on the figure-8: junction
// types, incoming lanes, links with their directions, states, internal lanes
// and request indices, SUMO's foes matrix; the matrix cross-checked against
// libsumo (Lane::getInternalFoes through the adapter); bad inputs.
#include "taebp/scenario/net_file.h"

#include "taebp/controller/sumo_adapter.h"
#include "taebp/scenario/scenario.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "net_support.h"
#include "test_support.h"

#include <algorithm>
#include <iostream>
#include <map>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

namespace taebp::net {
namespace {

using ::testing::HasSubstr;
using ::testing::UnorderedElementsAre;
using test::ErrorOf;
using test::TempDir;

// The link from one lane to another (fails the test when there is none).
const Link& L(const NetFile& net, const std::string& from, const std::string& to) {
  for (const Link& l : net.links())
    if (l.from_lane == from && l.to_lane == to) return l;
  ADD_FAILURE() << "no link " << from << " -> " << to << " in " << net.path();
  static const Link none;
  return none;
}

// SUMO's foes bit of two links of one junction (either way round).
bool Foes(const NetFile& net, const Link& a, const Link& b) {
  const Junction* j = net.FindJunction(a.junction);
  if (!j || a.junction != b.junction || a.index < 0 || b.index < 0) {
    ADD_FAILURE() << "links " << a.from_lane << ">" << a.to_lane << " and " << b.from_lane << ">"
                  << b.to_lane << " are not two indexed links of one junction";
    return false;
  }
  return j->foes[a.index][b.index] || j->foes[b.index][a.index];
}

bool Contains(const std::vector<std::string>& v, const std::string& s) {
  return std::find(v.begin(), v.end(), s) != v.end();
}

// Structure every junction of a net with internal links must have: one link
// per request index, each connection from a lane ending at the junction
// among them, the index's internal lane on the link's way, the maps.
void CheckStructure(const NetFile& net) {
  SCOPED_TRACE(net.path());
  std::map<std::string, int> links_at;
  for (const Link& l : net.links()) ++links_at[l.junction];
  for (const auto& [id, j] : net.junctions()) {
    if (j.type == "internal") continue;
    SCOPED_TRACE("junction " + id);
    const std::size_t n = j.int_lanes.size();
    ASSERT_EQ(j.foes.size(), n);
    ASSERT_EQ(j.links.size(), n) << "a link per request index";
    EXPECT_EQ(links_at[id], static_cast<int>(n)) << "every connection into the junction indexed";
    for (std::size_t k = 0; k < n; ++k) {
      ASSERT_EQ(j.foes[k].size(), n);
      EXPECT_FALSE(j.foes[k][k]);
      ASSERT_GE(j.links[k], 0) << "request index " << k << " (" << j.int_lanes[k]
                               << ") has no link";
      const Link& l = net.links()[j.links[k]];
      EXPECT_EQ(l.index, static_cast<int>(k));
      EXPECT_EQ(l.junction, id);
      EXPECT_TRUE(Contains(j.inc_lanes, l.from_lane)) << l.from_lane;
      EXPECT_EQ(net.EdgeEnd(net.FindLane(l.from_lane)->edge), id);
      ASSERT_FALSE(l.internal.empty());
      EXPECT_EQ(l.internal.front(), l.via);
      EXPECT_TRUE(Contains(l.internal, j.int_lanes[k]))
          << j.int_lanes[k] << " is not on the way of " << l.from_lane << " > " << l.to_lane;
      for (const std::string& in : l.internal) {
        const Lane* lane = net.FindLane(in);
        ASSERT_NE(lane, nullptr) << in;
        EXPECT_TRUE(net.FindEdge(lane->edge)->IsInternal()) << in;
      }
      ASSERT_NE(net.FindLane(l.to_lane), nullptr);
      EXPECT_FALSE(net.FindEdge(net.FindLane(l.to_lane)->edge)->IsInternal());
      const std::vector<int>& from = net.LinksFrom(l.from_lane);
      EXPECT_NE(std::find(from.begin(), from.end(), j.links[k]), from.end());
      EXPECT_TRUE(Contains(net.Predecessors(l.to_lane), l.from_lane));
      for (std::size_t m = 0; m < n; ++m) {
        if (j.links[m] < 0) continue;
        if (net.links()[j.links[m]].from_lane == l.from_lane) {
          EXPECT_FALSE(j.foes[k][m]) << "links from one lane are never foes";
        }
      }
    }
  }
}

// ------------------------------------------------------------------ T junction

TEST(NetFile, PriorityTJunction) {
  TempDir dir("taebp_net");
  const NetFile net = NetFile::Load(test::TJunction(dir, "t", "priority"));
  CheckStructure(net);
  const Junction* c = net.FindJunction("C");
  ASSERT_NE(c, nullptr);
  EXPECT_EQ(c->type, "priority");
  EXPECT_THAT(c->inc_lanes, UnorderedElementsAre("WC_0", "EC_0", "SC_0"));
  EXPECT_EQ(c->links.size(), 6u);
  for (const char* dead : {"W", "E", "S"}) EXPECT_EQ(net.FindJunction(dead)->type, "dead_end");

  const Link& ws = L(net, "WC_0", "CE_0");
  const Link& wr = L(net, "WC_0", "CS_0");
  const Link& es = L(net, "EC_0", "CW_0");
  const Link& el = L(net, "EC_0", "CS_0");
  const Link& sr = L(net, "SC_0", "CE_0");
  const Link& sl = L(net, "SC_0", "CW_0");
  EXPECT_EQ(ws.dir, 's');
  EXPECT_EQ(wr.dir, 'r');
  EXPECT_EQ(es.dir, 's');
  EXPECT_EQ(el.dir, 'l');
  EXPECT_EQ(sr.dir, 'r');
  EXPECT_EQ(sl.dir, 'l');
  // The major road keeps priority; its left turn and the stem yield.
  EXPECT_EQ(ws.state, 'M');
  EXPECT_EQ(wr.state, 'M');
  EXPECT_EQ(es.state, 'M');
  EXPECT_EQ(el.state, 'm');
  EXPECT_EQ(sr.state, 'm');
  EXPECT_EQ(sl.state, 'm');
  // The major left turn waits inside the junction at an internal junction:
  // two internal lanes, and the junction's intLanes name the second.
  ASSERT_EQ(el.internal.size(), 2u);
  EXPECT_EQ(c->int_lanes[el.index], el.internal[1]);
  for (const Link* l : {&ws, &wr, &es, &sr, &sl}) EXPECT_EQ(l->internal.size(), 1u);
  // Conflicts.
  EXPECT_FALSE(Foes(net, ws, es));  // opposite straights
  EXPECT_TRUE(Foes(net, el, ws));   // left across the opposite straight
  EXPECT_TRUE(Foes(net, el, wr));   // merge into CS
  EXPECT_TRUE(Foes(net, sr, ws));   // merge into CE
  EXPECT_TRUE(Foes(net, sl, ws));
  EXPECT_TRUE(Foes(net, sl, es));
  EXPECT_TRUE(Foes(net, sl, el));
  EXPECT_FALSE(Foes(net, wr, sr));
  EXPECT_FALSE(Foes(net, es, sr));
}

TEST(NetFile, StopTJunctions) {
  TempDir dir("taebp_net");
  // All-way stop: every link is an all-way stop link.
  const NetFile all = NetFile::Load(test::TJunction(dir, "t_all", "allway_stop"));
  CheckStructure(all);
  EXPECT_EQ(all.FindJunction("C")->type, "allway_stop");
  EXPECT_EQ(all.FindJunction("C")->links.size(), 6u);
  for (int id : all.FindJunction("C")->links) EXPECT_EQ(all.links()[id].state, 'w');
  EXPECT_FALSE(Foes(all, L(all, "WC_0", "CE_0"), L(all, "EC_0", "CW_0")));
  EXPECT_TRUE(Foes(all, L(all, "EC_0", "CS_0"), L(all, "WC_0", "CE_0")));
  EXPECT_TRUE(Foes(all, L(all, "EC_0", "CS_0"), L(all, "WC_0", "CS_0")));
  // Two-way stop: the stem stops, the major road does not.
  const NetFile two = NetFile::Load(test::TJunction(dir, "t_two", "priority_stop"));
  CheckStructure(two);
  EXPECT_EQ(two.FindJunction("C")->type, "priority_stop");
  EXPECT_EQ(L(two, "SC_0", "CE_0").state, 's');
  EXPECT_EQ(L(two, "SC_0", "CW_0").state, 's');
  EXPECT_EQ(L(two, "WC_0", "CE_0").state, 'M');
  EXPECT_EQ(L(two, "EC_0", "CW_0").state, 'M');
  // SUMO's priority_stop makes every yielding link a stop link: the major
  // road's left turn stops too (its vehicles are held like the stem's).
  EXPECT_EQ(L(two, "EC_0", "CS_0").state, 's');
}

// ------------------------------------------------------------------ 4-way

TEST(NetFile, FourWayWithTurns) {
  TempDir dir("taebp_net");
  for (const char* type : {"priority", "allway_stop", "priority_stop"}) {
    SCOPED_TRACE(type);
    const NetFile net = NetFile::Load(test::FourWay(dir, std::string("x_") + type, type));
    CheckStructure(net);
    const Junction* c = net.FindJunction("C");
    EXPECT_EQ(c->type, type);
    EXPECT_THAT(c->inc_lanes, UnorderedElementsAre("NC_0", "EC_0", "SC_0", "WC_0"));
    EXPECT_EQ(c->links.size(), 12u);
    // From each approach: right, straight, left (no U-turns).
    const std::map<std::string, std::vector<std::string>> to = {
        {"N", {"CW", "CS", "CE"}}, {"E", {"CN", "CW", "CS"}},
        {"S", {"CE", "CN", "CW"}}, {"W", {"CS", "CE", "CN"}}};
    for (const auto& [from, exits] : to) {
      EXPECT_EQ(net.LinksFrom(from + "C_0").size(), 3u);
      EXPECT_EQ(L(net, from + "C_0", exits[0] + "_0").dir, 'r');
      EXPECT_EQ(L(net, from + "C_0", exits[1] + "_0").dir, 's');
      EXPECT_EQ(L(net, from + "C_0", exits[2] + "_0").dir, 'l');
    }
    const Link& ns = L(net, "NC_0", "CS_0");
    const Link& sn = L(net, "SC_0", "CN_0");
    const Link& ew = L(net, "EC_0", "CW_0");
    const Link& we = L(net, "WC_0", "CE_0");
    const Link& nl = L(net, "NC_0", "CE_0");
    const Link& el = L(net, "EC_0", "CS_0");
    const Link& nr = L(net, "NC_0", "CW_0");
    const Link& sl = L(net, "SC_0", "CW_0");
    EXPECT_FALSE(Foes(net, ns, sn));
    EXPECT_FALSE(Foes(net, ew, we));
    EXPECT_TRUE(Foes(net, ns, ew));
    EXPECT_TRUE(Foes(net, ns, we));
    EXPECT_TRUE(Foes(net, nl, sn));  // left against the opposite straight
    EXPECT_TRUE(Foes(net, el, we));
    EXPECT_TRUE(Foes(net, nr, ew));  // merges into CW
    EXPECT_TRUE(Foes(net, nr, sl));
    EXPECT_FALSE(Foes(net, nr, we));
    EXPECT_FALSE(Foes(net, nr, sn));
    if (std::string(type) != "allway_stop") {
      // The major road's left turns wait at an internal junction.
      for (const Link* l : {&el, &L(net, "WC_0", "CN_0")}) {
        EXPECT_EQ(l->internal.size(), 2u) << l->from_lane;
        EXPECT_EQ(l->state, std::string(type) == "priority" ? 'm' : 's');
      }
      EXPECT_EQ(ew.state, 'M');
      EXPECT_EQ(ns.state, std::string(type) == "priority" ? 'm' : 's');
    } else {
      for (int id : c->links) EXPECT_EQ(net.links()[id].state, 'w');
    }
  }
}

// ------------------------------------------------------------------ grids
// B1 of the grid, as hard-coded in tests/junction/interception_test.cc.
const char* const kB1Foes[12] = {
    "000100010000", "111100110000", "110111110000", "100010000000",
    "100110000111", "111110000110", "010000000100", "110000111100",
    "110000110111", "000000100010", "000111100110", "000110111110"};

TEST(NetFile, Grid4x4) {
  TempDir dir("taebp_net");
  const NetFile net = NetFile::Load(test::Netgenerate(dir, "grid", 4, "allway_stop"));
  CheckStructure(net);
  int junctions = 0;
  std::map<std::size_t, int> by_links;
  for (const auto& [id, j] : net.junctions()) {
    if (j.type == "internal") continue;
    ++junctions;
    EXPECT_EQ(j.type, "allway_stop") << id;
    ++by_links[j.links.size()];
  }
  EXPECT_EQ(junctions, 16);
  // 4 inner junctions with 4 approaches x 3 movements, 8 sides with 3 x 2,
  // 4 corners with 2 x 1.
  EXPECT_EQ(by_links, (std::map<std::size_t, int>{{2, 4}, {6, 8}, {12, 4}}));
  EXPECT_EQ(net.links().size(), 104u);
  // B1 is the junction of the SUMO-free tests, link by link.
  const Junction* b1 = net.FindJunction("B1");
  ASSERT_NE(b1, nullptr);
  EXPECT_EQ(b1->inc_lanes, (std::vector<std::string>{"B2B1_0", "C1B1_0", "B0B1_0", "A1B1_0"}));
  const char* const to[12] = {"B1A1_0", "B1B0_0", "B1C1_0", "B1B2_0", "B1A1_0", "B1B0_0",
                              "B1C1_0", "B1B2_0", "B1A1_0", "B1B0_0", "B1C1_0", "B1B2_0"};
  const char dirs[] = "rslrslrslrsl";
  for (int k = 0; k < 12; ++k) {
    const Link& l = net.links()[b1->links[k]];
    EXPECT_EQ(l.from_lane, b1->inc_lanes[k / 3]) << k;
    EXPECT_EQ(l.to_lane, to[k]) << k;
    EXPECT_EQ(l.dir, dirs[k]) << k;
    EXPECT_EQ(l.state, 'w') << k;
    for (int m = 0; m < 12; ++m)
      EXPECT_EQ(b1->foes[k][m], kB1Foes[k][11 - m] == '1') << k << "," << m;
  }
  // With fringe edges: every grid junction has four approaches, and the
  // fringe ends in dead ends.
  const NetFile fringe =
      NetFile::Load(test::Netgenerate(dir, "grid_fringe", 4, "priority_stop", 50));
  CheckStructure(fringe);
  int stops = 0, dead = 0;
  for (const auto& [id, j] : fringe.junctions()) {
    if (j.type == "priority_stop") {
      ++stops;
      EXPECT_EQ(j.links.size(), 12u) << id;
    }
    dead += j.type == "dead_end";
  }
  EXPECT_EQ(stops, 16);
  EXPECT_EQ(dead, 16);
}

TEST(NetFile, Figure8) {
  const NetFile net = NetFile::Load(DefaultNetworkPath());
  CheckStructure(net);
  const Junction* c = net.FindJunction("C");
  ASSERT_NE(c, nullptr);
  EXPECT_EQ(c->type, "allway_stop");
  ASSERT_EQ(c->links.size(), 2u);
  const Link& a = net.links()[c->links[0]];
  const Link& b = net.links()[c->links[1]];
  EXPECT_EQ(a.dir, 's');
  EXPECT_EQ(b.dir, 's');
  EXPECT_EQ(a.state, 'w');
  EXPECT_TRUE(c->foes[0][1]);
  EXPECT_TRUE(c->foes[1][0]);
  EXPECT_NE(a.from_lane, b.from_lane);
  for (const char* side : {"E", "W"}) {
    EXPECT_EQ(net.FindJunction(side)->type, "priority");
    EXPECT_EQ(net.FindJunction(side)->links.size(), 1u);
  }
  EXPECT_LT(net.boundary_min.x, net.boundary_max.x);
  EXPECT_LT(net.boundary_min.y, net.boundary_max.y);
}

// ------------------------------------------------------------------ against libsumo
// SUMO's <request foes> and libsumo's Lane::getInternalFoes are two views of
// one relation. They are comparable for links from different incoming lanes:
// getInternalFoes also lists the internal lanes of the other links from the
// same lane (they share their start), which the request never marks (links
// from one lane do not wait for each other). A link is a foe of another in
// libsumo's view when an internal lane of one is among the internal foes of
// an internal lane of the other.
//
// Findings (SUMO 1.15), asserted below: both include merges (two links into
// the same lane); every libsumo foe pair is a request foe pair; the request
// has more only for two left turns that each wait at an internal junction
// (opposite major-road lefts at a priority junction): SUMO keeps them foes in
// the request though their internal lanes do not intersect (each waits in
// the middle of the junction while the other passes).
struct CrossCheck {
  long pairs = 0, both = 0, neither = 0;
  std::vector<std::string> file_only, sumo_only;
};

CrossCheck CompareWithLibsumo(const NetFile& net) {
  CrossCheck out;
  Sumo().Start({"sumo", "-n", net.path(), "--no-step-log", "true", "--xml-validation", "never",
               "--no-warnings", "true"});
  std::map<std::string, std::set<std::string>> foes_of;
  auto internal_foes = [&](const std::string& lane) -> const std::set<std::string>& {
    auto it = foes_of.find(lane);
    if (it == foes_of.end()) {
      const std::vector<std::string> f = Sumo().LaneInternalFoes(lane);
      it = foes_of.emplace(lane, std::set<std::string>(f.begin(), f.end())).first;
    }
    return it->second;
  };
  for (const auto& [id, j] : net.junctions()) {
    const std::size_t n = j.links.size();
    for (std::size_t a = 0; a < n; ++a) {
      if (j.links[a] < 0) {
        ADD_FAILURE() << id << ": request index " << a << " has no link";
        continue;
      }
      for (std::size_t b = a + 1; b < n; ++b) {
        if (j.links[b] < 0) continue;
        const Link& la = net.links()[j.links[a]];
        const Link& lb = net.links()[j.links[b]];
        bool geo_ab = false, geo_ba = false;
        for (const std::string& x : la.internal)
          for (const std::string& y : lb.internal) {
            geo_ab |= internal_foes(x).count(y) > 0;
            geo_ba |= internal_foes(y).count(x) > 0;
          }
        EXPECT_EQ(geo_ab, geo_ba) << "libsumo's internal foes are not symmetric for "
                                  << la.via << " and " << lb.via;
        if (la.from_lane == lb.from_lane) {
          EXPECT_TRUE(geo_ab) << "libsumo lists links from one lane as internal foes";
          continue;
        }
        ++out.pairs;
        const bool file = j.foes[a][b] || j.foes[b][a];
        EXPECT_EQ(j.foes[a][b], j.foes[b][a]) << id << " " << a << "," << b;
        const std::string name = id + ": " + la.from_lane + ">" + la.to_lane + " (" + la.dir +
                                 ") / " + lb.from_lane + ">" + lb.to_lane + " (" + lb.dir + ")";
        if (file && geo_ab) ++out.both;
        if (!file && !geo_ab) ++out.neither;
        if (file && !geo_ab) out.file_only.push_back(name);
        if (!file && geo_ab) out.sumo_only.push_back(name);
        if (file && !geo_ab) {
          EXPECT_EQ(la.dir, 'l') << name;
          EXPECT_EQ(lb.dir, 'l') << name;
          EXPECT_EQ(la.internal.size(), 2u) << name;
          EXPECT_EQ(lb.internal.size(), 2u) << name;
        }
      }
    }
  }
  Sumo().Close();
  return out;
}

TEST(NetFileAgainstLibsumo, FoesMatchInternalFoesWhereComparable) {
  TempDir dir("taebp_net");
  const std::vector<std::string> nets = {
      test::TJunction(dir, "t_pri", "priority"),
      test::TJunction(dir, "t_all", "allway_stop"),
      test::TJunction(dir, "t_two", "priority_stop"),
      test::FourWay(dir, "x_pri", "priority"),
      test::FourWay(dir, "x_all", "allway_stop"),
      test::FourWay(dir, "x_two", "priority_stop"),
      test::Netgenerate(dir, "grid", 4, "allway_stop"),
      test::Netgenerate(dir, "grid_two", 3, "priority_stop", 50),
      DefaultNetworkPath()};
  long pairs = 0, both = 0, file_only = 0;
  for (const std::string& path : nets) {
    SCOPED_TRACE(path);
    const NetFile net = NetFile::Load(path);
    const CrossCheck c = CompareWithLibsumo(net);
    EXPECT_GT(c.both, 0);
    EXPECT_TRUE(c.sumo_only.empty()) << "libsumo foes that the request does not have, e.g. "
                                     << c.sumo_only.front();
    std::cout << path.substr(path.rfind('/') + 1) << ": " << c.pairs << " pairs, " << c.both
              << " foes in both, " << c.neither << " in neither, " << c.file_only.size()
              << " only in the request";
    for (const std::string& f : c.file_only) std::cout << "\n    " << f;
    std::cout << "\n";
    pairs += c.pairs;
    both += c.both;
    file_only += static_cast<long>(c.file_only.size());
  }
  EXPECT_GT(pairs, 1000);
  EXPECT_GT(both, 500);
  // The opposite major-road left turns of the priority 4-way, the same in its
  // priority_stop version, and one pair per junction of the 3x3 two-way grid.
  EXPECT_EQ(file_only, 1 + 1 + 9);
}

TEST(NetFileAgainstLibsumo, MergesAreFoesInBothViews) {
  TempDir dir("taebp_net");
  const NetFile net = NetFile::Load(test::Netgenerate(dir, "grid", 4, "allway_stop"));
  const Junction* b1 = net.FindJunction("B1");
  // B1 link 0 (north, right into A1) merges with link 4 (east straight into
  // A1) and link 8 (south left into A1).
  EXPECT_TRUE(b1->foes[0][4]);
  EXPECT_TRUE(b1->foes[0][8]);
  EXPECT_FALSE(b1->foes[0][1]);  // same lane
  Sumo().Start({"sumo", "-n", net.path(), "--no-step-log", "true", "--xml-validation", "never"});
  const std::vector<std::string> f = Sumo().LaneInternalFoes(":B1_0_0");
  Sumo().Close();
  EXPECT_TRUE(Contains(f, ":B1_4_0"));
  EXPECT_TRUE(Contains(f, ":B1_8_0"));
  EXPECT_TRUE(Contains(f, ":B1_1_0"));  // same lane: listed by libsumo
  EXPECT_FALSE(Contains(f, ":B1_10_0"));
}

// ------------------------------------------------------------------ bad input

TEST(NetFileBadInput, ClearMessagesNamingTheFile) {
  TempDir dir("taebp_net");
  const std::string missing = (dir.path() / "nope.net.xml").string();
  std::string msg = ErrorOf<std::runtime_error>([&] { NetFile::Load(missing); });
  EXPECT_THAT(msg, HasSubstr(missing));
  EXPECT_THAT(msg, HasSubstr("no such file"));

  const std::string garbage = dir.Write("garbage.net.xml", "not <xml at all <<<\x01\x02");
  msg = ErrorOf<std::runtime_error>([&] { NetFile::Load(garbage); });
  EXPECT_THAT(msg, HasSubstr(garbage));
  EXPECT_THAT(msg, HasSubstr("not a readable XML file"));

  const std::string empty = dir.Write("empty.net.xml", "");
  msg = ErrorOf<std::runtime_error>([&] { NetFile::Load(empty); });
  EXPECT_THAT(msg, HasSubstr(empty));

  const std::string routes =
      dir.Write("routes.xml", "<routes><vehicle id=\"a\" depart=\"0\"/></routes>\n");
  msg = ErrorOf<std::runtime_error>([&] { NetFile::Load(routes); });
  EXPECT_THAT(msg, HasSubstr(routes));
  EXPECT_THAT(msg, HasSubstr("not a SUMO network"));
  EXPECT_THAT(msg, HasSubstr("<routes>"));

  const std::string bare = dir.Write(
      "bare.net.xml",
      "<net version=\"1.9\">\n  <junction id=\"J\" type=\"dead_end\" x=\"0\" y=\"0\"/>\n</net>\n");
  msg = ErrorOf<std::runtime_error>([&] { NetFile::Load(bare); });
  EXPECT_THAT(msg, HasSubstr(bare));
  EXPECT_THAT(msg, HasSubstr("without edges"));

  // A directory is not a file.
  msg = ErrorOf<std::runtime_error>([&] { NetFile::Load(dir.path().string()); });
  EXPECT_THAT(msg, HasSubstr(dir.path().string()));
  EXPECT_THAT(msg, HasSubstr("a folder, not a file"));
}

}  // namespace
}  // namespace taebp::net
