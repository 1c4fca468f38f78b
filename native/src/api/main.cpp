// `gaitlab` CLI entry point: native executable, and main() of the Node WASM build.
#include "api/cli.h"

int main(int argc, char** argv) { return gaitlab::api::runCli(argc, argv); }
