// The one config loader's reading of keys: every config struct loaded through
// the structs' Serialize() schema, unknown keys rejected, errors naming the
// key, the value and where it came from. The loader's other parts: yaml_text.cc
// (the text), config_overrides.cc (--set), config_json.cc (saving).
#include "taebp/config/config.h"
#include "taebp/config/reference.h"
#include "taebp/base/number_text.h"
#include "yaml_keys.h"
#include "yaml_text.h"

#include <nlohmann/json.hpp>
#include <yaml-cpp/depthguard.h>
#include <yaml-cpp/eventhandler.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <set>
#include <sstream>
#include <type_traits>

namespace taebp {

using config_text::ApplyOverride;
using config_text::Clip;
using config_text::InvalidUtf8;
using config_text::IsOptional;
using config_text::IsVector;
using config_text::Join;
using config_text::Origins;
using config_text::Show;
using config_text::OneDocument;
using config_text::ParseFileYaml;
using config_text::ParseYaml;
using config_text::ReadFileText;

namespace {


// T::ReadNull(): what `~` means for a section that used to be optional.
template <typename T, typename = void>
struct HasReadNull : std::false_type {};
template <typename T>
struct HasReadNull<T, std::void_t<decltype(std::declval<T&>().ReadNull())>> : std::true_type {};

class YamlReader {
 public:
  YamlReader(const YAML::Node& node, std::string prefix, const Origins* origins,
             bool require_all)
      : node_(node), prefix_(std::move(prefix)), origins_(origins), require_all_(require_all) {}

  template <typename T>
  void Visit(const char* name, T* value) {
    visited_.insert(name);
    const YAML::Node child = node_[name];
    const std::string key = Join(prefix_, name);
    if (!child.IsDefined()) {
      if (require_all_) Fail(key, node_, "missing required key '" + key + "'");
      return;
    }
    Read(child, key, value);
  }

  // Any key in the map that the schema did not visit is an error, and so is a
  // key given twice (yaml-cpp keeps both and node[name] would silently read the
  // first).
  void RejectUnknown() const {
    RejectDuplicates(node_, prefix_);
    for (const auto& kv : node_) {
      const std::string name = kv.first.as<std::string>();
      if (!visited_.count(name)) {
        std::string known;
        for (const auto& v : visited_) known += (known.empty() ? "" : ", ") + v;
        Fail(Join(prefix_, name), kv.first,
             "unknown key '" + Join(prefix_, name) + "' (known keys here: " + known + ")" +
                 DeeperKeys(name));
      }
    }
  }

 private:
  // "; did you mean model.experience.design?": the keys of the schema under
  // this section, deeper down, whose last part is `name` (a key written one
  // level too high, e.g. model.design for model.experience.design).
  std::string DeeperKeys(const std::string& name) const {
    const std::string under = prefix_.empty() ? "" : prefix_ + ".";
    const std::string leaf = "." + name;
    std::string out;
    for (const KeyDoc& d : ConfigKeyDocs()) {
      const std::string k = d.key;
      if (k.size() > under.size() + leaf.size() && k.compare(0, under.size(), under) == 0 &&
          k.compare(k.size() - leaf.size(), leaf.size(), leaf) == 0)
        out += (out.empty() ? "; did you mean " : " or ") + k;
    }
    return out.empty() ? out : out + "?";
  }

  [[noreturn]] void Fail(const std::string& key, const YAML::Node& node,
                         const std::string& what) const {
    throw ConfigError(origins_->Locate(key, node) + ": " + what);
  }

  void RejectDuplicates(const YAML::Node& map, const std::string& prefix) const {
    std::map<std::string, int> seen;  // key -> line of its first occurrence
    for (const auto& kv : map) {
      if (!kv.first.IsScalar())  // `? [a, b]: 1` or `? : 1`
        Fail(prefix, kv.first,
             "a key " + std::string(prefix.empty() ? "" : "in '" + prefix + "' ") +
                 "must be a name, got " + Show(kv.first));
      const std::string name = kv.first.as<std::string>();
      const auto [it, fresh] = seen.emplace(name, kv.first.Mark().line + 1);
      if (!fresh)
        Fail(Join(prefix, name), kv.first,
             "key '" + Join(prefix, name) + "' is given twice (first on line " +
                 std::to_string(it->second) + ")");
    }
  }

  void ReadScalarCheck(const YAML::Node& node, const std::string& key, const char* expected) {
    if (!node.IsScalar())
      Fail(key, node, "key '" + key + "' expects " + expected + ", got " + Show(node));
  }

  // A number is written as one: a quoted scalar ("0.7", as JSON writes a
  // string) is text, refused with the fix, in a YAML file and a Python dict alike.
  void RejectQuoted(const YAML::Node& node, const std::string& key, const char* expected) {
    if (node.Tag() == "!")
      Fail(key, node, "key '" + key + "' expects " + expected + ", got the string " +
                          Show(node) + " (quoted: write the number without quotes)");
  }
  // An integer's text: an integral number written with a decimal point
  // (8.0, as a float of Python or pandas prints) is that integer; any other
  // fraction stays, to be refused.
  static std::string WholeNumberText(const std::string& s) {
    const std::size_t dot = s.find('.');
    if (dot == std::string::npos || dot == 0 || dot + 1 == s.size() ||
        s.find_first_not_of('0', dot + 1) != std::string::npos ||
        s.find_first_not_of("+-0123456789") != dot)
      return s;
    return s.substr(0, dot);
  }
  void Read(const YAML::Node& node, const std::string& key, int* value) {
    ReadScalarCheck(node, key, "an integer");
    RejectQuoted(node, key, "an integer");
    // Decimal digits only: YAML 1.1 (yaml-cpp) reads 010 as octal 8 and 0x10
    // as 16, while the tables would show the text (010): refused, not guessed.
    const std::string s = WholeNumberText(node.Scalar());
    const std::size_t digits = s.find_first_not_of("+-") == 1 ? 1 : 0;
    const bool decimal = s.size() > digits &&
                         s.find_first_not_of("0123456789", digits) == std::string::npos;
    if (decimal && s.size() > digits + 1 && s[digits] == '0')
      Fail(key, node, "key '" + key + "' = " + Show(node) +
                          ": an integer with a leading zero (YAML 1.1 reads it as octal); "
                          "write it without the zero");
    long long v = 0;
    if (decimal && s.size() - digits > 10)
      v = std::numeric_limits<long long>::max();  // out of range below, not "not an integer"
    else if (!decimal || !YAML::convert<long long>::decode(YAML::Node(s), v))
      Fail(key, node, "key '" + key + "' expects an integer (decimal digits), got " + Show(node));
    if (v < std::numeric_limits<int>::min() || v > std::numeric_limits<int>::max())
      Fail(key, node, "key '" + key + "' = " + Show(node) + " is out of range (at most " +
                          std::to_string(std::numeric_limits<int>::max()) + ")");
    *value = static_cast<int>(v);
  }
  void Read(const YAML::Node& node, const std::string& key, std::uint64_t* value) {
    ReadScalarCheck(node, key, "a non-negative integer");
    RejectQuoted(node, key, "a non-negative integer");
    const std::string s = WholeNumberText(node.Scalar());
    if (s.empty() || s.find_first_not_of("0123456789") != std::string::npos)
      Fail(key, node, "key '" + key + "' expects a non-negative integer, got " + Show(node));
    if (s.size() > 1 && s[0] == '0')  // as for int: YAML 1.1 would read 010 as octal 8
      Fail(key, node, "key '" + key + "' = " + Show(node) +
                          ": an integer with a leading zero (YAML 1.1 reads it as octal); "
                          "write it without the zero");
    try {
      *value = std::stoull(s);
    } catch (const std::exception&) {
      Fail(key, node, "key '" + key + "' expects a non-negative integer, got " + Show(node));
    }
  }
  void Read(const YAML::Node& node, const std::string& key, double* value) {
    ReadScalarCheck(node, key, "a number");
    RejectQuoted(node, key, "a number");
    double v = 0;
    const std::string& s = node.Scalar();
    bool is_bool_word = s == "true" || s == "false" || s == "yes" || s == "no";
    if (is_bool_word || !YAML::convert<double>::decode(node, v))
      Fail(key, node, "key '" + key + "' expects a number, got " + Show(node));
    // Infinite and NaN values mean nothing in a config, and JSON (summary.json,
    // sweep.json) cannot carry them.
    if (!std::isfinite(v))
      Fail(key, node, "key '" + key + "' expects a finite number, got " + Show(node));
    *value = v;
  }
  void Read(const YAML::Node& node, const std::string& key, bool* value) {
    ReadScalarCheck(node, key, "true or false");
    if (!YAML::convert<bool>::decode(node, *value))
      Fail(key, node, "key '" + key + "' expects true or false, got " + Show(node));
  }
  void Read(const YAML::Node& node, const std::string& key, std::string* value) {
    ReadScalarCheck(node, key, "a string");
    *value = node.Scalar();
  }
  // An option with a fixed set of values (enums.h): its name, checked here once.
  template <typename E, std::enable_if_t<HasEnumNames<E>::value, int> = 0>
  void Read(const YAML::Node& node, const std::string& key, E* value) {
    if (!node.IsScalar() || !ParseEnum(node.Scalar(), value))
      Fail(key, node, key + " = " + Show(node) + " is not one of: " + EnumChoices<E>());
  }
  void Read(const YAML::Node& node, const std::string& key, TrustSpec* value) {
    if (node.IsScalar()) {
      double v = 0;
      Read(node, key, &v);
      *value = TrustSpec::Fixed(v);
      return;
    }
    if (!node.IsMap())
      Fail(key, node, "key '" + key + "' expects a number or a distribution map, got " + Show(node));
    TrustSpec t;
    const YAML::Node dist = node["dist"];
    if (!dist.IsDefined())
      Fail(key, node, "key '" + key + ".dist' is missing (uniform, beta or discrete)");
    RejectDuplicates(node, key);
    // A fixed trust is a number (trust: 0.6), not a map.
    if (!dist.IsScalar() || !ParseEnum(dist.Scalar(), &t.dist) || t.IsFixed())
      Fail(key + ".dist", dist, key + ".dist = " + Show(dist) +
                                    " is not one of: uniform, beta, discrete");
    const std::vector<std::string> allowed = TrustDistKeys(t.dist);
    for (const auto& kv : node) {
      const std::string name = kv.first.as<std::string>();
      if (name == "dist") continue;
      if (std::find(allowed.begin(), allowed.end(), name) == allowed.end()) {
        std::string known;
        for (const auto& a : allowed) known += (known.empty() ? "" : ", ") + a;
        Fail(key + "." + name, kv.first, "unknown key '" + key + "." + name + "' for dist " +
                                             EnumName(t.dist) + " (known keys: dist, " + known +
                                             ")");
      }
    }
    auto need = [&](const char* name) {
      const YAML::Node n = node[name];
      if (!n.IsDefined())
        Fail(key, node, "key '" + key + "." + name + "' is missing for dist " +
                            EnumName(t.dist));
      return n;
    };
    if (t.dist == TrustDist::kUniform) {
      Read(need("low"), key + ".low", &t.low);
      Read(need("high"), key + ".high", &t.high);
    } else if (t.dist == TrustDist::kBeta) {
      Read(need("alpha"), key + ".alpha", &t.alpha);
      Read(need("beta"), key + ".beta", &t.beta);
    } else {
      Read(need("values"), key + ".values", &t.values);
      if (node["weights"].IsDefined()) Read(node["weights"], key + ".weights", &t.weights);
    }
    *value = t;
  }
  void Read(const YAML::Node& node, const std::string& key,
            std::vector<std::pair<std::string, std::vector<std::string>>>* value) {
    if (!node.IsMap())
      Fail(key, node, "key '" + key + "' expects a map of KEY: [values...], got " + Show(node));
    RejectDuplicates(node, key);
    value->clear();
    for (const auto& kv : node) {
      const std::string name = kv.first.as<std::string>();
      const std::string sub = key + "." + name;
      if (!kv.second.IsSequence())
        Fail(sub, kv.second, "key '" + sub + "' expects a list of values, got " + Show(kv.second));
      std::vector<std::string> values;
      for (const auto& v : kv.second) {
        YAML::Emitter e;
        e << YAML::Flow << v;
        values.push_back(e.c_str());
      }
      value->emplace_back(name, std::move(values));
    }
  }
  template <typename T>
  void Read(const YAML::Node& node, const std::string& key, std::optional<T>* value) {
    if (node.IsNull()) {
      value->reset();
      return;
    }
    T v{};
    Read(node, key, &v);
    *value = v;
  }
  template <typename T>
  void Read(const YAML::Node& node, const std::string& key, std::vector<T>* value) {
    if (!node.IsSequence())
      Fail(key, node, "key '" + key + "' expects a list, got " + Show(node));
    value->clear();
    for (std::size_t i = 0; i < node.size(); ++i) {
      T v{};
      Read(node[i], key + "[" + std::to_string(i) + "]", &v);
      value->push_back(std::move(v));
    }
  }
  // Nested config struct.
  template <typename T, typename = decltype(std::declval<T&>().Serialize(
                            static_cast<YamlReader*>(nullptr)))>
  void Read(const YAML::Node& node, const std::string& key, T* value) {
    // A section that was once optional reads `~` (unset) as it meant then
    // (ReadNull: e.g. scenario.major_road, off), so old result folders rerun.
    if constexpr (HasReadNull<T>::value) {
      if (node.IsNull()) {
        value->ReadNull();
        return;
      }
    }
    if (!node.IsMap()) Fail(key, node, "key '" + key + "' expects a map, got " + Show(node));
    YamlReader sub(node, key, origins_, require_all_);
    value->Serialize(&sub);
    sub.RejectUnknown();
  }

  YAML::Node node_;
  std::string prefix_;
  const Origins* origins_;
  bool require_all_;
  std::set<std::string> visited_;
};




template <typename T>
T ReadRoot(const YAML::Node& root, const Origins& origins, const std::string& origin,
           bool require_all) {
  T config;
  if (!root.IsDefined() || root.IsNull()) {
    if (require_all) throw ConfigError(origin + ": the file is empty");
    return config;
  }
  if (!root.IsMap()) throw ConfigError(origin + ": expected a map of keys at the top level");
  YamlReader reader(root, "", &origins, require_all);
  config.Serialize(&reader);
  reader.RejectUnknown();
  return config;
}

}  // namespace

static ExperimentConfig ParseExperimentRoot(YAML::Node root, Origins origins,
                                            const std::string& origin,
                                            const std::vector<std::string>& overrides) {
  for (const std::string& o : overrides) ApplyOverride(root, o, &origins);
  ExperimentConfig config = ReadRoot<ExperimentConfig>(root, origins, origin, false);
  std::string why;
  if (!config.IsValid(&why)) {
    const std::string key = why.substr(0, why.find_first_of(" :"));
    throw ConfigError(origins.For(key) + ": " + why);
  }
  return config;
}

std::string ReadConfigFile(const std::string& path) { return ReadFileText(path); }


struct ExperimentTemplate::Impl {
  std::string text;
  YAML::Node root;  // `base` applied, without the sweep: section
  std::string origin;
  std::vector<std::string> base;
  Origins origins{""};
};

ExperimentTemplate::ExperimentTemplate(const std::string& yaml_text, const std::string& origin,
                                       const std::vector<std::string>& base) {
  auto impl = std::make_shared<Impl>();
  impl->text = yaml_text;
  impl->root = ParseYaml(yaml_text, origin);
  impl->origin = origin;
  impl->base = base;
  impl->origins = Origins(origin);
  for (const std::string& o : base) ApplyOverride(impl->root, o, &impl->origins);
  // The sweep: section is the same for every point: not copied per Load
  // (a grid of N values would make N loads cost N^2).
  if (impl->root.IsMap()) impl->root.remove("sweep");
  impl->origins.Forget("sweep");
  impl_ = std::move(impl);
}

ExperimentTemplate::~ExperimentTemplate() = default;

ExperimentConfig ExperimentTemplate::Load(const std::vector<std::string>& overrides) const {
  try {
    return ParseExperimentRoot(YAML::Clone(impl_->root), impl_->origins, impl_->origin, overrides);
  } catch (const ConfigError&) {
    // YAML::Clone drops the line numbers: the message from a fresh parse.
    std::vector<std::string> all = impl_->base;
    all.push_back("sweep=~");
    all.insert(all.end(), overrides.begin(), overrides.end());
    return ParseExperimentRoot(ParseYaml(impl_->text, impl_->origin), Origins(impl_->origin),
                               impl_->origin, all);
  }
}

ExperimentConfig ParseExperimentConfig(const std::string& yaml_text, const std::string& origin,
                                       const std::vector<std::string>& overrides) {
  return ParseExperimentRoot(ParseYaml(yaml_text, origin), Origins(origin), origin, overrides);
}

ExperimentConfig LoadExperimentConfig(const std::string& path,
                                      const std::vector<std::string>& overrides) {
  return ParseExperimentRoot(ParseFileYaml(path), Origins(path), path, overrides);
}


ProblemConfig LoadProblemConfig(const std::string& path) {
  YAML::Node root = ParseFileYaml(path);
  Origins origins(path);
  return ReadRoot<ProblemConfig>(root, origins, path, true);
}

ProblemConfig ParseProblemConfig(const std::string& yaml_text, const std::string& origin) {
  YAML::Node root = ParseYaml(yaml_text, origin);
  if (!root.IsDefined() || root.IsNull())
    throw ConfigError(origin + ": the problem is empty (no keys)");
  Origins origins(origin);
  return ReadRoot<ProblemConfig>(root, origins, origin, true);
}


}  // namespace taebp
