// Generated demand on a network's fringe: every edge that enters the network
// from a dead end gets random arrivals (a Poisson process of `flow` vehicles
// per hour, seeded), each a SUMO `<trip>` to a uniformly random fringe exit
// other than the way back, routed by SUMO (fastest path) when it departs.
#pragma once

#include "taebp/scenario/net_file.h"

#include <cstdint>
#include <string>
#include <vector>

namespace taebp {

struct DemandSpec {
  double flow = 300;   // veh/h per entering fringe edge
  double begin = 0;    // s, first departure time not before
  double end = 3600;   // s, no departure at or after
  std::uint64_t seed = 1;
  // The generated vehicle type ("car").
  double length = 5, width = 1.8, min_gap = 2, accel = 2.6, decel = 4.5, max_speed = 13.89;
};

struct FringeEdges {
  std::vector<std::string> entries, exits;
};
// Normal edges leaving (entries) and reaching (exits) dead-end junctions.
FringeEdges FindFringe(const net::NetFile& net);

struct Trip {
  std::string id;
  double depart = 0;
  std::string from, to;
};
// The trips, sorted by departure time (ties by entry order). Throws
// std::invalid_argument when the network has no fringe entries or exits.
std::vector<Trip> FringeTrips(const net::NetFile& net, const DemandSpec& spec);

// Writes the trips and their vType as a SUMO routes file; returns the count.
// Throws ConfigError (naming scenario.demand) on failure.
long WriteFringeDemand(const net::NetFile& net, const DemandSpec& spec, const std::string& path);

}  // namespace taebp
