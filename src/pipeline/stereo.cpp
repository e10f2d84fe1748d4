// The Chapter 6 pipeline: tracks (6.3.1) -> contour-respecting depth maps
// and a triangle soup (6.3.2) -> filtered soup (6.3.2) -> Delaunay
// refinement with the soup as the oracle (6.3.3) -> hole filling (6.6).

#include "sharpmesh/errors.h"
#include "sharpmesh/stereo_reconstruct.h"
#include "core/parallel.h"

namespace sharpmesh {

void StereoReconstructionOptions::check() const {
  tracks.check();
  track_photo.check();
  depth_maps.check();
  filters.check();
  fill.check();
  meshing.check();
  if (threads < 0) throw InvalidArgument("threads must be 0 (every core) or a positive count (got " + format_number(threads) + ")");
  if (!(max_hole >= 0 && max_hole <= 10)) throw InvalidArgument("the largest hole to fill must be in [0, 10] half diagonals, got " + format_number(max_hole));
}

namespace {

StereoReconstruction run_stereo(StereoModel& model, const std::vector<GreyImage>& images, const StereoReconstructionOptions& options,
                                const Progress& progress) {
  options.check();
  model.validate("the stereo model");
  if (model.cameras.size() < 2) throw InvalidInput("stereo reconstruction needs at least 2 cameras, the model has " + format_number(model.cameras.size()));
  if (images.size() != model.cameras.size())
    throw InvalidArgument("one image per camera is needed (" + format_number(model.cameras.size()) + " cameras, " +
                          format_number(images.size()) + " images)");
  for (std::size_t v = 0; v < images.size(); ++v)
    if (images[v].width != model.cameras[v].width || images[v].height != model.cameras[v].height)
      throw InvalidInput("image " + model.cameras[v].image_name + " does not have its camera's size");
  StereoReconstruction result;
  {
    StageTimer timer(result.stages, "tracks");
    result.tracks = preprocess_tracks(model, options.tracks, progress);
    if (options.track_photo.enabled) result.removed_track_photo = filter_tracks_photo(model, images, options.track_photo, progress);
  }
  if (model.tracks.size() < 3) throw InvalidInput("fewer than 3 tracks are left after filtering: nothing to reconstruct");

  {
    StageTimer timer(result.stages, "depth maps");
    std::vector<DepthMap> maps(model.cameras.size());
    report_progress(progress, "depth maps", 0.0);
    // One image per task: each builds its own triangulations.
    detail::parallel_for(model.cameras.size(), [&](std::size_t v) {
      const std::vector<std::uint8_t> contours =
          detect_contours(images[v].pixels, images[v].width, images[v].height, options.depth_maps);
      maps[v] = build_depth_map(model, static_cast<std::uint32_t>(v), contours, options.depth_maps);
    });
    report_progress(progress, "depth maps", 1.0);
    for (const Track& t : model.tracks) result.soup.vertices.push_back(t.position);
    for (const DepthMap& map : maps) {
      result.contour_tracks += map.ctracks.size();
      result.contour_edges += map.constraints.size();
      result.soup_triangles += map.triangles.size();
      result.soup.faces.insert(result.soup.faces.end(), map.triangles.begin(), map.triangles.end());
    }
    remove_duplicate_triangles(result.soup.faces);
    result.soup_unique = result.soup.faces.size();
  }
  if (result.soup.faces.empty()) throw InvalidInput("no image has 3 tracks to triangulate: the soup is empty");

  {
    StageTimer timer(result.stages, "soup filters");
    result.filters = filter_soup(result.soup, model, images, options.filters, progress);
  }
  if (result.soup.faces.empty()) throw NumericalFailure("every soup triangle was filtered out: nothing to mesh");

  {
    StageTimer timer(result.stages, "soup fill");
    result.fill = fill_soup_from_tracks(result.soup, model, options.fill, options.meshing.size * soup_half_diagonal(result.soup),
                                        options.filters.sight_margin, result.filters.occluded, progress);
  }
  {
    StageTimer timer(result.stages, "meshing");
    result.meshing = mesh_soup(result.soup, options.meshing, progress);
  }
  // Manifold first: the holes are then the boundary cycles of one oriented surface.
  if (options.manifold) {
    StageTimer timer(result.stages, "manifold");
    result.manifold = make_manifold(result.meshing.mesh);
  }
  if (options.max_hole > 0) {
    StageTimer timer(result.stages, "hole filling");
    HoleFillingOptions holes;
    holes.max_perimeter = options.max_hole * result.meshing.half_diagonal;
    holes.merge_split_vertices = !options.manifold;
    result.holes = fill_holes(result.meshing.mesh, holes, progress);
  }
  return result;
}

}  // namespace

StereoReconstruction reconstruct_stereo(StereoModel& model, const std::vector<GreyImage>& images,
                                        const StereoReconstructionOptions& options, const Progress& progress) {
  return detail::run_with_threads(options.threads, [&] { return run_stereo(model, images, options, progress); });
}

}  // namespace sharpmesh
