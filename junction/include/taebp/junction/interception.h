// One controlled junction's interception logic, free of SUMO: when an AV and an
// HV meet there, the paper's game between them, and the order in which the
// two are handed back to SUMO. Everything else at the junction is SUMO's: its
// own junction model (allway_stop, priority_stop) gives right of way to every
// vehicle that is not part of an AV-HV encounter. The network controller
// (controller/) reports what SUMO shows each step and executes the commands;
// tests drive it with fake time and fake vehicles (README "Only AV-HV
// encounters are the controller's").
//
// The rules:
// - Meeting. An AV and an HV *meet* when, in one simulation step, both are
//   the front vehicles of stop-controlled lanes of this junction whose
//   movements conflict in SUMO's `<request foes>`, one of them waits at its
//   line (front within 1 m of it, below 0.5 m/s) and the other waits at its
//   own line too or is coming to a stop there (front within
//   `meeting_distance` of it), both exits have room for them (keep clear:
//   Environment::ExitHasRoom), and no encounter is running here. (SUMO's
//   all-way stop lets a waiting head go in the very step a conflicting foe
//   comes to a halt, so two heads are almost never halted together: the
//   pair SUMO is about to order is one waiting and one arriving.) The
//   controller holds nobody before that step, so a vehicle that meets nobody
//   drives exactly as SUMO has it. Several candidate pairs: the head that
//   came to its line first (then the lower approach index) picks its first
//   conflicting partner of the other kind, waiting partners first.
// - The game's premise. A meeting is an encounter only where "AV goes, HV
//   drives recklessly" collides (EncounterModel::Game, conflict_geometry.h);
//   other meetings are counted and left to SUMO.
// - The encounter. The controller holds the waiting one at once and the
//   arriving one when it has come to its line (a partner that has not within
//   `kArrivalLimit` seconds, or that stops being its lane's front, ends the
//   meeting: the held one is handed back, counted in AbandonedMeetings),
//   then draws the AV's intent and signal, waits until both stand still and
//   no vehicle inside the junction can touch the AV on its way
//   (Environment::WayClear: nor will anyone there come to yield to an AV
//   nudged into its path), lets the AV nudge as drawn from its committed
//   scheme, and the HV reads the displacement SUMO reports.
//   Then, as the paper has it (EncounterSequence): an AV that goes and an HV that drives
//   recklessly are released with SUMO's right of way off (they collide if both
//   go: SUMO's collision check says whether they do); so is a careful move
//   while its partner still stands yielding in the junction or at its line (an
//   HV driving if clear past a still AV that may have nudged into the
//   junction: SUMO's rules would make it wait for that AV for ever). A careful
//   move whose partner is on its way and inside the junction (the HV driving
//   if clear after the AV went, the still AV after the HV) is handed back to
//   SUMO's own rules, which make it yield to the partner at their crossing
//   point (as SUMO does for any foe already in the junction: crossing-point
//   following) and decide when it enters. A still AV whose nudge took its
//   front past its line is inside the junction itself, where SUMO no longer
//   makes it yield (it has passed its link): it is handed back only once the
//   HV has passed its way through the junction (Environment::Passed) or left
//   the junction. Every move of the game waits until no vehicle inside the
//   junction can touch it on its way through (Environment::WayClear: with
//   SUMO's right of way off it would not yield); every move but the reckless
//   HV's also waits for room at its exit and, at a two-way stop, a gap in the
//   major road; when the AV goes and the HV drives recklessly, the two start
//   together (the game's premise), so there each waits with the other for
//   both ways (and at a two-way stop the major road on both movements) to
//   clear. A nudged AV standing inside the junction makes SUMO stop vehicles
//   in the junction for it, possibly in the way of a move of the game, where
//   they would wait for it for ever and it for them: such a vehicle, when its
//   own way is clear, is let past the AV (Command::kUnblock: SUMO's car
//   following and links ahead still apply, vehicles already in the junction
//   are disregarded until it has left it).
// - Third vehicles. While a meeting or an encounter runs, a vehicle waiting at a stop line
//   of this junction on a movement that conflicts with the AV's or the HV's is
//   held there; it is handed back once both encounter vehicles are on their
//   way (SUMO's own logic then makes it yield to them). A new meeting may
//   form once both are inside the junction (a move not yet begun is neither
//   at the lines a meeting looks at nor inside where the new moves' ways are
//   checked); the encounter is recorded when both have left the junction.
// - The major-road encounter (Timing::major_road, two-way stops only;
//   docs/beyond/major-road.md). An AV waiting (standing) at a minor stop line
//   and an HV approaching on a major movement that conflicts with it (the
//   front of its approach lane, driven by SUMO) meet when no encounter runs
//   here and EncounterModel::MajorRoad says the approach is the game now
//   (ClassifyMajorRoadApproach on SUMO's distances and speeds and the
//   junction's conflict geometry, the premise "both proceed collides"). The
//   AV is held and nudges as drawn; the signal lasts as long as the scheme's
//   nudge whatever the draw (a still AV stands that long), and the HV keeps
//   its speed meanwhile with SUMO's right of way off (kCruise: it does not
//   brake for the nudged AV). Then the HV reads SUMO's displacement: DR, it
//   keeps its speed through the junction; DC, it brakes at the comfortable
//   deceleration after its reaction time (kYield) and is handed back to
//   SUMO's rules once the AV that went has passed its way, or, when the AV
//   waits, drives on past it after `confirm_delay` (right of way off). The
//   AV that goes is released at once (the two start together: the premise);
//   the AV that waits goes back to SUMO's rules (its stop sign and gap
//   acceptance) once the HV is inside the junction, or, nudged past its
//   line, once the HV has passed its way and its own way and the major road
//   are clear.
#pragma once

#include "taebp/encounter/encounter.h"

#include <functional>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace taebp::junction {

enum class Rule { kAllWay, kTwoWay };
const char* ToString(Rule rule);

struct Movement {
  int approach = 0;        // index of the approach (incoming lane) it starts from
  bool controlled = true;  // a stop link: its vehicles halt at the line
  char dir = 's';          // SUMO direction: s, l, r, t, ...
  std::string from_lane, to_lane;  // for records
};

struct JunctionSpec {
  std::string id;
  Rule rule = Rule::kAllWay;
  int approaches = 0;
  std::vector<Movement> movements;
  // conflict[i][j]: movements i and j cross or merge (from SUMO's foes).
  std::vector<std::vector<bool>> conflict;
  bool Conflict(int a, int b) const { return conflict[a][b] || conflict[b][a]; }
  // Throws std::invalid_argument when sizes disagree.
  void Validate() const;
};

// The pairs of movements on which an AV and an HV can ever meet as a game at
// this junction (the run's junctions.csv `game_pairs`): two stop-controlled
// movements from different approaches that conflict (the paper's game: both
// at their lines), and with `major_road` also a stop-controlled movement
// against a conflicting uncontrolled one (the AV at the minor line, the HV on
// the major road). 0: no game can form here, whatever the traffic (a two-way
// stop with a single stop-controlled approach and the major-road game off).
// Whether a meeting on such a pair is a game is still decided per meeting
// (both proceeding must collide).
int GamePairs(const JunctionSpec& spec, bool major_road);

struct Timing {
  double confirm_delay = 1.0;  // s: an HV driving if clear facing a still AV waits this long
  // The major-road encounter (two-way stops): off unless set.
  bool major_road = false;
  double yield_decel = 3.0;    // m/s^2: a DC major-road HV brakes this hard
  double reaction_time = 0.0;  // s: after its decision, before it brakes
};

// What the logic asks of the world (SUMO, through the controller).
class Environment {
 public:
  virtual ~Environment() = default;
  // No vehicle inside the junction other than `vehicle` and `partner` can
  // still touch `vehicle` on its way through it: each one on a movement
  // conflicting with its own has passed its way (conflict_geometry.h
  // PassedWay), or stands still clear of it (yielding: SUMO's rules make a
  // vehicle in the junction wait for a foe ahead on the crossing, and
  // waiting for it would wait for ever).
  virtual bool WayClear(int vehicle, int partner) = 0;
  // WayClear for a still AV its nudge took past its line, going after its
  // major-road partner: a vehicle standing still inside the junction clear of where the
  // AV stands is not held by it, and may start any step (SUMO releases a
  // vehicle waiting at an internal stop for the partner as the partner
  // passes, in the step the AV would go: the random_nudge collision at B0 of
  // the two-way grid, issue 43), so it must have passed the AV's way too.
  // Vehicles the AV itself holds (it stands in their way) stay, as in WayClear.
  virtual bool WayClearOfStarters(int vehicle, int partner) { return WayClear(vehicle, partner); }
  // The vehicle stands still (a held vehicle may take a step or two to stop).
  virtual bool Standing(int vehicle) = 0;
  // Keep clear: the vehicle's exit on `movement` can take it with its rear
  // off the junction (asked of both before a meeting, and of a move of the
  // game before it is released).
  virtual bool ExitHasRoom(int movement, int vehicle) = 0;
  // Two-way stops: no major-road vehicle inside or within the critical gap
  // on a movement conflicting with `movement`.
  virtual bool MajorClear(int movement) = 0;
  // The vehicle's front is past its stop line, inside the junction (a nudge
  // can take a held AV there).
  virtual bool PastLine(int vehicle) = 0;
  // `first`, on its way, has passed `second`'s way through the junction: no
  // body of it from now on can touch `second` on the junction
  // (conflict_geometry.h PassedWay).
  virtual bool Passed(int first, int second) = 0;
  // Vehicles standing still inside the junction in `vehicle`'s way that SUMO
  // keeps waiting there for a vehicle of the game standing in the junction (a
  // nudged AV: SUMO makes a vehicle in the junction wait for a foe ahead of
  // it on their crossing for as long as that foe stands), and that could
  // drive on without touching anyone inside: each one's way is clear of every
  // vehicle there (moving ones on their ways, still ones where they stand).
  virtual std::vector<int> Unblockable(int vehicle, int partner) {
    (void)vehicle, (void)partner;
    return {};
  }
  // Unblockable for WayClearOfStarters: also the still vehicles clear of
  // `vehicle` where they stand whose way crosses its way (SUMO may keep them
  // waiting for the nudged AV by its links' priorities, not its body): let
  // past, they go first, and the AV after them.
  virtual std::vector<int> UnblockableStarters(int vehicle, int partner) {
    return Unblockable(vehicle, partner);
  }
  // The major-road encounter: no major-road vehicle but `hv` (on
  // `hv_movement`) and those behind it on its way is inside or within the
  // critical gap plus `extra` seconds of a major movement conflicting with
  // `movement`.
  virtual bool MajorClearBut(int movement, int hv, int hv_movement, double extra) {
    (void)hv, (void)hv_movement, (void)extra;
    return MajorClear(movement);
  }
};

// An HV approaching a two-way stop on a major (not stop-controlled) movement:
// the front vehicle of its approach lane, SUMO's view this step.
struct MajorAt {
  int vehicle = -1;
  int movement = -1;
  double gap = 0;    // m from its front to its stop line (the approach lane's end), along its
                     // route (it may still be on a lane feeding the approach lane)
  double speed = 0;  // m/s
};

// Is an approach the major-road game (EncounterModel::MajorRoad)?
struct MajorVerdict {
  enum class Kind {
    kNotYet,  // not now (the HV still far, the major road busy): ask again next step
    kGame,    // form the encounter now
    kNever,   // not for this pair (it passed the window, or the premise fails)
  };
  Kind kind = Kind::kNotYet;
  double signal = 0;  // s: how long the signal lasts (the scheme's nudge; a still AV stands it)
};

// The paper's game for one AV-HV pair: the AV's draw from its committed
// scheme and the HV's reading of the displacement SUMO reports.
class EncounterModel {
 public:
  virtual ~EncounterModel() = default;
  virtual AvDraw Draw(int av, int hv) = 0;
  virtual HvReading Read(int av, int hv, double observed) = 0;
  // Is the meeting the paper's game: would the two collide if both
  // proceeded (conflict_geometry.h BothProceedCollide)?
  virtual bool Game(int av, int hv, int av_movement, int hv_movement) {
    (void)av, (void)hv, (void)av_movement, (void)hv_movement;
    return true;
  }
  // The major-road encounter: is the AV waiting at its minor line and the
  // approaching HV `hv` (its front `hv_gap` m before its line at `hv_speed`)
  // the game now? (persuasion/major_road.h ClassifyMajorRoadApproach, and the
  // premise on the geometry.)
  virtual MajorVerdict MajorRoad(int av, const MajorAt& hv, int av_movement) {
    (void)av, (void)hv, (void)av_movement;
    return {};
  }
};

// A vehicle halted at its stop line this step (SUMO's view).
struct AtLine {
  int vehicle = -1;
  VehicleKind kind = VehicleKind::kHV;
  int movement = -1;
  bool waiting = true;  // at its line (else: coming to a stop there)
  double since = 0;     // when it came to its line (waiting ones)
};

struct Command {
  enum class Kind {
    kHold,        // keep it where it is (setSpeed 0)
    kStartNudge,  // the AV: creep `distance` m (0: stay), then report NudgeDone
    kRelease,     // drive through with SUMO's right of way off (the game's go / DR)
    kHandBack,    // SUMO's own rules again (a careful release, a held third vehicle)
    kUnblock,     // a vehicle SUMO keeps waiting inside the junction for a vehicle of the
                  // game may pass it (Environment::Unblockable) until it has left the junction
    kCruise,      // a major-road HV: keep `speed` with SUMO's right of way off (the signal, DR)
    kYield,       // a major-road HV (DC): brake at `speed` m/s^2 from `delay` s on
  };
  Kind kind = Kind::kHold;
  int vehicle = -1;
  double distance = 0;
  double speed = 0;
  double delay = 0;     // kYield: reaction time
  double duration = 0;  // kStartNudge: the signal lasts at least this long (a still AV too)
  int movement = -1;    // kCruise: the HV's movement
  int partner = -1;     // kRelease, kCruise: the other vehicle of the game (named to SUMO as
                        // the vehicle the move disregards: docs/encounter-rules.md)
  bool in_encounter = false;  // a release or hand-back of an encounter vehicle: report Cleared
};

// A finished AV-HV encounter (both vehicles have left the junction).
struct EncounterOutcome {
  int av = -1, hv = -1;
  int av_movement = -1, hv_movement = -1;
  double time = 0;        // formed
  double decided_at = 0;  // the HV decided
  AvDraw draw;
  HvReading reading;
  bool collision = false;
  // SUMO reported the two colliding after one was handed back to SUMO's
  // rules (not a move of the game: `collision` stays false).
  bool collision_after_handback = false;
  bool major_road = false;  // the major-road encounter (the HV approached on the major road)
};

class Interception {
 public:
  Interception(JunctionSpec spec, Timing timing);

  const JunctionSpec& spec() const { return spec_; }

  static constexpr double kArrivalLimit = 10.0;  // s

  // One step: `at_line` holds the front vehicle of every stop-controlled lane
  // of this junction that waits at its line or is coming to a stop there
  // (held ones included, as waiting). Returns the commands to execute.
  // `major`: HVs approaching on major movements (Timing::major_road only).
  std::vector<Command> Step(double now, const std::vector<AtLine>& at_line, Environment& env,
                            EncounterModel& model, const std::vector<MajorAt>& major = {});
  // An encounter vehicle released has entered the junction (its front past
  // its stop line).
  void Entered(int vehicle, double now);
  // An encounter vehicle released or handed back has left the junction.
  void Cleared(int vehicle, double now);
  // The nudging AV finished its creep; `observed` is SUMO's displacement.
  void NudgeDone(int av, double observed, double now, EncounterModel& model);
  // SUMO reported a collision between two vehicles; true if they were the AV
  // and HV of the encounter running here.
  bool Collided(int a, int b);
  // Encounters finished since the last call.
  std::vector<EncounterOutcome> TakeFinished();

  // A meeting or an encounter holds vehicles here, encounter vehicles are
  // still on their way out, or a finished encounter waits to be taken.
  bool Busy() const {
    return encounter_.has_value() || !leaving_.empty() || !thirds_.empty() || !finished_.empty();
  }
  // Encounters begun (drawn) at or after `since` and not finished.
  int Encounters(double since = -1e300) const {
    int n = encounter_ && encounter_->drawn && encounter_->out.time >= since ? 1 : 0;
    for (const Active& a : leaving_) n += a.out.time >= since ? 1 : 0;
    return n;
  }
  int HeldThirds() const { return static_cast<int>(thirds_.size()); }
  // AV-HV meetings that were not the game (each pair counted once).
  long NonGameMeetings() const { return non_game_; }
  // Meetings whose arriving partner never came to its line.
  long AbandonedMeetings() const { return abandoned_; }
  double LastActivity() const { return last_activity_; }
  std::string Describe(const std::function<std::string(int)>& name) const;

 private:
  struct Active {
    EncounterOutcome out;
    bool av_held = false, hv_held = false;
    bool drawn = false;  // both at their lines: the game has begun
    bool nudge_started = false, nudged = false;
    std::optional<EncounterSequence> sequence;
    bool av_released = false, hv_released = false;
    bool av_entered = false, hv_entered = false;
    bool av_cleared = false, hv_cleared = false;
    double hv_cleared_at = -1;  // when the HV left the junction (Cleared)
    bool av_handed_back = false, hv_handed_back = false;  // to SUMO's rules
    bool major = false;         // the major-road encounter
    bool major_moves = false;   // its first moves after the decision issued
  };
  // A major-road meeting, if one forms now (Timing::major_road).
  void FormMajor(double now, const std::vector<AtLine>& at_line,
                 const std::vector<MajorAt>& major, Environment& env, EncounterModel& model,
                 std::vector<Command>* out);
  // The major-road encounter after the HV decided.
  void StepMajor(double now, Environment& env, std::vector<Command>* out);
  // Both released: watched until they have left the junction.
  void Hand();
  bool ConflictsWithEncounter(int movement) const;
  // A meeting: the waiting ones held (the draw comes once both are).
  void Form(double now, const AtLine& av, const AtLine& hv, std::vector<Command>* out);

  // The parts of Step, in its order. Thirds of an ended encounter handed
  // back; pairs judged not the game forgotten once either left its line.
  void Forget(const std::vector<AtLine>& at_line, std::vector<Command>* out);
  // Who meets whom (not at the major road): the head first at its line picks
  // its earliest partner; a meeting that is the game is formed.
  void Meet(double now, const std::vector<AtLine>& at_line, Environment& env,
            EncounterModel& model, std::vector<Command>* out);
  void ForgetMajor(const std::vector<AtLine>& at_line, const std::vector<MajorAt>& major);
  // Third vehicles at the line on conflicting movements wait for the encounter.
  void HoldThirds(const std::vector<AtLine>& at_line, std::vector<Command>* out);
  // The arriving partner held at its line, then the draw: true once drawn;
  // false while arriving or when the meeting was abandoned.
  bool Arrive(double now, const std::vector<AtLine>& at_line, EncounterModel& model,
              std::vector<Command>* out);
  void StartNudge(Environment& env, std::vector<Command>* out);
  // After the HV decided: the releases as the paper orders them.
  void Release(double now, Environment& env, std::vector<Command>* out);
  // Whether each move may go (room, the major road) and has its way.
  struct Ways {
    bool av_may = false, hv_may = false, av_way = false, hv_way = false;
  };
  Ways WaysOf(Environment& env, bool av_past) const;
  // Lets vehicles SUMO stopped for the nudged AV pass it; true if any.
  bool Unblock(Environment& env, const Ways& w, std::vector<Command>* out);

  JunctionSpec spec_;
  Timing timing_;
  std::optional<Active> encounter_;             // holding vehicles
  std::vector<Active> leaving_;                 // both released, not both out of the junction
  std::vector<int> thirds_;                    // held for the running encounter
  std::set<std::pair<int, int>> not_game_;     // (AV, HV) meeting now, judged not the game
  std::set<std::pair<int, int>> major_never_;  // (AV, HV) major-road approaches judged never
  std::vector<EncounterOutcome> finished_;
  double last_activity_ = 0;
  long non_game_ = 0, abandoned_ = 0;
};

}  // namespace taebp::junction
