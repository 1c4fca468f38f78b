// The `gaitlab` command line (native CLI, and the same code under Node through the WASM build's
// callMain). Subcommands print one JSON document on stdout with --json; errors go to stderr
// with a non-zero exit status.
#pragma once

namespace gaitlab::api {

int runCli(int argc, char** argv);

}  // namespace gaitlab::api
