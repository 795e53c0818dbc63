// One controlled junction's decision logic, free of SUMO: who may enter when,
// who meets whom, and the order of releases in an AV-HV encounter. The network
// controller (controller/) feeds it events read from SUMO and executes its
// commands; tests drive it with fake time and fake vehicles.
//
// Rules (README "Junctions and right of way"):
// - all-way stop: every approach stops; heads go first come, first served
//   (by arrival at the line, then approach order); a head whose movement
//   conflicts with nothing in or entering the junction, nor with an earlier
//   waiting head, may go at the same time as others (followers on the same
//   movement, opposite straights, right turns).
// - two-way stop: only the minor approaches (SUMO's stop links) are held;
//   the major road keeps SUMO's priority. A minor head also needs the major
//   road clear (Environment::MajorClear: no major vehicle within the
//   critical gap on a conflicting movement).
// - A head "looks both ways" for `arrival_window` seconds after it became
//   ready: it arrived, or the last conflicting vehicle cleared its path
//   (spec.clear_at). A conflicting head that was ready by the end of that
//   window meets it: an AV and an HV form an AV-HV encounter (the paper's
//   two-player game) when both proceeding would collide
//   (EncounterModel::Game); otherwise, and for two of a kind, they go by
//   arrival time. Meetings are
//   pairwise: a third conflicting head waits for the encounter to finish, so
//   every decision stays the two-player game. (Looking again after the
//   junction frees is what lets the figure-8's two queues meet; it costs
//   `arrival_window` per conflicting release, the protocol's price in
//   capacity.)
// - Keep clear: a head whose exit cannot take it with its rear off the
//   junction (Environment::ExitHasRoom) is not considered; it blocks nobody.
#pragma once

#include "taebp/junction/intersection.h"

#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace taebp::junction {

enum class Rule { kAllWay, kTwoWay };
const char* ToString(Rule rule);

struct Movement {
  int approach = 0;        // index of the approach (incoming lane) it starts from
  bool controlled = true;  // a stop link: its vehicles are held at the line
  char dir = 's';          // SUMO direction: s, l, r, t, ...
  std::string from_lane, to_lane;  // for records
};

struct JunctionSpec {
  std::string id;
  Rule rule = Rule::kAllWay;
  int approaches = 0;
  std::vector<Movement> movements;
  // conflict[i][j]: movements i and j cross or merge (symmetric; from SUMO).
  std::vector<std::vector<bool>> conflict;
  // clear_at[i][j] (optional): how far (m, from the stop line) the rear of a
  // vehicle on movement i must have driven before movement j may go (past
  // the crossing point; ConflictGeometry). Empty: until it left the junction.
  std::vector<std::vector<double>> clear_at;
  bool Conflict(int a, int b) const { return conflict[a][b] || conflict[b][a]; }
  // Throws std::invalid_argument when sizes disagree.
  void Validate() const;
};

struct Timing {
  double arrival_window = 1.0;  // s
  double confirm_delay = 1.0;   // s
};

// What the logic needs to know about the world when it decides.
class Environment {
 public:
  virtual ~Environment() = default;
  // Keep clear: can `vehicle`'s exit on `movement` take it with its rear off
  // the junction, counting every vehicle already headed there and `also`
  // more that are about to be (an encounter partner bound for the same exit)?
  virtual bool ExitHasRoom(int movement, int vehicle, int also = 0) = 0;
  // Two-way stops: no major-road vehicle inside or within the critical gap
  // on a movement conflicting with `movement`. Always true at all-way stops.
  virtual bool MajorClear(int movement) = 0;
};

// The paper's game for one AV-HV pair: the AV's draw from its committed
// scheme and the HV's reading of the displacement SUMO reports.
class EncounterModel {
 public:
  virtual ~EncounterModel() = default;
  virtual AvDraw Draw(int av, int hv) = 0;
  virtual HvReading Read(int av, int hv, double observed) = 0;
  // Is the meeting of this AV and HV the paper's game: would they collide if
  // both proceeded (conflict_geometry.h BothProceedCollide)? A meeting that
  // is not a game (a merge the AV leads, a crossing one of them has passed
  // before the other comes) goes by arrival, as two of a kind do.
  virtual bool Game(int av, int hv, int av_movement, int hv_movement) {
    (void)av, (void)hv, (void)av_movement, (void)hv_movement;
    return true;
  }
};

struct Command {
  enum class Kind {
    kRelease,     // vehicle: drive through (reckless: an HV driving recklessly)
    kStartNudge,  // vehicle (an AV): creep `distance` m (0: stay), then report NudgeDone
  };
  Kind kind = Kind::kRelease;
  int vehicle = -1;
  bool reckless = false;
  double distance = 0;
};

// A finished AV-HV encounter (both vehicles have cleared the junction).
struct EncounterOutcome {
  int av = -1, hv = -1;
  int av_movement = -1, hv_movement = -1;
  double time = 0;        // formed
  double decided_at = 0;  // the HV decided
  AvDraw draw;
  HvReading reading;
  bool collision = false;
};

class JunctionLogic {
 public:
  JunctionLogic(JunctionSpec spec, Timing timing);

  const JunctionSpec& spec() const { return spec_; }

  // A vehicle came to a stop at the line of its approach (the head).
  void Arrive(int vehicle, VehicleKind kind, int movement, double now);
  // Where a released vehicle's rear is: metres driven past its stop line
  // (negative while it is still before it). Unblocks the movements it has
  // passed (spec().clear_at).
  void Progress(int vehicle, double rear, double now);
  // A released vehicle's rear left the junction.
  void Cleared(int vehicle, double now);
  // A nudging AV finished its creep; `observed` is the displacement SUMO
  // reported since its hold (also for a nudge of 0).
  void NudgeDone(int av, double observed, double now, EncounterModel& model);
  // SUMO reported a collision between two vehicles; returns true if they
  // were the AV and HV of an encounter in progress here.
  bool Collided(int a, int b);

  // This step's commands (releases, nudges) at time `now`.
  std::vector<Command> Decide(double now, Environment& env, EncounterModel& model);

  // Encounters finished since the last call.
  std::vector<EncounterOutcome> TakeFinished();

  // State, for stall checks and tests.
  int Waiting() const { return static_cast<int>(heads_.size()); }
  int InJunction() const { return static_cast<int>(inside_.size()); }
  int Encounters() const { return static_cast<int>(encounters_.size()); }
  // AV-HV meetings that were not a game (EncounterModel::Game), so far.
  long NonGameMeetings() const { return non_game_; }
  double LastActivity() const { return last_activity_; }
  // The waiting heads, the vehicles inside and the encounters, for messages;
  // `name` turns a vehicle handle into its id.
  std::string Describe(const std::function<std::string(int)>& name) const;

 private:
  struct HeadState {
    int vehicle;
    VehicleKind kind;
    int movement;
    double arrival;
    double ready;  // max(arrival, when the last conflicting vehicle cleared)
  };
  struct Inside {  // released, not yet cleared
    int vehicle;
    int movement;
    double rear = -1e300;  // m past the stop line
  };
  struct Active {
    EncounterOutcome out;
    bool nudged = false;  // NudgeDone received
    std::optional<EncounterSequence> sequence;
    bool av_released = false, hv_released = false;
    bool av_cleared = false, hv_cleared = false;
  };

  bool Blocked(int movement) const;  // conflicts with a vehicle inside or in an encounter
  bool Blocks(const Inside& in, int movement) const;
  void Release(std::vector<Command>* out, int vehicle, int movement, bool reckless, double now);

  JunctionSpec spec_;
  Timing timing_;
  std::vector<HeadState> heads_;
  std::vector<Inside> inside_;
  std::vector<Active> encounters_;
  std::vector<EncounterOutcome> finished_;
  double last_activity_ = 0;
  long non_game_ = 0;
};

}  // namespace taebp::junction
