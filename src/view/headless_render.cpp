// PNG of the viewer page by a headless browser (Chromium's --screenshot, with
// SwiftShader for WebGL, so no display or GPU is needed). The page reports
// its state on <body> (web/src/viewer.js); --dump-dom reads it back in the
// same run, so a page that failed is an error, not a blank picture.
#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <string>
#include <thread>
#include <vector>

#include "io/atomic_file.h"
#include "sharpmesh/errors.h"
#include "sharpmesh/view.h"

extern char** environ;

namespace sharpmesh {
namespace {

namespace fs = std::filesystem;

std::string find_browser(const RenderOptions& options) {
  if (!options.browser.empty()) {
    if (access(options.browser.c_str(), X_OK) != 0)
      throw InvalidArgument("render: the browser '" + options.browser + "' is not an executable file");
    return options.browser;
  }
  const char* path = std::getenv("PATH");
  std::string dirs = path ? path : "/usr/bin:/bin";
  for (const char* name : {"chromium", "chromium-browser", "google-chrome"}) {
    std::size_t start = 0;
    while (start <= dirs.size()) {
      const std::size_t end = std::min(dirs.find(':', start), dirs.size());
      const std::string candidate = dirs.substr(start, end - start) + "/" + name;
      if (end > start && access(candidate.c_str(), X_OK) == 0) return candidate;
      start = end + 1;
    }
  }
  throw InvalidArgument("render: no headless browser found; install chromium (apt-get install chromium) or name one (--browser, SHARPMESH_BROWSER)");
}

/// A private folder under the system's temporary directory, removed on exit.
struct ScratchFolder {
  fs::path path;
  ScratchFolder() {
    std::string pattern = (fs::temp_directory_path() / "sharpmesh-render-XXXXXX").string();
    if (!mkdtemp(pattern.data())) throw InvalidInput("render: cannot create a folder in " + fs::temp_directory_path().string());
    path = pattern;
  }
  ~ScratchFolder() {
    std::error_code ignored;
    fs::remove_all(path, ignored);
  }
};

std::string read_file(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

/// Runs argv with stdout and stderr to files; kills its whole process group on timeout.
int run_with_timeout(const std::vector<std::string>& argv, const fs::path& out, const fs::path& err, double timeout) {
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&actions, 1, out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
  posix_spawn_file_actions_addopen(&actions, 2, err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
  posix_spawnattr_t attributes;
  posix_spawnattr_init(&attributes);
  posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETPGROUP);
  posix_spawnattr_setpgroup(&attributes, 0);
  std::vector<char*> args;
  for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  pid_t pid = 0;
  const int spawned = posix_spawn(&pid, argv[0].c_str(), &actions, &attributes, args.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  posix_spawnattr_destroy(&attributes);
  if (spawned != 0) throw InvalidArgument("render: cannot start " + argv[0]);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout);
  int status = 0;
  while (waitpid(pid, &status, WNOHANG) == 0) {
    if (std::chrono::steady_clock::now() > deadline) {
      kill(-pid, SIGKILL);
      waitpid(pid, &status, 0);
      throw NumericalFailure("render: the browser did not finish within " + format_number(timeout) + " s");
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  kill(-pid, SIGKILL);  // helpers the browser may have left behind
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

/// The value of attribute `name` of the page's <body> tag ("" when absent).
std::string body_attribute(const std::string& dom, const std::string& name) {
  const std::size_t body = dom.find("<body");
  if (body == std::string::npos) return {};
  const std::string tag = dom.substr(body, dom.find('>', body) - body);
  const std::size_t at = tag.find(" " + name + "=\"");
  if (at == std::string::npos) return {};
  const std::size_t start = at + name.size() + 3;
  return tag.substr(start, tag.find('"', start) - start);
}

}  // namespace

void RenderOptions::check() const {
  if (width < 16 || height < 16 || width > 8192 || height > 8192)
    throw InvalidArgument("render: the picture size must be 16 to 8192 pixels a side (got " + format_number(width) + " x " +
                          format_number(height) + ")");
  if (!(timeout_seconds > 0) || !std::isfinite(timeout_seconds)) throw InvalidArgument("render: the timeout must be positive");
}

void render_png(const std::string& png_path, const ViewScene& scene, const ViewOptions& view, const RenderOptions& render) {
  render.check();
  const std::string browser = find_browser(render);
  const std::string page = viewer_page(scene, view);
  cv::Mat beside;
  if (!render.beside.empty()) {
    beside = cv::imread(render.beside, cv::IMREAD_COLOR);
    if (beside.empty()) throw InvalidInput(render.beside + ": not a readable picture");
  }
  ScratchFolder scratch;
  const fs::path html = scratch.path / "page.html", shot = scratch.path / "shot.png";
  {
    std::ofstream out(html, std::ios::binary);
    out << page;
    if (!out) throw InvalidInput("render: cannot write " + html.string());
  }
  const std::vector<std::string> argv = {
      browser, "--headless", "--no-sandbox", "--use-angle=swiftshader", "--enable-unsafe-swiftshader",
      "--hide-scrollbars", "--mute-audio", "--no-first-run", "--disable-extensions", "--force-device-scale-factor=1",
      "--user-data-dir=" + (scratch.path / "profile").string(),
      "--window-size=" + std::to_string(render.width) + "," + std::to_string(render.height),
      "--virtual-time-budget=30000", "--screenshot=" + shot.string(), "--dump-dom", "file://" + html.string()};
  const int code = run_with_timeout(argv, scratch.path / "dom.html", scratch.path / "browser.log", render.timeout_seconds);
  const std::string dom = read_file(scratch.path / "dom.html");
  const std::string status = body_attribute(dom, "data-status");
  if (status != "ready") {
    const std::string error = body_attribute(dom, "data-last-error");
    throw NumericalFailure("render: the page did not render (" +
                           (!error.empty() ? error : dom.empty() ? browser + " exited with code " + std::to_string(code) : "status '" + status + "'") + ")");
  }
  if (const std::string errors = body_attribute(dom, "data-errors"); errors != "0")
    throw NumericalFailure("render: the page reported " + errors + " error(s): " + body_attribute(dom, "data-last-error"));
  const std::string png = read_file(shot);
  const cv::Mat image = cv::imdecode(cv::Mat(1, int(png.size()), CV_8U, const_cast<char*>(png.data())), cv::IMREAD_GRAYSCALE);
  if (image.empty()) throw NumericalFailure("render: the browser wrote no picture");
  cv::Scalar mean, deviation;
  cv::meanStdDev(image, mean, deviation);
  if (deviation[0] < 2.0) throw NumericalFailure("render: the picture is blank");
  io::AtomicFile file(png_path);
  if (beside.empty()) {
    file.write(png);
  } else {
    const cv::Mat shot_image = cv::imdecode(cv::Mat(1, int(png.size()), CV_8U, const_cast<char*>(png.data())), cv::IMREAD_COLOR);
    cv::Mat scaled, both;
    const double scale = static_cast<double>(shot_image.rows) / beside.rows;
    cv::resize(beside, scaled, cv::Size(std::max(1, static_cast<int>(std::lround(beside.cols * scale))), shot_image.rows), 0, 0, cv::INTER_AREA);
    cv::hconcat(scaled, shot_image, both);
    std::vector<std::uint8_t> encoded;
    if (!cv::imencode(".png", both, encoded)) throw NumericalFailure("render: the picture could not be encoded");
    file.write(encoded.data(), encoded.size());
  }
  file.commit();
}

}  // namespace sharpmesh
