// Networks built by the tests with SUMO's own tools: netconvert from small
// plain-XML node/edge files, and netgenerate grids.
#pragma once

#include "test_support.h"

#include <gtest/gtest.h>

#include <sys/wait.h>

#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>

namespace taebp::test {

// Runs a shell command with its output in `log`; returns the exit status.
inline int Shell(const std::string& command, const std::string& log) {
  const int rc = std::system((command + " >" + log + " 2>&1").c_str());
  return rc == -1 ? -1 : WEXITSTATUS(rc);
}

inline std::string ReadText(const std::string& path) {
  std::ifstream in(path);
  std::ostringstream os;
  os << in.rdbuf();
  return os.str();
}

// netconvert of <nodes>/<edges> bodies into dir/name.net.xml (no U-turns).
inline std::string Netconvert(const TempDir& dir, const std::string& name,
                              const std::string& nodes, const std::string& edges,
                              const std::string& extra = "") {
  const std::string nod = dir.Write(name + ".nod.xml", "<nodes>\n" + nodes + "</nodes>\n");
  const std::string edg = dir.Write(name + ".edg.xml", "<edges>\n" + edges + "</edges>\n");
  const std::string net = (dir.path() / (name + ".net.xml")).string();
  const std::string log = (dir.path() / (name + ".log")).string();
  const int rc = Shell("netconvert --node-files " + nod + " --edge-files " + edg +
                           " --no-turnarounds true --xml-validation never " + extra +
                           " --output-file " + net,
                       log);
  EXPECT_EQ(rc, 0) << ReadText(log);
  return net;
}

// netgenerate --grid with n x n junctions of `type`, no U-turns.
inline std::string Netgenerate(const TempDir& dir, const std::string& name, int n,
                               const std::string& type, double attach_length = 0) {
  const std::string net = (dir.path() / (name + ".net.xml")).string();
  const std::string log = (dir.path() / (name + ".log")).string();
  std::string cmd = "netgenerate --grid --grid.number " + std::to_string(n) +
                    " --default-junction-type " + type +
                    " --no-turnarounds true --tls.guess false --xml-validation never";
  if (attach_length > 0) cmd += " --grid.attach-length " + std::to_string(attach_length);
  const int rc = Shell(cmd + " --output-file " + net, log);
  EXPECT_EQ(rc, 0) << ReadText(log);
  return net;
}

// A 4-way crossing C with 100 m arms N, E, S, W (single lanes, both ways);
// the east-west road has priority 2, the north-south one 1.
inline std::string FourWay(const TempDir& dir, const std::string& name, const std::string& type) {
  return Netconvert(
      dir, name,
      "  <node id=\"C\" x=\"0\" y=\"0\" type=\"" + type + "\"/>\n"
      "  <node id=\"N\" x=\"0\" y=\"100\" type=\"dead_end\"/>\n"
      "  <node id=\"S\" x=\"0\" y=\"-100\" type=\"dead_end\"/>\n"
      "  <node id=\"E\" x=\"100\" y=\"0\" type=\"dead_end\"/>\n"
      "  <node id=\"W\" x=\"-100\" y=\"0\" type=\"dead_end\"/>\n",
      "  <edge id=\"WC\" from=\"W\" to=\"C\" priority=\"2\" numLanes=\"1\"/>\n"
      "  <edge id=\"CW\" from=\"C\" to=\"W\" priority=\"2\" numLanes=\"1\"/>\n"
      "  <edge id=\"EC\" from=\"E\" to=\"C\" priority=\"2\" numLanes=\"1\"/>\n"
      "  <edge id=\"CE\" from=\"C\" to=\"E\" priority=\"2\" numLanes=\"1\"/>\n"
      "  <edge id=\"NC\" from=\"N\" to=\"C\" priority=\"1\" numLanes=\"1\"/>\n"
      "  <edge id=\"CN\" from=\"C\" to=\"N\" priority=\"1\" numLanes=\"1\"/>\n"
      "  <edge id=\"SC\" from=\"S\" to=\"C\" priority=\"1\" numLanes=\"1\"/>\n"
      "  <edge id=\"CS\" from=\"C\" to=\"S\" priority=\"1\" numLanes=\"1\"/>\n");
}

// A T: the east-west road (priority 2) with a stem to the south (priority 1).
inline std::string TJunction(const TempDir& dir, const std::string& name, const std::string& type,
                             const std::string& extra = "") {
  return Netconvert(
      dir, name,
      "  <node id=\"C\" x=\"0\" y=\"0\" type=\"" + type + "\"/>\n"
      "  <node id=\"S\" x=\"0\" y=\"-100\" type=\"dead_end\"/>\n"
      "  <node id=\"E\" x=\"100\" y=\"0\" type=\"dead_end\"/>\n"
      "  <node id=\"W\" x=\"-100\" y=\"0\" type=\"dead_end\"/>\n",
      "  <edge id=\"WC\" from=\"W\" to=\"C\" priority=\"2\" numLanes=\"1\"/>\n"
      "  <edge id=\"CW\" from=\"C\" to=\"W\" priority=\"2\" numLanes=\"1\"/>\n"
      "  <edge id=\"EC\" from=\"E\" to=\"C\" priority=\"2\" numLanes=\"1\"/>\n"
      "  <edge id=\"CE\" from=\"C\" to=\"E\" priority=\"2\" numLanes=\"1\"/>\n"
      "  <edge id=\"SC\" from=\"S\" to=\"C\" priority=\"1\" numLanes=\"1\"/>\n"
      "  <edge id=\"CS\" from=\"C\" to=\"S\" priority=\"1\" numLanes=\"1\"/>\n",
      extra);
}

}  // namespace taebp::test
