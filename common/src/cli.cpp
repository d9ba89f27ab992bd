#include "mmh/common/cli.hpp"

#include <cmath>
#include <cstdio>
#include <iostream>
#include <sstream>

namespace mmh {

bool parseVector3(const std::string& text, Eigen::Vector3d* out) {
  std::stringstream s(text);
  std::string part;
  Eigen::Vector3d v;
  int i = 0;
  while (std::getline(s, part, ',')) {
    if (i >= 3) return false;
    try {
      size_t used = 0;
      v[i] = std::stod(part, &used);
      if (used != part.size() || !std::isfinite(v[i])) return false;
    } catch (...) {
      return false;
    }
    ++i;
  }
  if (i != 3) return false;
  *out = v;
  return true;
}

void ArgParser::addString(const std::string& name, std::string* value, const std::string& help) {
  options_.push_back({name, help, *value, true, [value](const std::string& v) {
                        *value = v;
                        return true;
                      }});
}

void ArgParser::addDouble(const std::string& name, double* value, const std::string& help) {
  std::ostringstream d;
  d << *value;
  options_.push_back({name, help, d.str(), true, [value](const std::string& v) {
                        try {
                          size_t used = 0;
                          double x = std::stod(v, &used);
                          if (used != v.size() || !std::isfinite(x)) return false;
                          *value = x;
                          return true;
                        } catch (...) {
                          return false;
                        }
                      }});
}

void ArgParser::addInt(const std::string& name, int* value, const std::string& help) {
  options_.push_back({name, help, std::to_string(*value), true, [value](const std::string& v) {
                        try {
                          size_t used = 0;
                          int x = std::stoi(v, &used);
                          if (used != v.size()) return false;
                          *value = x;
                          return true;
                        } catch (...) {
                          return false;
                        }
                      }});
}

void ArgParser::addFlag(const std::string& name, bool* value, const std::string& help) {
  options_.push_back({name, help, "", false, [value](const std::string&) {
                        *value = true;
                        return true;
                      }});
}

void ArgParser::addVector3(const std::string& name, Eigen::Vector3d* value,
                           const std::string& help) {
  std::ostringstream d;
  d << (*value)[0] << "," << (*value)[1] << "," << (*value)[2];
  options_.push_back({name, help, d.str(), true,
                      [value](const std::string& v) { return parseVector3(v, value); }});
}

void ArgParser::addPositional(const std::string& name, std::vector<std::string>* values,
                              const std::string& help) {
  positional_ = values;
  positional_name_ = name;
  positional_help_ = help;
}

std::string ArgParser::usage() const {
  std::ostringstream s;
  s << "usage: " << program_ << " [options]";
  if (positional_) s << " " << positional_name_;
  s << "\n" << summary_ << "\n\noptions:\n";
  for (const Option& o : options_) {
    s << "  " << o.name << (o.takes_value ? " VALUE" : "") << "\n      " << o.help;
    if (o.takes_value && !o.default_text.empty()) s << " (default: " << o.default_text << ")";
    s << "\n";
  }
  if (positional_) s << "  " << positional_name_ << "\n      " << positional_help_ << "\n";
  s << "  --help\n      print this help\n";
  return s.str();
}

bool ArgParser::parse(int argc, char** argv, int* exit_code) {
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--help" || arg == "-h") {
      std::cout << usage();
      *exit_code = 0;
      return false;
    }
    std::string name = arg, inline_value;
    bool has_inline = false;
    const size_t eq = arg.find('=');
    if (arg.rfind("--", 0) == 0 && eq != std::string::npos) {
      name = arg.substr(0, eq);
      inline_value = arg.substr(eq + 1);
      has_inline = true;
    }
    const Option* match = nullptr;
    for (const Option& o : options_)
      if (o.name == name) match = &o;
    if (!match) {
      if (positional_ && arg.rfind("--", 0) != 0) {
        positional_->push_back(arg);
        continue;
      }
      std::cerr << program_ << ": unknown option '" << arg << "'\n" << usage();
      *exit_code = 2;
      return false;
    }
    std::string value;
    if (match->takes_value) {
      if (has_inline) {
        value = inline_value;
      } else if (i + 1 < argc) {
        value = argv[++i];
      } else {
        std::cerr << program_ << ": option " << name << " needs a value\n";
        *exit_code = 2;
        return false;
      }
    }
    if (!match->set(value)) {
      std::cerr << program_ << ": bad value '" << value << "' for " << name << " (" << match->help
                << ")\n";
      *exit_code = 2;
      return false;
    }
  }
  *exit_code = 0;
  return true;
}

}  // namespace mmh
