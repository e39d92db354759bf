// The C++ wrapper and the OpenMesh adapter on real meshes read with OpenMesh.
// Usage: capmesh_cpp_tests CASE MESH_DIR WORK_DIR   (one CTest test per CASE)
#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/PolyMesh_ArrayKernelT.hh>
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <functional>
#include <map>
#include <set>
#include <stdexcept>
#include <string>

#include "capmesh_openmesh.hpp"
#include <array>

namespace {

struct DoubleTraits : OpenMesh::DefaultTraits {
  typedef OpenMesh::Vec3d Point;
  typedef OpenMesh::Vec3d Normal;
};
using DMesh = OpenMesh::TriMesh_ArrayKernelT<DoubleTraits>;
using FMesh = OpenMesh::TriMesh_ArrayKernelT<>;

int failures = 0;
#define CHECK(cond)                                                                 \
  do {                                                                              \
    if (!(cond)) {                                                                  \
      std::fprintf(stderr, "%s:%d: CHECK failed: %s\n", __FILE__, __LINE__, #cond); \
      ++failures;                                                                   \
    }                                                                               \
  } while (0)

std::string mesh_dir, work_dir;

template <class M>
M read(const std::string &name) {
  M mesh;
  if (!OpenMesh::IO::read_mesh(mesh, mesh_dir + "/" + name)) throw std::runtime_error("OpenMesh cannot read " + name);
  return mesh;
}

/// Lines starting with "f " in an OBJ file: what OpenMesh must have read.
std::size_t obj_faces(const std::string &name) {
  std::ifstream in(mesh_dir + "/" + name);
  std::string line;
  std::size_t n = 0;
  while (std::getline(in, line))
    if (line.rfind("f ", 0) == 0) ++n;
  return n;
}

/// A number in a flat JSON report: the first "key": value.
double json_number(const std::string &json, const std::string &key) {
  auto at = json.find("\"" + key + "\":");
  if (at == std::string::npos) throw std::runtime_error("no " + key + " in report");
  return std::strtod(json.c_str() + at + key.size() + 3, nullptr);
}

template <class M>
int boundary_loops(const M &mesh) {
  std::set<int> seen;
  int loops = 0;
  for (auto h : mesh.halfedges()) {
    if (!mesh.is_boundary(h) || seen.count(h.idx())) continue;
    ++loops;
    auto g = h;
    do {
      seen.insert(g.idx());
      g = mesh.next_halfedge_handle(g);
    } while (g != h);
  }
  return loops;
}

template <class M>
long euler(const M &mesh) {
  return static_cast<long>(mesh.n_vertices()) - static_cast<long>(mesh.n_edges()) + static_cast<long>(mesh.n_faces());
}

const char *helmet = "open_meg_helmet_babysquid_mne.obj";
const char *bunny = "closed_bunny_npm.obj";

void remesh_uniform_openmesh() {
  FMesh input = read<FMesh>(helmet);  // OpenMesh's default float mesh
  CHECK(input.n_faces() == obj_faces(helmet));
  CHECK(boundary_loops(input) == 1);
  auto out = capmesh::openmesh::remesh(input, capmesh::RemeshOptions::uniform(2000));
  const double faces = static_cast<double>(out.mesh.n_faces());
  std::printf("helmet %zu faces -> %zu faces (2000 asked), d_face_relative %.4f\n", input.n_faces(), out.mesh.n_faces(),
              json_number(out.report_json, "d_face_relative"));
  CHECK(std::fabs(faces - 2000.0) <= 200.0);
  CHECK(json_number(out.report_json, "faces") == faces);
  CHECK(boundary_loops(out.mesh) == 1);  // still an open disk
  CHECK(euler(out.mesh) == 1);
  CHECK(json_number(out.report_json, "d_surface_sampled_relative") < 0.01);
  // Written and read back by OpenMesh.
  const std::string path = work_dir + "/helmet_remeshed.off";
  CHECK(OpenMesh::IO::write_mesh(out.mesh, path));
  FMesh back = read<FMesh>("../helmet_remeshed.off");
  CHECK(back.n_faces() == out.mesh.n_faces());
}

void remesh_lat_long() {
  DMesh input = read<DMesh>(helmet);
  auto out = capmesh::openmesh::remesh(input, capmesh::RemeshOptions::lat_long(10, 24));
  std::printf("lat-long 10 x 24: %zu faces\n", out.mesh.n_faces());
  CHECK(out.mesh.n_faces() == 24u + 2u * 24u * 9u);  // pole fan + two triangles per quad
  CHECK(boundary_loops(out.mesh) == 1);
}

void closed_bunny() {
  DMesh input = read<DMesh>(bunny);
  CHECK(input.n_faces() == obj_faces(bunny));
  CHECK(boundary_loops(input) == 0);
  capmesh::ParamOptions options;
  options.smoothing = 0.0;
  auto out = capmesh::openmesh::parameterize(input, options);
  CHECK(out.mesh.n_vertices() == input.n_vertices());
  CHECK(out.mesh.n_faces() == input.n_faces());
  CHECK(boundary_loops(out.mesh) == 0);  // closed in, closed out
  CHECK(euler(out.mesh) == 2);
  double worst = 0.0;
  for (auto v : out.mesh.vertices()) worst = std::max(worst, std::fabs(out.mesh.point(v).norm() - 1.0));
  std::printf("bunny on the sphere: max | |p| - 1 | = %.2e, Z* = %.4f\n", worst, json_number(out.report_json, "z_star"));
  CHECK(worst < 1e-9);
  // Remeshing a closed surface gives a closed genus-0 mesh.
  auto remeshed = capmesh::openmesh::remesh(input, capmesh::RemeshOptions::uniform(2000));
  const double faces = static_cast<double>(remeshed.mesh.n_faces());
  std::printf("bunny remeshed: %zu faces (2000 asked)\n", remeshed.mesh.n_faces());
  CHECK(std::fabs(faces - 2000.0) <= 200.0);
  CHECK(boundary_loops(remeshed.mesh) == 0);
  CHECK(euler(remeshed.mesh) == 2);
}

void harmonics() {
  DMesh input = read<DMesh>(helmet);
  auto out = capmesh::openmesh::harmonics(input, capmesh::HarmonicsOptions(6));
  CHECK(out.mesh.n_faces() == input.n_faces());
  CHECK(json_number(out.report_json, "order") == 6.0);
  CHECK(out.report_json.find("\"errors_by_order\"") != std::string::npos);
}

void metrics() {
  DMesh input = read<DMesh>(helmet);
  capmesh::Arrays arrays = capmesh::openmesh::to_arrays(input);
  capmesh::Result r = capmesh::remesh(arrays.view(), capmesh::RemeshOptions::uniform(1000));
  std::string m = capmesh::metrics(arrays.view(), r.mesh.view());
  CHECK(json_number(m, "faces") == static_cast<double>(r.mesh.face_count()));
  CHECK(std::fabs(json_number(m, "d_face_relative") - json_number(r.report_json, "d_face_relative")) < 1e-12);
  // Identical meshes: zero surface distance (up to rounding).
  std::string self = capmesh::metrics(arrays.view(), arrays.view());
  std::printf("self distance %.3e\n", json_number(self, "d_surface_sampled_relative"));
  CHECK(json_number(self, "d_surface_sampled_relative") < 1e-12);
}

void cancel_by_callback() {
  DMesh input = read<DMesh>(helmet);
  int calls = 0;
  std::set<capmesh::Stage> stages;
  capmesh::Progress stop_third = [&](capmesh::Stage stage, double fraction, const char *) {
    CHECK(fraction >= 0.0 && fraction <= 1.0);
    stages.insert(stage);
    return ++calls < 3;
  };
  try {
    capmesh::openmesh::remesh(input, capmesh::RemeshOptions::uniform(1000), stop_third);
    CHECK(false);
  } catch (const capmesh::Error &e) {
    CHECK(e.status() == capmesh::Status::Cancelled);
    CHECK(!e.message().empty());
  }
  CHECK(calls == 3);
  CHECK(stages.count(capmesh::Stage::Validate) == 1);
  // A callback that never cancels sees the remesh stage and lets the call finish.
  calls = 0;
  stages.clear();
  capmesh::Progress keep = [&](capmesh::Stage stage, double, const char *) {
    stages.insert(stage);
    ++calls;
    return true;
  };
  auto out = capmesh::openmesh::remesh(input, capmesh::RemeshOptions::uniform(1000), keep);
  CHECK(out.mesh.n_faces() > 0);
  CHECK(stages.count(capmesh::Stage::Remesh) == 1);
}

void callback_exception() {
  DMesh input = read<DMesh>(helmet);
  capmesh::Progress thrower = [](capmesh::Stage, double, const char *) -> bool { throw std::logic_error("stop here"); };
  try {
    capmesh::openmesh::parameterize(input, capmesh::ParamOptions(), thrower);
    CHECK(false);
  } catch (const std::logic_error &e) {
    CHECK(std::string(e.what()) == "stop here");  // the callback's own exception, rethrown
  }
}

/// The remesh options of the shape stage reach capmesh: the default is shape+area, Area skips
/// the shape stage, the iteration counts are used, an unknown optimisation is refused.
void optimize_options() {
  DMesh input = read<DMesh>(helmet);
  capmesh::RemeshOptions o = capmesh::RemeshOptions::uniform(1000);
  CHECK(o.optimize == CAPMESH_V1_OPTIMIZE_SHAPE_AND_AREA);
  CHECK(o.relax_iterations == 40 && o.polish_iterations == 85 && o.area_steps == 6 && o.shape_weight == 0.13 && o.resample == 1 && o.creases == CAPMESH_V1_CREASES_AUTO);
  CHECK(capmesh::RemeshOptions::uniform(1000).with_creases(capmesh::Creases::Keep).creases == CAPMESH_V1_CREASES_KEEP);
  CHECK(o.crease_deg == 60.0 && capmesh::RemeshOptions::uniform(1000).with_crease_angle(45.0).crease_deg == 45.0);
  CHECK(o.polish_tolerance == 1e-3 && capmesh::RemeshOptions::uniform(1000).with_polish_tolerance(0.0).polish_tolerance == 0.0);
  CHECK(o.fill_holes == 0 && capmesh::RemeshOptions::uniform(1000).with_fill_holes(true).fill_holes == 1);
  CHECK(o.subdivide_coarse == 1 && capmesh::RemeshOptions::uniform(1000).with_subdivide_coarse(false).subdivide_coarse == 0);
  CHECK(o.coarse_map == 1 && capmesh::RemeshOptions::uniform(1000).with_coarse_map(false).coarse_map == 0);
  CHECK(o.placement == CAPMESH_V1_PLACEMENT_FITTED);
  CHECK(capmesh::RemeshOptions::uniform(1000).with_vertices_on_surface(true).placement == CAPMESH_V1_PLACEMENT_ON_SURFACE);
  auto shaped = capmesh::openmesh::remesh(input, o);
  CHECK(shaped.report_json.find("\"optimize\":\"shape+area\"") != std::string::npos);
  auto area = capmesh::openmesh::remesh(input, capmesh::RemeshOptions::uniform(1000).with_optimize(capmesh::Optimize::Area));
  CHECK(area.report_json.find("\"optimize\":\"area\"") != std::string::npos);
  CHECK(o.sizing == CAPMESH_V1_SIZING_UNIFORM && o.sizing_strength == 3.0);
  CHECK(capmesh::RemeshOptions::uniform(1000).with_curvature_sizing(2.0).sizing == CAPMESH_V1_SIZING_CURVATURE);
  auto few = capmesh::openmesh::remesh(input, capmesh::RemeshOptions::uniform(1000).with_shape_iterations(2, 3).with_surface_sizing());
  CHECK(few.report_json.find("\"sizing\":\"surface\"") != std::string::npos);
  const auto shape_at = few.report_json.find("\"shape\":{");
  CHECK(shape_at != std::string::npos);
  if (shape_at != std::string::npos) CHECK(json_number(few.report_json.substr(shape_at), "iterations") == 5.0);
  std::printf("shape+area %zu faces, area %zu faces\n", shaped.mesh.n_faces(), area.mesh.n_faces());
  capmesh::RemeshOptions bad = capmesh::RemeshOptions::uniform(1000);
  bad.optimize = 7;
  try {
    capmesh::openmesh::remesh(input, bad);
    CHECK(false);
  } catch (const capmesh::Error &e) {
    CHECK(e.status() == capmesh::Status::InvalidArgument);
    CHECK(e.message().find("optimize = 7") != std::string::npos);
  }
}

void misuse_raw() {
  DMesh input = read<DMesh>(helmet);
  capmesh::Arrays a = capmesh::openmesh::to_arrays(input);
  capmesh_v1_mesh *out = nullptr;
  // NULL view
  CHECK(capmesh_v1_remesh(nullptr, nullptr, nullptr, nullptr, &out, nullptr) == CAPMESH_V1_INVALID_ARGUMENT);
  CHECK(std::strlen(capmesh_v1_last_error()) > 0);
  // NULL positions with a nonzero count
  capmesh_v1_mesh_view v = a.view();
  v.positions = nullptr;
  CHECK(capmesh_v1_parameterize(&v, nullptr, nullptr, nullptr, &out, nullptr) == CAPMESH_V1_INVALID_ARGUMENT);
  CHECK(std::strstr(capmesh_v1_last_error(), "positions") != nullptr);
  // Out-of-range index
  capmesh::Arrays bad = a;
  bad.triangles[7] = 1u << 30;
  const capmesh_v1_mesh_view bad_view = bad.view();
  CHECK(capmesh_v1_remesh(&bad_view, nullptr, nullptr, nullptr, &out, nullptr) == CAPMESH_V1_INVALID_MESH);
  CHECK(std::strstr(capmesh_v1_last_error(), "refers to vertex") != nullptr);
  // Count mismatch: a vertex count smaller than the indices use
  const capmesh_v1_mesh_view good = a.view();
  v = a.view();
  v.vertex_count /= 2;
  CHECK(capmesh_v1_remesh(&v, nullptr, nullptr, nullptr, &out, nullptr) == CAPMESH_V1_INVALID_MESH);
  CHECK(std::strlen(capmesh_v1_last_error()) > 0);
  // Zero faces, NULL output pointer, bad option values
  v = a.view();
  v.face_count = 0;
  CHECK(capmesh_v1_remesh(&v, nullptr, nullptr, nullptr, &out, nullptr) == CAPMESH_V1_INVALID_MESH);
  CHECK(capmesh_v1_remesh(&good, nullptr, nullptr, nullptr, nullptr, nullptr) == CAPMESH_V1_INVALID_ARGUMENT);
  capmesh_v1_remesh_options o = capmesh_v1_remesh_options_default();
  o.grid = 5;
  CHECK(capmesh_v1_remesh(&good, &o, nullptr, nullptr, &out, nullptr) == CAPMESH_V1_INVALID_ARGUMENT);
  CHECK(std::strlen(capmesh_v1_last_error()) > 0);
  CHECK(out == nullptr);
  char *report = nullptr;
  CHECK(capmesh_v1_metrics(&good, nullptr, &report) == CAPMESH_V1_INVALID_ARGUMENT);
  CHECK(report == nullptr);
}

void misuse_wrapper() {
  DMesh input = read<DMesh>(helmet);
  capmesh::Arrays bad = capmesh::openmesh::to_arrays(input);
  bad.positions[3 * 10 + 1] = std::nan("");
  try {
    capmesh::remesh(bad.view());
    CHECK(false);
  } catch (const capmesh::Error &e) {
    CHECK(e.status() == capmesh::Status::InvalidMesh);
    CHECK(e.message().find("vertex 10") != std::string::npos);
  }
  capmesh::RemeshOptions o = capmesh::RemeshOptions::uniform(0);
  try {
    capmesh::remesh(capmesh::openmesh::to_arrays(input).view(), o);
    CHECK(false);
  } catch (const capmesh::Error &e) {
    CHECK(e.status() == capmesh::Status::InvalidArgument);
  }
  // Moving and destroying empty handles is fine.
  capmesh::Mesh empty;
  capmesh::Mesh moved = std::move(empty);
  CHECK(!moved && moved.face_count() == 0);
}

void openmesh_adapter() {
  // float and double meshes give the same arrays up to float rounding.
  FMesh f = read<FMesh>(helmet);
  DMesh d = read<DMesh>(helmet);
  capmesh::Arrays af = capmesh::openmesh::to_arrays(f), ad = capmesh::openmesh::to_arrays(d);
  CHECK(af.triangles == ad.triangles);
  CHECK(af.positions.size() == ad.positions.size());
  double worst = 0.0;
  for (std::size_t i = 0; i < ad.positions.size(); ++i) worst = std::max(worst, std::fabs(af.positions[i] - ad.positions[i]));
  CHECK(worst < 1e-5);
  // Deleted vertices are skipped and faces renumbered.
  d.request_vertex_status();
  d.request_face_status();
  d.request_edge_status();
  d.request_halfedge_status();
  auto first = *d.vertices_begin();
  std::size_t faces_at_first = 0;
  for (auto fh : d.vf_range(first)) {
    (void)fh;
    ++faces_at_first;
  }
  d.delete_vertex(first, true);
  capmesh::Arrays after = capmesh::openmesh::to_arrays(d);
  CHECK(after.positions.size() == ad.positions.size() - 3);
  CHECK(after.triangles.size() == ad.triangles.size() - 3 * faces_at_first);
  for (uint32_t i : after.triangles) CHECK(i < after.positions.size() / 3);
  // A quad is refused.
  OpenMesh::PolyMesh_ArrayKernelT<> quad;
  std::vector<OpenMesh::PolyMesh_ArrayKernelT<>::VertexHandle> vh;
  for (int i = 0; i < 4; ++i) vh.push_back(quad.add_vertex({float(i % 2), float(i / 2), 0.f}));
  quad.add_face(vh[0], vh[1], vh[3], vh[2]);
  try {
    capmesh::openmesh::to_arrays(quad);
    CHECK(false);
  } catch (const std::invalid_argument &) {
  }
}

void cap_map() {
  // The wrapper: the cap vertices give the input vertices back, off-cap points are flagged,
  // the forward map returns to the cap; on an open and a closed surface.
  for (const char *name : {helmet, bunny}) {
    DMesh input = read<DMesh>(name);
    capmesh::Arrays arrays = capmesh::openmesh::to_arrays(input);
    capmesh::CapMap map = capmesh::parameterize_map(arrays.view());
    CHECK(map && map.vertex_count() == input.n_vertices() && map.face_count() == input.n_faces());
    CHECK(json_number(map.report_json(), "z_star") < 1.0);
    const auto points = map.inverse(map.cap_positions(), map.vertex_count());
    double worst = 0.0, worst_forward = 0.0;
    for (std::size_t v = 0; v < points.size(); ++v) {
      CHECK(points[v].located && points[v].face < input.n_faces());
      for (int k = 0; k < 3; ++k) worst = std::max(worst, std::fabs(points[v].position[k] - arrays.positions[3 * v + k]));
      const auto x = map.forward(points[v].face, points[v].barycentric);
      for (int k = 0; k < 3; ++k) worst_forward = std::max(worst_forward, std::fabs(x[k] - map.cap_positions()[3 * v + k]));
    }
    std::printf("%s: cap vertices back to the input within %.2e, forward within %.2e\n", name, worst, worst_forward);
    CHECK(worst < 1e-9);
    CHECK(worst_forward < 1e-6);
    const capmesh::SurfacePoint off = map.inverse(std::array<double, 3>{0.0, 0.0, 2.0});
    CHECK(!off.located && off.face == CAPMESH_V1_NO_FACE && std::isnan(off.position[0]));
    try {
      map.forward(static_cast<uint32_t>(input.n_faces()), {1.0, 0.0, 0.0});
      CHECK(false);
    } catch (const capmesh::Error &e) {
      CHECK(e.status() == capmesh::Status::InvalidArgument);
      CHECK(e.message().find("face") != std::string::npos);
    }
    // Moved, the map still works; the moved-from one is empty.
    capmesh::CapMap moved = std::move(map);
    CHECK(!map && moved.inverse(std::array<double, 3>{0.0, 0.0, 1.0}).located);
  }
}

void cap_map_openmesh() {
  // The OpenMesh adapter: the map of a float mesh, faces as OpenMesh handles, and
  // remesh_located's sources reproduce the remesh's positions on the input's faces.
  FMesh input = read<FMesh>(helmet);
  capmesh::CapMap map = capmesh::openmesh::parameterize_map(input);
  const auto handles = capmesh::openmesh::face_handles(input);
  CHECK(handles.size() == map.face_count());
  const auto point = map.inverse(std::array<double, 3>{0.0, 0.0, 1.0});
  CHECK(point.located);
  OpenMesh::Vec3d p(0, 0, 0);
  int corner = 0;
  for (auto v : input.fv_range(handles.at(point.face))) p += OpenMesh::vector_cast<OpenMesh::Vec3d>(input.point(v)) * point.barycentric[corner++];
  double d = 0.0;
  for (int k = 0; k < 3; ++k) d = std::max(d, std::fabs(p[k] - point.position[k]));
  CHECK(d < 1e-5);
  capmesh::Arrays arrays = capmesh::openmesh::to_arrays(input);
  // On the surface (fitted vertices sit off their source points along their normals).
  auto located = capmesh::remesh_located(arrays.view(), capmesh::RemeshOptions::uniform(1500).with_vertices_on_surface(true));
  const uint32_t *faces = located.mesh.source_faces();
  const double *weights = located.mesh.source_barycentrics();
  CHECK(faces != nullptr && weights != nullptr);
  double worst = 0.0;
  for (std::size_t v = 0; faces != nullptr && v < located.mesh.vertex_count(); ++v)
    for (int k = 0; k < 3; ++k) {
      double x = 0.0;
      for (int c = 0; c < 3; ++c) x += weights[3 * v + c] * arrays.positions[3 * arrays.triangles[3 * faces[v] + c] + k];
      worst = std::max(worst, std::fabs(x - located.mesh.positions()[3 * v + k]));
    }
  std::printf("remesh_located: %zu vertices on their input faces within %.2e\n", located.mesh.vertex_count(), worst);
  CHECK(worst < 1e-6);
  CHECK(capmesh::remesh(arrays.view(), capmesh::RemeshOptions::uniform(500)).mesh.source_faces() == nullptr);
}

}  // namespace

int main(int argc, char **argv) {
  if (argc < 4) {
    std::fprintf(stderr, "usage: %s CASE MESH_DIR WORK_DIR\n", argv[0]);
    return 2;
  }
  mesh_dir = argv[2];
  work_dir = argv[3];
  const std::map<std::string, std::function<void()>> cases = {
      {"remesh_uniform_openmesh", remesh_uniform_openmesh},
      {"remesh_lat_long", remesh_lat_long},
      {"closed_bunny", closed_bunny},
      {"harmonics", harmonics},
      {"metrics", metrics},
      {"cancel_by_callback", cancel_by_callback},
      {"callback_exception", callback_exception},
      {"optimize_options", optimize_options},
      {"misuse_raw", misuse_raw},
      {"misuse_wrapper", misuse_wrapper},
      {"openmesh_adapter", openmesh_adapter},
      {"cap_map", cap_map},
      {"cap_map_openmesh", cap_map_openmesh},
  };
  auto it = cases.find(argv[1]);
  if (it == cases.end()) {
    std::fprintf(stderr, "unknown case %s\n", argv[1]);
    return 2;
  }
  try {
    it->second();
  } catch (const std::exception &e) {
    std::fprintf(stderr, "unexpected exception: %s\n", e.what());
    ++failures;
  }
  std::printf("%s: %s\n", argv[1], failures ? "FAILED" : "passed");
  return failures ? 1 : 0;
}
