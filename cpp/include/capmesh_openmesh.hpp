// capmesh <-> OpenMesh: convert OpenMesh triangle meshes (OpenMesh::TriMesh_ArrayKernelT<T>,
// float or double points) to capmesh's flat arrays and capmesh results back to OpenMesh.
//
//   capmesh::openmesh::to_arrays(mesh)            -> capmesh::Arrays (view() for the C ABI)
//   capmesh::openmesh::to_mesh<MyMesh>(result)    -> MyMesh
//   capmesh::openmesh::remesh / parameterize / harmonics   OpenMesh in, OpenMesh out
//   capmesh::openmesh::parameterize_map(mesh)     -> capmesh::CapMap (inverse / forward map)
//   capmesh::openmesh::face_handles(mesh)         -> the OpenMesh face of each capmesh face index
//
// Vertices deleted (status flag) are skipped and the rest renumbered in iteration order;
// faces must be triangles. Include OpenMesh before this header.
#ifndef CAPMESH_OPENMESH_HPP
#define CAPMESH_OPENMESH_HPP

#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>

#include "capmesh_map.hpp"

namespace capmesh {
namespace openmesh {

/// Flat arrays of an OpenMesh triangle mesh (xyz as double, 0-based indices).
/// Throws std::invalid_argument for a face that is not a triangle or a mesh too large for
/// 32-bit indices.
template <class OMesh>
Arrays to_arrays(const OMesh &mesh) {
  Arrays out;
  const std::size_t unset = std::numeric_limits<std::size_t>::max();
  std::vector<std::size_t> index(mesh.n_vertices(), unset);
  std::size_t next = 0;
  out.positions.reserve(3 * mesh.n_vertices());
  for (auto vh : mesh.vertices()) {  // skips deleted vertices
    const auto &p = mesh.point(vh);
    out.positions.push_back(static_cast<double>(p[0]));
    out.positions.push_back(static_cast<double>(p[1]));
    out.positions.push_back(static_cast<double>(p[2]));
    index[static_cast<std::size_t>(vh.idx())] = next++;
  }
  if (next > std::numeric_limits<uint32_t>::max()) throw std::invalid_argument("capmesh: too many vertices for 32-bit indices");
  out.triangles.reserve(3 * mesh.n_faces());
  for (auto fh : mesh.faces()) {
    std::size_t corners = 0;
    for (auto vh : mesh.fv_range(fh)) {
      if (++corners > 3) break;
      out.triangles.push_back(static_cast<uint32_t>(index[static_cast<std::size_t>(vh.idx())]));
    }
    if (corners != 3) throw std::invalid_argument("capmesh: face " + std::to_string(fh.idx()) + " is not a triangle");
  }
  return out;
}

/// An OpenMesh mesh with the vertices and triangles of `mesh` (points converted to
/// OMesh::Point's scalar). Throws std::runtime_error when OpenMesh refuses a face (a complex
/// edge or vertex).
template <class OMesh>
OMesh to_mesh(const Mesh &mesh) {
  using Scalar = typename OMesh::Point::value_type;
  OMesh out;
  const std::size_t nv = mesh.vertex_count(), nf = mesh.face_count();
  const double *p = mesh.positions();
  const uint32_t *t = mesh.triangles();
  std::vector<typename OMesh::VertexHandle> handles;
  handles.reserve(nv);
  for (std::size_t v = 0; v < nv; ++v)
    handles.push_back(out.add_vertex(typename OMesh::Point(static_cast<Scalar>(p[3 * v]), static_cast<Scalar>(p[3 * v + 1]),
                                                           static_cast<Scalar>(p[3 * v + 2]))));
  for (std::size_t f = 0; f < nf; ++f) {
    auto fh = out.add_face(handles[t[3 * f]], handles[t[3 * f + 1]], handles[t[3 * f + 2]]);
    if (!fh.is_valid()) throw std::runtime_error("capmesh: OpenMesh refused triangle " + std::to_string(f) + " (complex edge or vertex)");
  }
  return out;
}

/// Result of the OpenMesh-level entry points.
template <class OMesh>
struct MeshResult {
  OMesh mesh;
  std::string report_json;
};

/// capmesh::remesh with OpenMesh in and out.
template <class OMesh>
MeshResult<OMesh> remesh(const OMesh &mesh, const RemeshOptions &options = {}, const Progress &progress = {}) {
  Arrays in = to_arrays(mesh);
  Result r = capmesh::remesh(in.view(), options, progress);
  return {to_mesh<OMesh>(r.mesh), std::move(r.report_json)};
}

/// capmesh::parameterize with OpenMesh in and out (the cap mesh).
template <class OMesh>
MeshResult<OMesh> parameterize(const OMesh &mesh, const ParamOptions &options = {}, const Progress &progress = {}) {
  Arrays in = to_arrays(mesh);
  Result r = capmesh::parameterize(in.view(), options, progress);
  return {to_mesh<OMesh>(r.mesh), std::move(r.report_json)};
}

/// capmesh::harmonics with OpenMesh in and out (the reconstruction).
template <class OMesh>
MeshResult<OMesh> harmonics(const OMesh &mesh, const HarmonicsOptions &options = {}, const Progress &progress = {}) {
  Arrays in = to_arrays(mesh);
  Result r = capmesh::harmonics(in.view(), options, progress);
  return {to_mesh<OMesh>(r.mesh), std::move(r.report_json)};
}

/// capmesh::parameterize_map of an OpenMesh mesh: the map, whose inverse gives faces in
/// the numbering of to_arrays (face_handles() turns them into OpenMesh handles) and whose
/// cap positions follow the non-deleted vertices in iteration order.
template <class OMesh>
CapMap parameterize_map(const OMesh &mesh, const ParamOptions &options = {}, const Progress &progress = {}) {
  Arrays in = to_arrays(mesh);
  return capmesh::parameterize_map(in.view(), options, progress);
}

/// The OpenMesh face handle of each face index capmesh uses for `mesh` (its non-deleted faces
/// in iteration order, as to_arrays numbers them).
template <class OMesh>
std::vector<typename OMesh::FaceHandle> face_handles(const OMesh &mesh) {
  std::vector<typename OMesh::FaceHandle> out;
  out.reserve(mesh.n_faces());
  for (auto fh : mesh.faces()) out.push_back(fh);
  return out;
}

}  // namespace openmesh
}  // namespace capmesh

#endif  // CAPMESH_OPENMESH_HPP
