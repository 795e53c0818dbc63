#include "taebp/controller/experiment.h"

#include "taebp/controller/sumo_adapter.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <utility>

#include <sys/wait.h>
#include <unistd.h>

#ifndef TAEBP_DEFAULT_NET
#define TAEBP_DEFAULT_NET "sumo_net/figure8.net.xml"
#endif
#ifndef TAEBP_DEFAULT_LOOP_LENGTH
#define TAEBP_DEFAULT_LOOP_LENGTH 80.0
#endif

namespace taebp {
namespace {

namespace fs = std::filesystem;
using persuasion::Policy;

// The figure-8: lap C_E, E_C, C_W, W_C. Approach 0 arrives on E_C and leaves
// on C_W; approach 1 arrives on W_C and leaves on C_E.
constexpr std::array<const char*, 4> kLap = {"C_E", "E_C", "C_W", "W_C"};
constexpr std::array<const char*, 2> kIncoming = {"E_C", "W_C"};
constexpr std::array<const char*, 2> kOutgoing = {"C_W", "C_E"};
constexpr const char* kCentre = "C";
constexpr double kHoldDuration = 1e9;  // s; released explicitly

// Speed modes (bits: 1 safe speed, 2 max accel, 4 max decel, 8 right of way,
// 16 red light, 32 ignore foes already in the junction).
constexpr int kModeReleased = 55;  // controller decides the junction; keep car-following
constexpr int kModeCreep = 0;      // exact commanded speeds during a nudge

enum class Phase { kApproaching, kWaiting, kNudging, kHolding, kCrossing };

// Vehicle colours under RunOptions::colour_states (r, g, b).
enum class Paint { kType, kNudging, kDr, kDc, kCollided };
constexpr std::array<std::array<int, 3>, 5> kPaintRgb = {{
    {0, 0, 0}, {255, 220, 0}, {255, 140, 0}, {0, 200, 0}, {255, 0, 255}}};
constexpr std::array<int, 3> kAvRgb = {0, 0, 255};
constexpr std::array<int, 3> kHvRgb = {255, 0, 0};

struct Veh {
  std::string id;
  VehicleKind kind = VehicleKind::kHV;
  int approach = 0;  // approach of the next (or current) stop
  Phase phase = Phase::kApproaching;
  double arrival = 0;
  double hold_odometer = 0;
  double trust = 0;  // HV's true theta
  bool speed_controlled = false;  // setSpeed active (nudge)
  Paint paint = Paint::kType;     // colour shown (RunOptions::colour_states)
  persuasion::CommittedScheme scheme;   // HV only: the AV's design for this HV
  persuasion::PredictedOutcome theory;  // HV only: predicted outcome of that design
};

struct ActiveEncounter {
  int av = -1, hv = -1;
  EncounterRecord record;
  double target = 0;       // commanded + overshoot
  double creep_speed = 0;  // last commanded creep speed
  std::optional<EncounterSequence> sequence;
  bool av_cleared = false, hv_cleared = false;
};

double Dist(const XY& a, const XY& b) { return std::hypot(a.x - b.x, a.y - b.y); }

std::string Fmt(double v) {
  std::ostringstream os;
  os.precision(6);
  os << v;
  return os.str();
}

class Run {
 public:
  Run(const ExperimentConfig& config, Policy policy, const ScenarioFiles& files,
      RunOptions options = {})
      : cfg_(config), sc_(config.scenario), policy_(policy), files_(files), opts_(std::move(options)),
        model_(MakeLikelihood(config.model.likelihood)),
        rng_(config.scenario.seed) {
    params_.prior_go = config.model.prior_go;
    params_.collision_penalty = config.model.collision_penalty;
    const ModelConfig& m = config.model;
    // The design reported in summary.json: for the population's mean trust
    // (per-HV designs under `exact` knowledge are in the encounter rows).
    const double population_hat = DesignTrust(m, policy, m.trust.Mean());
    out_.policy = persuasion::ToString(policy);
    out_.scheme = persuasion::CommitScheme(policy, params_, population_hat, *model_);
    out_.theory = ExpectedOutcome(m, policy);
  }

  double ExecuteBare() {
    StartSumo();
    try {
      SetUp();
      const long steps = std::lround(sc_.duration / sc_.step_length);
      for (long k = 0; k < steps; ++k) sumo::Step();
    } catch (...) {
      sumo::Close();
      throw;
    }
    const double t = sumo::Time();
    sumo::Close();
    return t;
  }

  PolicyRun Execute() {
    StartSumo();
    try {
      SetUp();
      if (opts_.after_start) opts_.after_start();
      Loop();
      if (opts_.before_close) opts_.before_close();
    } catch (...) {
      sumo::Close();
      throw;
    }
    sumo::Close();
    return std::move(out_);
  }

 private:
  // SUMO is closed by the caller's catch from here on: a scenario that does
  // not fit the network (a ConfigError in SetUp) leaves no simulation open.
  void StartSumo() {
    const fs::path net = files_.net;
    std::ostringstream dt, seed;
    dt.precision(17);
    dt << sc_.step_length;
    seed << (sc_.seed % 2147483647ULL);
    sumo::Start({"sumo", "-n", net.string(), "--step-length", dt.str(), "--seed", seed.str(),
                 "--collision.check-junctions", "true", "--collision.action", "warn",
                 "--collision.mingap-factor", "0", "--time-to-teleport", "-1",
                 "--no-step-log", "true", "--no-warnings", "true",
                 "--duration-log.disable", "true", "--xml-validation", "never"});
  }

  void SetUp() {
    out_.sumo_version = sumo::Version();
    ReadNetwork();
    sumo::AddVehicleType({"AV", sc_.cruise_speed, sc_.min_gap, sc_.vehicle_length,
                          sc_.vehicle_width, sc_.accel, sc_.decel, kAvRgb[0], kAvRgb[1], kAvRgb[2]});
    sumo::AddVehicleType({"HV", sc_.cruise_speed, sc_.min_gap, sc_.vehicle_length,
                          sc_.vehicle_width, sc_.accel, sc_.decel, kHvRgb[0], kHvRgb[1], kHvRgb[2]});
    PlaceVehicles();
    DrawTrust();
  }

  void ReadNetwork() {
    const XY centre = sumo::JunctionPosition(kCentre);
    for (int i = 0; i < 4; ++i) {
      lap_len_[i] = sumo::LaneLength(std::string(kLap[i]) + "_0");
      lap_ += lap_len_[i];
    }
    for (int k = 0; k < 2; ++k) {
      const std::string lane = std::string(kIncoming[k]) + "_0";
      const std::vector<XY> shape = sumo::LaneShape(lane);
      const double line_to_centre = Dist(shape.back(), centre);
      const double len = sumo::LaneLength(lane);
      if (sc_.stop_distance < line_to_centre)
        throw ConfigError("scenario.stop_distance = " + Fmt(sc_.stop_distance) +
                          " is inside the junction: the stop line of " + kIncoming[k] +
                          " is " + Fmt(line_to_centre) + " m from the centre");
      hold_pos_[k] = len - (sc_.stop_distance - line_to_centre);
      if (hold_pos_[k] < sc_.vehicle_length + 1.0)
        throw ConfigError("scenario.stop_distance = " + Fmt(sc_.stop_distance) +
                          " does not fit on edge " + kIncoming[k] + " (" + Fmt(len) + " m)");
    }
  }

  // Spreads the vehicles evenly over the lap (types interleaved), avoiding the
  // hold zone before the stop line and the first vehicle length of each edge.
  void PlaceVehicles() {
    const int n = sc_.avs + sc_.hvs;
    const double lap = lap_;
    const double spacing = lap / n;
    const double need = sc_.vehicle_length + sc_.min_gap;
    if (spacing < need + 0.5)
      throw ConfigError("scenario.avs + scenario.hvs = " + std::to_string(n) +
                        " vehicles do not fit on the " + Fmt(lap) + " m track (each needs " +
                        Fmt(need) + " m); raise scenario.loop_length or use fewer vehicles");
    const int reps = static_cast<int>(std::ceil(sc_.duration * sc_.cruise_speed / lap)) + 3;
    for (int start = 0; start < 4; ++start) {
      std::vector<std::string> edges;
      for (int r = 0; r < reps; ++r)
        for (int i = 0; i < 4; ++i) edges.push_back(kLap[(start + i) % 4]);
      sumo::AddRoute("lap" + std::to_string(start), edges);
    }
    int avs_placed = 0;
    double last_pos = -1e9;
    for (int k = 0; k < n; ++k) {
      // Bresenham interleaving: AV whenever the AV quota advances.
      const bool is_av = (static_cast<long>(k + 1) * sc_.avs) / n > (static_cast<long>(k) * sc_.avs) / n;
      double pos = std::max(k * spacing + sc_.vehicle_length + 0.5, last_pos + need);
      // Moves pos forward to the first admissible spot: not within the first
      // vehicle length of an edge, not in the hold zone before a stop line.
      // The spot is kept as (edge, on_edge) so that round-off in acc + x - acc
      // cannot send the search back to where it was (it only moves forward).
      int edge = 0;
      double on_edge = 0;
      for (;;) {
        double acc = 0;
        edge = 0;
        while (edge < 4 && pos >= acc + lap_len_[edge]) acc += lap_len_[edge++];
        if (edge >= 4)
          throw ConfigError("scenario.avs + scenario.hvs = " + std::to_string(n) +
                            " vehicles do not fit on the track; raise scenario.loop_length");
        on_edge = std::max(pos - acc, sc_.vehicle_length + 0.5);
        const bool incoming = (edge == 1 || edge == 3);
        const double last = incoming ? hold_pos_[edge == 1 ? 0 : 1] - 2.0 : lap_len_[edge];
        if (on_edge <= last) {
          pos = acc + on_edge;
          break;
        }
        pos = acc + lap_len_[edge];  // next edge (its start zone is skipped above)
      }
      last_pos = pos;
      Veh v;
      v.kind = is_av ? VehicleKind::kAV : VehicleKind::kHV;
      v.id = (is_av ? "av" : "hv") + std::to_string(is_av ? avs_placed : k - avs_placed);
      if (is_av) ++avs_placed;
      v.approach = (edge == 0 || edge == 1) ? 0 : 1;
      sumo::AddVehicle(v.id, "lap" + std::to_string(edge), is_av ? "AV" : "HV", on_edge);
      vehs_.push_back(v);
    }
  }

  // Each HV draws its trust (own random stream, so the encounter draws do not
  // depend on it); each AV-HV pair's scheme follows the trust knowledge.
  void DrawTrust() {
    std::seed_seq seq{static_cast<std::uint32_t>(sc_.seed & 0xffffffffu),
                      static_cast<std::uint32_t>(sc_.seed >> 32), 0x74727573u};
    std::mt19937_64 trust_rng(seq);
    for (Veh& v : vehs_) {
      if (v.kind != VehicleKind::kHV) continue;
      v.trust = cfg_.model.trust.IsFixed() ? cfg_.model.trust.value
                                           : cfg_.model.trust.Draw(Uniform01(trust_rng));
      out_.hv_trust.push_back(v.trust);
      const double hat = DesignTrust(cfg_.model, policy_, v.trust);
      v.scheme = persuasion::CommitScheme(policy_, params_, hat, *model_);
      v.theory = persuasion::PredictOutcome(v.scheme, params_, v.trust, *model_);
    }
  }

  void SetNextStop(Veh& v) {
    sumo::SetStop(v.id, kIncoming[v.approach], hold_pos_[v.approach], kHoldDuration);
    v.phase = Phase::kApproaching;
  }

  // Shows a vehicle's state by its colour; only with colour_states (no SUMO
  // call otherwise, nor when the colour is already shown).
  void SetPaint(int i, Paint paint) {
    Veh& v = vehs_[i];
    if (!opts_.colour_states || v.paint == paint) return;
    const std::array<int, 3>& rgb =
        paint != Paint::kType ? kPaintRgb[static_cast<int>(paint)]
                              : (v.kind == VehicleKind::kAV ? kAvRgb : kHvRgb);
    sumo::SetColor(v.id, rgb[0], rgb[1], rgb[2]);
    v.paint = paint;
  }

  int IndexOf(const std::string& id) const {
    for (std::size_t i = 0; i < vehs_.size(); ++i)
      if (vehs_[i].id == id) return static_cast<int>(i);
    return -1;
  }

  void Loop() {
    const double dt = sc_.step_length;
    const long steps = std::lround(sc_.duration / dt);
    sumo::Step();  // inserts every vehicle at t = 0 + dt
    for (Veh& v : vehs_) SetNextStop(v);
    double junction_free_since = sumo::Time();
    double last_crossing = junction_free_since;
    // Free flow crosses at least once per loop; allow a full lap, the
    // controller's own waits and a minute.
    const double stall_limit =
        opts_.stall_limit >= 0
            ? opts_.stall_limit
            : lap_ / sc_.cruise_speed + sc_.confirm_delay + sc_.arrival_window + 60.0;
    for (long k = 1; k < steps; ++k) {
      sumo::Step();
      const double now = sumo::Time();
      if (sumo::TeleportNumber() > 0) ++out_.teleports;

      // Arrivals at the stop line.
      if (sumo::StopStartingNumber() > 0) {
        for (const std::string& id : sumo::StopStartingIDs()) {
          const int i = IndexOf(id);
          if (i < 0) continue;
          Veh& v = vehs_[i];
          v.phase = Phase::kWaiting;
          v.arrival = now;
          v.hold_odometer = sumo::Distance(id);
          head_[v.approach] = i;
        }
      }

      if (sumo::CollidingNumber() > 0) AttributeCollisions();

      // Crossing vehicles: cleared once the rear is on the outgoing edge.
      for (auto it = crossing_.begin(); it != crossing_.end();) {
        Veh& v = vehs_[*it];
        const int exit_approach = 1 - v.approach;  // approach index was advanced at release
        const std::string road = sumo::RoadID(v.id);
        if (road == kOutgoing[exit_approach] &&
            sumo::LanePosition(v.id) >= sc_.vehicle_length) {
          if (enc_ && *it == enc_->av) enc_->av_cleared = true;
          if (enc_ && *it == enc_->hv) enc_->hv_cleared = true;
          SetPaint(*it, Paint::kType);
          it = crossing_.erase(it);
          last_crossing = now;
          if (crossing_.empty()) junction_free_since = now;
        } else {
          ++it;
        }
      }

      if (enc_) {
        StepEncounter(now);
        if (enc_ && enc_->av_cleared && enc_->hv_cleared) {
          out_.encounters.push_back(enc_->record);
          enc_.reset();
          junction_free_since = now;
        }
      }

      if (!enc_ && crossing_.empty()) {
        std::optional<Head> heads[2];
        for (int a = 0; a < 2; ++a) {
          if (head_[a] < 0 || !LoopHasRoom(1 - a)) continue;  // don't block the box
          const Veh& v = vehs_[head_[a]];
          heads[a] = Head{head_[a], v.kind, a, v.arrival, std::max(v.arrival, junction_free_since)};
        }
        const RightOfWay row = DecideRightOfWay(heads[0], heads[1], now, sc_.arrival_window);
        if (row.kind == RightOfWay::Kind::kRelease) {
          Release(row.first, now);
        } else if (row.kind == RightOfWay::Kind::kEncounter) {
          BeginEncounter(row.first, row.second, now);
        }
      }
      out_.longest_gap_without_crossing =
          std::max(out_.longest_gap_without_crossing, now - last_crossing);
      if (now - last_crossing > stall_limit) {
        // The rest of the run would measure nothing: stop and say what to change.
        const std::string track = files_.loop_length > 0
                                      ? "scenario.loop_length = " + Fmt(files_.loop_length) + " m"
                                      : "scenario.network = '" + files_.net + "'";
        throw ConfigError(track + ": traffic stalled (gridlock?), no vehicle crossed the centre " +
                          "between t = " + Fmt(last_crossing) + " s and t = " + Fmt(now) +
                          " s with " + std::to_string(vehs_.size()) +
                          " vehicles; try a longer scenario.loop_length or fewer vehicles");
      }
    }
    out_.simulated_seconds = sumo::Time();
  }

  // Keep-clear rule: a head may enter the junction only if the loop it drives
  // into can take one more vehicle with that vehicle's rear off the junction,
  // even if every vehicle already in that loop (counted by the approach it is
  // heading to, which changes at release) ends up queued at the loop's stop
  // line. Without it a vehicle can stop in the junction behind a full loop
  // whose head waits for the junction: gridlock (seen at 80 m with 16
  // vehicles and 2-6 AVs under TA-EBP). Counting instead of reading positions
  // costs no SUMO call and never delays a release into a loop with room.
  bool LoopHasRoom(int loop) const {
    int in_loop = 0;
    for (const Veh& v : vehs_) in_loop += (v.approach == loop);
    const double queue_space = lap_len_[2 * loop] + hold_pos_[loop] - sc_.vehicle_length;
    return in_loop * (sc_.vehicle_length + sc_.min_gap) <= queue_space;
  }

  // Every release, DR or not, ignores SUMO's junction logic (kModeReleased):
  // the controller has decided the junction.
  void Release(int i, double now) {
    Veh& v = vehs_[i];
    if (v.speed_controlled) {
      sumo::SetSpeed(v.id, -1);
      v.speed_controlled = false;
    } else {
      sumo::Resume(v.id);
    }
    sumo::SetSpeedMode(v.id, kModeReleased);
    head_[v.approach] = -1;
    const double wait = now - v.arrival;
    out_.wait_sum += wait;
    out_.wait_max = std::max(out_.wait_max, wait);
    (v.kind == VehicleKind::kAV ? out_.crossings_av : out_.crossings_hv) += 1;
    v.approach = 1 - v.approach;  // next stop is on the other approach
    SetNextStop(v);
    v.phase = Phase::kCrossing;
    crossing_.push_back(i);
  }

  void BeginEncounter(int av, int hv, double now) {
    enc_.emplace();
    enc_->av = av;
    enc_->hv = hv;
    EncounterRecord& r = enc_->record;
    r.time = now;
    r.av = vehs_[av].id;
    r.hv = vehs_[hv].id;
    r.hv_trust = vehs_[hv].trust;
    r.theory_dc = vehs_[hv].theory.dc_rate;
    r.theory_collision = vehs_[hv].theory.collision_rate;
    const AvDraw draw = DrawAv(vehs_[hv].scheme, params_.prior_go, rng_);
    r.intent_go = draw.intent_go;
    r.commanded = draw.nudge_distance;
    r.av_first = draw.goes_first;
    if (draw.nudge) {
      Veh& v = vehs_[av];
      enc_->target = draw.nudge_distance + kNudgeOvershoot;
      sumo::Resume(v.id);
      sumo::SetSpeedMode(v.id, kModeCreep);
      v.speed_controlled = true;
      v.phase = Phase::kNudging;
      SetPaint(av, Paint::kNudging);
      enc_->creep_speed = CreepSpeed(enc_->target, 0.0, 0.0, sc_.step_length, sc_.accel,
                                     sc_.decel, sc_.creep_speed);
      sumo::SetSpeed(v.id, enc_->creep_speed);
    } else {
      Decide(now, 0.0);
    }
  }

  void Decide(double now, double observed) {
    EncounterRecord& r = enc_->record;
    const HvReading reading =
        ReadNudge(vehs_[enc_->hv].scheme, params_, r.hv_trust, *model_, observed);
    r.observed = observed;
    r.posterior = reading.posterior;
    r.hv_dc = reading.drives_if_clear;
    r.decided_at = now;
    SetPaint(enc_->hv, r.hv_dc ? Paint::kDc : Paint::kDr);
    enc_->sequence.emplace(r.av_first, r.hv_dc, now, sc_.confirm_delay);
  }

  void StepEncounter(double now) {
    ActiveEncounter& e = *enc_;
    Veh& av = vehs_[e.av];
    if (av.phase == Phase::kNudging) {
      const double covered = sumo::Distance(av.id) - av.hold_odometer;
      const double v = CreepSpeed(e.target, covered, e.creep_speed, sc_.step_length,
                                  sc_.accel, sc_.decel, sc_.creep_speed);
      if (v <= 0.0 && e.creep_speed <= 0.0) {
        av.phase = Phase::kHolding;
        Decide(now, covered);
      } else {
        e.creep_speed = v;
        sumo::SetSpeed(av.id, v);
        return;
      }
    }
    if (!e.sequence) return;
    for (const auto& rel : e.sequence->Update(now, e.av_cleared, e.hv_cleared)) {
      Release(rel.av ? e.av : e.hv, now);
    }
  }

  void AttributeCollisions() {
    for (const SumoCollision& c : sumo::Collisions()) {
      if (enc_) {
        const std::string& a = vehs_[enc_->av].id;
        const std::string& h = vehs_[enc_->hv].id;
        if ((c.collider == a && c.victim == h) || (c.collider == h && c.victim == a)) {
          enc_->record.collision = true;
          if (!enc_->av_cleared) SetPaint(enc_->av, Paint::kCollided);
          if (!enc_->hv_cleared) SetPaint(enc_->hv, Paint::kCollided);
          continue;
        }
      }
      ++out_.other_collisions;
    }
  }

  const ExperimentConfig& cfg_;
  const ScenarioConfig& sc_;
  Policy policy_;
  ScenarioFiles files_;
  RunOptions opts_;
  std::unique_ptr<persuasion::LikelihoodModel> model_;
  persuasion::AvHvParams params_;
  std::mt19937_64 rng_;
  PolicyRun out_;

  std::array<double, 4> lap_len_{};
  double lap_ = 0;  // sum of lap_len_
  std::array<double, 2> hold_pos_{};
  std::vector<Veh> vehs_;
  int head_[2] = {-1, -1};
  std::vector<int> crossing_;
  std::optional<ActiveEncounter> enc_;
};

}  // namespace

std::string DefaultNetworkPath() { return TAEBP_DEFAULT_NET; }

namespace {

// Runs a program (no shell) with stdout/stderr to `log`; returns its exit code.
int RunProgram(const std::vector<std::string>& args, const std::string& log) {
  std::vector<char*> argv;
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  const pid_t pid = fork();
  if (pid < 0) return -1;
  if (pid == 0) {
    if (FILE* f = std::fopen(log.c_str(), "a")) {
      dup2(fileno(f), 1);
      dup2(fileno(f), 2);
    }
    execvp(argv[0], argv.data());
    _exit(127);
  }
  int status = 0;
  while (waitpid(pid, &status, 0) < 0) {
  }
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

}  // namespace

// Generated once into the cache (atomically: built in a private directory,
// then renamed into place).
std::string GeneratedFigure8(double loop) {
  const fs::path built = fs::path(DefaultNetworkPath()).parent_path();
  const fs::path script = built / "make_figure8.py";
  char name[64];
  std::snprintf(name, sizeof name, "figure8-L%.3f", loop);
  const fs::path dir = built / "cache" / name;
  const fs::path net = dir / "figure8.net.xml";
  if (fs::exists(net)) return net.string();
  if (!fs::exists(script))
    throw ConfigError("scenario.loop_length = " + Fmt(loop) + " needs " + script.string() +
                      ", which is missing: rebuild the project");
  fs::create_directories(dir.parent_path());
  const fs::path tmp = dir.parent_path() / (std::string(name) + ".tmp." + std::to_string(getpid()));
  fs::create_directories(tmp);
  const std::string log = (tmp / "generate.log").string();
  char loop_text[32];
  std::snprintf(loop_text, sizeof loop_text, "%.3f", loop);
  if (RunProgram({"python3", script.string(), "--loop-length", loop_text, "--out-dir", tmp.string()},
                 log) != 0 ||
      RunProgram({"netconvert", "--node-files", (tmp / "figure8.nod.xml").string(), "--edge-files",
                  (tmp / "figure8.edg.xml").string(), "--connection-files",
                  (tmp / "figure8.con.xml").string(), "--no-turnarounds", "true",
                  "--offset.disable-normalization", "true", "--precision", "4",
                  "--xml-validation", "never", "--output-file", (tmp / "figure8.net.xml").string()},
                 log) != 0) {
    throw ConfigError("scenario.loop_length = " + Fmt(loop) +
                      ": generating the network failed, see " + log);
  }
  std::error_code ec;
  fs::rename(tmp, dir, ec);  // another process may have won the race: use its copy
  if (ec) fs::remove_all(tmp);
  return net.string();
}

double RequiredLoopLength(const ScenarioConfig& sc) {
  const int n = sc.avs + sc.hvs;
  // Each vehicle needs length + gap (+0.5 m slack); a quarter more covers the
  // zones where none is placed (hold zone, edge starts). Two loops per lap.
  // Measured with 5 m vehicles, 2 m gaps and stop 3 m (tests/controller/
  // trust_test.cc re-checks it): placement first fails at 70 m for 16
  // vehicles (this gives 80, the paper's track), and loops below ~45 m
  // gridlock even with 8 vehicles, hence the 50 m floor.
  return std::max(50.0, std::ceil(1.25 * n * (sc.vehicle_length + sc.min_gap + 0.5) / 2.0 + 5.0));
}

ScenarioFiles ResolveScenarioFiles(const ExperimentConfig& config, const std::string& config_dir) {
  ScenarioFiles files;
  const ScenarioConfig& sc = config.scenario;
  if (sc.network.empty()) {
    double loop = sc.loop_length;
    const double needed = RequiredLoopLength(sc);
    if (loop < needed) {
      if (!sc.auto_length)
        throw ConfigError("scenario.loop_length = " + Fmt(loop) + " m is too short for " +
                          std::to_string(sc.avs + sc.hvs) + " vehicles (needs " + Fmt(needed) +
                          " m); raise it or set scenario.auto_length: true");
      files.notes.push_back("scenario.loop_length grown from " + Fmt(loop) + " to " +
                            Fmt(needed) + " m to fit " + std::to_string(sc.avs + sc.hvs) +
                            " vehicles");
      loop = needed;
    }
    files.loop_length = loop;
    if (std::abs(loop - TAEBP_DEFAULT_LOOP_LENGTH) < 1e-9) {
      files.net = DefaultNetworkPath();
      if (!fs::exists(files.net))
        throw ConfigError("the built-in network " + files.net +
                          " is missing: build the project (tools/run or tools/test) first");
    } else {
      files.net = GeneratedFigure8(loop);
    }
    return files;
  }
  fs::path p = config.scenario.network;
  if (p.is_relative() && !config_dir.empty()) p = fs::path(config_dir) / p;
  if (!fs::is_regular_file(p))
    throw ConfigError("scenario.network = '" + config.scenario.network + "': no such file (" +
                      p.string() + ")");
  files.net = p.string();
  return files;
}

double DesignTrust(const ModelConfig& model, Policy policy, double theta) {
  if (policy == Policy::kNoTrust) return 1.0;
  const std::string k = model.Knowledge();
  if (k == "assumed") return model.assumed_trust.value_or(theta);
  if (k == "population_mean") return model.trust.Mean();
  return theta;
}

persuasion::PredictedOutcome ExpectedOutcome(const ModelConfig& model, Policy policy, int points) {
  persuasion::AvHvParams params{model.prior_go, model.collision_penalty};
  const auto lik = MakeLikelihood(model.likelihood);
  auto at = [&](double theta) {
    const auto scheme =
        persuasion::CommitScheme(policy, params, DesignTrust(model, policy, theta), *lik);
    return persuasion::PredictOutcome(scheme, params, theta, *lik);
  };
  if (model.trust.IsFixed()) return at(model.trust.value);
  std::vector<std::pair<double, double>> nodes;  // (theta, weight)
  const TrustSpec& t = model.trust;
  if (t.dist == "discrete") {
    const double total = t.TotalWeight();
    for (std::size_t i = 0; i < t.values.size(); ++i)
      nodes.emplace_back(t.values[i], t.Weight(i) / total);
  } else {
    for (int j = 0; j < points; ++j) nodes.emplace_back(t.Quantile((j + 0.5) / points), 1.0 / points);
  }
  persuasion::PredictedOutcome e;
  for (const auto& [theta, w] : nodes) {
    const auto o = at(theta);
    e.dc_rate += w * o.dc_rate;
    e.collision_rate += w * o.collision_rate;
    e.nudge_rate += w * o.nudge_rate;
    e.av_first_rate += w * o.av_first_rate;
  }
  return e;
}

std::vector<std::string> ScenarioWarnings(const ExperimentConfig& config) {
  std::vector<std::string> w;
  const double reach = config.scenario.stop_distance - config.model.likelihood.s_max;
  if (reach < config.scenario.vehicle_width / 2) {
    w.push_back("a nudge of up to model.likelihood.s_max = " + Fmt(config.model.likelihood.s_max) +
                " m from scenario.stop_distance = " + Fmt(config.scenario.stop_distance) +
                " m can put the AV's nose inside the crossing path (needs stop_distance >= s_max + "
                "vehicle_width/2 = " + Fmt(config.model.likelihood.s_max + config.scenario.vehicle_width / 2) +
                " m): a waiting, nudged AV can then be hit");
  }
  return w;
}

std::unique_ptr<persuasion::LikelihoodModel> MakeLikelihood(const LikelihoodConfig& c) {
  if (c.type == "logistic")
    return std::make_unique<persuasion::LogisticLikelihood>(c.s_max, c.steepness, c.midpoint);
  if (c.type == "linear") return std::make_unique<persuasion::LinearLikelihood>(c.s_max);
  throw persuasion::InvalidArgument("likelihood '" + c.type + "' is not linear or logistic");
}

double RunBareSumo(const ExperimentConfig& config, const ScenarioFiles& files) {
  Run run(config, Policy::kNoEbp, files);
  return run.ExecuteBare();
}

PolicyRun RunPolicy(const ExperimentConfig& config, Policy policy, const ScenarioFiles& files,
                    const RunOptions& options) {
  Run run(config, policy, files, options);
  return run.Execute();
}

}  // namespace taebp
