#include "sim/stepping.h"

namespace gaitlab::sim {

const char* modeName(Mode mode) {
  switch (mode) {
    case Mode::Serial: return "serial";
    case Mode::Controller: return "controller";
    case Mode::Full: return "full";
  }
  return "?";
}

bool parseMode(const std::string& name, Mode* out) {
  for (Mode m : {Mode::Serial, Mode::Controller, Mode::Full}) {
    if (name == modeName(m)) {
      *out = m;
      return true;
    }
  }
  return false;
}

}  // namespace gaitlab::sim
