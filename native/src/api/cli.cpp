#include "api/cli.h"

#include <cstdio>
#include <cstring>
#include <string>

namespace gaitlab::api {

namespace {

const char* kUsage =
    "usage: gaitlab [--version] [--help] <command> [options]\n"
    "\n"
    "Physics-driven procedural locomotion for bipeds and quadrupeds (Bullet Physics).\n"
    "\n"
    "commands:\n"
    "  (none yet)   walk, bench and optimize arrive with the controller, crowd and optimizer\n"
    "\n"
    "options:\n"
    "  --version    print the version and exit\n"
    "  --help       print this help and exit\n";

}  // namespace

int runCli(int argc, char** argv) {
  if (argc < 2) {
    std::fputs(kUsage, stderr);
    return 2;
  }
  const std::string cmd = argv[1];
  if (cmd == "--version" || cmd == "-V") {
    std::printf("gaitlab %s\n", GAITLAB_VERSION);
    return 0;
  }
  if (cmd == "--help" || cmd == "-h" || cmd == "help") {
    std::fputs(kUsage, stdout);
    return 0;
  }
  std::fprintf(stderr, "gaitlab: unknown command '%s' (see gaitlab --help)\n", cmd.c_str());
  return 2;
}

}  // namespace gaitlab::api
