// sharpmesh: from 3D point clouds to feature-preserving meshes.
// Exit codes: 0 success, 1 bad data or failed computation, 2 bad usage, 130 interrupted.
#include <tbb/global_control.h>

#include <csignal>
#include <cstdio>
#include <cstring>
#include <unistd.h>

#include "cgal_messages.h"
#include "cli.h"
#include "sharpmesh/errors.h"
#include "sharpmesh/version.h"

namespace sharpmesh::io {
void remove_pending_temporaries() noexcept;
}

namespace {

extern "C" void on_interrupt(int) {
  // Outputs are only ever written to temporaries renamed when complete, so
  // removing the temporaries and leaving at once loses nothing.
  sharpmesh::io::remove_pending_temporaries();
  const char message[] = "sharpmesh: interrupted, no output written\n";
  [[maybe_unused]] auto ignored = ::write(STDERR_FILENO, message, sizeof message - 1);
  ::_exit(130);
}

}  // namespace

int main(int argc, char** argv) {
  std::signal(SIGINT, on_interrupt);
  std::signal(SIGTERM, on_interrupt);
  using namespace sharpmesh;
  const cli::CgalMessageFilter cgal_messages;
  CLI::App app{"sharpmesh: turns 3D point clouds into compact triangle meshes whose sharp edges stay sharp.\n"
               "Lengths are relative: mesh sizes in multiples of the average spacing, distances in\n"
               "fractions of the bounding-box diagonal (see each command's --help)."};
  app.require_subcommand(1);
  app.set_version_flag("--version", "sharpmesh " SHARPMESH_VERSION);
  std::vector<cli::Command> commands = {cli::add_info(app), cli::add_clean(app), cli::add_sample(app), cli::add_eval(app),
                                        cli::add_reconstruct(app), cli::add_features(app), cli::add_eval_features(app), cli::add_make_scene(app),
                                        cli::add_stereo(app), cli::add_eval_stereo(app), cli::add_view(app), cli::add_render(app),
                                        cli::add_decimate(app)};
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::fprintf(stderr, "sharpmesh: error: %s (see --help)\n", e.what());
    return 2;
  }
  try {
    for (const cli::Command& command : commands) {
      if (!command.app->parsed()) continue;
      const int threads = command.common->threads;
      std::unique_ptr<tbb::global_control> control;
      if (threads > 0) control = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, threads);
      command.run();
    }
  } catch (const InvalidArgument& e) {
    std::fprintf(stderr, "sharpmesh: error: %s\n", e.what());
    return 2;
  } catch (const Cancelled&) {
    std::fprintf(stderr, "sharpmesh: cancelled, no output written\n");
    return 130;
  } catch (const Error& e) {
    std::fprintf(stderr, "sharpmesh: error: %s\n", e.what());
    return 1;
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "sharpmesh: error: out of memory\n");
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "sharpmesh: internal error: %s\n", e.what());
    return 1;
  }
  return 0;
}
