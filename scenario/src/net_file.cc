#include "taebp/scenario/net_file.h"

#include "taebp/config/config.h"  // NotAFile

#include <pugixml.hpp>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <stdexcept>

namespace taebp::net {
namespace {

std::vector<std::string> Words(const char* text) {
  std::vector<std::string> out;
  std::istringstream in(text ? text : "");
  for (std::string w; in >> w;) out.push_back(w);
  return out;
}

std::vector<Point> Shape(const char* text) {
  std::vector<Point> out;
  for (const std::string& w : Words(text)) {
    const auto comma = w.find(',');
    if (comma == std::string::npos) continue;
    out.push_back({std::atof(w.substr(0, comma).c_str()), std::atof(w.c_str() + comma + 1)});
  }
  return out;
}

std::string LaneId(const std::string& edge, int index) { return edge + "_" + std::to_string(index); }

const std::vector<int> kNoLinks;
const std::vector<std::string> kNoLanes;

// The <net> element of a SUMO network file, parsed into `doc`; a
// runtime_error naming the file when it is not one.
pugi::xml_node ReadNet(const std::string& path, pugi::xml_document* doc) {
  // Read by us, not by pugixml's load_file: a directory opens with fopen on
  // Linux and its "size" made pugixml ask for 2^63 bytes.
  if (const std::string why = NotAFile(path); !why.empty())
    throw std::runtime_error(path + ": " + why + " (a SUMO network file is expected)");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(path + ": cannot open the file (does it exist?)");
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw std::runtime_error(path + ": cannot read the file");
  const std::string content = text.str();
  const pugi::xml_parse_result parsed = doc->load_buffer(content.data(), content.size());
  if (!parsed) {
    throw std::runtime_error(path + ": not a readable XML file (" +
                             std::string(parsed.description()) + " at byte " +
                             std::to_string(parsed.offset) + ")");
  }
  const pugi::xml_node root = doc->child("net");
  if (!root)
    throw std::runtime_error(path + ": not a SUMO network (no <net> element; root is <" +
                             std::string(doc->first_child().name()) + ">)");
  return root;
}

// The edges and their lanes (SUMO's permissions read for passenger cars).
void ReadEdges(const pugi::xml_node& root, std::map<std::string, Edge>* edges,
               std::map<std::string, Lane>* lanes) {
  for (pugi::xml_node e : root.children("edge")) {
    Edge edge;
    edge.id = e.attribute("id").as_string();
    edge.from = e.attribute("from").as_string();
    edge.to = e.attribute("to").as_string();
    edge.function = e.attribute("function").as_string();
    edge.priority = e.attribute("priority").as_int(0);
    for (pugi::xml_node l : e.children("lane")) {
      Lane lane;
      lane.id = l.attribute("id").as_string();
      lane.edge = edge.id;
      lane.index = l.attribute("index").as_int(0);
      lane.length = l.attribute("length").as_double(0);
      lane.width = l.attribute("width").as_double(3.2);
      lane.speed = l.attribute("speed").as_double(13.89);
      lane.shape = Shape(l.attribute("shape").as_string());
      // SUMO's permissions: `allow` lists the classes (or "all"), else
      // `disallow` removes some; passenger cars are what the demand uses.
      auto has_passenger = [](const std::vector<std::string>& classes) {
        return std::find(classes.begin(), classes.end(), "passenger") != classes.end() ||
               std::find(classes.begin(), classes.end(), "all") != classes.end();
      };
      if (pugi::xml_attribute a = l.attribute("allow"))
        lane.passenger = has_passenger(Words(a.as_string()));
      else if (pugi::xml_attribute d = l.attribute("disallow"))
        lane.passenger = !has_passenger(Words(d.as_string()));
      if (static_cast<int>(edge.lanes.size()) <= lane.index) edge.lanes.resize(lane.index + 1);
      edge.lanes[lane.index] = lane.id;
      (*lanes)[lane.id] = lane;
    }
    (*edges)[edge.id] = edge;
  }
}

// A junction: its lanes and SUMO's foes matrix (request index by index).
Junction ReadJunction(const pugi::xml_node& j) {
  Junction junction;
  junction.id = j.attribute("id").as_string();
  junction.type = j.attribute("type").as_string();
  junction.pos = {j.attribute("x").as_double(), j.attribute("y").as_double()};
  junction.inc_lanes = Words(j.attribute("incLanes").as_string());
  junction.int_lanes = Words(j.attribute("intLanes").as_string());
  std::vector<std::string> foes;
  for (pugi::xml_node r : j.children("request")) {
    const int index = r.attribute("index").as_int(-1);
    if (index < 0) continue;
    if (static_cast<int>(foes.size()) <= index) foes.resize(index + 1);
    foes[index] = r.attribute("foes").as_string();
  }
  const int n = static_cast<int>(foes.size());
  junction.foes.assign(n, std::vector<bool>(n, false));
  for (int i = 0; i < n; ++i) {
    const std::string& bits = foes[i];
    const int len = static_cast<int>(bits.size());
    for (int k = 0; k < n && k < len; ++k) junction.foes[i][k] = bits[len - 1 - k] == '1';
  }
  return junction;
}

}  // namespace

NetFile NetFile::Load(const std::string& path) {
  pugi::xml_document doc;
  const pugi::xml_node root = ReadNet(path, &doc);
  NetFile net;
  net.path_ = path;
  if (const pugi::xml_node loc = root.child("location")) {
    const std::string b = loc.attribute("convBoundary").as_string();
    double v[4] = {0, 0, 0, 0};
    std::istringstream in(b);
    char comma;
    in >> v[0] >> comma >> v[1] >> comma >> v[2] >> comma >> v[3];
    net.boundary_min = {v[0], v[1]};
    net.boundary_max = {v[2], v[3]};
  }
  ReadEdges(root, &net.edges_, &net.lanes_);
  if (net.edges_.empty()) throw std::runtime_error(path + ": a SUMO network without edges");
  for (pugi::xml_node j : root.children("junction")) {
    Junction junction = ReadJunction(j);
    net.junctions_[junction.id] = std::move(junction);
  }
  // Connections: normal -> normal (the links) and internal -> next (the chains).
  std::map<std::string, std::pair<std::string, std::string>> internal_next;  // lane -> (via, to)
  struct Raw {
    std::string from_lane, to_lane, via;
    char dir, state;
  };
  std::vector<Raw> normal;
  for (pugi::xml_node c : root.children("connection")) {
    const std::string from = c.attribute("from").as_string();
    const std::string to = c.attribute("to").as_string();
    Raw raw{LaneId(from, c.attribute("fromLane").as_int(0)),
            LaneId(to, c.attribute("toLane").as_int(0)), c.attribute("via").as_string(),
            c.attribute("dir").as_string("s")[0], c.attribute("state").as_string("M")[0]};
    const Edge* fe = net.FindEdge(from);
    if (fe && fe->IsInternal()) {
      internal_next[raw.from_lane] = {raw.via, raw.to_lane};
    } else if (fe) {
      normal.push_back(raw);
    }
  }
  for (const Raw& raw : normal) {
    Link link;
    link.from_lane = raw.from_lane;
    link.to_lane = raw.to_lane;
    link.via = raw.via;
    link.dir = raw.dir;
    link.state = raw.state;
    const Lane* from = net.FindLane(raw.from_lane);
    const Edge* edge = from ? net.FindEdge(from->edge) : nullptr;
    link.junction = edge ? edge->to : "";
    for (std::string lane = raw.via; !lane.empty() && link.internal.size() < 16;) {
      link.internal.push_back(lane);
      const auto it = internal_next.find(lane);
      if (it == internal_next.end()) break;
      lane = it->second.first;  // the next internal lane, or "" when the next is the to-lane
    }
    // The request index is the position of the link's internal lane in the
    // junction's intLanes. A turn that waits at an internal junction (a left
    // turn yielding to the opposite straight) is listed there by its second
    // internal lane, not by `via`: look along the whole way.
    auto jt = net.junctions_.find(link.junction);
    if (jt != net.junctions_.end()) {
      const auto& il = jt->second.int_lanes;
      for (std::size_t k = 0; k < il.size() && link.index < 0; ++k)
        for (const std::string& lane : link.internal)
          if (il[k] == lane) link.index = static_cast<int>(k);
    }
    const int id = static_cast<int>(net.links_.size());
    net.links_.push_back(link);
    net.links_from_[link.from_lane].push_back(id);
    net.predecessors_[link.to_lane].push_back(link.from_lane);
    if (jt != net.junctions_.end() && link.index >= 0) {
      auto& links = jt->second.links;
      if (static_cast<int>(links.size()) <= link.index) links.resize(link.index + 1, -1);
      links[link.index] = id;
    }
  }
  return net;
}

const Junction* NetFile::FindJunction(const std::string& id) const {
  const auto it = junctions_.find(id);
  return it == junctions_.end() ? nullptr : &it->second;
}
const Edge* NetFile::FindEdge(const std::string& id) const {
  const auto it = edges_.find(id);
  return it == edges_.end() ? nullptr : &it->second;
}
bool NetFile::IsCarEdge(const Edge& e) const {
  if (!e.function.empty()) return false;
  for (const std::string& lane : e.lanes) {
    const Lane* l = FindLane(lane);
    if (l && l->passenger) return true;
  }
  return false;
}
std::map<std::string, std::set<std::string>> NetFile::CarNeighbours() const {
  std::map<std::string, std::set<std::string>> neighbours;
  for (const auto& [id, e] : edges_) {
    if (!IsCarEdge(e) || e.from == e.to) continue;
    neighbours[e.from].insert(e.to);
    neighbours[e.to].insert(e.from);
  }
  return neighbours;
}

std::vector<std::string> NetFile::FringeJunctions() const {
  const std::map<std::string, std::set<std::string>> neighbours = CarNeighbours();
  std::vector<std::string> out;
  for (const auto& [id, j] : junctions_) {
    const auto it = neighbours.find(id);
    bool one = it != neighbours.end() && it->second.size() == 1;
    // A loop's far end (the figure-8's E and W) has one neighbour too, but
    // traffic goes on through it; at a dead end it can only turn around.
    for (int l : j.links)
      if (l >= 0 && links_[static_cast<std::size_t>(l)].dir != 't') one = false;
    if (one || j.type == "dead_end") out.push_back(id);
  }
  return out;
}
const Lane* NetFile::FindLane(const std::string& id) const {
  const auto it = lanes_.find(id);
  return it == lanes_.end() ? nullptr : &it->second;
}
const std::vector<int>& NetFile::LinksFrom(const std::string& lane) const {
  const auto it = links_from_.find(lane);
  return it == links_from_.end() ? kNoLinks : it->second;
}
const std::vector<std::string>& NetFile::Predecessors(const std::string& lane) const {
  const auto it = predecessors_.find(lane);
  return it == predecessors_.end() ? kNoLanes : it->second;
}
std::string NetFile::EdgeEnd(const std::string& edge) const {
  const Edge* e = FindEdge(edge);
  return e ? e->to : "";
}

}  // namespace taebp::net
