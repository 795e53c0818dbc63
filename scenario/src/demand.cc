#include "taebp/scenario/demand.h"

#include "taebp/config/config.h"
#include "taebp/base/number_text.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <deque>
#include <set>
#include <fstream>
#include <random>
#include <stdexcept>

namespace taebp {
namespace {

// A portable uniform in [0, 1) (the standard distributions are
// implementation-defined).
double Uniform01(std::mt19937_64& rng) { return static_cast<double>(rng() >> 11) * 0x1.0p-53; }

}  // namespace

namespace {

// The car edges reachable from `from` through the junctions' links between
// car lanes (breadth first over edges).
std::set<std::string> Reachable(const net::NetFile& net, const std::string& from) {
  std::set<std::string> seen = {from};
  std::deque<std::string> todo = {from};
  while (!todo.empty()) {
    const net::Edge* e = net.FindEdge(todo.front());
    todo.pop_front();
    for (const std::string& lane : e->lanes) {
      const net::Lane* l = net.FindLane(lane);
      if (!l || !l->passenger) continue;
      for (int k : net.LinksFrom(lane)) {
        const net::Lane* to = net.FindLane(net.links()[static_cast<std::size_t>(k)].to_lane);
        if (!to || !to->passenger) continue;
        if (seen.insert(to->edge).second) todo.push_back(to->edge);
      }
    }
  }
  return seen;
}

}  // namespace

// Entries leave a fringe junction (NetFile::FringeJunctions: a dead end by
// topology), exits end at one; both must be open to cars (an OpenStreetMap
// import has footways and tracks at its fringe too).
FringeEdges FindFringe(const net::NetFile& net) {
  FringeEdges f;
  const std::vector<std::string> fringe = net.FringeJunctions();
  auto on_fringe = [&](const std::string& j) {
    return std::binary_search(fringe.begin(), fringe.end(), j);
  };
  for (const auto& [id, e] : net.edges()) {
    if (!net.IsCarEdge(e)) continue;
    if (on_fringe(e.from)) f.entries.push_back(id);
    if (on_fringe(e.to)) f.exits.push_back(id);
  }
  return f;
}

namespace {

// The controlled junctions' approaches open to cars, sorted: minor (a car
// link that yields or stops there, and no straight car link with the right of
// way: a major road's approach has both when its left turn yields) and major
// (a straight car link with the right of way). Cars' links only (an OSM
// sidewalk's link to a walking area goes straight on with 'M').
struct Approaches {
  std::vector<std::string> minor, major;
};
Approaches FindApproaches(const net::NetFile& net, const std::vector<std::string>& junctions) {
  const std::set<std::string> at(junctions.begin(), junctions.end());
  Approaches a;
  for (const auto& [id, e] : net.edges()) {
    if (!net.IsCarEdge(e) || !at.count(e.to)) continue;
    bool yields = false, major = false;
    for (const std::string& lane : e.lanes) {
      const net::Lane* from = net.FindLane(lane);
      if (!from || !from->passenger) continue;
      for (int k : net.LinksFrom(lane)) {
        const net::Link& link = net.links()[static_cast<std::size_t>(k)];
        const net::Lane* to = net.FindLane(link.to_lane);
        if (link.junction != e.to || !to || !to->passenger) continue;
        if (link.state != 'M') yields = true;
        if (link.state == 'M' && link.dir == 's') major = true;
      }
    }
    if (yields && !major) a.minor.push_back(id);
    if (major) a.major.push_back(id);
  }
  return a;
}

// The minor roads' and the major roads' destinations: the minor roads and
// the fringe exits.
std::vector<std::string> CityExits(const net::NetFile& net, const std::vector<std::string>& minor) {
  std::vector<std::string> exits = minor;
  const std::vector<std::string> out = FindFringe(net).exits;
  exits.insert(exits.end(), out.begin(), out.end());
  std::sort(exits.begin(), exits.end());
  exits.erase(std::unique(exits.begin(), exits.end()), exits.end());
  return exits;
}

// One Poisson stream of `flow` veh/h per entry, each trip to a uniformly
// random destination among f.exits it can reach, other than those ending at
// the entry's `home` junction (fringe: where it comes from, the way back;
// otherwise: the junction it approaches). Each entry has its own random
// stream (seed, salt, index): adding an edge does not shift the others.
void AppendStreams(const net::NetFile& net, const FringeEdges& f, bool fringe, double flow,
                   std::uint32_t salt, const DemandSpec& spec, std::vector<Trip>* trips) {
  const double rate = flow / 3600.0;  // per second
  for (std::size_t k = 0; k < f.entries.size(); ++k) {
    const std::string& entry = f.entries[k];
    const std::string home = fringe ? net.FindEdge(entry)->from : net.FindEdge(entry)->to;
    // The destinations a car can reach from this origin (one-way streets,
    // turn restrictions).
    const std::set<std::string> reachable = Reachable(net, entry);
    std::vector<std::string> exits;
    for (const std::string& x : f.exits)
      if (net.FindEdge(x)->to != home && reachable.count(x)) exits.push_back(x);
    if (exits.empty()) continue;
    std::seed_seq seq{static_cast<std::uint32_t>(spec.seed & 0xffffffffu),
                      static_cast<std::uint32_t>(spec.seed >> 32), salt,
                      static_cast<std::uint32_t>(k)};
    std::mt19937_64 rng(seq);
    double t = spec.begin;
    for (;;) {
      t += -std::log1p(-Uniform01(rng)) / rate;
      if (t >= spec.end) break;
      const std::size_t pick =
          std::min(exits.size() - 1, static_cast<std::size_t>(Uniform01(rng) * exits.size()));
      trips->push_back({"", t, entry, exits[pick]});
    }
  }
}

}  // namespace

FringeEdges FindMinorRoads(const net::NetFile& net, const std::vector<std::string>& junctions) {
  FringeEdges f;
  f.entries = FindApproaches(net, junctions).minor;
  f.exits = CityExits(net, f.entries);
  return f;
}

FringeEdges FindMajorRoads(const net::NetFile& net, const std::vector<std::string>& junctions) {
  const Approaches a = FindApproaches(net, junctions);
  FringeEdges f;
  f.entries = a.major;
  f.exits = CityExits(net, a.minor);
  return f;
}

std::vector<Trip> DemandTrips(const net::NetFile& net, const DemandSpec& spec) {
  const bool fringe = spec.origins == DemandOrigins::kFringe;
  const FringeEdges f = fringe ? FindFringe(net) : FindMinorRoads(net, spec.junctions);
  if (f.entries.empty() || f.exits.empty())
    throw std::invalid_argument(
        "the network " + net.path() +
        (fringe ? " has no fringe (no car edge from or to a junction with one neighbour) for generated demand"
                : " has no minor road (an approach of a controlled junction with a car link that "
                  "yields or stops and none going straight on with the right of way) for generated "
                  "demand (origins: minor_roads)") +
        "; give scenario.routes instead");
  std::vector<Trip> trips;
  AppendStreams(net, f, fringe, spec.flow, 0x64656d64u, spec, &trips);
  if (spec.major_flow > 0) {
    const FringeEdges m = FindMajorRoads(net, spec.junctions);
    if (m.entries.empty() || m.exits.empty()) {
      throw std::invalid_argument("the network " + net.path() +
                                  " has no major road (an approach of a controlled junction with "
                                  "a straight car link that has the right of way) for major_flow = " +
                                  NumberText(spec.major_flow, 6) + " veh/h; set it to 0");
    }
    AppendStreams(net, m, false, spec.major_flow, 0x6d616a72u, spec, &trips);
  }
  std::stable_sort(trips.begin(), trips.end(),
                   [](const Trip& a, const Trip& b) { return a.depart < b.depart; });
  for (std::size_t i = 0; i < trips.size(); ++i) trips[i].id = "d" + std::to_string(i);
  return trips;
}

long WriteDemand(const net::NetFile& net, const DemandSpec& spec, const std::string& path) {
  std::vector<Trip> trips;
  try {
    trips = DemandTrips(net, spec);
  } catch (const std::invalid_argument& e) {
    throw ConfigError(std::string("scenario.demand: ") + e.what());
  }
  std::ofstream out(path);
  if (!out) throw ConfigError("scenario.demand: cannot write " + path);
  char buf[512];
  out << "<routes>\n"
      << "    <vType id=\"car\" length=\"" << NumberText(spec.length, 6) << "\" width=\""
      << NumberText(spec.width, 6) << "\" minGap=\"" << NumberText(spec.min_gap, 6)
      << "\" accel=\"" << NumberText(spec.accel, 6) << "\" decel=\"" << NumberText(spec.decel, 6)
      << "\" maxSpeed=\"" << NumberText(spec.max_speed, 6) << "\" sigma=\"0\" speedDev=\"0\"/>\n";
  for (const Trip& t : trips) {
    std::snprintf(buf, sizeof buf,
                  "    <trip id=\"%s\" type=\"car\" depart=\"%.2f\" from=\"%s\" to=\"%s\" "
                  "departLane=\"best\" departSpeed=\"max\"/>\n",
                  t.id.c_str(), t.depart, t.from.c_str(), t.to.c_str());
    out << buf;
  }
  out << "</routes>\n";
  if (!out) throw ConfigError("scenario.demand: writing " + path + " failed");
  return static_cast<long>(trips.size());
}

}  // namespace taebp
