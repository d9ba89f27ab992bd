#include "mmh/common/config_validation.hpp"

#include "mmh/common/config_constraints.hpp"
#include "mmh/common/config_registry.hpp"

namespace mmh {
namespace {

void collectUnknownKeys(const YAML::Node& map, const std::string& prefix, const Config& config,
                        std::vector<std::string>* problems) {
  for (const auto& entry : map) {
    std::string key;
    try {
      key = entry.first.as<std::string>();
    } catch (const YAML::Exception&) {
      problems->push_back(config.source() + ": a key under '" + prefix + "' is not a name");
      continue;
    }
    const std::string path = prefix.empty() ? key : prefix + "." + key;
    if (findConfigKey(path) != nullptr) continue;
    if (isConfigSection(path)) {
      if (entry.second.IsMap()) {
        collectUnknownKeys(entry.second, path, config, problems);
      } else {
        problems->push_back(config.source() + ": key '" + path + "' must be a section (mapping)");
      }
      continue;
    }
    std::string problem = "unknown key '" + path + "' in " + config.source();
    const std::string nearest = nearestConfigKey(path);
    if (!nearest.empty()) problem += " (did you mean '" + nearest + "'?)";
    problems->push_back(problem);
  }
}

// Reads the key through the getter of its type, which checks presence, type and range.
void readKey(const Config& config, const KeySpec& spec) {
  switch (spec.type) {
    case KeyType::kDouble:
      config.getDouble(spec.name);
      return;
    case KeyType::kInt:
      config.getInt(spec.name);
      return;
    case KeyType::kBool:
      config.getBool(spec.name);
      return;
    case KeyType::kEnum:
      config.getString(spec.name);
      return;
    case KeyType::kVector3:
      config.getVector3(spec.name);
      return;
  }
}

}  // namespace

std::vector<std::string> configProblems(const Config& config) {
  std::vector<std::string> problems;
  collectUnknownKeys(config.root(), "", config, &problems);
  for (const KeySpec& spec : configKeys()) {
    try {
      readKey(config, spec);
    } catch (const ConfigError& e) {
      problems.push_back(e.what());
    }
  }
  for (const std::string& violation : constraintViolations(config)) problems.push_back(violation);
  return problems;
}

void validateConfig(const Config& config) {
  const std::vector<std::string> problems = configProblems(config);
  if (problems.empty()) return;
  std::string message = problems.front();
  for (size_t i = 1; i < problems.size(); ++i) message += "\n" + problems[i];
  throw ConfigError(message);
}

}  // namespace mmh
