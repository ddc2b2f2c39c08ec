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

namespace meshsal::cli {

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

// Whether the command argv names shares its work over MPI ranks (Command::uses_ranks).
static bool uses_ranks(int argc, char** argv) {
  if (argc < 2) return false;
  for (const Command& c : registry())
    if (argv[1] == std::string(c.name)) return c.uses_ranks;
  return false;
}

}  // namespace meshsal::cli

// How this process ends after a thrown error or a usage line: under MPI before the work
// every rank agrees (the line printed once, by rank 0; no MPI_Abort); during the work a
// rank that fails ends every rank (mpi_abort), so that none waits forever in a collective
// for it; else the line and the status, as always.
static int fail(int status, const std::string& line) {
  using namespace meshsal::cli;
  if (mpi_world().active && !mpi_work_begun()) {
    const RanksStopped all = mpi_stop_before_work(status, line);
    if (!all.line.empty()) std::fprintf(stderr, "%s\n", all.line.c_str());
    return all.status;
  }
  if (mpi_world().active) mpi_abort(status, line);
  if (!line.empty()) std::fprintf(stderr, "%s\n", line.c_str());
  return status;
}

// A command's own return (batch's agreed status included): never an abort; under MPI a
// rank that never met the others before the work meets them now.
static int done(int status) {
  using namespace meshsal::cli;
  if (mpi_world().active && !mpi_work_begun()) return fail(status, "");
  return status;
}

static int run_main(int argc, char** argv) {
  using namespace meshsal::cli;
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
  // Help and the version: printed by rank 0 alone under MPI.
  const auto say = [&app](const CLI::ParseError& e) {
    return done(meshsal::cli::mpi_world().rank == 0 ? app.exit(e) : 0);
  };
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return say(e);
  } catch (const CLI::CallForAllHelp& e) {
    return say(e);
  } catch (const CLI::CallForVersion& e) {
    return say(e);
  } catch (const CLI::ParseError& e) {
    // Usage errors: one line, exit status 2 (bad input files exit with 1).
    return fail(2, "error: " + printable(e.what()) + " (see --help)");
  }
  try {
    for (auto& [sub, run] : runs)
      if (sub->parsed()) return done(run());
  } catch (const meshsal::cli::RanksStopped& stop) {
    if (!stop.line.empty()) std::fprintf(stderr, "%s\n", stop.line.c_str());
    return stop.status;
  } catch (const UsageError& e) {
    return fail(2, "error: " + printable(e.what()) + " (see --help)");
  } catch (const meshsal::RequestError& e) {
    // Options that do not combine, found by the library's one rule (check_request).
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
  // Under mpirun (or srun) only a command that shares its work over the ranks starts MPI
  // (MPI_Init, which may take its own arguments out of argv: mpi_world.h). Any other runs
  // on rank 0 alone, as one process; the other ranks end at once, silently, with 0, rather
  // than each do the whole work and write the same files.
  if (meshsal::cli::uses_ranks(argc, argv)) meshsal::cli::mpi_start(&argc, &argv);
  else if (meshsal::cli::mpi_launcher_rank() > 0) return 0;
  const int status = run_main(argc, argv);
  meshsal::cli::mpi_stop();
  return status;
}
