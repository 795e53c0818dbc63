// The static topology of a SUMO network, read from its .net.xml: edges and
// lanes, junctions with their SUMO type, their connections (movements: from
// lane -> via internal lane -> to lane, direction, link state) and SUMO's own
// conflict matrix (each junction's `<request foes=...>`, the relation SUMO's
// junction logic uses: crossing and merging movements). SUMO-free (pugixml);
// tests cross-check it against libsumo's Lane::getInternalFoes.
#pragma once

#include <map>
#include <set>
#include <string>
#include <vector>

namespace taebp::net {

struct Point {
  double x = 0, y = 0;
};

struct Lane {
  std::string id;
  std::string edge;
  int index = 0;
  double length = 0, width = 3.2, speed = 13.89;
  std::vector<Point> shape;
  bool passenger = true;     // SUMO's allow/disallow let class "passenger" drive here
};

struct Edge {
  std::string id;
  std::string from, to;      // junction ids (empty for internal edges)
  std::string function;      // "" (normal), "internal", "walkingarea", ...
  int priority = 0;
  std::vector<std::string> lanes;  // lane ids by index
  bool IsInternal() const { return function == "internal"; }
};

// One link of a junction: from a normal lane, through internal lanes, to a
// normal lane.
struct Link {
  std::string junction;
  int index = -1;            // SUMO's request index at the junction
  std::string from_lane, to_lane;
  std::string via;           // first internal lane ("" without internal links)
  std::vector<std::string> internal;  // every internal lane on the way, in order
  char dir = 's';            // s, l, r, t, L, R (partly left/right)
  char state = 'M';          // M major, m minor, = equal, s stop, w allway stop, ...
};

struct Junction {
  std::string id;
  std::string type;          // SUMO type: allway_stop, priority_stop, priority, ...
  Point pos;
  std::vector<std::string> inc_lanes, int_lanes;
  std::vector<int> links;    // indices into NetFile::links(), ordered by request index
  // foes[i][j]: link i and link j conflict (SUMO's foes bit), by request index.
  std::vector<std::vector<bool>> foes;
};

class NetFile {
 public:
  // Reads a .net.xml. Throws std::runtime_error naming the file when it is
  // missing, not XML, or not a SUMO network.
  static NetFile Load(const std::string& path);

  const std::string& path() const { return path_; }
  const std::map<std::string, Junction>& junctions() const { return junctions_; }
  const std::map<std::string, Edge>& edges() const { return edges_; }
  const std::vector<Link>& links() const { return links_; }

  const Junction* FindJunction(const std::string& id) const;
  const Edge* FindEdge(const std::string& id) const;
  const Lane* FindLane(const std::string& id) const;
  // The links leaving a normal lane (indices into links()).
  const std::vector<int>& LinksFrom(const std::string& lane) const;
  // Normal lanes with a link into `lane` (its predecessors).
  const std::vector<std::string>& Predecessors(const std::string& lane) const;
  // A normal edge cars may use: one of its lanes lets class passenger drive.
  bool IsCarEdge(const Edge& e) const;
  // Each junction's neighbours for cars: the other junctions its normal car
  // edges lead to or come from (a junction without a car edge is absent).
  std::map<std::string, std::set<std::string>> CarNeighbours() const;
  // The network's fringe for cars: the junctions whose car edges (in or out)
  // lead to exactly one other junction and where a vehicle can only turn
  // around (a dead end by topology, whatever type netgenerate or netconvert
  // gave it: netgenerate types a grid's dead ends with its turnarounds
  // --default-junction-type), and those typed dead_end. Sorted.
  std::vector<std::string> FringeJunctions() const;
  // The junction at the end of a normal edge ("" if unknown).
  std::string EdgeEnd(const std::string& edge) const;
  // The network's bounding box (convBoundary).
  Point boundary_min, boundary_max;

 private:
  std::string path_;
  std::map<std::string, Junction> junctions_;
  std::map<std::string, Edge> edges_;
  std::map<std::string, Lane> lanes_;
  std::vector<Link> links_;
  std::map<std::string, std::vector<int>> links_from_;
  std::map<std::string, std::vector<std::string>> predecessors_;
};

}  // namespace taebp::net
