// The controlled junctions as the controller needs them, read once from the
// network file, free of SUMO: each junction's movements (SUMO's links, their
// conflicts from `<request foes>`), its stop-controlled approach lanes, each
// movement's exit (the lanes it fills up to the next stop line, for keep
// clear), the major-road lanes a two-way stop's gap check looks along, and
// each movement's centreline for the game's premise (conflict_geometry.h).
// Route edges are numbered as vehicles bring them (EdgeIndex).
#pragma once

#include "taebp/config/config.h"
#include "taebp/junction/conflict_geometry.h"
#include "taebp/junction/interception.h"
#include "taebp/report/results.h"
#include "taebp/scenario/net_file.h"
#include "taebp/scenario/scenario.h"

#include <map>
#include <optional>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

namespace taebp::control {

// The lanes a movement's exit fills before the next stop line.
struct Exit {
  std::vector<std::string> lanes;
  double capacity = 0;  // m
};

struct MovementInfo {
  std::string from_lane, to_lane;
  std::vector<std::string> internal;
  std::string to_edge;
  char dir = 's';
  char state = 'M';             // SUMO's link state (M: right of way over every foe)
  bool controlled = false;      // a stop link (all links of its lane are)
  int exit = -1;                // Topology::exit()
  std::vector<int> major_foes;  // major movements (same junction) in conflict
  // Lanes feeding this (major) movement with the distance from their end to
  // the line, for the gap check.
  std::vector<std::pair<std::string, double>> feeders;
  // Its path from the approach lane through the junction onto the exit lane
  // (front, length and kinematics filled per vehicle by the game's premise).
  junction::Mover mover;
  // Where each lane of the path begins on it, and how the lane's positions
  // (SUMO's lane length) scale onto the path's arc (the shape's length).
  struct LaneOnPath {
    std::string lane;
    double start = 0, scale = 1;
  };
  std::vector<LaneOnPath> lanes_on_path;
  // The arc of a front at `pos` on `lane` (-1: the lane is not on the path).
  double ArcOf(const std::string& lane, double pos) const;
  // Major movements at two-way stops: the feeders upstream of the approach
  // lane (a major-road HV may still be on one: OSM approach lanes are often
  // shorter than the game's window), each with where its end lies on the path
  // extended backwards (negative arcs: before the approach lane).
  struct Upstream {
    std::string lane;
    double end = 0, length = 0;
  };
  std::vector<Upstream> upstream;
  // Is `lane` upstream of the approach lane on this movement's feeders?
  bool IsUpstream(const std::string& lane) const;
  // The arc of a front at `pos` on `lane` on the path or upstream of it
  // (nullopt: neither).
  std::optional<double> PathArc(const std::string& lane, double pos) const;
};

struct ApproachInfo {  // a stop-controlled lane into a controlled junction
  std::string lane;
  std::string edge;
  double length = 0;
  // The speed limit of the lane and of the lanes leading into it (m/s): the
  // fastest a vehicle of speed factor 1 comes along it.
  double speed = 0;
  bool only_lane = true;  // its edge has no other lane (no vehicle can change into it ahead)
  int junction = -1;
};

struct JunctionInfo {
  ControlledJunction info;
  junction::JunctionSpec spec;
  std::vector<MovementInfo> movements;
  std::vector<int> approaches;        // Topology::approaches() indices
  std::vector<std::string> incoming;  // every lane into it (the stall check)
  std::vector<int> incoming_approach;  // as incoming: its approach (a stop line), or -1
  // Two-way stops: the lanes of its major (not stop-controlled) movements.
  std::vector<std::string> major_lanes;
};

class Topology {
 public:
  // Throws ConfigError for a controlled junction that is not in the net.
  // `sample_interval`: the seconds between two once-a-second samples.
  Topology(const ScenarioConfig& sc, const Scenario& scenario, const net::NetFile& net,
           double sample_interval);

  const std::vector<JunctionInfo>& junctions() const { return junctions_; }
  const std::vector<ApproachInfo>& approaches() const { return approaches_; }
  const Exit& exit(int k) const { return exits_[k]; }
  // The approaches of one edge (a vehicle on it may change to any of them).
  const std::vector<int>& ApproachesOfEdge(const std::string& edge) const;

  // Route edges, numbered as vehicles bring them.
  int EdgeIndex(const std::string& edge);
  int JunctionAtEnd(int edge) const { return edge_junction_[edge]; }  // -1: not controlled
  const std::string& EdgeName(int edge) const { return edge_names_[edge]; }
  double EdgeLength(int edge) const { return edge_length_[edge]; }

  // The movement at junction `j` from `lane` onto `next_edge` (-1: none).
  int MovementFor(int j, const std::string& lane, const std::string& next_edge) const;
  // The same for a major (not stop-controlled) movement.
  int MajorMovementFor(int j, const std::string& lane, const std::string& next_edge) const;

  // Farther than any vehicle drives between two samples (speed factors up to
  // 2, and a margin): which junctions a vehicle is near.
  double reach() const { return reach_; }
  // The fastest lane of the network (m/s).
  double vmax() const { return vmax_; }

 private:
  // The parts of the constructor: one junction's movements and SUMO's
  // conflicts between them; its stop approaches; the lanes that feed a major
  // movement up to `reach` metres (two-way stops).
  JunctionInfo MovementsOf(const ControlledJunction& cj, const net::Junction& nj);
  void AddApproaches(JunctionInfo* junction, int jx);
  void AddFeeders(MovementInfo* major, double reach) const;
  bool Controlled(const std::string& junction_id) const { return junction_index_.count(junction_id); }
  int ExitFor(const std::string& to_lane);
  junction::Mover MoverFor(MovementInfo* m) const;

  const net::NetFile& net_;
  std::vector<JunctionInfo> junctions_;
  std::map<std::string, int> junction_index_;
  std::vector<ApproachInfo> approaches_;
  std::map<std::string, std::vector<int>> edge_approaches_;
  std::vector<Exit> exits_;
  std::map<std::string, int> exit_index_;
  std::unordered_map<std::string, int> edge_index_;
  std::vector<int> edge_junction_;
  std::vector<std::string> edge_names_;
  std::vector<double> edge_length_;
  double reach_ = 60;
  double vmax_ = 0;
};

}  // namespace taebp::control
