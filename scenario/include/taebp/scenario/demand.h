// Generated demand: every origin edge gets random departures (a Poisson
// process of `flow` vehicles per hour, seeded), each a SUMO `<trip>` to a
// uniformly random destination it can reach, routed by SUMO (fastest path)
// when it departs. Origins on the fringe (edges entering the network from a
// dead end, bound for a fringe exit other than the way back) or on the minor
// roads (the approaches of the controlled junctions that yield or stop and
// do not go straight on with the right of way, bound for another junction's
// minor approach or a fringe exit). On top of either, `major_flow` vehicles
// per hour from every major approach of the junctions (the major roads' own
// traffic), bound like the minor roads' trips.
#pragma once

#include "taebp/config/enums.h"
#include "taebp/scenario/net_file.h"

#include <cstdint>
#include <string>
#include <vector>

namespace taebp {

struct DemandSpec {
  DemandOrigins origins = DemandOrigins::kFringe;
  // minor_roads, major_flow: the junctions whose minor / major approaches
  // are origins (the controlled ones).
  std::vector<std::string> junctions;
  double flow = 300;   // veh/h per origin edge
  double major_flow = 0;  // veh/h per major approach of `junctions`, on top
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
// The minor approaches of `junctions` (entries): car edges ending there
// with a car link that yields or stops (state not 'M') and no straight car
// link with the right of way (a major approach whose left turn yields),
// sorted; the exits are they and the fringe exits (side streets and the way
// out of the city).
FringeEdges FindMinorRoads(const net::NetFile& net, const std::vector<std::string>& junctions);
// The major approaches of `junctions` (entries): car edges ending there with
// a straight car link that has the right of way ('M'), sorted; the exits are
// those of FindMinorRoads.
FringeEdges FindMajorRoads(const net::NetFile& net, const std::vector<std::string>& junctions);

struct Trip {
  std::string id;
  double depart = 0;
  std::string from, to;
};
// The trips, sorted by departure time (ties: the origins' trips before the
// major roads', then by entry order). Throws std::invalid_argument when the
// network has no origins or destinations (no major approach, with major_flow).
std::vector<Trip> DemandTrips(const net::NetFile& net, const DemandSpec& spec);

// Writes the trips and their vType as a SUMO routes file; returns the count.
// Throws ConfigError (naming scenario.demand) on failure.
long WriteDemand(const net::NetFile& net, const DemandSpec& spec, const std::string& path);

}  // namespace taebp
