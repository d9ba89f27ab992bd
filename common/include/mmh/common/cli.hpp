// Tiny command-line parser for the service and tool executables: named options with help text,
// clear errors for unknown options or missing values.
#pragma once

#include <Eigen/Core>
#include <functional>
#include <string>
#include <vector>

namespace mmh {

class ArgParser {
 public:
  ArgParser(std::string program, std::string summary)
      : program_(std::move(program)), summary_(std::move(summary)) {}

  void addString(const std::string& name, std::string* value, const std::string& help);
  void addDouble(const std::string& name, double* value, const std::string& help);
  void addInt(const std::string& name, int* value, const std::string& help);
  void addFlag(const std::string& name, bool* value, const std::string& help);
  // "x,y,z" into a vector.
  void addVector3(const std::string& name, Eigen::Vector3d* value, const std::string& help);
  // Remaining non-option arguments (e.g. a log file) go here; without it they are an error.
  void addPositional(const std::string& name, std::vector<std::string>* values,
                     const std::string& help);

  // Returns false after printing help (--help) or an error; `exit_code` tells which.
  bool parse(int argc, char** argv, int* exit_code);
  std::string usage() const;

 private:
  struct Option {
    std::string name, help, default_text;
    bool takes_value;
    std::function<bool(const std::string&)> set;
  };
  std::string program_, summary_;
  std::vector<Option> options_;
  std::vector<std::string>* positional_ = nullptr;
  std::string positional_name_, positional_help_;
};

// Parses "x,y,z"; false if malformed or not finite.
bool parseVector3(const std::string& text, Eigen::Vector3d* out);

}  // namespace mmh
