// --set KEY=VALUE on a config's YAML before its keys are read: a map VALUE
// for a config section is merged into it key by key, anything else replaced;
// each written key remembers the --set that wrote it (for error messages).
#include "taebp/config/config.h"

#include "yaml_keys.h"
#include "yaml_text.h"

#include <yaml-cpp/depthguard.h>
#include <yaml-cpp/yaml.h>

#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace taebp::config_text {

namespace {

// The key paths of the config sections: nested structs, into which a map
// VALUE of --set is merged key by key (everything else is replaced).
class SectionCollector {
 public:
  SectionCollector(std::set<std::string>* out, std::string prefix)
      : out_(out), prefix_(std::move(prefix)) {}
  template <typename T>
  void Visit(const char* name, T* value) {
    Collect(Join(prefix_, name), value);
  }

 private:
  template <typename T>
  void Collect(const std::string& key, std::optional<T>*) {
    T inner{};
    Collect(key, &inner);
  }
  template <typename T>
  void Collect(const std::string& key, T* value) {
    if constexpr (HasSerialize<T>::value) {
      out_->insert(key);
      SectionCollector sub(out_, key);
      value->Serialize(&sub);
    }
  }
  template <typename T, typename = void>
  struct HasSerialize : std::false_type {};
  template <typename T>
  struct HasSerialize<T, std::void_t<decltype(std::declval<T&>().Serialize(
                             static_cast<SectionCollector*>(nullptr)))>> : std::true_type {};

  std::set<std::string>* out_;
  std::string prefix_;
};

const std::set<std::string>& ExperimentSections() {
  static const std::set<std::string> sections = [] {
    std::set<std::string> s;
    ExperimentConfig c;
    SectionCollector collector(&s, "");
    c.Serialize(&collector);
    return s;
  }();
  return sections;
}

// node[name] = value, except that a map value for a config section that is
// already a map is merged into it key by key (recursively for sub-sections).
// `written` gets the key path of every value set.
void Assign(YAML::Node node, const std::string& name, const std::string& key,
            const YAML::Node& value, std::vector<std::string>* written) {
  YAML::Node existing = node[name];
  if (value.IsMap() && ExperimentSections().count(key) && existing.IsDefined() &&
      existing.IsMap()) {
    for (const auto& kv : value) {
      if (!kv.first.IsScalar()) {  // the loader names it as an unknown key
        existing[kv.first] = kv.second;
        written->push_back(key);
        continue;
      }
      const std::string sub = kv.first.Scalar();
      Assign(existing, sub, key + "." + sub, kv.second, written);
    }
    return;
  }
  node[name] = value;
  written->push_back(key);
}

// Sets root[a][b][c] = value for key "a.b.c", creating maps on the way.
void SetPath(YAML::Node node, const std::vector<std::string>& parts, std::size_t i,
             const YAML::Node& value, const std::string& text, std::vector<std::string>* written) {
  if (!node.IsMap() && !node.IsNull())
    throw ConfigError("--set " + text + ": " +
                      (i == 0 ? std::string("the config is not a map of keys")
                              : "'" + parts[i - 1] + "' is not a map"));
  if (i + 1 == parts.size()) {
    std::string key;
    for (const std::string& p : parts) key = Join(key, p);
    Assign(node, parts[i], key, value, written);
    return;
  }
  YAML::Node child = node[parts[i]];
  if (!child.IsDefined() || child.IsNull()) {
    node[parts[i]] = YAML::Node(YAML::NodeType::Map);
    child = node[parts[i]];
  }
  SetPath(child, parts, i + 1, value, text, written);
}

}  // namespace

void ApplyOverride(YAML::Node& root, const std::string& text, Origins* origins) {
  if (InvalidUtf8(text) != std::string::npos)
    throw ConfigError("--set " + text + ": not UTF-8 text");
  const auto eq = text.find('=');
  if (eq == std::string::npos || eq == 0)
    throw ConfigError("--set " + text + ": expected KEY=VALUE (e.g. scenario.avs=4)");
  const std::string key = text.substr(0, eq);
  const std::string value_text = text.substr(eq + 1);
  std::vector<std::string> parts;
  std::stringstream ss(key);
  for (std::string part; std::getline(ss, part, '.');) {
    if (part.empty()) throw ConfigError("--set " + text + ": empty component in key '" + key + "'");
    parts.push_back(part);
  }
  YAML::Node value;
  try {
    value = value_text.empty() ? YAML::Node(YAML::NodeType::Null)
                               : OneDocument(value_text, "--set " + Clip(text) + ": the value");
  } catch (const YAML::DeepRecursion& e) {
    throw ConfigError("--set " + text + ": value is not valid YAML: nested more than " +
                      std::to_string(e.depth() - 1) + " levels deep");
  } catch (const YAML::ParserException& e) {
    throw ConfigError("--set " + text + ": value is not valid YAML: " + e.msg);
  }
  if (!root.IsDefined() || root.IsNull()) root = YAML::Node(YAML::NodeType::Map);
  std::vector<std::string> written;
  SetPath(root, parts, 0, value, text, &written);
  for (const std::string& k : written) origins->AddOverride(k, text);
}

}  // namespace taebp::config_text
