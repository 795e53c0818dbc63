// The network controller: SUMO decides right of way everywhere; the
// controller watches the stop lines of the controlled junctions and
// intercepts AV-HV encounters only (junction/interception.h says when and
// how). It registers vehicles as they depart (AV or HV, the HV's trust and
// the AV's design for it), reads which vehicles are halted at the lines of
// junctions where an AV and an HV may both be, holds the encounter's two
// (setSpeed 0) and third vehicles that would cross them, runs the nudge
// (speed mode 0, exact creep), lets the HV read SUMO's displacement,
// releases the game's moves with SUMO's right of way off (speed mode 55) and
// hands careful moves back to SUMO (speed mode 31), attributes SUMO's
// collisions, and collects the outputs.
//
// Per-step work: nothing at a junction no AV or no HV can reach within a
// second (so nothing at all at AV share 0 or 1); at the others, a stop line's
// lane only from the first step a vehicle can be within reach of a meeting
// there (stop_lines.h, Observe); two getters per vehicle crossing or nudging
// for an encounter. Every vehicle is read once per simulated second (route
// progress).
//
// Its parts live in controller/src, one job each (network_controller.cc
// lists them in the order a step runs them); SUMO is reached only through
// SumoWorld (sumo_world.h), which a test can fake.
#pragma once

#include "taebp/config/config.h"
#include "taebp/report/results.h"
#include "taebp/scenario/net_file.h"
#include "taebp/scenario/scenario.h"

#include <functional>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>

namespace taebp {

class SumoWorld;

// A nudge SUMO did not realise (scenario.nudge_check: error).
class NudgeError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Traffic stalled at a junction under scenario.stall_action: error (a
// controller policy; sumo_native's stalls are always recorded). what() names
// the junction, what waits there and why; junction(), since() (the last
// progress) and detected() are the stall's record. RunPolicy catches it and
// returns the run measured up to the stall (PolicyRun::stall_error).
class StallError : public std::runtime_error {
 public:
  explicit StallError(const std::string& what, std::string junction = {}, double since = 0,
                      double detected = 0)
      : std::runtime_error(what), junction_(std::move(junction)), since_(since),
        detected_(detected) {}
  const std::string& junction() const { return junction_; }
  double since() const { return since_; }
  double detected() const { return detected_; }

 private:
  std::string junction_;
  double since_, detected_;
};

struct ControllerOptions {
  bool colour_states = false;  // paint vehicles by state (sumo-gui)
  double stall_limit = -1;     // s; < 0: the scenario's default
};

class NetworkController {
 public:
  // `policy` empty: sumo_native (SUMO's own junction logic; the controller
  // only observes and measures). `world`: the simulation it reads and
  // commands (default: this process's SUMO, Sumo() of sumo_adapter.h); not owned.
  NetworkController(const ExperimentConfig& config, std::optional<persuasion::Policy> policy,
                    const Scenario& scenario, const net::NetFile& net,
                    const ControllerOptions& options, SumoWorld* world = nullptr);
  ~NetworkController();
  NetworkController(const NetworkController&) = delete;
  NetworkController& operator=(const NetworkController&) = delete;

  // SUMO has started: vehicle types and the figure-8's vehicles.
  void Start();
  // After each Sumo().Step(). Throws StallError, NudgeError.
  void Step();
  // After the last step, SUMO still running: the totals so far.
  PolicyRun Finish();
  // For progress reports: vehicles in the network now, encounters recorded
  // so far (finished, after the warm-up).
  long VehiclesNow() const;
  long EncountersSoFar() const;
  // Whether vehicle `id` entered the network as an AV (decided once, at its
  // departure: control::IsAv); SUMO's tripinfo is split by this.
  bool DepartedAsAv(const std::string& id) const;
  // scenario.paired: whether this process is a branch of a paired game
  // (paired.h), and its end where the run cannot go on (it ended, an error):
  // the branch's row as far as it got, then the process ends.
  bool InBranch() const;
  [[noreturn]] void EndBranch(const std::string& status, const std::string& error = "");

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace taebp
