// capmesh C++ wrapper: header-only RAII over the C ABI in capmesh.h.
//
//   capmesh::Mesh        owns a capmesh_v1_mesh* (move-only, freed in the destructor)
//   capmesh::Error       thrown on every non-OK status: status() and the library's message
//   capmesh::Progress    std::function<bool(Stage, double, const char*)>; return false to cancel
//   capmesh::parameterize / remesh / harmonics / metrics   the four entry points
//   capmesh::remesh_located   remesh, each new vertex with its input face and barycentrics
//   capmesh::CapMap           the map as an object (inverse and forward map): capmesh_map.hpp
//
// Inputs are capmesh_v1_mesh_view (pointers into the caller's arrays); capmesh::Arrays owns
// flat arrays and hands out such a view. capmesh_openmesh.hpp converts OpenMesh meshes.
//
// An exception thrown by the progress callback cancels the computation and is rethrown by the
// entry point after capmesh returned (it never unwinds through the C ABI).
//
// Link with libcapmesh.so or libcapmesh.a (cargo build --release --no-default-features --features capi); the static
// library also needs -lpthread -ldl -lm.
#ifndef CAPMESH_HPP
#define CAPMESH_HPP

#include <cstddef>
#include <cstdint>
#include <exception>
#include <functional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "capmesh.h"

namespace capmesh {

/// Status codes of the C ABI.
enum class Status : int32_t {
  Ok = CAPMESH_V1_OK,
  InvalidArgument = CAPMESH_V1_INVALID_ARGUMENT,
  InvalidMesh = CAPMESH_V1_INVALID_MESH,
  Numerical = CAPMESH_V1_NUMERICAL,
  Unsupported = CAPMESH_V1_UNSUPPORTED,
  Cancelled = CAPMESH_V1_CANCELLED,
  Internal = CAPMESH_V1_INTERNAL,
};

/// Short name of a status ("invalid mesh", ...).
inline const char *status_name(Status s) {
  switch (s) {
    case Status::Ok: return "ok";
    case Status::InvalidArgument: return "invalid argument";
    case Status::InvalidMesh: return "invalid mesh";
    case Status::Numerical: return "numerical failure";
    case Status::Unsupported: return "unsupported";
    case Status::Cancelled: return "cancelled";
    case Status::Internal: return "internal error";
  }
  return "unknown status";
}

/// A failed capmesh call: the status and capmesh_v1_last_error() at the time of the failure.
class Error : public std::runtime_error {
 public:
  Error(Status status, const std::string &message)
      : std::runtime_error(std::string(status_name(status)) + ": " + message), status_(status), message_(message) {}
  Status status() const noexcept { return status_; }
  /// The library's message alone (what() prefixes the status name).
  const std::string &message() const noexcept { return message_; }

 private:
  Status status_;
  std::string message_;
};

/// Pipeline stages reported to the progress callback.
enum class Stage : int32_t {
  Validate = CAPMESH_V1_STAGE_VALIDATE,
  Flatten = CAPMESH_V1_STAGE_FLATTEN,
  RadiusSearch = CAPMESH_V1_STAGE_RADIUS_SEARCH,
  Transport = CAPMESH_V1_STAGE_TRANSPORT,
  Project = CAPMESH_V1_STAGE_PROJECT,
  Remesh = CAPMESH_V1_STAGE_REMESH,
  Harmonics = CAPMESH_V1_STAGE_HARMONICS,
};

/// What the remesh optimises after the pull-back (capmesh_v1_remesh_options.optimize).
enum class Optimize : int32_t {
  /// Shape stage then area equalization: well-shaped triangles of near-equal area (default).
  ShapeAndArea = CAPMESH_V1_OPTIMIZE_SHAPE_AND_AREA,
  /// Area equalization alone: the cap grid's connectivity, near-equal areas.
  Area = CAPMESH_V1_OPTIMIZE_AREA,
  /// The paper's plain pull-back (CAPMESH_V1_OPTIMIZE_NONE; not `None`, a macro of X11).
  Plain = CAPMESH_V1_OPTIMIZE_NONE,
};

/// Whether the shape stage puts vertices on the input's creases.
enum class Creases : int32_t {
  /// Kept with curvature sizing only (default).
  Auto = CAPMESH_V1_CREASES_AUTO,
  /// Kept.
  Keep = CAPMESH_V1_CREASES_KEEP,
  /// Not kept.
  Off = CAPMESH_V1_CREASES_OFF,
};

/// Progress sink: completed fraction of `stage` in [0, 1] and a short message. Return false to
/// cancel (the call then throws Error with Status::Cancelled). Called on the calling thread.
using Progress = std::function<bool(Stage stage, double fraction, const char *message)>;

/// Library version string.
inline std::string version() { return capmesh_v1_version(); }

/// A mesh returned by capmesh (owning, move-only).
class Mesh {
 public:
  Mesh() noexcept = default;
  /// Take ownership of a handle returned by the C ABI.
  explicit Mesh(capmesh_v1_mesh *handle) noexcept : handle_(handle) {}
  Mesh(const Mesh &) = delete;
  Mesh &operator=(const Mesh &) = delete;
  Mesh(Mesh &&other) noexcept : handle_(std::exchange(other.handle_, nullptr)) {}
  Mesh &operator=(Mesh &&other) noexcept {
    if (this != &other) {
      capmesh_v1_mesh_free(handle_);
      handle_ = std::exchange(other.handle_, nullptr);
    }
    return *this;
  }
  ~Mesh() { capmesh_v1_mesh_free(handle_); }

  std::size_t vertex_count() const noexcept { return capmesh_v1_mesh_vertex_count(handle_); }
  std::size_t face_count() const noexcept { return capmesh_v1_mesh_face_count(handle_); }
  /// 3 * vertex_count() coordinates, valid while this Mesh lives.
  const double *positions() const noexcept { return capmesh_v1_mesh_positions(handle_); }
  /// 3 * face_count() vertex indices, valid while this Mesh lives.
  const uint32_t *triangles() const noexcept { return capmesh_v1_mesh_triangles(handle_); }
  /// For a mesh from remesh_located(): vertex_count() input face indices, one per vertex;
  /// nullptr otherwise. Valid while this Mesh lives.
  const uint32_t *source_faces() const noexcept { return capmesh_v1_mesh_source_faces(handle_); }
  /// For a mesh from remesh_located(): 3 * vertex_count() weights of the corners of each
  /// vertex's input face (in that face's order); nullptr otherwise.
  const double *source_barycentrics() const noexcept { return capmesh_v1_mesh_source_barycentrics(handle_); }
  /// A view of this mesh, to pass it back into capmesh (e.g. to metrics()).
  capmesh_v1_mesh_view view() const noexcept { return {positions(), vertex_count(), triangles(), face_count()}; }
  capmesh_v1_mesh *get() const noexcept { return handle_; }
  explicit operator bool() const noexcept { return handle_ != nullptr; }

 private:
  capmesh_v1_mesh *handle_ = nullptr;
};

/// Flat caller-side arrays (xyz per vertex, three indices per triangle) and their view.
struct Arrays {
  std::vector<double> positions;
  std::vector<uint32_t> triangles;
  /// View into the arrays, valid while they are not modified.
  capmesh_v1_mesh_view view() const noexcept {
    return {positions.data(), positions.size() / 3, triangles.data(), triangles.size() / 3};
  }
};

/// Parameterization options with capmesh's defaults (see capmesh.h for each field).
struct ParamOptions : capmesh_v1_param_options {
  ParamOptions() : capmesh_v1_param_options(capmesh_v1_param_options_default()) {}
};

/// Remeshing options with capmesh's defaults (uniform grid of about 5000 faces, shape+area
/// optimisation with 40 relaxation and up to 85 polish iterations, shape weight 0.13, edge
/// splits and collapses on).
/// The fields of capmesh_v1_remesh_options can be set directly; the with_* setters chain.
struct RemeshOptions : capmesh_v1_remesh_options {
  RemeshOptions() : capmesh_v1_remesh_options(capmesh_v1_remesh_options_default()) {}
  /// What is optimised after the pull-back.
  RemeshOptions &with_optimize(Optimize o) {
    optimize = static_cast<int32_t>(o);
    return *this;
  }
  /// Relaxation and polish iterations of the shape stage.
  RemeshOptions &with_shape_iterations(uint32_t relax, uint32_t polish) {
    relax_iterations = relax;
    polish_iterations = polish;
    return *this;
  }
  /// Weight of the shape term against the area term in the polish (>= 0).
  RemeshOptions &with_shape_weight(double weight) {
    shape_weight = weight;
    return *this;
  }
  /// Split long and collapse short edges in the shape stage.
  RemeshOptions &with_resample(bool on) {
    resample = on ? 1 : 0;
    return *this;
  }
  /// Equal surface areas covered through the map: a uniform vertex density on the surface,
  /// closer to folded inputs, less equal chord areas (the CLI's `--sizing surface`).
  RemeshOptions &with_surface_sizing() {
    sizing = CAPMESH_V1_SIZING_SURFACE;
    return *this;
  }
  /// Smaller faces where the surface is curved, of strength > 0 (the CLI's
  /// `--sizing curvature=S`; 3 for `--sizing curvature`).
  RemeshOptions &with_curvature_sizing(double strength = 3.0) {
    sizing = CAPMESH_V1_SIZING_CURVATURE;
    sizing_strength = strength;
    return *this;
  }
  /// Whether vertices are put on the input's creases and joined by edges (the CLI's
  /// `--creases auto|keep|off`; auto, the default, keeps them with curvature sizing only).
  RemeshOptions &with_creases(Creases c) {
    creases = static_cast<int32_t>(c);
    return *this;
  }
  /// The crease bound in degrees, in (0, 180): input edges bent more are creases, and no edge
  /// flip bends a pair of faces more (the CLI's `--crease-angle`; 60 by default).
  RemeshOptions &with_crease_angle(double degrees) {
    crease_deg = degrees;
    return *this;
  }
  /// The polish stops once an iteration moves the vertices by less than this root mean
  /// square, in edge lengths, after its global area steps (>= 0; 0: every iteration runs).
  RemeshOptions &with_polish_tolerance(double tolerance) {
    polish_tolerance = tolerance;
    return *this;
  }
  /// Fill each hole of an open surface with a fan of faces and remesh the closed surface (the
  /// CLI's `--fill-holes`).
  RemeshOptions &with_fill_holes(bool on) {
    fill_holes = on ? 1 : 0;
    return *this;
  }
  /// Map an input with fewer faces than the remesh through a midpoint-subdivided copy, and
  /// split its edges longer than three times the remesh's (true, the default), or map it as it is
  /// (false: the CLI's `--no-subdivide`).
  RemeshOptions &with_subdivide_coarse(bool on) {
    subdivide_coarse = on ? 1 : 0;
    return *this;
  }
  /// With the shape stage, map a closed input of many more vertices than the remesh needs
  /// through a decimated copy sized to the remesh (true, the default) or at the detail of the
  /// parameterization options (false: the CLI's `--fine-map`; always so without the stage).
  RemeshOptions &with_coarse_map(bool on) {
    coarse_map = on ? 1 : 0;
    return *this;
  }
  /// Leave the vertices on the input surface (true) instead of fitting the faces to it in the
  /// least-squares sense (the default; the CLI's `--placement`).
  RemeshOptions &with_vertices_on_surface(bool on) {
    placement = on ? CAPMESH_V1_PLACEMENT_ON_SURFACE : CAPMESH_V1_PLACEMENT_FITTED;
    return *this;
  }
  /// Uniform grid of about `faces` faces.
  static RemeshOptions uniform(uint32_t faces) {
    RemeshOptions o;
    o.grid = CAPMESH_V1_GRID_UNIFORM;
    o.faces = faces;
    return o;
  }
  /// Latitude/longitude grid.
  static RemeshOptions lat_long(uint32_t rings, uint32_t sectors) {
    RemeshOptions o;
    o.grid = CAPMESH_V1_GRID_LAT_LONG;
    o.rings = rings;
    o.sectors = sectors;
    return o;
  }
};

/// Harmonics options with capmesh's defaults (order 10, the paper's adaptive harmonics); set
/// `basis = CAPMESH_V1_BASIS_SCHA` for spherical cap harmonics, `resample_faces` for a cap grid.
struct HarmonicsOptions : capmesh_v1_harmonics_options {
  HarmonicsOptions() : capmesh_v1_harmonics_options(capmesh_v1_harmonics_options_default()) {}
  explicit HarmonicsOptions(uint32_t max_order) : HarmonicsOptions() { order = max_order; }
};

/// A result mesh and its JSON report.
struct Result {
  Mesh mesh;
  std::string report_json;
};

namespace detail {

/// Owns a char* returned by capmesh.
inline std::string take_string(char *text) {
  if (text == nullptr) return {};
  std::string out(text);
  capmesh_v1_string_free(text);
  return out;
}

/// Throws Error for a non-OK status, with the thread's last error text.
inline void check(capmesh_v1_status status) {
  if (status != CAPMESH_V1_OK) throw Error(static_cast<Status>(status), capmesh_v1_last_error());
}

/// Bridges a Progress to the C callback; keeps an exception thrown by it for rethrowing.
struct ProgressBridge {
  const Progress *progress;
  std::exception_ptr exception;

  static int32_t call(void *user, int32_t stage, double fraction, const char *message) noexcept {
    auto *self = static_cast<ProgressBridge *>(user);
    try {
      return (*self->progress)(static_cast<Stage>(stage), fraction, message) ? 0 : 1;
    } catch (...) {
      self->exception = std::current_exception();
      return 1;
    }
  }

  capmesh_v1_progress_fn fn() const noexcept { return (progress != nullptr && *progress) ? &ProgressBridge::call : nullptr; }

  /// After the C call: rethrow the callback's exception, else throw for a non-OK status.
  void finish(capmesh_v1_status status) const {
    if (exception) std::rethrow_exception(exception);
    check(status);
  }
};

}  // namespace detail

/// Map `mesh` onto its cap. Result: the input connectivity with the vertices on the cap.
inline Result parameterize(const capmesh_v1_mesh_view &mesh, const ParamOptions &options = {},
                           const Progress &progress = {}) {
  detail::ProgressBridge bridge{&progress, nullptr};
  capmesh_v1_mesh *out = nullptr;
  char *report = nullptr;
  capmesh_v1_status s = capmesh_v1_parameterize(&mesh, &options, bridge.fn(), &bridge, &out, &report);
  Result r{Mesh(out), detail::take_string(report)};
  bridge.finish(s);
  return r;
}

/// Remesh an open disk-like surface through its cap.
inline Result remesh(const capmesh_v1_mesh_view &mesh, const RemeshOptions &options = {},
                     const Progress &progress = {}) {
  detail::ProgressBridge bridge{&progress, nullptr};
  capmesh_v1_mesh *out = nullptr;
  char *report = nullptr;
  capmesh_v1_status s = capmesh_v1_remesh(&mesh, &options, bridge.fn(), &bridge, &out, &report);
  Result r{Mesh(out), detail::take_string(report)};
  bridge.finish(s);
  return r;
}

/// remesh(), also recording each new vertex's point of the input (Mesh::source_faces() and
/// Mesh::source_barycentrics()), to carry per-vertex data (colour, quality, ...) across.
inline Result remesh_located(const capmesh_v1_mesh_view &mesh, const RemeshOptions &options = {},
                             const Progress &progress = {}) {
  detail::ProgressBridge bridge{&progress, nullptr};
  capmesh_v1_mesh *out = nullptr;
  char *report = nullptr;
  capmesh_v1_status s = capmesh_v1_remesh_located(&mesh, &options, bridge.fn(), &bridge, &out, &report);
  Result r{Mesh(out), detail::take_string(report)};
  bridge.finish(s);
  return r;
}

/// Fit harmonics up to options.order; result: the order-N reconstruction.
inline Result harmonics(const capmesh_v1_mesh_view &mesh, const HarmonicsOptions &options = {},
                        const Progress &progress = {}) {
  detail::ProgressBridge bridge{&progress, nullptr};
  capmesh_v1_mesh *out = nullptr;
  char *report = nullptr;
  capmesh_v1_status s = capmesh_v1_harmonics(&mesh, &options, bridge.fn(), &bridge, &out, &report);
  Result r{Mesh(out), detail::take_string(report)};
  bridge.finish(s);
  return r;
}

/// Remeshing quality of `remeshed` against `original`, as JSON.
inline std::string metrics(const capmesh_v1_mesh_view &original, const capmesh_v1_mesh_view &remeshed) {
  char *report = nullptr;
  capmesh_v1_status s = capmesh_v1_metrics(&original, &remeshed, &report);
  std::string out = detail::take_string(report);
  detail::check(s);
  return out;
}

}  // namespace capmesh

#endif  // CAPMESH_HPP
