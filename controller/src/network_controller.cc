#include "taebp/controller/network_controller.h"

#include "taebp/controller/sumo_adapter.h"
#include "taebp/junction/conflict_geometry.h"
#include "taebp/junction/design.h"
#include "taebp/junction/hv_population.h"
#include "taebp/junction/intersection.h"
#include "taebp/junction/interception.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <random>
#include <set>
#include <sstream>
#include <unordered_map>

namespace taebp {
namespace {

using junction::Command;
using junction::Interception;
using persuasion::Policy;

// Speed modes (bits: 1 safe speed, 2 max accel, 4 max decel, 8 right of way,
// 16 red light, 32 ignore foes already in the junction).
constexpr int kModeDefault = 31;   // SUMO's own rules (stop signs included)
constexpr int kModeReleased = 55;  // the controller decided the junction; keep car-following
constexpr int kModeCreep = 0;      // exact commanded speeds during a nudge

constexpr double kHaltSpeed = 0.1;      // m/s: SUMO's halting threshold
constexpr double kAtLine = 1.0;         // m: a front this near the lane end is at the line
constexpr double kSlow = 0.5;           // m/s: a front at its line slower than this waits there
constexpr double kStopGap = 0.1;        // m: SUMO halts a front this far before the lane end
constexpr double kMajorNear = 3.0;      // m: a major-road vehicle this near the line is entering

// kFree: SUMO drives it. kHeld: held at its line (an encounter's vehicle, or a
// third vehicle waiting for one). kNudging/kNudged: the encounter's AV.
// kCrossing: an encounter vehicle released (SUMO's right of way off) or handed
// back, until it has left the junction.
enum class State { kFree, kHeld, kNudging, kNudged, kCrossing };

// Vehicle colours under colour_states (r, g, b).
enum class Paint { kType, kNudging, kDr, kDc, kCollided };
constexpr std::array<std::array<int, 3>, 5> kPaintRgb = {
    {{0, 0, 0}, {255, 220, 0}, {255, 140, 0}, {0, 200, 0}, {255, 0, 255}}};
constexpr std::array<int, 3> kAvRgb = {0, 0, 255};
constexpr std::array<int, 3> kHvRgb = {255, 0, 0};

std::string Fmt(double v) {
  std::ostringstream os;
  os.precision(6);
  os << v;
  return os.str();
}

// A uniform in [0, 1) that depends only on (seed, text, salt): each vehicle's
// draws are independent of departure order and of the other vehicles.
double HashUniform(std::uint64_t seed, const std::string& text, std::uint64_t salt) {
  std::uint64_t h = 1469598103934665603ULL;  // FNV-1a
  for (unsigned char c : text) {
    h ^= c;
    h *= 1099511628211ULL;
  }
  std::uint64_t x = seed * 0x9E3779B97F4A7C15ULL ^ h ^ (salt << 1);
  for (int i = 0; i < 2; ++i) {  // splitmix64 finaliser, twice
    x += 0x9E3779B97F4A7C15ULL;
    x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ULL;
    x = (x ^ (x >> 27)) * 0x94D049BB133111EBULL;
    x ^= x >> 31;
  }
  return static_cast<double>(x >> 11) * 0x1.0p-53;
}
constexpr std::uint64_t kSaltAv = 0x6176;     // "av"
constexpr std::uint64_t kSaltTrust = 0x7472;  // "tr"

struct Veh {
  std::string id;
  bool alive = false;
  VehicleKind kind = VehicleKind::kHV;
  double trust = 0;
  double length = 5, min_gap = 2;
  double width = 1.8, accel = 2.6, max_speed = 13.89;  // its SUMO type's (BothProceedCollide)
  std::vector<int> route;  // edge indices
  int route_pos = 0;       // route index already counted
  State state = State::kFree;
  int junction = -1, movement = -1, approach = -1;
  double held_since = 0, hold_odometer = 0;
  double line_since = -1;  // halted at its stop line since (-1: not there)
  double line_gap = 0;     // m from its front to the stop line when halted there
  bool reckless = false;   // released with SUMO's right of way off
  std::vector<int> near;   // controlled junctions whose stop line it may reach within a second
  double target = 0, creep_speed = 0, commanded = 0;
  std::string lane;        // while crossing: the lane it was last seen on
  Paint paint = Paint::kType;
  int open_encounters = 0;  // formed, not yet recorded: the slot is not reused before
};

struct Chain {  // the lanes a movement's exit fills before the next stop line
  std::vector<std::string> lanes;
  double capacity = 0;
};

struct MovementRt {
  std::string from_lane, to_lane;
  std::vector<std::string> internal;
  std::string to_edge;
  char dir = 's';
  bool controlled = false;
  int chain = -1;
  std::vector<int> major_foes;  // major movements (same junction) in conflict
  // Lanes feeding this (major) movement with the distance from their end to
  // the line, for the gap check.
  std::vector<std::pair<std::string, double>> feeders;
  // Its path from the approach lane through the junction onto the exit lane
  // (front, length and kinematics filled per vehicle): EncounterModel::Game.
  junction::Mover mover;
};

struct ApproachRt {
  std::string lane;
  double length = 0;
  int junction = -1;
  int front = -1;  // the vehicle at its line last time it was looked at
  ApproachStats stats;
};

struct JunctionRt {
  ControlledJunction info;
  std::unique_ptr<Interception> logic;
  std::vector<MovementRt> movements;
  std::vector<int> approaches;  // global approach indices (stop-controlled lanes)
  std::vector<std::string> incoming;  // every lane into it (stall check)
  JunctionRun run;
  int near_av = 0, near_hv = 0;  // vehicles that may reach its stop lines within a second
  std::vector<junction::AtLine> at_line;  // this step
  double last_progress = 0;     // a vehicle last passed it (route progress)
  bool waiting = false;         // vehicles halted on its incoming lanes (last sample)
  bool watched = false;         // looked at this step (Watched)
  double waiting_since = 0;     // since when (an idle junction is not stalled)
  bool stall_recorded = false;  // this stall episode is in the outputs
  double stall_since = -1;
};

}  // namespace

struct NetworkController::Impl : junction::EncounterModel {
  Impl(const ExperimentConfig& config, std::optional<Policy> policy, const Scenario& scenario,
       const net::NetFile& net, const ControllerOptions& options)
      : cfg(config),
        sc(config.scenario),
        policy(policy),
        scenario(scenario),
        net(net),
        opts(options),
        model(MakeLikelihood(config.model.likelihood)),
        rng(config.scenario.seed) {
    params.prior_go = config.model.prior_go;
    params.collision_penalty = config.model.collision_penalty;
    out.policy = policy ? persuasion::ToString(*policy) : kSumoNative;
    out.scenario_kind = sc.kind;
    if (policy) {
      // Each HV's trust, the AV's design for it, its reading (hv_population.h).
      population = std::make_unique<HvPopulation>(config, *policy);
      out.scheme = population->PopulationScheme();
      out.theory = population->Theory();
    }
    dt = sc.step_length;
    sample_every = std::max(1L, std::lround(1.0 / dt));
    BuildTopology();
  }

  // ------------------------------------------------------------ topology
  int EdgeIndex(const std::string& edge) {
    const auto it = edge_index.find(edge);
    if (it != edge_index.end()) return it->second;
    const int k = static_cast<int>(edge_junction.size());
    edge_index.emplace(edge, k);
    const std::string end = net.EdgeEnd(edge);
    const auto jt = junction_index.find(end);
    edge_junction.push_back(jt == junction_index.end() ? -1 : jt->second);
    edge_names.push_back(edge);
    double length = 0;
    if (const net::Edge* e = net.FindEdge(edge); e && !e->lanes.empty())
      if (const net::Lane* l = net.FindLane(e->lanes.front())) length = l->length;
    edge_length.push_back(length);
    return k;
  }

  bool Controlled(const std::string& junction_id) const { return junction_index.count(junction_id); }

  int ChainFor(const std::string& to_lane) {
    const auto it = chain_index.find(to_lane);
    if (it != chain_index.end()) return it->second;
    Chain c;
    std::string lane = to_lane;
    for (int guard = 0; guard < 64 && !lane.empty(); ++guard) {
      const net::Lane* l = net.FindLane(lane);
      if (!l) break;
      c.lanes.push_back(lane);
      c.capacity += l->length;
      const std::string end = net.EdgeEnd(l->edge);
      if (end.empty() || Controlled(end)) {
        if (!end.empty()) c.capacity -= 0.1;  // SUMO halts 0.1 m before the line
        break;
      }
      const std::vector<int>& out_links = net.LinksFrom(lane);
      if (out_links.size() != 1 || c.capacity > 1000.0) break;
      const net::Link& link = net.links()[out_links[0]];
      for (const std::string& in : link.internal) {
        c.lanes.push_back(in);
        if (const net::Lane* il = net.FindLane(in)) c.capacity += il->length;
      }
      lane = link.to_lane;
    }
    const int k = static_cast<int>(chains.size());
    chains.push_back(c);
    chain_index.emplace(to_lane, k);
    return k;
  }

  // Appends a lane's shape to a path (a point equal to the path's last is
  // skipped: consecutive lanes share their end points); returns the length added.
  static double AppendShape(const net::Lane& lane, std::vector<junction::Point2>* path) {
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

  // A movement's centreline: the approach lane, the internal lanes, the exit
  // lane, with their speed limits; the stop line and the junction's end on it
  // (the vehicle's size and kinematics are filled in per meeting: Game).
  junction::Mover MoverFor(const MovementRt& m) const {
    junction::Mover mv;
    double arc = 0;
    auto add = [&](const std::string& lane_id) {
      const net::Lane* l = net.FindLane(lane_id);
      if (!l) return;
      mv.limits.emplace_back(arc, l->speed);
      arc += AppendShape(*l, &mv.path);
    };
    add(m.from_lane);
    mv.entry = arc;
    for (const std::string& in : m.internal) add(in);
    mv.exit = arc;
    add(m.to_lane);
    return mv;
  }

  void BuildTopology() {
    double vmax = sc.cruise_speed;
    for (const auto& [id, e] : net.edges())
      for (const std::string& lane : e.lanes)
        if (const net::Lane* l = net.FindLane(lane)) vmax = std::max(vmax, l->speed);
    reach = 2.0 * vmax * sample_every * dt + 10.0;  // speed factors up to 2, and a margin
    for (std::size_t j = 0; j < scenario.junctions.size(); ++j)
      junction_index.emplace(scenario.junctions[j].id, static_cast<int>(j));
    for (const ControlledJunction& cj : scenario.junctions) {
      const net::Junction* nj = net.FindJunction(cj.id);
      if (!nj) throw ConfigError("junction '" + cj.id + "' is not in " + net.path());
      JunctionRt rt;
      rt.info = cj;
      junction::JunctionSpec spec;
      spec.id = cj.id;
      spec.rule = cj.type == "priority_stop" ? junction::Rule::kTwoWay : junction::Rule::kAllWay;
      std::map<std::string, int> approach_of;  // lane -> approach within junction
      std::vector<int> link_of;                // movement -> request index
      // A lane is a stop approach when all its links are stop links: at a
      // priority_stop junction SUMO also marks the major road's yielding
      // left turns 's', but that road does not stop (SUMO drives it).
      std::map<std::string, bool> stop_approach;
      for (int id : nj->links) {
        if (id < 0) continue;
        const net::Link& link = net.links()[id];
        const bool stop = link.state == 's' || link.state == 'w';
        auto [it, fresh] = stop_approach.emplace(link.from_lane, stop);
        if (!fresh) it->second = it->second && stop;
      }
      for (std::size_t li = 0; li < nj->links.size(); ++li) {
        const int id = nj->links[li];
        if (id < 0) continue;
        const net::Link& link = net.links()[id];
        MovementRt m;
        m.from_lane = link.from_lane;
        m.to_lane = link.to_lane;
        m.internal = link.internal;
        m.dir = link.dir;
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
          spec.conflict[a][b] = nj->foes[link_of[a]][link_of[b]];
      for (std::size_t a = 0; a < n; ++a) rt.movements[a].mover = MoverFor(rt.movements[a]);
      const int jx = static_cast<int>(junctions.size());
      for (std::size_t a = 0; a < n; ++a) {
        MovementRt& m = rt.movements[a];
        m.chain = ChainFor(m.to_lane);
        if (!m.controlled) continue;
        for (std::size_t b = 0; b < n; ++b)
          if (!rt.movements[b].controlled && spec.Conflict(static_cast<int>(a), static_cast<int>(b)))
            m.major_foes.push_back(static_cast<int>(b));
      }
      // Approaches with a stop link: where heads are held.
      std::map<std::string, bool> stop_lane;
      for (const MovementRt& m : rt.movements) stop_lane[m.from_lane] |= m.controlled;
      for (const auto& [lane, has_stop] : stop_lane) rt.incoming.push_back(lane);
      for (const auto& [lane, has_stop] : stop_lane) {
        if (!has_stop) continue;
        ApproachRt ap;
        ap.lane = lane;
        const net::Lane* l = net.FindLane(lane);
        ap.length = l ? l->length : 0;
        ap.junction = jx;
        ap.stats.lane = lane;
        rt.approaches.push_back(static_cast<int>(approaches.size()));
        approaches.push_back(ap);
      }
      // Feeders of the major movements (two-way stops): the gap check looks
      // this far upstream.
      if (spec.rule == junction::Rule::kTwoWay) {
        for (MovementRt& m : rt.movements) {
          if (m.controlled) continue;
          const net::Lane* l = net.FindLane(m.from_lane);
          const double reach = (l ? l->speed : 13.89) * sc.critical_gap + kMajorNear;
          std::vector<std::pair<std::string, double>> frontier = {{m.from_lane, 0.0}};
          std::set<std::string> seen;
          while (!frontier.empty()) {
            auto [lane, offset] = frontier.back();
            frontier.pop_back();
            if (!seen.insert(lane).second) continue;
            m.feeders.emplace_back(lane, offset);
            const net::Lane* fl = net.FindLane(lane);
            const double next = offset + (fl ? fl->length : 0);
            if (next >= reach) continue;
            for (const std::string& p : net.Predecessors(lane)) frontier.emplace_back(p, next);
          }
        }
      }
      junction::Timing timing{sc.confirm_delay};
      rt.logic = std::make_unique<Interception>(std::move(spec), timing);
      rt.run.id = cj.id;
      rt.run.type = cj.type;
      rt.run.original_type = cj.original_type;
      rt.run.rule = junction::ToString(rt.logic->spec().rule);
      junctions.push_back(std::move(rt));
    }
    for (JunctionRt& j : junctions)
      for (int a : j.approaches) j.run.approaches.push_back(approaches[a].stats);
  }

  // ------------------------------------------------------------ environment
  struct Env : junction::Environment {
    Impl* self = nullptr;
    JunctionRt* j = nullptr;
    bool AreaClear(int av_movement, int hv_movement) override {
      return self->AreaClear(*j, av_movement, hv_movement);
    }
    bool Standing(int vehicle) override { return self->Standing(vehicle); }
    bool ExitHasRoom(int movement, int vehicle) override {
      return self->ExitHasRoom(*j, movement, vehicle);
    }
    bool MajorClear(int movement) override { return self->MajorClear(*j, movement); }
  };

  // A held vehicle has come to a standstill: the nudge is measured from here.
  bool Standing(int h) {
    Veh& v = vehs[h];
    if (sumo::Speed(v.id) > 0.0) return false;
    v.hold_odometer = sumo::Distance(v.id);
    return true;
  }

  // No vehicle inside the junction on the two movements or on any movement
  // conflicting with them (the encounter's two are still at their lines).
  bool AreaClear(const JunctionRt& j, int av_movement, int hv_movement) {
    const junction::JunctionSpec& spec = j.logic->spec();
    for (std::size_t k = 0; k < j.movements.size(); ++k) {
      const int m = static_cast<int>(k);
      if (m != av_movement && m != hv_movement && !spec.Conflict(m, av_movement) &&
          !spec.Conflict(m, hv_movement))
        continue;
      for (const std::string& in : j.movements[k].internal)
        if (sumo::LaneVehicleNumber(in) > 0) return false;
    }
    return true;
  }

  // Keep clear: a head enters only if its exit can take it with its rear off
  // the junction. Two forms of one rule, by what the exit can be relied on
  // to do:
  // - closed loops (the figure-8): vehicles leave a loop only through this
  //   junction, so every vehicle already headed into the loop is counted as
  //   if queued at its end (a full loop is a gridlock of its own);
  // - open networks: vehicles on the exit move on through the next junction,
  //   so the exit needs room behind its last vehicle now, less the vehicles
  //   already released towards it (SUMO's own keepClear does the same).
  bool ExitHasRoom(const JunctionRt& j, int movement, int vehicle) {
    const MovementRt& m = j.movements[movement];
    const Chain& c = chains[m.chain];
    const Veh& v = vehs[vehicle];
    const double unit = v.length + v.min_gap;
    // Headed into this exit, not yet on it: inside the junction on a
    // movement into it (whoever drives them), and encounter vehicles released
    // towards it still on their approach lanes.
    long inflight = 0;
    for (const MovementRt& k : j.movements) {
      if (k.chain != m.chain) continue;
      for (const std::string& in : k.internal) {
        if (sumo::LaneVehicleNumber(in) == 0) continue;
        for (const std::string& id : sumo::LaneVehicleIDs(in)) inflight += id != v.id;  // a nudged AV
      }
    }
    for (int h : crossing) {
      const Veh& w = vehs[h];
      if (w.junction < 0) continue;
      const MovementRt& wm = junctions[w.junction].movements[w.movement];
      if (wm.chain == m.chain && w.lane == wm.from_lane) ++inflight;
    }
    if (scenario.lap.empty()) {
      const std::vector<std::string> ids = sumo::LaneVehicleIDs(m.to_lane);
      const net::Lane* exit = net.FindLane(m.to_lane);
      double free = exit ? exit->length : 0;
      if (ids.empty() && inflight == 0) return true;  // an empty exit, however short
      if (!ids.empty()) free = sumo::LanePosition(ids.front()) - sumo::Length(ids.front());
      return free - inflight * unit >= unit;
    }
    long ahead = inflight;
    for (const std::string& lane : c.lanes) ahead += sumo::LaneVehicleNumber(lane);
    return ahead * unit + v.length <= c.capacity;
  }

  // Two-way stops: no major vehicle inside or about to reach a conflicting
  // major movement within the critical gap.
  bool MajorClear(const JunctionRt& j, int movement) {
    // A halted major vehicle is yielding (SUMO's rules, e.g. to the AV that
    // nudged into the junction): it starts only when SUMO sees the way clear,
    // so it counts as no traffic; waiting for it would wait for ever.
    auto moving = [&](const std::string& id) { return sumo::Speed(id) >= kHaltSpeed; };
    for (int k : j.movements[movement].major_foes) {
      const MovementRt& mk = j.movements[k];
      for (const std::string& in : mk.internal) {
        if (sumo::LaneVehicleNumber(in) == 0) continue;
        for (const std::string& id : sumo::LaneVehicleIDs(in))
          if (moving(id)) return false;
      }
      for (const auto& [lane, offset] : mk.feeders) {
        const std::vector<std::string> ids = sumo::LaneVehicleIDs(lane);
        if (ids.empty()) continue;
        const std::string& front = ids.back();
        const double speed = sumo::Speed(front);
        if (speed < kHaltSpeed) continue;
        const net::Lane* l = net.FindLane(lane);
        const double dist = offset + (l ? l->length : 0) - sumo::LanePosition(front);
        if (dist < kMajorNear) return false;
        // Time to reach the line accelerating from its speed now: within the
        // critical gap, no gap.
        const double reach = (-speed + std::sqrt(speed * speed + 2.0 * sc.accel * dist)) / sc.accel;
        if (reach < sc.critical_gap) return false;
      }
    }
    return true;
  }

  // ------------------------------------------------------------ encounter model
  AvDraw Draw(int av, int hv) override {
    ++vehs[av].open_encounters;
    ++vehs[hv].open_encounters;
    return DrawAv(population->Commit(vehs[av].id, vehs[hv].id), params.prior_go, rng);
  }
  // The paper's game needs "AV goes, HV drives recklessly" to be a collision:
  // predicted on the two movements' geometry from where the two vehicles
  // would start, the AV from its Go signal (s* ahead of where it is held
  // when its scheme nudges on Go). Figure-8: its crossing is always the game.
  bool Game(int av, int hv, int av_movement, int hv_movement) override {
    if (!sc.IsNetwork()) return true;
    const Veh& a = vehs[av];
    const Veh& h = vehs[hv];
    JunctionRt& j = junctions[a.junction];
    junction::Mover ma = j.movements[av_movement].mover;
    junction::Mover mh = j.movements[hv_movement].mover;
    for (auto [m, v] : {std::pair{&ma, &a}, std::pair{&mh, &h}}) {
      m->length = v->length;
      m->width = v->width;
      m->accel = v->accel;
      m->max_speed = v->max_speed;
    }
    ma.front = ma.entry - a.line_gap + population->GoSignal(h.id);
    mh.front = mh.entry - h.line_gap;
    const bool collides = junction::BothProceedCollide(ma, mh, dt);
    verdicts[{av, hv}] = collides;
    if (collides || sc.encounter_pairs == "all") return true;
    if (now >= sc.warmup) ++j.run.meetings_not_game;
    return false;
  }

  HvReading Read(int av, int hv, double observed) override {
    const HvReading r = population->Read(vehs[av].id, vehs[hv].id, observed);
    SetPaint(hv, r.drives_if_clear ? Paint::kDc : Paint::kDr);
    return r;
  }

  // ------------------------------------------------------------ vehicles
  void SetPaint(int h, Paint paint) {
    Veh& v = vehs[h];
    if (!opts.colour_states || v.paint == paint) return;
    const std::array<int, 3>& rgb = paint != Paint::kType
                                        ? kPaintRgb[static_cast<int>(paint)]
                                        : (v.kind == VehicleKind::kAV ? kAvRgb : kHvRgb);
    sumo::SetColor(v.id, rgb[0], rgb[1], rgb[2]);
    v.paint = paint;
  }

  void Register(const std::string& id) {
    int h;
    if (!free_slots.empty()) {
      h = free_slots.back();
      free_slots.pop_back();
    } else {
      h = static_cast<int>(vehs.size());
      vehs.emplace_back();
    }
    Veh v;
    v.id = id;
    v.alive = true;
    bool av;
    if (sc.av_share) {
      av = HashUniform(sc.seed, id, kSaltAv) < *sc.av_share;
    } else {
      const std::string type = sumo::TypeID(id);
      av = std::find(sc.av_types.begin(), sc.av_types.end(), type) != sc.av_types.end();
    }
    v.kind = av ? VehicleKind::kAV : VehicleKind::kHV;
    if (!av) {
      const TrustSpec& t = cfg.model.trust;
      v.trust = t.IsFixed() ? t.value : t.Draw(HashUniform(sc.seed, id, kSaltTrust));
      if (policy) population->Add(id, v.trust);
      if (out.hv_trust.size() < kTrustListMax) out.hv_trust.push_back(v.trust);
    }
    v.length = sumo::Length(id);
    v.min_gap = sumo::MinGap(id);
    if (sc.IsNetwork()) {  // for the game's premise (Game): route files may bring their own types
      v.width = sumo::Width(id);
      v.accel = sumo::Accel(id);
      v.max_speed = sumo::MaxSpeed(id);
    }
    for (const std::string& e : sumo::Route(id)) v.route.push_back(EdgeIndex(e));
    v.route_pos = std::max(0, sumo::RouteIndex(id));
    vehs[h] = std::move(v);
    index[id] = h;
    UpdateNear(h);
    if (opts.colour_states) {
      vehs[h].paint = Paint::kNudging;  // force the first paint
      SetPaint(h, Paint::kType);
    }
    if (now >= sc.warmup) ++out.network.departed;
  }

  // Counts the controlled junctions a vehicle passed since the last count.
  void CountProgress(int h, int new_pos) {
    Veh& v = vehs[h];
    const int last = static_cast<int>(v.route.size()) - 1;
    new_pos = std::min(new_pos, last);
    for (int k = v.route_pos; k < new_pos; ++k) {
      const int j = edge_junction[v.route[k]];
      if (j < 0) continue;
      junctions[j].last_progress = now;
      last_crossing = now;
      if (now < sc.warmup) continue;
      (v.kind == VehicleKind::kAV ? junctions[j].run.crossings_av : junctions[j].run.crossings_hv)++;
    }
    v.route_pos = std::max(v.route_pos, new_pos);
  }

  void Unregister(const std::string& id) {
    const auto it = index.find(id);
    if (it == index.end()) return;
    const int h = it->second;
    Veh& v = vehs[h];
    CountProgress(h, static_cast<int>(v.route.size()) - 1);
    v.alive = false;
    if (population && v.kind == VehicleKind::kHV) population->Remove(id);
    if (v.state == State::kCrossing) Clear(h);  // left the network inside a junction
    SetNear(h, {});
    if (now >= sc.warmup) ++out.network.arrived;
    v.route.clear();
    index.erase(it);
    if (v.open_encounters == 0) free_slots.push_back(h);  // else once recorded
  }

  // ------------------------------------------------------------ watching
  // Which controlled junctions' stop lines a vehicle may reach before the next
  // sample (a second from now): those its route reaches within the farthest a
  // vehicle can drive in that time, counted from the end of its current edge
  // (so the junction ending its current edge always counts). A junction is
  // watched in a step only while an AV and an HV may both be at its lines:
  // a run without AVs or without HVs reads nothing per step.
  void UpdateNear(int h) {
    Veh& v = vehs[h];
    std::vector<int> near;
    double ahead = 0;
    for (std::size_t k = v.route_pos; k < v.route.size(); ++k) {
      if (k > static_cast<std::size_t>(v.route_pos)) ahead += edge_length[v.route[k]];
      if (ahead > reach) break;
      const int j = edge_junction[v.route[k]];
      if (j >= 0 && std::find(near.begin(), near.end(), j) == near.end()) near.push_back(j);
    }
    if (!scenario.lap.empty() && near.empty()) near.push_back(0);  // the figure-8's centre
    SetNear(h, std::move(near));
  }
  void SetNear(int h, std::vector<int> near) {
    Veh& v = vehs[h];
    const int sign_av = v.kind == VehicleKind::kAV;
    for (int j : v.near) (sign_av ? junctions[j].near_av : junctions[j].near_hv)--;
    v.near = std::move(near);
    for (int j : v.near) (sign_av ? junctions[j].near_av : junctions[j].near_hv)++;
  }

  int MovementFor(const JunctionRt& j, const std::string& lane, const Veh& v) const {
    const int next = v.route_pos + 1;
    if (next >= static_cast<int>(v.route.size())) return -1;
    const std::string& next_edge = edge_names[v.route[next]];
    for (std::size_t m = 0; m < j.movements.size(); ++m) {
      const MovementRt& mv = j.movements[m];
      if (mv.controlled && mv.from_lane == lane && mv.to_edge == next_edge)
        return static_cast<int>(m);
    }
    return -1;
  }

  // The front vehicles of a watched junction's stop-controlled lanes that
  // wait at their lines (front within kAtLine, below kSlow) or are coming to
  // a stop there (front within scenario.meeting_distance): SUMO's view this
  // step (junction/interception.h, "Meeting").
  void ObserveLines(JunctionRt& j) {
    j.at_line.clear();
    const int jx = static_cast<int>(&j - junctions.data());
    for (int a : j.approaches) {
      ApproachRt& ap = approaches[a];
      int h = -1;
      if (sumo::LaneVehicleNumber(ap.lane) > 0) {
        const std::vector<std::string> ids = sumo::LaneVehicleIDs(ap.lane);
        const auto it = ids.empty() ? index.end() : index.find(ids.back());
        if (it != index.end()) h = it->second;
      }
      if (ap.front >= 0 && ap.front != h) LeftLine(ap.front);
      ap.front = h;
      if (h < 0) continue;
      Veh& v = vehs[h];
      if (v.state == State::kHeld) {
        if (v.movement >= 0) j.at_line.push_back({h, v.kind, v.movement, true, v.line_since});
        continue;
      }
      if (v.state != State::kFree) continue;
      if (v.junction != jx) {  // new at the front of this lane
        v.junction = jx;
        CountProgress(h, sumo::RouteIndex(v.id));
        KeepCirculating(h);
        v.movement = MovementFor(j, ap.lane, v);
        v.line_since = -1;
      }
      if (v.movement < 0) continue;  // e.g. needs another lane for its next edge
      const double gap = ap.length - sumo::LanePosition(v.id);
      if (gap > sc.meeting_distance && gap > kAtLine) continue;
      const bool waiting = gap <= kAtLine && sumo::Speed(v.id) < kSlow;
      if (waiting && v.line_since < 0) v.line_since = now;
      if (!waiting) v.line_since = -1;
      v.line_gap = waiting ? gap : kStopGap;
      j.at_line.push_back({h, v.kind, v.movement, waiting, v.line_since});
    }
  }

  // A free vehicle that was the front of a watched lane is no longer (SUMO
  // let it go, or the junction is no longer watched).
  void LeftLine(int h) {
    Veh& v = vehs[h];
    if (v.state != State::kFree) return;
    v.line_since = -1;
    v.movement = v.junction = -1;
  }

  // ------------------------------------------------------------ holding
  void Hold(JunctionRt& j, int h) {
    Veh& v = vehs[h];
    sumo::SetSpeed(v.id, 0.0);
    v.state = State::kHeld;
    v.junction = static_cast<int>(&j - junctions.data());
    v.held_since = now;
  }

  void CountWait(JunctionRt& j, const Veh& v) {
    if (now < sc.warmup) return;
    const double wait = now - v.held_since;
    j.run.wait_sum += wait;
    j.run.wait_max = std::max(j.run.wait_max, wait);
    ++j.run.held;
  }

  // An encounter vehicle drives on: with SUMO's right of way off (the AV
  // that goes, the HV that drives recklessly) or under SUMO's own rules (a
  // careful release); watched until it has left the junction.
  void Release(JunctionRt& j, int h, bool reckless) {
    Veh& v = vehs[h];
    sumo::SetSpeedMode(v.id, reckless ? kModeReleased : kModeDefault);
    sumo::SetSpeed(v.id, -1);
    CountWait(j, v);
    v.state = State::kCrossing;
    v.reckless = reckless;
    v.lane = j.movements[v.movement].from_lane;
    crossing.push_back(h);
  }

  // A third vehicle held for an encounter: SUMO's again.
  void HandBack(JunctionRt& j, int h) {
    Veh& v = vehs[h];
    sumo::SetSpeed(v.id, -1);
    CountWait(j, v);
    v.state = State::kFree;  // still its lane's front: ObserveLines goes on looking
  }

  // A released encounter vehicle's rear left the junction: SUMO's rules again.
  void Clear(int h) {
    Veh& v = vehs[h];
    JunctionRt& j = junctions[v.junction];
    j.logic->Cleared(h, now);
    crossing.erase(std::remove(crossing.begin(), crossing.end(), h), crossing.end());
    v.state = State::kFree;
    v.junction = v.movement = -1;
    v.line_since = -1;
    if (!v.alive) return;
    if (v.reckless) sumo::SetSpeedMode(v.id, kModeDefault);
    v.reckless = false;
    SetPaint(h, Paint::kType);
  }

  // Figure-8: one shared route per starting edge, a lap long (added once at
  // the start). A vehicle that cleared the centre switches to the one that
  // starts on its edge, so it always reaches past the next stop line;
  // nothing accumulates however long the run.
  static std::string LapRoute(const std::string& edge) { return "lap_" + edge; }
  std::vector<std::string> LapFrom(std::size_t start) const {
    std::vector<std::string> route;
    for (std::size_t i = 0; i < 4; ++i) route.push_back(scenario.lap[(start + i) % 4]);
    return route;
  }
  // Figure-8: switches a vehicle on the last edge of its route to the lap
  // starting there (from the once-a-second sampling, and at the stop line).
  void KeepCirculating(int h) {
    Veh& v = vehs[h];
    if (scenario.lap.empty() || v.route_pos + 1 < static_cast<int>(v.route.size())) return;
    ExtendLap(h);
  }
  void ExtendLap(int h) {
    Veh& v = vehs[h];
    const std::string edge = sumo::RoadID(v.id);
    const auto it = std::find(scenario.lap.begin(), scenario.lap.end(), edge);
    if (it == scenario.lap.end()) return;
    CountProgress(h, sumo::RouteIndex(v.id));
    sumo::SetRouteID(v.id, LapRoute(edge));
    v.route.clear();
    for (const std::string& e : LapFrom(static_cast<std::size_t>(it - scenario.lap.begin())))
      v.route.push_back(EdgeIndex(e));
    v.route_pos = 0;
  }

  bool ClearedJunction(const Veh& v, const std::string& lane) const {
    const JunctionRt& j = junctions[v.junction];
    const MovementRt& m = j.movements[v.movement];
    if (lane == m.from_lane) return false;
    if (std::find(m.internal.begin(), m.internal.end(), lane) != m.internal.end()) return false;
    if (!lane.empty() && lane[0] == ':') return false;  // some other internal lane
    if (lane == m.to_lane) return sumo::LanePosition(v.id) >= v.length;
    return true;
  }

  void UpdateCrossing() {
    const std::vector<int> now_crossing = crossing;
    for (int h : now_crossing) {
      Veh& v = vehs[h];
      v.lane = sumo::LaneID(v.id);
      if (ClearedJunction(v, v.lane)) {
        Clear(h);
        continue;
      }
    }
  }

  // ------------------------------------------------------------ nudges
  void StartNudge(int h, double distance) {
    Veh& v = vehs[h];
    v.commanded = distance;
    if (distance <= 0.0) {
      v.state = State::kNudged;
      FinishNudge(h, sumo::Distance(v.id) - v.hold_odometer);
      return;
    }
    v.target = distance + kNudgeOvershoot;
    sumo::SetSpeedMode(v.id, kModeCreep);
    v.state = State::kNudging;
    SetPaint(h, Paint::kNudging);
    v.creep_speed = CreepSpeed(v.target, 0.0, 0.0, dt, sc.accel, sc.decel, sc.creep_speed);
    sumo::SetSpeed(v.id, v.creep_speed);
    nudging.push_back(h);
  }

  void UpdateNudges() {
    const std::vector<int> now_nudging = nudging;
    for (int h : now_nudging) {
      Veh& v = vehs[h];
      const double covered = sumo::Distance(v.id) - v.hold_odometer;
      const double speed =
          CreepSpeed(v.target, covered, v.creep_speed, dt, sc.accel, sc.decel, sc.creep_speed);
      if (speed <= 0.0 && v.creep_speed <= 0.0) {
        nudging.erase(std::remove(nudging.begin(), nudging.end(), h), nudging.end());
        v.state = State::kNudged;
        FinishNudge(h, covered);
      } else {
        v.creep_speed = speed;
        sumo::SetSpeed(v.id, speed);
      }
    }
  }

  // The run checks every realised nudge: s <= d <= s + tolerance (a still
  // AV: |d| <= tolerance).
  void FinishNudge(int h, double observed) {
    Veh& v = vehs[h];
    const double s = v.commanded;
    if (!NudgeRealised(s, observed, kNudgeTolerance)) {
      if (sc.nudge_check == "error")
        throw NudgeError("junction '" + junctions[v.junction].info.id + "', AV " + v.id +
                         " at t = " + Fmt(now) + " s: commanded nudge " + Fmt(s) +
                         " m, SUMO reported " + Fmt(observed) + " m (tolerance " +
                         Fmt(kNudgeTolerance) +
                         " m); set scenario.nudge_check: count to record it and go on");
      ++out.nudges_unrealised;
    }
    junctions[v.junction].logic->NudgeDone(h, observed, now, *this);
  }

  // ------------------------------------------------------------ collisions
  void AttributeCollisions() {
    std::set<std::pair<std::string, std::string>> pairs;
    for (const SumoCollision& c : sumo::Collisions())
      pairs.insert(std::minmax(c.collider, c.victim));
    for (const auto& pair : pairs) {
      if (colliding.count(pair)) continue;  // the same episode as last step
      const auto a = index.find(pair.first), b = index.find(pair.second);
      bool matched = false;
      if (a != index.end() && b != index.end()) {
        for (JunctionRt& j : junctions) {
          if (j.logic->Collided(a->second, b->second)) {
            matched = true;
            SetPaint(a->second, Paint::kCollided);
            SetPaint(b->second, Paint::kCollided);
            break;
          }
        }
      }
      if (!matched && now >= sc.warmup) {
        ++out.other_collisions;
        auto game_move = [&](const auto& it) {
          if (it == index.end()) return false;
          const Veh& w = vehs[it->second];
          return w.state == State::kCrossing && w.reckless;
        };
        if (game_move(a) || game_move(b)) ++out.other_collisions_game_move;
      }
    }
    colliding = std::move(pairs);
  }

  // ------------------------------------------------------------ decisions
  // One watched junction's step: what SUMO shows at its lines, then the
  // interception's commands.
  void Decide(JunctionRt& j) {
    ObserveLines(j);
    Env env;
    env.self = this;
    env.j = &j;
    const long abandoned = j.logic->AbandonedMeetings();
    const std::vector<junction::Command> commands = j.logic->Step(now, j.at_line, env, *this);
    if (now >= sc.warmup) j.run.meetings_abandoned += j.logic->AbandonedMeetings() - abandoned;
    for (const junction::Command& c : commands) {
      switch (c.kind) {
        case Command::Kind::kHold:
          Hold(j, c.vehicle);
          break;
        case Command::Kind::kStartNudge:
          if (now >= sc.warmup) ++out.encounters_formed;
          StartNudge(c.vehicle, c.distance);
          break;
        case Command::Kind::kRelease:
          Release(j, c.vehicle, true);
          break;
        case Command::Kind::kHandBack:
          if (c.in_encounter) {
            Release(j, c.vehicle, false);
          } else {
            HandBack(j, c.vehicle);
          }
          break;
      }
    }
    for (const junction::EncounterOutcome& e : j.logic->TakeFinished()) {
      Record(j, e);
      for (int h : {e.av, e.hv})
        if (--vehs[h].open_encounters == 0 && !vehs[h].alive) free_slots.push_back(h);
    }
  }

  // A junction is looked at in a step while an AV and an HV may both be at
  // its lines, or while it holds vehicles; on leaving that, what it saw is
  // forgotten.
  bool Watched(JunctionRt& j) {
    const bool watched = (j.near_av > 0 && j.near_hv > 0) || j.logic->Busy();
    if (!watched && j.watched) {
      for (int a : j.approaches) {
        if (approaches[a].front >= 0) LeftLine(approaches[a].front);
        approaches[a].front = -1;
      }
    }
    j.watched = watched;
    return watched;
  }

  void Record(const JunctionRt& j, const junction::EncounterOutcome& e) {
    EncounterRecord r;
    if (const auto it = verdicts.find({e.av, e.hv}); it != verdicts.end()) {
      r.both_proceed_collides = it->second;
      verdicts.erase(it);
    }
    // The HV's trust (before), the theory, and the updates of trust and beliefs.
    population->Finish(vehs[e.av].id, vehs[e.hv].id, e.draw, e.reading, e.collision,
                       e.time >= sc.warmup, &r);
    if (e.time < sc.warmup) return;
    r.time = e.time;
    r.junction = j.info.id;
    r.av = vehs[e.av].id;
    r.hv = vehs[e.hv].id;
    const MovementRt& am = j.movements[e.av_movement];
    const MovementRt& hm = j.movements[e.hv_movement];
    r.av_movement = am.from_lane + ">" + am.to_lane;
    r.hv_movement = hm.from_lane + ">" + hm.to_lane;
    r.av_dir = am.dir;
    r.hv_dir = hm.dir;
    r.intent_go = e.draw.intent_go;
    r.commanded = e.draw.nudge_distance;
    r.observed = e.reading.observed;
    r.posterior = e.reading.posterior;
    r.hv_dc = e.reading.drives_if_clear;
    r.av_first = e.draw.goes_first;
    r.collision = e.collision;
    r.decided_at = e.decided_at;

    out.encounters.push_back(r);
  }

  // What waits at a stalled junction: each incoming lane with halted
  // vehicles, its front vehicle and who holds it.
  std::string StallDetail(JunctionRt& j) {
    std::string out;
    for (const std::string& lane : j.incoming) {
      const int halting = sumo::LaneHaltingNumber(lane);
      if (halting == 0) continue;
      const std::vector<std::string> ids = sumo::LaneVehicleIDs(lane);
      if (ids.empty()) continue;
      const std::string& front = ids.back();
      const auto it = index.find(front);
      std::string state = "driven by SUMO";
      if (it != index.end()) {
        const Veh& v = vehs[it->second];
        state = v.state == State::kHeld       ? "held by the controller"
                : v.state == State::kCrossing ? "released by the controller"
                : v.state == State::kFree     ? "driven by SUMO"
                                              : "nudging";
      }
      const net::Lane* l = net.FindLane(lane);
      out += "; lane " + lane + ": " + std::to_string(halting) + " halted, front " + front + " " +
             Fmt((l ? l->length : 0) - sumo::LanePosition(front)) + " m before the line (" +
             state + ")";
    }
    const std::string held = j.logic->Describe([&](int h) { return vehs[h].id; });
    if (!held.empty()) out += "; " + held;
    return out;
  }

  // The safety net (every policy, sumo_native included): a junction with
  // vehicles halted on its incoming lanes through which no vehicle has passed
  // for stall_limit seconds (route progress, read each second). Checked each
  // second at every controlled junction.
  void CheckStalls() {
    std::optional<StallError> error;  // the first, once every stalled junction is recorded
    for (JunctionRt& j : junctions) {
      // A junction nobody waited at is idle, not stalled: the clock starts
      // when vehicles began to wait, or at the last progress after that.
      const double progress =
          std::max({j.last_progress, j.logic->LastActivity(), j.waiting_since});
      if (!j.waiting || now - progress <= stall_limit) {
        if (!j.waiting) j.stall_recorded = false;
        continue;
      }
      if (progress > j.stall_since) j.stall_recorded = false;
      if (j.stall_recorded) continue;
      const std::string what =
          "junction '" + j.info.id + "' (" + j.run.rule + "): traffic stalled, vehicles waiting " +
          "on its incoming lanes and none passed it between t = " + Fmt(progress) +
          " s and t = " + Fmt(now) + " s" +
          (scenario.loop_length > 0
               ? " (scenario.loop_length = " + Fmt(scenario.loop_length) +
                     " m; try a longer track or fewer vehicles)"
               : " (gridlock: lower the demand, or set scenario.stall_action: record to measure "
                 "it)");
      j.stall_recorded = true;
      j.stall_since = progress;
      out.stalls.push_back({j.info.id, progress, now});
      // SUMO's own logic (sumo_native) is the baseline, not the controller:
      // its stalls are recorded, never an error.
      if (sc.stall_action == "error" && policy && !error)
        error.emplace(what + StallDetail(j), j.info.id, progress, now);
    }
    if (error) throw *error;
  }

  // Once a simulated second: route progress (junction crossings, the
  // figure-8's circulation, which junctions each vehicle is near), queues,
  // the demand waiting to depart, stalls.
  void Sample() {
    for (const auto& [id, h] : index) {
      CountProgress(h, sumo::RouteIndex(id));
      KeepCirculating(h);
      UpdateNear(h);
    }
    std::vector<char> was_waiting(junctions.size());
    for (std::size_t i = 0; i < junctions.size(); ++i) {
      JunctionRt& j = junctions[i];
      was_waiting[i] = j.waiting;
      j.waiting = false;
      for (const std::string& lane : j.incoming)
        if (sumo::LaneHaltingNumber(lane) > 0) {
          j.waiting = true;
          break;
        }
    }
    for (ApproachRt& ap : approaches) {
      if (now < sc.warmup) break;
      const double q = sumo::LaneHaltingNumber(ap.lane);
      ap.stats.queue_max = std::max(ap.stats.queue_max, q);
      ap.stats.queue_sum += q;
      ++ap.stats.samples;
    }
    for (std::size_t i = 0; i < junctions.size(); ++i)
      if (junctions[i].waiting && !was_waiting[i]) junctions[i].waiting_since = now;
    CheckStalls();
    if (population) population->Sample(now);
    if (now < sc.warmup) return;
    if (scenario.kind == "network") {
      out.network.vehicles_max =
          std::max(out.network.vehicles_max, static_cast<long>(index.size()));
      const long pending = static_cast<long>(sumo::PendingVehicles().size());
      out.network.pending_max = std::max(out.network.pending_max, pending);
      out.network.pending_end = pending;
    }
  }

  // ------------------------------------------------------------ members
  const ExperimentConfig& cfg;
  const ScenarioConfig& sc;
  std::optional<Policy> policy;
  const Scenario& scenario;
  const net::NetFile& net;
  ControllerOptions opts;
  std::unique_ptr<persuasion::LikelihoodModel> model;
  persuasion::AvHvParams params;
  std::mt19937_64 rng;
  std::unique_ptr<HvPopulation> population;  // policy runs only
  PolicyRun out;
  double dt = 0.1;
  long sample_every = 10;
  long steps = 0;
  double now = 0;
  double last_crossing = 0;
  double stall_limit = 120;
  static constexpr std::size_t kTrustListMax = 100000;

  std::vector<Veh> vehs;
  std::vector<int> free_slots;
  std::unordered_map<std::string, int> index;
  std::vector<JunctionRt> junctions;
  std::map<std::string, int> junction_index;
  std::vector<ApproachRt> approaches;
  std::vector<Chain> chains;
  std::map<std::string, int> chain_index;
  std::unordered_map<std::string, int> edge_index;
  std::vector<int> edge_junction;
  std::vector<std::string> edge_names;
  std::vector<double> edge_length;
  double reach = 60;  // m: farther than any vehicle drives in a second (UpdateNear)
  std::vector<int> crossing, nudging;
  std::set<std::pair<std::string, std::string>> colliding;
  std::map<std::pair<int, int>, bool> verdicts;  // (AV, HV) met: would both proceeding collide
};

NetworkController::NetworkController(const ExperimentConfig& config,
                                     std::optional<persuasion::Policy> policy,
                                     const Scenario& scenario, const net::NetFile& net,
                                     const ControllerOptions& options)
    : impl_(std::make_unique<Impl>(config, policy, scenario, net, options)) {}

NetworkController::~NetworkController() = default;

void NetworkController::Start() {
  Impl& s = *impl_;
  const ScenarioConfig& sc = s.sc;
  s.out.sumo_version = sumo::Version();
  if (!s.scenario.placed.empty()) {
    sumo::AddVehicleType({"AV", sc.cruise_speed, sc.min_gap, sc.vehicle_length, sc.vehicle_width,
                          sc.accel, sc.decel, kAvRgb[0], kAvRgb[1], kAvRgb[2]});
    sumo::AddVehicleType({"HV", sc.cruise_speed, sc.min_gap, sc.vehicle_length, sc.vehicle_width,
                          sc.accel, sc.decel, kHvRgb[0], kHvRgb[1], kHvRgb[2]});
    for (std::size_t i = 0; i < s.scenario.lap.size(); ++i)
      sumo::AddRoute(Impl::LapRoute(s.scenario.lap[i]), s.LapFrom(i));
    for (const PlacedVehicle& v : s.scenario.placed)
      sumo::AddVehicle(v.id, Impl::LapRoute(v.route.front()), v.is_av ? "AV" : "HV", v.depart_pos);
  }
  if (s.opts.stall_limit >= 0) {
    s.stall_limit = s.opts.stall_limit;
  } else if (s.scenario.loop_length > 0) {
    // Free flow crosses at least once per loop; allow a full lap, the
    // controller's own waits and a minute.
    s.stall_limit =
        2 * s.scenario.loop_length / sc.cruise_speed + sc.confirm_delay + 60.0;
  } else {
    s.stall_limit = 120.0;
  }
  s.now = sumo::Time();
  s.last_crossing = s.now;
  for (JunctionRt& j : s.junctions) j.last_progress = s.now;
}

void NetworkController::Step() {
  Impl& s = *impl_;
  s.now = sumo::Time();
  ++s.steps;
  if (sumo::TeleportNumber() > 0 && s.now >= s.sc.warmup) ++s.out.teleports;
  if (sumo::DepartedNumber() > 0)
    for (const std::string& id : sumo::DepartedIDs()) s.Register(id);
  if (sumo::ArrivedNumber() > 0)
    for (const std::string& id : sumo::ArrivedIDs()) s.Unregister(id);
  if (sumo::CollidingNumber() > 0 || !s.colliding.empty()) s.AttributeCollisions();
  if (s.policy) {
    if (!s.crossing.empty()) s.UpdateCrossing();
    if (!s.nudging.empty()) s.UpdateNudges();
    for (JunctionRt& j : s.junctions)
      if (s.Watched(j)) s.Decide(j);
  }
  if (s.steps % s.sample_every == 0) s.Sample();
  s.out.longest_gap_without_crossing =
      std::max(s.out.longest_gap_without_crossing, s.now - s.last_crossing);
}

PolicyRun NetworkController::Finish() {
  Impl& s = *impl_;
  s.now = sumo::Time();
  for (const auto& [id, h] : s.index) s.CountProgress(h, sumo::RouteIndex(id));
  s.out.simulated_seconds = s.now;
  s.out.measured_seconds = std::max(0.0, s.now - s.sc.warmup);
  if (s.population) {
    s.out.beyond = s.population->Results(s.now);
    s.out.theory = s.population->Theory();
  } else {
    s.out.beyond.on = s.cfg.BeyondPaper();  // sumo_native: the same columns as the others
  }
  for (JunctionRt& j : s.junctions) {
    for (std::size_t k = 0; k < j.approaches.size(); ++k)
      j.run.approaches[k] = s.approaches[j.approaches[k]].stats;
    s.out.crossings_av += j.run.crossings_av;
    s.out.crossings_hv += j.run.crossings_hv;
    s.out.wait_sum += j.run.wait_sum;
    s.out.wait_max = std::max(s.out.wait_max, j.run.wait_max);
    s.out.held += j.run.held;
    s.out.encounters_unfinished += j.logic->Encounters();
    s.out.junctions.push_back(j.run);
  }
  return std::move(s.out);
}

}  // namespace taebp
