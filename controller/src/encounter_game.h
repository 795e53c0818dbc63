// The paper's game for the AV-HV pairs the interception logic forms
// (junction::EncounterModel): the AV's draw from the scheme it committed to
// for this HV, whether the meeting is the game at all (would "AV goes, HV
// drives recklessly" collide on the junction's geometry, and waiting not:
// conflict_geometry.h PredictBothProceed, PassedWay), and the HV's reading of the
// displacement SUMO reported, through the HV population (trust, designs,
// learning: encounter/hv_population.h). Record turns a finished encounter
// into its row of encounters.csv.
#pragma once

#include "run_state.h"

#include <map>
#include <random>
#include <set>
#include <utility>

namespace taebp::control {

class VehicleCommands;
class Pairing;

class EncounterGame : public junction::EncounterModel {
 public:
  explicit EncounterGame(RunState& s);
  void set_commands(VehicleCommands* commands) { commands_ = commands; }
  void set_pairing(Pairing* pairing) { pairing_ = pairing; }
  // A paired game's branch (paired.h): the game of (av, hv) is played by
  // `population` (the branch's policy); every other game by the run's own.
  void PlayPairWith(int av, int hv, HvPopulation* population) {
    branch_pair_ = {av, hv};
    branch_population_ = population;
  }

  AvDraw Draw(int av, int hv) override;
  bool Game(int av, int hv, int av_movement, int hv_movement) override;
  junction::MajorVerdict MajorRoad(int av, const junction::MajorAt& hv, int av_movement) override;
  HvReading Read(int av, int hv, double observed) override;

  // A finished encounter of junction j: its record (after the warm-up), the
  // population's trust and belief updates, and the two vehicles' slots.
  void Record(const JunctionState& j, const junction::EncounterOutcome& e);

 private:
  RunState& s_;
  VehicleCommands* commands_ = nullptr;  // the HV's colour once it decided
  Pairing* pairing_ = nullptr;           // scenario.paired: a game forms, a game finished
  persuasion::AvHvParams params_;
  std::mt19937_64 rng_;
  std::map<std::pair<int, int>, Premise> verdicts_;
  // The nudge the game's rules assume for every policy (the likelihood's s_max).
  double LargestNudge() const;  // (AV, HV) met: does the game's premise hold
  // Major-road encounters running, (AV, HV): their game is the major road's.
  std::set<std::pair<int, int>> major_;
  GameKind KindOf(int av, int hv) const {
    return major_.count({av, hv}) ? GameKind::kMajorRoad : GameKind::kStopLines;
  }
  std::pair<int, int> branch_pair_{-1, -1};
  HvPopulation* branch_population_ = nullptr;
  HvPopulation& PopulationOf(int av, int hv) const {
    if (branch_population_ && branch_pair_ == std::make_pair(av, hv)) return *branch_population_;
    return *s_.population;
  }
  // The (AV, HV) movers of a major-road approach and their conflict zones,
  // per pair (the geometry does not change while the AV waits).
  struct MajorGeometry {
    int av_movement = -1, hv_movement = -1;
    double signal = 0;  // s: the largest nudge's creep (every policy's signal lasts that long)
    double line = 0;    // the AV's front on its path where it stands at its line
    junction::Mover av, hv;  // av: at the largest nudge (LargestNudge); hv: from its path's start
    junction::ConflictZone hv_zone, av_zone;
  };
  std::map<std::pair<int, int>, MajorGeometry> major_geometry_;
  const MajorGeometry& GeometryOf(int av, const junction::MajorAt& at, int av_movement);
  bool HvWayClear(const JunctionInfo& info, const MovementInfo& hm, double v) const;
  // The premise of a major-road pair at the HV's decision, on where SUMO has
  // the two then (the AV going from where it stands, the HV at its speed).
  Premise MajorPremiseNow(int av, int hv) const;
};

}  // namespace taebp::control
