// Triangle soup filtering (thesis 6.3.2): lines of sight must cross free
// space (visibility, up to t3 crossings), every vertex must be seen by a
// non-grazing line of sight, big triangles must not be anamorphic, and big
// regular triangles must be photo-consistent.

#include <algorithm>
#include <atomic>
#include <cmath>

#include "core/knn.h"
#include "sharpmesh/errors.h"
#include "sharpmesh/stereo_reconstruct.h"
#include "core/ray_caster.h"
#include "core/parallel.h"

namespace sharpmesh {

void SoupFilterOptions::check() const {
  if (max_crossings < 0) throw InvalidArgument("the visibility threshold t3 must be >= 0, got " + format_number(max_crossings));
  if (!(sight_margin >= 0 && sight_margin <= 100)) throw InvalidArgument("the line-of-sight margin must be in [0, 100] average spacings");
  if (!(grazing_angle > 0 && grazing_angle <= 90)) throw InvalidArgument("the grazing angle must be in (0, 90] degrees");
  if (!(big_radius > 0)) throw InvalidArgument("the big-triangle radius must be positive");
  if (!(max_radius_edge >= 0.5773)) throw InvalidArgument("the radius-edge bound must be >= 1/sqrt(3) (the equilateral triangle)");
  if (!(ncc_threshold >= -1 && ncc_threshold <= 1)) throw InvalidArgument("the NCC threshold must be in [-1, 1]");
}

SightCrossings count_sight_crossings(const TriangleSoup& soup, const StereoModel& model, double margin,
                                     const Progress& progress) {
  SightCrossings result;
  result.per_face.assign(soup.faces.size(), 0);
  result.per_track.resize(model.tracks.size());
  if (soup.faces.empty()) return result;
  const detail::RayCaster caster(soup);
  std::vector<Vec3> centers;
  for (const Camera& c : model.cameras) centers.push_back(c.center());
  // Faces incident to each track: a line of sight may end on them (vertices
  // past the tracks are not tracks: the soup's fill, 6.6).
  std::vector<std::vector<std::uint32_t>> incident(model.tracks.size());
  for (std::uint32_t f = 0; f < soup.faces.size(); ++f)
    for (std::uint32_t v : soup.faces[f])
      if (v < incident.size()) incident[v].push_back(f);
  detail::parallel_chunks(
      model.tracks.size(), 64,
      [&](std::size_t begin, std::size_t end) {
        std::vector<std::uint32_t> faces;
        for (std::size_t t = begin; t != end; ++t) {
          const Vec3& p = model.tracks[t].position;
          for (std::uint32_t v : model.tracks[t].views) {
            const Vec3 sight = p - centers[v];
            const double length = norm(sight);
            if (!(length > margin)) continue;
            faces.clear();
            caster.crossed_faces(centers[v], centers[v] + ((length - margin) / length) * sight, faces);
            for (std::uint32_t f : faces) {
              const auto& own = incident[t];
              if (std::find(own.begin(), own.end(), f) != own.end()) continue;
              result.per_track[t].push_back({v, f});
            }
          }
        }
      },
      progress, "visibility filter", 8192);
  for (const auto& crossings : result.per_track)
    for (const auto& [view, face] : crossings) ++result.per_face[face];
  return result;
}

namespace {

struct Shape {
  double circumradius = 0;
  double radius_edge = 0;  // circumradius / shortest edge
  Vec3 unit_normal{0, 0, 0};
};

Shape shape_of(const Vec3& a, const Vec3& b, const Vec3& c) {
  Shape s;
  const double ab = distance(a, b), bc = distance(b, c), ca = distance(c, a);
  const Vec3 n = cross(b - a, c - a);
  const double twice_area = norm(n);
  if (!(twice_area > 0)) {
    s.circumradius = s.radius_edge = INFINITY;
    return s;
  }
  s.unit_normal = (1.0 / twice_area) * n;
  s.circumradius = ab * bc * ca / (2.0 * twice_area);
  s.radius_edge = s.circumradius / std::min({ab, bc, ca});
  return s;
}

std::vector<std::uint32_t> common_views(const Triangle& f, const StereoModel& model) {
  std::vector<std::uint32_t> a = model.tracks[f[0]].views, b = model.tracks[f[1]].views, c = model.tracks[f[2]].views;
  std::sort(a.begin(), a.end());
  std::sort(b.begin(), b.end());
  std::sort(c.begin(), c.end());
  std::vector<std::uint32_t> ab, abc;
  std::set_intersection(a.begin(), a.end(), b.begin(), b.end(), std::back_inserter(ab));
  std::set_intersection(ab.begin(), ab.end(), c.begin(), c.end(), std::back_inserter(abc));
  return abc;
}

// Beyond the thesis: the other side of the visibility constraint (6.3.2).
// A track hidden behind kept triangles (at most max_crossings crossings)
// from most of its views is a matching outlier: it makes pits behind the
// surface that no line of sight crosses. Marks them in stats.occluded.
void mark_occluded_tracks(const SightCrossings& crossings, const StereoModel& model, std::uint32_t max_crossings,
                          SoupFilterStats& stats) {
  std::vector<bool>& occluded = stats.occluded;
  occluded.assign(model.tracks.size(), false);
  std::vector<std::uint32_t> blocked_views;
  for (std::size_t t = 0; t < model.tracks.size(); ++t) {
    blocked_views.clear();
    for (const auto& [view, face] : crossings.per_track[t])
      if (crossings.per_face[face] <= max_crossings) blocked_views.push_back(view);
    std::sort(blocked_views.begin(), blocked_views.end());
    const auto blocked = static_cast<std::size_t>(std::unique(blocked_views.begin(), blocked_views.end()) - blocked_views.begin());
    occluded[t] = 2 * blocked > model.tracks[t].views.size();
    stats.occluded_tracks += occluded[t];
  }
}

}  // namespace

SoupFilterStats filter_soup(TriangleSoup& soup, const StereoModel& model, const std::vector<GreyImage>& images,
                            const SoupFilterOptions& options, const Progress& progress) {
  options.check();
  SoupFilterStats stats;
  stats.input = soup.faces.size();
  if (soup.faces.empty()) return stats;
  if (soup.vertices.size() != model.tracks.size()) throw InvalidArgument("the soup's vertices are not the model's tracks");
  if (!images.empty() && images.size() != model.cameras.size()) throw InvalidArgument("one image per view is needed for the photo-consistency filter");
  const double spacing = model.tracks.size() > 7
                             ? detail::average_spacing(soup.vertices, detail::KnnIndex(soup.vertices), 6)
                             : 0.0;
  enum Verdict : std::uint8_t { Keep, Visibility, Occluded, Grazing, Anamorphic, Photo, BigRegular };

  // Shape filters first: each triangle's verdict depends on it alone, and the
  // visibility count of a triangle does not depend on the other triangles, so
  // counting lines of sight only through the survivors changes nothing but time.
  std::vector<Vec3> centers;
  for (const Camera& c : model.cameras) centers.push_back(c.center());
  const double cos_grazing = std::cos(options.grazing_angle * M_PI / 180.0);
  std::vector<std::uint8_t> verdict(soup.faces.size(), Keep);
  report_progress(progress, "shape filters", 0.0);
  detail::parallel_chunks(soup.faces.size(), 1024, [&](std::size_t begin, std::size_t end) {
    for (std::size_t f = begin; f != end; ++f) {
      const Triangle& t = soup.faces[f];
      const std::array<Vec3, 3> p{soup.vertices[t[0]], soup.vertices[t[1]], soup.vertices[t[2]]};
      const Shape s = shape_of(p[0], p[1], p[2]);
      if (!std::isfinite(s.circumradius)) {
        verdict[f] = Anamorphic;
        continue;
      }
      // Grazing: some vertex is seen only at more than grazing_angle from the normal.
      for (int k = 0; k < 3 && verdict[f] == Keep; ++k) {
        bool seen_well = false;
        for (std::uint32_t v : model.tracks[t[k]].views) {
          const Vec3 sight = centers[v] - p[k];
          if (std::abs(dot(s.unit_normal, sight)) >= cos_grazing * norm(sight)) {
            seen_well = true;
            break;
          }
        }
        if (!seen_well) verdict[f] = Grazing;
      }
      if (verdict[f] != Keep || !(s.circumradius > options.big_radius * spacing)) continue;
      verdict[f] = s.radius_edge > options.max_radius_edge ? Anamorphic : BigRegular;
    }
  });
  report_progress(progress, "shape filters", 1.0);

  // Visibility (6.3.2): lines of sight through the surviving triangles.
  TriangleSoup survivors;
  survivors.vertices = soup.vertices;
  std::vector<std::size_t> survivor_of;
  for (std::size_t f = 0; f < soup.faces.size(); ++f)
    if (verdict[f] == Keep || verdict[f] == BigRegular) {
      survivors.faces.push_back(soup.faces[f]);
      survivor_of.push_back(f);
    }
  if (!survivors.faces.empty()) {
    const SightCrossings crossings = count_sight_crossings(survivors, model, options.sight_margin * spacing, progress);
    const auto max_crossings = static_cast<std::uint32_t>(options.max_crossings);
    for (std::size_t s = 0; s < survivors.faces.size(); ++s)
      if (crossings.per_face[s] > max_crossings) verdict[survivor_of[s]] = Visibility;
    // The triangles of occluded tracks go.
    mark_occluded_tracks(crossings, model, max_crossings, stats);
    const std::vector<bool>& occluded = stats.occluded;
    for (std::size_t s = 0; options.remove_occluded_tracks && s < survivors.faces.size(); ++s) {
      const Triangle& t = survivors.faces[s];
      if (verdict[survivor_of[s]] != Visibility && (occluded[t[0]] || occluded[t[1]] || occluded[t[2]]))
        verdict[survivor_of[s]] = Occluded;
    }
  }

  // Photo-consistency (6.3.2) of the big regular triangles left.
  std::atomic<std::size_t> tested{0};
  report_progress(progress, "photo-consistency filter", 0.0);
  detail::parallel_chunks(soup.faces.size(), 64, [&](std::size_t begin, std::size_t end) {
    for (std::size_t f = begin; f != end; ++f) {
      if (verdict[f] != BigRegular) continue;
      verdict[f] = Keep;
      if (!options.photo_consistency || images.empty()) continue;
      const Triangle& t = soup.faces[f];
      const double ncc = triangle_ncc({soup.vertices[t[0]], soup.vertices[t[1]], soup.vertices[t[2]]}, common_views(t, model), model, images);
      if (std::isnan(ncc)) continue;
      tested.fetch_add(1, std::memory_order_relaxed);
      if (ncc < options.ncc_threshold) verdict[f] = Photo;
    }
  });
  report_progress(progress, "photo-consistency filter", 1.0);
  stats.photo_tested = tested.load();

  std::vector<Triangle> kept;
  kept.reserve(soup.faces.size());
  for (std::size_t f = 0; f < soup.faces.size(); ++f) {
    switch (verdict[f]) {
      case Keep: kept.push_back(soup.faces[f]); break;
      case Visibility: ++stats.removed_visibility; break;
      case Occluded: ++stats.removed_occluded; break;
      case Grazing: ++stats.removed_grazing; break;
      case Anamorphic: ++stats.removed_anamorphic; break;
      case Photo: ++stats.removed_photo; break;
      default: break;
    }
  }
  soup.faces = std::move(kept);
  stats.output = soup.faces.size();
  return stats;
}

}  // namespace sharpmesh
