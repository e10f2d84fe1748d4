// Beyond the thesis (6.3.1 assumes matched tracks): a track must be
// matchable. Its image windows in its views must show texture and agree
// (mean pairwise NCC of small fronto-parallel windows); tracks failing this,
// such as mismatches floating in front of the sky, are removed.

#include <atomic>
#include <cmath>

#include "sharpmesh/errors.h"
#include "sharpmesh/stereo_reconstruct.h"
#include "core/grey_sampling.h"
#include "core/parallel.h"

namespace sharpmesh {
namespace {

/// The (2h+1)^2 window around a pixel, bilinear; false when it leaves the image.
bool window(const GreyImage& image, const Vec2& center, int h, std::vector<double>& values) {
  values.clear();
  double value;
  for (int dy = -h; dy <= h; ++dy)
    for (int dx = -h; dx <= h; ++dx) {
      if (!detail::sample_bilinear(image, {center[0] + dx, center[1] + dy}, value)) return false;
      values.push_back(value);
    }
  return true;
}

/// Centres the window and scales it to unit norm; false when it has no texture.
bool normalise(std::vector<double>& w, double min_std) {
  double mean = 0;
  for (double v : w) mean += v;
  mean /= static_cast<double>(w.size());
  double ss = 0;
  for (double& v : w) {
    v -= mean;
    ss += v * v;
  }
  if (ss < min_std * min_std * static_cast<double>(w.size())) return false;
  const double s = 1.0 / std::sqrt(ss);
  for (double& v : w) v *= s;
  return true;
}

}  // namespace

double track_ncc(const Track& track, const StereoModel& model, const std::vector<GreyImage>& images, int half_window,
                 double min_texture) {
  std::vector<std::vector<double>> windows;
  std::vector<double> w;
  int textureless = 0;
  for (std::uint32_t v : track.views) {
    Vec2 pixel;
    if (v >= images.size() || !model.cameras[v].project(track.position, pixel) || !window(images[v], pixel, half_window, w)) continue;
    if (normalise(w, min_texture))
      windows.push_back(w);
    else
      ++textureless;
  }
  if (windows.size() < 2) return textureless > 0 ? -1.0 : NAN;  // no texture to match: not a matchable track
  double sum = 0;
  int pairs = 0;
  for (std::size_t i = 0; i < windows.size(); ++i)
    for (std::size_t j = i + 1; j < windows.size(); ++j) {
      double c = 0;
      for (std::size_t k = 0; k < windows[i].size(); ++k) c += windows[i][k] * windows[j][k];
      sum += c;
      ++pairs;
    }
  return sum / pairs;
}

std::size_t filter_tracks_photo(StereoModel& model, const std::vector<GreyImage>& images, const TrackPhotoOptions& options,
                                const Progress& progress) {
  options.check();
  if (images.size() != model.cameras.size()) throw InvalidArgument("one image per view is needed for the track photo-consistency filter");
  std::vector<std::uint8_t> keep(model.tracks.size(), 1);
  report_progress(progress, "track photo-consistency", 0.0);
  detail::parallel_chunks(model.tracks.size(), 256, [&](std::size_t begin, std::size_t end) {
    for (std::size_t t = begin; t != end; ++t) {
      const double ncc = track_ncc(model.tracks[t], model, images, options.half_window, options.min_texture);
      keep[t] = std::isnan(ncc) || ncc >= options.min_ncc;  // NaN: windows off the images, undecided
    }
  });
  report_progress(progress, "track photo-consistency", 1.0);
  std::vector<Track> kept;
  kept.reserve(model.tracks.size());
  for (std::size_t t = 0; t < model.tracks.size(); ++t)
    if (keep[t]) kept.push_back(std::move(model.tracks[t]));
  const std::size_t removed = model.tracks.size() - kept.size();
  model.tracks = std::move(kept);
  return removed;
}

void TrackPhotoOptions::check() const {
  if (half_window < 1 || half_window > 15) throw InvalidArgument("the track window half size must be in [1, 15] pixels");
  if (!(min_ncc >= -1 && min_ncc <= 1)) throw InvalidArgument("the track NCC threshold must be in [-1, 1]");
  if (!(min_texture >= 0)) throw InvalidArgument("the minimum texture must be >= 0 grey levels");
}

}  // namespace sharpmesh
