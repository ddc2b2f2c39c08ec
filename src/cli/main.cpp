// meshsal: command-line entry point. Sub-commands register themselves (command.h).
#include <algorithm>
#include <cstdio>
#include <exception>
#include <map>
#include <vector>

#include "command.h"
#include "meshsal/meshsal.h"

namespace meshsal_cli {

static std::vector<Command>& registry() {
  static std::vector<Command> commands;
  return commands;
}

bool register_command(Command command) {
  registry().push_back(std::move(command));
  return true;
}

}  // namespace meshsal_cli

int main(int argc, char** argv) {
  using namespace meshsal_cli;
  CLI::App app{
      "meshsal: mesh saliency (Lee, Varshney, Jacobs 2005) on the CPU and on Vulkan GPUs,\n"
      "saliency-guided simplification and best-viewpoint selection.\n"
      "Run `meshsal COMMAND --help` for the options of a command."};
  app.footer("Environment: MESHSAL_MAX_INPUT=BYTES (K/M/G suffix allowed) caps what a .gz file may inflate to and a pipe may deliver, for every command (default: see README, Input).");
  app.require_subcommand(1);
  app.set_version_flag("--version", "meshsal 0.1");

  std::vector<Command> commands = registry();
  std::sort(commands.begin(), commands.end(),
            [](const Command& a, const Command& b) { return a.order < b.order; });
  std::map<CLI::App*, RunFn> runs;
  for (const Command& c : commands) {
    CLI::App* sub = app.add_subcommand(c.name, c.help);
    runs[sub] = c.setup(*sub);
  }

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    // Usage errors: one line, exit status 2 (bad input files exit with 1).
    std::fprintf(stderr, "error: %s (see --help)\n", e.what());
    return 2;
  }
  try {
    for (auto& [sub, run] : runs)
      if (sub->parsed()) return run();
  } catch (const meshsal::Error& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "error: out of memory\n");
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
  return 1;
}
