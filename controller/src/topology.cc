#include "topology.h"

#include <algorithm>
#include <cmath>
#include <set>
#include <string>
#include <tuple>

namespace taebp::control {
namespace {

constexpr double kMajorNear = 3.0;  // m: a major-road vehicle this near the line is entering

// Appends a lane's shape to a path (a point equal to the path's last is
// skipped: consecutive lanes share their end points); returns the length added.
double AppendShape(const net::Lane& lane, std::vector<junction::Point2>* path) {
  double added = 0;
  for (const net::Point& p : lane.shape) {
    if (!path->empty()) {
      const junction::Point2 q = path->back();
      if (q.x == p.x && q.y == p.y) continue;
      added += std::hypot(p.x - q.x, p.y - q.y);
    }
    path->push_back({p.x, p.y});
  }
  return added;
}

}  // namespace

Topology::Topology(const ScenarioConfig& sc, const Scenario& scenario, const net::NetFile& net,
                   double sample_interval)
    : net_(net) {
  double vmax = sc.cruise_speed;
  for (const auto& [id, e] : net.edges())
    for (const std::string& lane : e.lanes)
      if (const net::Lane* l = net.FindLane(lane)) vmax = std::max(vmax, l->speed);
  vmax_ = vmax;
  reach_ = 2.0 * vmax * sample_interval + 10.0;
  for (std::size_t j = 0; j < scenario.junctions.size(); ++j)
    junction_index_.emplace(scenario.junctions[j].id, static_cast<int>(j));
  for (const ControlledJunction& cj : scenario.junctions) {
    const net::Junction* nj = net.FindJunction(cj.id);
    if (!nj) throw ConfigError("junction '" + cj.id + "' is not in " + net.path());
    JunctionInfo rt = MovementsOf(cj, *nj);
    AddApproaches(&rt, static_cast<int>(junctions_.size()));
    // Feeders of the major movements (two-way stops): the gap check looks
    // this far upstream.
    if (rt.spec.rule == junction::Rule::kTwoWay) {
      for (const MovementInfo& m : rt.movements)
        if (!m.controlled && std::find(rt.major_lanes.begin(), rt.major_lanes.end(),
                                       m.from_lane) == rt.major_lanes.end())
          rt.major_lanes.push_back(m.from_lane);
      for (MovementInfo& m : rt.movements) {
        if (m.controlled) continue;
        const net::Lane* l = net.FindLane(m.from_lane);
        AddFeeders(&m, (l ? l->speed : 13.89) * sc.critical_gap + kMajorNear);
      }
    }
    junctions_.push_back(std::move(rt));
  }
}

JunctionInfo Topology::MovementsOf(const ControlledJunction& cj,
                                   const net::Junction& nj) {
  const net::NetFile& net = net_;
  JunctionInfo rt;
  rt.info = cj;
  junction::JunctionSpec& spec = rt.spec;
  spec.id = cj.id;
  spec.rule = cj.type == "priority_stop" ? junction::Rule::kTwoWay : junction::Rule::kAllWay;
  std::map<std::string, int> approach_of;  // lane -> approach within junction
  std::vector<int> link_of;                // movement -> request index
  // A lane is a stop approach when all its links are stop links: at a
  // priority_stop junction SUMO also marks the major road's yielding
  // left turns 's', but that road does not stop (SUMO drives it).
  std::map<std::string, bool> stop_approach;
  for (int id : nj.links) {
    if (id < 0) continue;
    const net::Link& link = net.links()[id];
    const bool stop = link.state == 's' || link.state == 'w';
    auto [it, fresh] = stop_approach.emplace(link.from_lane, stop);
    if (!fresh) it->second = it->second && stop;
  }
  for (std::size_t li = 0; li < nj.links.size(); ++li) {
    const int id = nj.links[li];
    if (id < 0) continue;
    const net::Link& link = net.links()[id];
    MovementInfo m;
    m.from_lane = link.from_lane;
    m.to_lane = link.to_lane;
    m.internal = link.internal;
    m.dir = link.dir;
    m.state = link.state;
    m.controlled = stop_approach[link.from_lane];
    if (const net::Lane* tl = net.FindLane(link.to_lane)) m.to_edge = tl->edge;
    if (!approach_of.count(link.from_lane)) {
      const int a = static_cast<int>(approach_of.size());
      approach_of.emplace(link.from_lane, a);
    }
    junction::Movement jm;
    jm.approach = approach_of[link.from_lane];
    jm.controlled = m.controlled;
    jm.dir = m.dir;
    jm.from_lane = m.from_lane;
    jm.to_lane = m.to_lane;
    spec.movements.push_back(jm);
    link_of.push_back(static_cast<int>(li));
    rt.movements.push_back(std::move(m));
  }
  spec.approaches = static_cast<int>(approach_of.size());
  const std::size_t n = spec.movements.size();
  spec.conflict.assign(n, std::vector<bool>(n, false));
  for (std::size_t a = 0; a < n; ++a)
    for (std::size_t b = 0; b < n; ++b)
      spec.conflict[a][b] = nj.foes[link_of[a]][link_of[b]];
  for (std::size_t a = 0; a < n; ++a) rt.movements[a].mover = MoverFor(&rt.movements[a]);
  for (std::size_t a = 0; a < n; ++a) {
    MovementInfo& m = rt.movements[a];
    m.exit = ExitFor(m.to_lane);
    if (!m.controlled) continue;
    for (std::size_t b = 0; b < n; ++b)
      if (!rt.movements[b].controlled && spec.Conflict(static_cast<int>(a), static_cast<int>(b)))
        m.major_foes.push_back(static_cast<int>(b));
  }
  return rt;
}

void Topology::AddApproaches(JunctionInfo* junction, int jx) {
  const net::NetFile& net = net_;
  JunctionInfo& rt = *junction;
  // Approaches with a stop link: where heads wait.
  std::map<std::string, bool> stop_lane;
  for (const MovementInfo& m : rt.movements) stop_lane[m.from_lane] |= m.controlled;
  for (const auto& [lane, has_stop] : stop_lane) {
    rt.incoming.push_back(lane);
    rt.incoming_approach.push_back(has_stop ? static_cast<int>(approaches_.size()) : -1);
    if (!has_stop) continue;
    ApproachInfo ap;
    ap.lane = lane;
    const net::Lane* l = net.FindLane(lane);
    ap.length = l ? l->length : 0;
    ap.speed = l ? l->speed : vmax_;
    for (const std::string& p : net.Predecessors(lane))
      if (const net::Lane* pl = net.FindLane(p)) ap.speed = std::max(ap.speed, pl->speed);
    ap.edge = l ? l->edge : std::string();
    if (const net::Edge* e = l ? net.FindEdge(l->edge) : nullptr) ap.only_lane = e->lanes.size() == 1;
    ap.junction = jx;
    rt.approaches.push_back(static_cast<int>(approaches_.size()));
    edge_approaches_[ap.edge].push_back(static_cast<int>(approaches_.size()));
    approaches_.push_back(ap);
  }
}

void Topology::AddFeeders(MovementInfo* major, double reach) const {
  const net::NetFile& net = net_;
  MovementInfo& m = *major;
  // (lane, distance from its end to the line, whether every link from
  // it to the approach lane has the right of way over every foe there)
  std::vector<std::tuple<std::string, double, bool>> frontier = {{m.from_lane, 0.0, true}};
  std::set<std::string> seen;
  while (!frontier.empty()) {
    auto [lane, offset, free] = frontier.back();
    frontier.pop_back();
    if (!seen.insert(lane).second) continue;
    m.feeders.emplace_back(lane, offset);
    const net::Lane* fl = net.FindLane(lane);
    // A major-road HV of an encounter may be here (it keeps its speed
    // with SUMO's right of way off, so only where nothing on its way
    // to the approach lane would have made it yield).
    if (offset > 0 && fl && free) m.upstream.push_back({lane, m.mover.entry - offset, fl->length});
    const double next = offset + (fl ? fl->length : 0);
    if (next >= reach) continue;
    // Each feeding lane and the internal lanes of the node between it
    // and this one (an OSM road's shape and lane-change nodes): a
    // vehicle there is on its way too, and their lengths are part of
    // its distance to the line.
    for (const std::string& p : net.Predecessors(lane)) {
      for (int li : net.LinksFrom(p)) {
        const net::Link& link = net.links()[static_cast<std::size_t>(li)];
        if (link.to_lane != lane) continue;
        const bool on = free && link.state == 'M';
        double d = next;
        for (auto in = link.internal.rbegin(); in != link.internal.rend(); ++in) {
          const net::Lane* il = net.FindLane(*in);
          const double len = il ? il->length : 0;
          if (seen.insert(*in).second) {
            m.feeders.emplace_back(*in, d);
            if (on && il) m.upstream.push_back({*in, m.mover.entry - d, len});
          }
          d += len;
        }
        frontier.emplace_back(p, d, on);
      }
    }
  }
}

const std::vector<int>& Topology::ApproachesOfEdge(const std::string& edge) const {
  static const std::vector<int> kNone;
  const auto it = edge_approaches_.find(edge);
  return it == edge_approaches_.end() ? kNone : it->second;
}

int Topology::EdgeIndex(const std::string& edge) {
  const auto it = edge_index_.find(edge);
  if (it != edge_index_.end()) return it->second;
  const int k = static_cast<int>(edge_junction_.size());
  edge_index_.emplace(edge, k);
  const std::string end = net_.EdgeEnd(edge);
  const auto jt = junction_index_.find(end);
  edge_junction_.push_back(jt == junction_index_.end() ? -1 : jt->second);
  edge_names_.push_back(edge);
  double length = 0;
  if (const net::Edge* e = net_.FindEdge(edge); e && !e->lanes.empty())
    if (const net::Lane* l = net_.FindLane(e->lanes.front())) length = l->length;
  edge_length_.push_back(length);
  return k;
}

int Topology::MovementFor(int j, const std::string& lane, const std::string& next_edge) const {
  const std::vector<MovementInfo>& movements = junctions_[j].movements;
  for (std::size_t m = 0; m < movements.size(); ++m) {
    const MovementInfo& mv = movements[m];
    if (mv.controlled && mv.from_lane == lane && mv.to_edge == next_edge)
      return static_cast<int>(m);
  }
  return -1;
}

int Topology::MajorMovementFor(int j, const std::string& lane, const std::string& next_edge) const {
  const std::vector<MovementInfo>& movements = junctions_[j].movements;
  for (std::size_t m = 0; m < movements.size(); ++m) {
    const MovementInfo& mv = movements[m];
    if (!mv.controlled && mv.from_lane == lane && mv.to_edge == next_edge)
      return static_cast<int>(m);
  }
  return -1;
}

int Topology::ExitFor(const std::string& to_lane) {
  const auto it = exit_index_.find(to_lane);
  if (it != exit_index_.end()) return it->second;
  Exit c;
  std::string lane = to_lane;
  for (int guard = 0; guard < 64 && !lane.empty(); ++guard) {
    const net::Lane* l = net_.FindLane(lane);
    if (!l) break;
    c.lanes.push_back(lane);
    c.capacity += l->length;
    const std::string end = net_.EdgeEnd(l->edge);
    if (end.empty() || Controlled(end)) {
      if (!end.empty()) c.capacity -= 0.1;  // SUMO halts 0.1 m before the line
      break;
    }
    const std::vector<int>& out_links = net_.LinksFrom(lane);
    if (out_links.size() != 1 || c.capacity > 1000.0) break;
    const net::Link& link = net_.links()[out_links[0]];
    for (const std::string& in : link.internal) {
      c.lanes.push_back(in);
      if (const net::Lane* il = net_.FindLane(in)) c.capacity += il->length;
    }
    lane = link.to_lane;
  }
  const int k = static_cast<int>(exits_.size());
  exits_.push_back(c);
  exit_index_.emplace(to_lane, k);
  return k;
}

// A movement's centreline: the approach lane, the internal lanes, the exit
// lane, with their speed limits; the stop line and the junction's end on it
// (the vehicle's size and kinematics are filled in per meeting); where each
// lane lies on it.
junction::Mover Topology::MoverFor(MovementInfo* m) const {
  junction::Mover mv;
  double arc = 0;
  auto add = [&](const std::string& lane_id) {
    const net::Lane* l = net_.FindLane(lane_id);
    if (!l) return;
    mv.limits.emplace_back(arc, l->speed);
    const double start = arc;
    arc += AppendShape(*l, &mv.path);
    m->lanes_on_path.push_back({lane_id, start, l->length > 0 ? (arc - start) / l->length : 1.0});
  };
  add(m->from_lane);
  mv.entry = arc;
  for (const std::string& in : m->internal) add(in);
  mv.exit = arc;
  add(m->to_lane);
  return mv;
}

double MovementInfo::ArcOf(const std::string& lane, double pos) const {
  for (const LaneOnPath& l : lanes_on_path)
    if (l.lane == lane) return l.start + pos * l.scale;
  return -1;
}

bool MovementInfo::IsUpstream(const std::string& lane) const {
  for (const Upstream& u : upstream)
    if (u.lane == lane) return true;
  return false;
}

std::optional<double> MovementInfo::PathArc(const std::string& lane, double pos) const {
  for (const LaneOnPath& l : lanes_on_path)
    if (l.lane == lane) return l.start + pos * l.scale;
  for (const Upstream& u : upstream)
    if (u.lane == lane) return u.end - u.length + pos;
  return std::nullopt;
}

}  // namespace taebp::control
