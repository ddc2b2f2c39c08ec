// meshsal: command-line entry point. Sub-commands register themselves (command.h).
#include <algorithm>
#include <cstdio>
#include <exception>
#include <map>
#include <string>
#include <vector>

#include "command.h"
#include "json_string.h"
#include "meshsal/meshsal.h"
#include "interrupt.h"
#include "mpi_world.h"

namespace meshsal_cli {

static std::vector<Command>& registry() {
  static std::vector<Command> commands;
  return commands;
}

bool register_command(Command command) {
  registry().push_back(std::move(command));
  return true;
}

// Edit distance (insertions, deletions, substitutions) between two short words.
static size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<size_t> row(b.size() + 1);
  for (size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (size_t i = 1; i <= a.size(); ++i) {
    size_t diag = row[0];
    row[0] = i;
    for (size_t j = 1; j <= b.size(); ++j) {
      const size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diag = up;
    }
  }
  return row[b.size()];
}

// ", did you mean 'NAME'?" for the nearest command name (a prefix of one counts as near),
// or "" when none is within a third of the word's length (at least 2 edits).
static std::string suggestion(const std::string& given, const std::vector<std::string>& names) {
  std::string best;
  size_t best_d = std::max<size_t>(2, given.size() / 3) + 1;
  for (const std::string& n : names) {
    const size_t d = n.compare(0, given.size(), given) == 0 ? 0 : edit_distance(given, n);
    if (d < best_d) best_d = d, best = n;
  }
  return best.empty() ? "" : ", did you mean '" + best + "'?";
}

}  // namespace meshsal_cli

// Under MPI a rank that fails ends every rank (mpi_abort), so that none waits forever in a
// collective for it; else the error line and the status, as always.
static int fail(int status, const std::string& line) {
  if (meshsal::cli::mpi_world().active) meshsal::cli::mpi_abort(status, line);
  std::fprintf(stderr, "%s\n", line.c_str());
  return status;
}

static int run_main(int argc, char** argv) {
  using namespace meshsal_cli;
  // Process-wide, so the program's choice, not the library's (which never sets it): the
  // command's stages reuse each other's freed memory instead of page-faulting it in again.
  meshsal::keep_freed_memory_for_reuse();
  install_interrupt_handler(!meshsal::cli::mpi_world().active);
  CLI::App app{
      "meshsal: mesh saliency (Lee, Varshney, Jacobs 2005) on the CPU and on Vulkan GPUs,\n"
      "saliency-guided simplification and best-viewpoint selection.\n"
      "Run `meshsal COMMAND --help` for the options of a command."};
  app.footer("Environment: MESHSAL_MAX_INPUT=BYTES (K/M/G suffix allowed) caps what a .gz file may inflate to and a pipe may deliver, for every command (default: see README, Input).");
  app.require_subcommand(1);
  app.set_version_flag("--version", "meshsal " MESHSAL_VERSION_STRING);

  std::vector<Command> commands = registry();
  std::sort(commands.begin(), commands.end(),
            [](const Command& a, const Command& b) { return a.order < b.order; });
  std::map<CLI::App*, RunFn> runs;
  for (const Command& c : commands) {
    CLI::App* sub = app.add_subcommand(c.name, c.help);
    runs[sub] = c.setup(*sub);
  }

  // An unknown command would otherwise read "The following arguments were not expected".
  if (argc > 1 && argv[1][0] != '-') {
    const std::string given = argv[1];
    std::vector<std::string> names;
    for (const Command& c : commands) names.push_back(c.name);
    if (std::find(names.begin(), names.end(), given) == names.end()) {
      return fail(2, "error: unknown command '" + printable(given) + "'" + suggestion(given, names) +
                         " (see meshsal --help)");
    }
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
    return fail(2, "error: " + printable(e.what()) + " (see --help)");
  }
  try {
    for (auto& [sub, run] : runs)
      if (sub->parsed()) return run();
  } catch (const UsageError& e) {
    return fail(2, "error: " + printable(e.what()) + " (see --help)");
  } catch (const meshsal::Cancelled&) {
    return fail(interrupted_exit(), "interrupted");
  } catch (const meshsal::Error& e) {
    return fail(1, "error: " + printable(e.what()));
  } catch (const std::bad_alloc&) {
    return fail(1, "error: out of memory");
  } catch (const std::exception& e) {
    return fail(1, "error: " + printable(e.what()));
  }
  return 1;
}

int main(int argc, char** argv) {
  // MPI_Init only under mpirun/srun (mpi_world.h); it may take its arguments out of argv.
  meshsal::cli::mpi_start(&argc, &argv);
  const int status = run_main(argc, argv);
  meshsal::cli::mpi_stop();
  return status;
}
