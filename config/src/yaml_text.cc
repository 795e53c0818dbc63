// The text of a YAML config before any key is read (yaml_text.h).
#include "yaml_text.h"

#include "taebp/config/config.h"

#include <yaml-cpp/depthguard.h>
#include <yaml-cpp/eventhandler.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <utility>
#include <vector>

namespace taebp {

std::string NotAFile(const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::file_status st = fs::status(path, ec);  // follows symbolic links
  switch (st.type()) {
    case fs::file_type::regular:
      return "";
    case fs::file_type::not_found: {
      std::error_code lec;
      if (fs::is_symlink(fs::symlink_status(path, lec)))
        return "a dangling symbolic link (to " + fs::read_symlink(path, lec).string() + ")";
      return "no such file";
    }
    case fs::file_type::directory:
      return "a folder, not a file";
    case fs::file_type::fifo:
      return "a FIFO (named pipe), not a file";
    case fs::file_type::socket:
      return "a socket, not a file";
    case fs::file_type::block:
    case fs::file_type::character:
      return "a device, not a file";
    default:
      return ec ? "cannot be looked at: " + ec.message() : "not a regular file";
  }
}

namespace config_text {
// The offset of the first byte of `s` that is not part of valid UTF-8
// (RFC 3629: no overlong forms, no surrogates, at most U+10FFFF), or npos.
std::size_t InvalidUtf8(const std::string& s) {
  std::size_t i = 0;
  while (i < s.size()) {
    const auto c = static_cast<unsigned char>(s[i]);
    std::size_t n = 0;
    unsigned min = 0;
    unsigned cp = 0;
    if (c < 0x80) { ++i; continue; }
    if (c >= 0xC2 && c <= 0xDF) { n = 1; cp = c & 0x1F; min = 0x80; }
    else if (c >= 0xE0 && c <= 0xEF) { n = 2; cp = c & 0x0F; min = 0x800; }
    else if (c >= 0xF0 && c <= 0xF4) { n = 3; cp = c & 0x07; min = 0x10000; }
    else return i;
    for (std::size_t k = 1; k <= n; ++k) {
      if (i + k >= s.size()) return i;
      const auto t = static_cast<unsigned char>(s[i + k]);
      if ((t & 0xC0) != 0x80) return i;
      cp = (cp << 6) | (t & 0x3F);
    }
    if (cp < min || cp > 0x10FFFF || (cp >= 0xD800 && cp <= 0xDFFF)) return i;
    i += n + 1;
  }
  return std::string::npos;
}

namespace {

// YAML is UTF-8 text (and every file taebp writes is JSON or YAML, which
// must be too): anything else is refused here, naming where.
void RequireUtf8(const std::string& text, const std::string& origin, bool lines) {
  const std::size_t bad = InvalidUtf8(text);
  if (bad == std::string::npos) return;
  std::string where = origin;
  if (lines) {
    const std::size_t line = 1 + static_cast<std::size_t>(
                                     std::count(text.begin(), text.begin() + bad, '\n'));
    where += ":" + std::to_string(line);
  }
  char byte[8];
  std::snprintf(byte, sizeof byte, "0x%02X", static_cast<unsigned char>(text[bad]));
  throw ConfigError(where + ": not UTF-8 text (byte " + byte +
                    "): save the file as UTF-8 (YAML is UTF-8)");
}

// The nodes of `node` with its aliases expanded (*a counts a's nodes again),
// counted up to `limit` (then `limit`): a few aliases nested ("alias bomb")
// name 10^8 nodes in a few lines, which reading or printing would walk.
std::size_t ExpandedNodes(const YAML::Node& node, std::size_t limit) {
  std::size_t n = 0;
  std::vector<YAML::Node> stack = {node};
  while (!stack.empty() && n < limit) {
    const YAML::Node x = stack.back();
    stack.pop_back();
    ++n;
    if (x.IsSequence()) {
      for (const YAML::Node& c : x) stack.push_back(c);
    } else if (x.IsMap()) {
      for (const auto& kv : x) {
        stack.push_back(kv.first);
        stack.push_back(kv.second);
      }
    }
  }
  return n;
}

// Counts a text's documents, nothing else.
struct NoEvents : YAML::EventHandler {
  void OnDocumentStart(const YAML::Mark&) override {}
  void OnDocumentEnd() override {}
  void OnNull(const YAML::Mark&, YAML::anchor_t) override {}
  void OnAlias(const YAML::Mark&, YAML::anchor_t) override {}
  void OnScalar(const YAML::Mark&, const std::string&, YAML::anchor_t, const std::string&) override {}
  void OnSequenceStart(const YAML::Mark&, const std::string&, YAML::anchor_t,
                       YAML::EmitterStyle::value) override {}
  void OnSequenceEnd() override {}
  void OnMapStart(const YAML::Mark&, const std::string&, YAML::anchor_t,
                  YAML::EmitterStyle::value) override {}
  void OnMapEnd() override {}
};

// The text's documents, counted up to one more than its "---" / "..." lines
// allow: yaml-cpp 0.7's parser does not advance past a stray flow indicator
// at the top level (a lone ',': YAML::LoadAll then returns empty documents
// without end, allocating until the memory is gone).
std::size_t DocumentCount(const std::string& text, const std::string& origin) {
  std::size_t markers = 0;
  std::istringstream lines(text);
  for (std::string line; std::getline(lines, line);)
    markers += line.rfind("---", 0) == 0 || line.rfind("...", 0) == 0;
  std::istringstream in(text);
  YAML::Parser parser(in);
  NoEvents events;
  std::size_t docs = 0;
  while (parser.HandleNextDocument(events))
    if (++docs > markers + 1)
      throw ConfigError(origin + ": not YAML that can be read: the parser stops advancing (a "
                        "stray ',' or other flow indicator outside [ ] or { }?)");
  return docs;
}

// A key given twice in any map of a text (yaml-cpp keeps both): a ConfigError
// at its line, before anything reads the map (a --set, or the sweep template
// dropping `sweep:`, would otherwise decide which of the two counts).
void RejectDuplicateKeys(const YAML::Node& root, const std::string& origin) {
  std::vector<std::pair<YAML::Node, std::string>> stack = {{root, ""}};
  while (!stack.empty()) {
    const auto [node, path] = stack.back();
    stack.pop_back();
    if (node.IsSequence()) {
      std::size_t i = 0;
      for (const YAML::Node& c : node) stack.emplace_back(c, path + "[" + std::to_string(i++) + "]");
    } else if (node.IsMap()) {
      std::map<std::string, int> seen;  // key -> line of its first occurrence
      for (const auto& kv : node) {
        if (!kv.first.IsScalar()) continue;  // the reader names a key that is no name
        const std::string key = (path.empty() ? "" : path + ".") + kv.first.Scalar();
        const auto [it, fresh] = seen.emplace(kv.first.Scalar(), kv.first.Mark().line + 1);
        if (!fresh)
          throw ConfigError(origin + ":" + std::to_string(kv.first.Mark().line + 1) + ": key '" +
                            key + "' is given twice (first on line " +
                            std::to_string(it->second) + ")");
        stack.emplace_back(kv.second, key);
      }
    }
  }
}

}  // namespace

// One YAML document, or a ConfigError naming `origin`: a second document
// (after a --- line) would be ignored by YAML::Load, and a run would use the
// first without a word.
YAML::Node OneDocument(const std::string& text, const std::string& origin) {
  const std::size_t docs = DocumentCount(text, origin);
  if (docs > 1)
    throw ConfigError(origin + ": holds " + std::to_string(docs) +
                      " YAML documents (separated by --- lines); a config is one document: "
                      "remove all but one");
  if (docs == 0) return YAML::Node();
  YAML::Node root = YAML::Load(text);
  if (ExpandedNodes(root, kMaxConfigNodes + 1) > kMaxConfigNodes)
    throw ConfigError(origin + ": more than " + std::to_string(kMaxConfigNodes) +
                      " YAML values once its aliases (*name) are expanded: a config that "
                      "large is an alias repeated inside an alias; write the values out");
  RejectDuplicateKeys(root, origin);
  return root;
}

YAML::Node ParseYaml(const std::string& text, const std::string& origin) {
  RequireUtf8(text, origin, true);
  try {
    return OneDocument(text, origin);
  } catch (const YAML::DeepRecursion& e) {
    throw ConfigError(origin + ":" + std::to_string(e.mark.line + 1) +
                      ": malformed YAML: nested more than " + std::to_string(e.depth() - 1) +
                      " levels deep");
  } catch (const YAML::ParserException& e) {
    throw ConfigError(origin + ":" + std::to_string(e.mark.line + 1) +
                      ": malformed YAML: " + e.msg);
  }
}

std::string ReadFileText(const std::string& path) {
  const std::string why = NotAFile(path);
  if (!why.empty()) throw ConfigError(path + ": " + why + " (a config file is expected)");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw ConfigError(path + ": cannot open the file (does it exist?)");
  std::ostringstream ss;
  ss << in.rdbuf();
  if (in.bad()) throw ConfigError(path + ": cannot read the file");
  return ss.str();
}

// A file whose YAML document is empty (no text, only comments, `---` or `~`):
// not a config. An explicit `{}` is.
YAML::Node ParseFileYaml(const std::string& path) {
  YAML::Node root = ParseYaml(ReadFileText(path), path);
  if (!root.IsDefined() || root.IsNull())
    throw ConfigError(path + ": the file is empty (no keys; `{}` means all defaults)");
  return root;
}

}  // namespace config_text
}  // namespace taebp
