// capmesh C++ wrapper of the cap map handle (capmesh_v1_map): parameterize once, then map
// cap points back onto the surface (the inverse map) and surface points onto the cap (the
// forward map). Header-only, over capmesh.h; see capmesh.hpp for Error, Progress and options.
//
//   capmesh::CapMap map = capmesh::parameterize_map(view);     // owns the handle (move-only)
//   std::vector<capmesh::SurfacePoint> s = map.inverse(points); // located or not, per point
//   std::array<double, 3> x = map.forward(face, {w0, w1, w2});
#ifndef CAPMESH_MAP_HPP
#define CAPMESH_MAP_HPP

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "capmesh.hpp"

namespace capmesh {

/// Where a cap point lies on the surface. `located` is false for a point off the cap (then the
/// other fields are NaN and face is CAPMESH_V1_NO_FACE): capmesh does not guess.
struct SurfacePoint {
  bool located = false;
  /// Input triangle holding the point.
  uint32_t face = CAPMESH_V1_NO_FACE;
  /// Weights of the triangle's three corners (in its order; >= 0, sum 1).
  std::array<double, 3> barycentric{};
  /// The point on the surface.
  std::array<double, 3> position{};
};

/// A surface mapped onto its cap (owning, move-only). Made by parameterize_map().
class CapMap {
 public:
  CapMap() noexcept = default;
  /// Take ownership of a handle returned by capmesh_v1_parameterize_map.
  explicit CapMap(capmesh_v1_map *handle, std::string report_json = {}) noexcept
      : handle_(handle), report_(std::move(report_json)) {}
  CapMap(const CapMap &) = delete;
  CapMap &operator=(const CapMap &) = delete;
  CapMap(CapMap &&other) noexcept : handle_(std::exchange(other.handle_, nullptr)), report_(std::move(other.report_)) {}
  CapMap &operator=(CapMap &&other) noexcept {
    if (this != &other) {
      capmesh_v1_map_free(handle_);
      handle_ = std::exchange(other.handle_, nullptr);
      report_ = std::move(other.report_);
    }
    return *this;
  }
  ~CapMap() { capmesh_v1_map_free(handle_); }

  std::size_t vertex_count() const noexcept { return capmesh_v1_map_vertex_count(handle_); }
  std::size_t face_count() const noexcept { return capmesh_v1_map_face_count(handle_); }
  /// 3 * vertex_count() coordinates of the input vertices on the cap, valid while this lives.
  const double *cap_positions() const noexcept { return capmesh_v1_map_cap_positions(handle_); }
  /// 2 * vertex_count() texture coordinates (the map's disk in [0, 1]^2, as `param --uv`).
  const double *uv() const noexcept { return capmesh_v1_map_uv(handle_); }
  /// The parameterization's JSON report.
  const std::string &report_json() const noexcept { return report_; }
  capmesh_v1_map *get() const noexcept { return handle_; }
  explicit operator bool() const noexcept { return handle_ != nullptr; }

  /// The inverse map of `count` cap points (`3 * count` doubles).
  std::vector<SurfacePoint> inverse(const double *points, std::size_t count) const {
    std::vector<double> positions(3 * count), weights(3 * count);
    std::vector<uint32_t> faces(count);
    std::vector<int32_t> located(count);
    detail::check(capmesh_v1_map_inverse(handle_, points, count, positions.data(), faces.data(), weights.data(),
                                         located.data(), nullptr));
    std::vector<SurfacePoint> out(count);
    for (std::size_t i = 0; i < count; ++i) {
      out[i].located = located[i] == CAPMESH_V1_POINT_LOCATED;
      out[i].face = faces[i];
      for (int k = 0; k < 3; ++k) {
        out[i].barycentric[k] = weights[3 * i + k];
        out[i].position[k] = positions[3 * i + k];
      }
    }
    return out;
  }

  /// The inverse map of cap points given as (x, y, z) triples.
  std::vector<SurfacePoint> inverse(const std::vector<std::array<double, 3>> &points) const {
    return inverse(points.empty() ? nullptr : points.front().data(), points.size());
  }

  /// The inverse map of one cap point.
  SurfacePoint inverse(const std::array<double, 3> &point) const { return inverse(point.data(), 1).front(); }

  /// The cap point of the surface point on `face` with corner weights `barycentric`. Throws
  /// Error (invalid argument) for a face out of range or weights that are not a point of it.
  std::array<double, 3> forward(uint32_t face, const std::array<double, 3> &barycentric) const {
    std::array<double, 3> out{};
    detail::check(capmesh_v1_map_forward(handle_, &face, barycentric.data(), 1, out.data()));
    return out;
  }

 private:
  capmesh_v1_map *handle_ = nullptr;
  std::string report_;
};

/// Map `mesh` onto its cap and keep the map (with its report).
inline CapMap parameterize_map(const capmesh_v1_mesh_view &mesh, const ParamOptions &options = {},
                               const Progress &progress = {}) {
  detail::ProgressBridge bridge{&progress, nullptr};
  capmesh_v1_map *out = nullptr;
  char *report = nullptr;
  capmesh_v1_status s = capmesh_v1_parameterize_map(&mesh, &options, bridge.fn(), &bridge, &out, &report);
  CapMap map(out, detail::take_string(report));
  bridge.finish(s);
  return map;
}

}  // namespace capmesh

#endif  // CAPMESH_MAP_HPP
