// Configs as JSON (ToJson: summary.json's config, provenance) and as YAML
// (ToYaml: the config.yaml a result folder reruns itself with), written
// through the structs' Serialize() schema; a YAML value as JSON.
#include "taebp/config/config.h"
#include "taebp/base/number_text.h"

#include "yaml_keys.h"
#include "yaml_text.h"

#include <nlohmann/json.hpp>
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

namespace taebp {
namespace config_text {

nlohmann::ordered_json YamlToJson(const YAML::Node& node) {
  if (node.IsMap()) {
    nlohmann::ordered_json j = nlohmann::ordered_json::object();
    for (const auto& kv : node)
      j[kv.first.IsScalar() ? kv.first.Scalar() : Show(kv.first)] = YamlToJson(kv.second);
    return j;
  }
  if (node.IsSequence()) {
    nlohmann::ordered_json j = nlohmann::ordered_json::array();
    for (const auto& v : node) j.push_back(YamlToJson(v));
    return j;
  }
  if (!node.IsDefined() || node.IsNull()) return nullptr;
  const std::string& s = node.Scalar();
  long long i = 0;
  double d = 0;
  bool b = false;
  if (node.Tag() != "!" && YAML::convert<long long>::decode(node, i) &&
      s.find_first_of(".eE") == std::string::npos)
    return i;
  if (node.Tag() != "!" && YAML::convert<double>::decode(node, d)) return d;
  if (node.Tag() != "!" && YAML::convert<bool>::decode(node, b)) return b;
  return s;
}

}  // namespace config_text

using config_text::IsOptional;
using config_text::IsVector;
using config_text::YamlToJson;

namespace {

// Writes a struct through the same schema into nlohmann::ordered_json.

class JsonWriter {
 public:
  explicit JsonWriter(nlohmann::ordered_json* out) : out_(out) {}
  template <typename T>
  void Visit(const char* name, T* value) {
    Write(&(*out_)[name], *value);
  }

 private:
  static void Write(nlohmann::ordered_json* j, const TrustSpec& t) {
    if (t.IsFixed()) {
      *j = t.value;
      return;
    }
    *j = nlohmann::ordered_json::object();
    (*j)["dist"] = EnumName(t.dist);
    if (t.dist == TrustDist::kUniform) {
      (*j)["low"] = t.low;
      (*j)["high"] = t.high;
    } else if (t.dist == TrustDist::kBeta) {
      (*j)["alpha"] = t.alpha;
      (*j)["beta"] = t.beta;
    } else {
      (*j)["values"] = t.values;
      if (!t.weights.empty()) (*j)["weights"] = t.weights;
    }
  }
  static void Write(nlohmann::ordered_json* j,
                    const std::vector<std::pair<std::string, std::vector<std::string>>>& grid) {
    *j = nlohmann::ordered_json::object();
    for (const auto& [key, values] : grid) {
      nlohmann::ordered_json arr = nlohmann::ordered_json::array();
      for (const std::string& v : values) arr.push_back(YamlToJson(YAML::Load(v)));
      (*j)[key] = arr;
    }
  }
  template <typename T>
  static void Write(nlohmann::ordered_json* j, const T& v) {
    if constexpr (IsOptional<T>::value) {
      if (v) Write(j, *v); else *j = nullptr;
    } else if constexpr (IsVector<T>::value) {
      *j = nlohmann::ordered_json::array();
      for (const auto& e : v) {
        nlohmann::ordered_json item;
        Write(&item, e);
        j->push_back(item);
      }
    } else if constexpr (std::is_arithmetic_v<T> || std::is_same_v<T, std::string>) {
      *j = v;
    } else if constexpr (HasEnumNames<T>::value) {
      *j = EnumName(v);
    } else {
      *j = nlohmann::ordered_json::object();
      JsonWriter sub(j);
      const_cast<T&>(v).Serialize(&sub);
    }
  }
  nlohmann::ordered_json* out_;
};

// A double as YAML text that reads back as the same double and as a number
// with a fraction (1.0, not 1: a sweep's grid keeps its values' text, so "1"
// and "1.0" are different grids): the shortest round-trip digits.
std::string YamlDouble(double v) {
  if (std::isnan(v)) return ".nan";
  if (std::isinf(v)) return v > 0 ? ".inf" : "-.inf";
  std::string s = NumberText(v);
  if (s.find_first_of(".eE") == std::string::npos) s += ".0";
  return s;
}

void EmitJson(YAML::Emitter& out, const nlohmann::ordered_json& j) {
  if (j.is_object()) {
    out << YAML::BeginMap;
    for (auto it = j.begin(); it != j.end(); ++it) {
      out << YAML::Key << it.key() << YAML::Value;
      EmitJson(out, it.value());
    }
    out << YAML::EndMap;
  } else if (j.is_array()) {
    out << YAML::Flow << YAML::BeginSeq;
    for (const auto& e : j) EmitJson(out, e);
    out << YAML::EndSeq;
  } else if (j.is_null()) {
    out << YAML::Null;
  } else if (j.is_string()) {
    out << j.get<std::string>();
  } else if (j.is_boolean()) {
    out << j.get<bool>();
  } else if (j.is_number_unsigned()) {
    out << j.get<std::uint64_t>();
  } else if (j.is_number_integer()) {
    out << j.get<long long>();
  } else {
    out << YamlDouble(j.get<double>());
  }
}

}  // namespace

std::string ToJson(const ExperimentConfig& config) {
  nlohmann::ordered_json j = nlohmann::ordered_json::object();
  JsonWriter w(&j);
  const_cast<ExperimentConfig&>(config).Serialize(&w);
  return j.dump();
}

std::string ToYaml(const ExperimentConfig& config) {
  YAML::Emitter out;
  EmitJson(out, nlohmann::ordered_json::parse(ToJson(config)));
  return std::string(out.c_str()) + "\n";
}

std::string YamlValueAsJson(const std::string& yaml_text) {
  return YamlToJson(config_text::ParseYaml(yaml_text, "value " + yaml_text)).dump();
}

}  // namespace taebp
