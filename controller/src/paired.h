// Paired games (scenario.paired, docs/paired.md): where a game forms (its two
// vehicles held at their lines, before the AV's draw), the run forks once per
// game policy of the config. Each child is a branch: the same process state,
// SUMO's (libsumo runs in this process) and the controller's, random number
// generators included, in which the controller plays from then on under the
// branch's policy; it follows the game until it finished and both vehicles
// reached the edge after its junction (or kPairedWindow, or the run's end),
// with only that game played under the branch's policy (every other game,
// running or new, stays the run's own),
// writes the outcome to a pipe and ends (_exit: no file of the run is
// touched, every descriptor but the pipe points at /dev/null). The parent
// waits for each branch in turn, keeps its row (PolicyRun::paired) and goes
// on under its own policy, exactly as without --paired.
#pragma once

#include "run_state.h"
#include "taebp/junction/pair_surrogates.h"

#include <memory>

#include <string>
#include <vector>

namespace taebp::control {

class EncounterGame;

class Pairing {
 public:
  explicit Pairing(RunState& s);

  // The game of (av, hv) forms now, before its draw. In the run: plays it in
  // a branch per paired policy and keeps their rows (returns after the last
  // one). In a branch: returns at once (its own games are not paired).
  // Returns in each branch too, which then follows the game.
  void GameForms(int av, int hv, EncounterGame& game);
  // The AV of a game drew its intent and signal (a branch keeps its game's).
  void Drawn(int av, int hv, const AvDraw& draw);
  // A game finished (its record, as encounters.csv has it).
  void Recorded(int av, int hv, const EncounterRecord& r);
  // Each step, after the controller's: a branch whose game is over writes
  // its row and ends the process.
  void Step();
  // A vehicle left the network.
  void Left(int h);

  bool InBranch() const { return branch_; }
  // A branch that cannot go on (the run ended, an error): writes its row as
  // far as it got and ends the process.
  [[noreturn]] void EndBranch(const std::string& status, const std::string& error = "");

 private:
  void StartBranch(persuasion::Policy policy, EncounterGame& game, int fd);
  PairedRecord Row(const std::string& status, const std::string& error) const;

  RunState& s_;
  std::vector<persuasion::Policy> policies_;  // the game policies of the config, in order
  long games_ = 0;
  // In a branch: the game it follows.
  bool branch_ = false;
  int fd_ = -1;
  int av_ = -1, hv_ = -1;
  std::string av_id_, hv_id_;
  std::string game_;
  persuasion::Policy policy_ = persuasion::Policy::kTaEbp;
  double formed_ = 0;
  int av_edge_ = -1, hv_edge_ = -1;  // route index of each one's edge at the junction
  double av_clear_ = kNoValue, hv_clear_ = kNoValue;
  bool recorded_ = false, drawn_ = false;
  AvDraw draw_;
  EncounterRecord record_;
  long third_before_ = 0;
  std::unique_ptr<HvPopulation> population_;  // the branch's policy, for its game only
  // Both vehicles each step while both are in the network (pair_surrogates.h).
  std::vector<junction::BodySample> av_track_, hv_track_;
  void Sample();
};

}  // namespace taebp::control
