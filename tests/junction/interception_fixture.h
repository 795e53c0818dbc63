// The fixture of the interception tests (interception_test.cc): the real
// junction B1 of
//   netgenerate --grid --grid.number 4 --default-junction-type allway_stop
//               --no-turnarounds true
// whose 12 links (request index = movement index) and <request foes> are
// copied below (tests/scenario/net_file_test.cc checks them against a freshly
// generated net), a fake Environment (conflict area, standstill, keep-clear,
// major road gaps) and a fake EncounterModel (scripted AV draws and HV readings).
#pragma once

#include "taebp/junction/interception.h"

#include <map>
#include <set>
#include <utility>
#include <vector>

namespace taebp::junction::fixture {

using Kind = Command::Kind;
constexpr VehicleKind kAV = VehicleKind::kAV;
constexpr VehicleKind kHV = VehicleKind::kHV;

// ------------------------------------------------------------------ the junction
// Approaches (incLanes order): 0 = from the north (B2B1_0), 1 = east (C1B1_0),
// 2 = south (B0B1_0), 3 = west (A1B1_0). Exits: A1 (west), B0 (south),
// C1 (east), B2 (north).
enum Mv {
  kNr = 0, kNs = 1, kNl = 2,   // north: right -> A1, straight -> B0, left -> C1
  kEr = 3, kEs = 4, kEl = 5,   // east:  right -> B2, straight -> A1, left -> B0
  kSr = 6, kSs = 7, kSl = 8,   // south: right -> C1, straight -> B2, left -> A1
  kWr = 9, kWs = 10, kWl = 11  // west:  right -> B0, straight -> C1, left -> B2
};
// SUMO's <request index="i" foes="..."/>: the last character is link 0.
inline const char* const kB1Foes[12] = {
    "000100010000", "111100110000", "110111110000", "100010000000",
    "100110000111", "111110000110", "010000000100", "110000111100",
    "110000110111", "000000100010", "000111100110", "000110111110"};
inline constexpr char kDirs[12] = {'r', 's', 'l', 'r', 's', 'l', 'r', 's', 'l', 'r', 's', 'l'};

inline JunctionSpec B1(Rule rule = Rule::kAllWay) {
  JunctionSpec s;
  s.id = "B1";
  s.rule = rule;
  s.approaches = 4;
  for (int m = 0; m < 12; ++m) {
    Movement mv;
    mv.approach = m / 3;
    mv.dir = kDirs[m];
    s.movements.push_back(mv);
  }
  s.conflict.assign(12, std::vector<bool>(12, false));
  for (int i = 0; i < 12; ++i)
    for (int k = 0; k < 12; ++k) s.conflict[i][k] = kB1Foes[i][11 - k] == '1';
  return s;
}

// ------------------------------------------------------------------ fakes
struct FakeEnv : Environment {
  std::set<int> way_blocked;  // vehicles someone inside the junction can still touch
  std::vector<int> way_asked;
  std::set<int> moving;            // vehicles not yet standing
  std::set<int> no_room_vehicles;  // keep clear
  std::set<int> major_busy;        // movements whose major road is not clear
  bool WayClear(int vehicle, int) override {
    way_asked.push_back(vehicle);
    return !way_blocked.count(vehicle);
  }
  bool Standing(int v) override { return !moving.count(v); }
  bool ExitHasRoom(int, int vehicle) override { return !no_room_vehicles.count(vehicle); }
  bool MajorClear(int movement) override { return !major_busy.count(movement); }
  std::set<int> past_line;  // vehicles whose front is past their line
  bool PastLine(int vehicle) override { return past_line.count(vehicle); }
  std::set<std::pair<int, int>> passed;  // (first, second): first passed second's way
  bool Passed(int first, int second) override { return passed.count({first, second}); }
  std::map<int, std::vector<int>> unblockable;  // by the vehicle whose way they block
  std::vector<int> Unblockable(int vehicle, int) override {
    const auto it = unblockable.find(vehicle);
    return it == unblockable.end() ? std::vector<int>{} : it->second;
  }
};

struct FakeModel : EncounterModel {
  std::map<int, AvDraw> draws;  // by AV; default: intent stop, no nudge
  std::map<int, bool> dc;       // by HV; default: DR
  std::set<std::pair<int, int>> not_game;
  std::vector<std::pair<int, int>> drawn, games;
  AvDraw Draw(int av, int hv) override {
    drawn.emplace_back(av, hv);
    const auto it = draws.find(av);
    return it == draws.end() ? AvDraw{} : it->second;
  }
  HvReading Read(int, int hv, double obs) override {
    HvReading r;
    r.observed = obs;
    const auto it = dc.find(hv);
    r.drives_if_clear = it != dc.end() && it->second;
    return r;
  }
  bool Game(int av, int hv, int, int) override {
    games.emplace_back(av, hv);
    return !not_game.count({av, hv});
  }
};

inline AvDraw Draw(bool go, double nudge) {
  AvDraw d;
  d.intent_go = go;
  d.goes_first = go;
  d.nudge = nudge > 0;
  d.nudge_distance = nudge;
  return d;
}

using Cmd = std::pair<Kind, int>;
inline std::vector<Cmd> Simple(const std::vector<Command>& cs) {
  std::vector<Cmd> out;
  for (const Command& c : cs) out.emplace_back(c.kind, c.vehicle);
  return out;
}
inline Cmd Hold(int v) { return {Kind::kHold, v}; }
inline Cmd Nudge(int v) { return {Kind::kStartNudge, v}; }
inline Cmd Rel(int v) { return {Kind::kRelease, v}; }
inline Cmd Back(int v) { return {Kind::kHandBack, v}; }
inline Cmd Unblock(int v) { return {Kind::kUnblock, v}; }
inline const std::vector<Cmd> kNone;

inline AtLine Wait(int v, VehicleKind k, int m, double since) { return {v, k, m, true, since}; }
inline AtLine Coming(int v, VehicleKind k, int m) { return {v, k, m, false, 0}; }

constexpr int kAv = 1, kHv = 2, kThird = 3, kAv2 = 4, kHv2 = 5;

struct Sim {
  Interception logic{B1(), Timing{1.0}};
  FakeEnv env;
  FakeModel model;
  std::vector<Cmd> Step(double t, const std::vector<AtLine>& at) {
    return Simple(logic.Step(t, at, env, model));
  }
};

}  // namespace taebp::junction::fixture
