// Command-line options of the `gaitlab` subcommands: "--name value" and "--flag", with numbers
// checked to be finite and within bounds, and errors that name the option. Every subcommand
// parses its command line here, so they all behave alike: `--help` (or -h) anywhere prints the
// subcommand's help, an integer option takes only whole numbers, and a seed is any 32-bit
// unsigned integer (kMaxSeed).
#pragma once
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <string>

namespace gaitlab::api {

// A refused command line: "gaitlab[ COMMAND]: MESSAGE (see gaitlab[ COMMAND] --help)" on stderr,
// exit status 2. `command` is empty for the top level.
inline int usageError(const std::string& command, const std::string& message) {
  const std::string name = command.empty() ? "gaitlab" : "gaitlab " + command;
  std::fprintf(stderr, "%s: %s (see %s --help)\n", name.c_str(), message.c_str(), name.c_str());
  return 2;
}

// Seeds: every subcommand takes [0, kMaxSeed] (the simulation's seed is a uint32_t).
constexpr long long kMaxSeed = 4294967295LL;

// "--name value" and "--flag" options; refuses anything not in `valued` or `flags`.
struct Options {
  std::map<std::string, std::string> values;
  std::set<std::string> flags;
  std::string error;
  bool help = false;  // --help or -h was given: print the subcommand's help, nothing else

  Options(int argc, char** argv, int first, const std::set<std::string>& valued,
          const std::set<std::string>& flagNames) {
    for (int i = first; i < argc; ++i) {
      const std::string a = argv[i];
      if (a == "--help" || a == "-h") {
        help = true;
        error.clear();
        return;
      }
      if (!error.empty()) continue;  // an error stands, unless --help follows
      if (flagNames.count(a)) {
        flags.insert(a);
      } else if (valued.count(a)) {
        if (i + 1 >= argc) {
          error = "option " + a + " needs a value";
          continue;
        }
        values[a] = argv[++i];
      } else {
        error = "unknown option '" + a + "'";
      }
    }
  }

  // A finite number within [lo, hi], or the default when absent.
  bool number(const std::string& name, double lo, double hi, double fallback, double* out) {
    auto it = values.find(name);
    if (it == values.end()) {
      *out = fallback;
      return true;
    }
    char* end = nullptr;
    const double v = std::strtod(it->second.c_str(), &end);
    if (end == it->second.c_str() || *end != '\0' || !std::isfinite(v)) {
      error = name + ": '" + it->second + "' is not a number";
      return false;
    }
    if (v < lo || v > hi) {
      error = name + ": " + it->second + " is outside [" + nlohmann::json(lo).dump() + ", " + nlohmann::json(hi).dump() + "]";
      return false;
    }
    *out = v;
    return true;
  }

  // An integer within [lo, hi], or the default when absent.
  bool integer(const std::string& name, long long lo, long long hi, long long fallback, long long* out) {
    double v;
    if (!number(name, static_cast<double>(lo), static_cast<double>(hi), static_cast<double>(fallback), &v))
      return false;
    if (v != std::floor(v)) {
      error = name + ": '" + values[name] + "' is not a whole number";
      return false;
    }
    *out = static_cast<long long>(v);
    return true;
  }
};

}  // namespace gaitlab::api
