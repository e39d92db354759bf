// OpenMesh reader and writer behind src/openmesh/bridge.rs.
#include "capmesh/src/openmesh/shim.h"

#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>

#include <stdexcept>
#include <string>
#include <vector>

namespace capmesh_openmesh {
namespace {

struct DoubleTraits : OpenMesh::DefaultTraits {
  typedef OpenMesh::Vec3d Point;
  typedef OpenMesh::Vec3d Normal;
};
using Mesh = OpenMesh::TriMesh_ArrayKernelT<DoubleTraits>;

}  // namespace

void read_mesh(rust::Str path, rust::Vec<double> &positions, rust::Vec<uint32_t> &triangles) {
  const std::string file(path);
  Mesh mesh;
  OpenMesh::IO::Options options;
  if (!OpenMesh::IO::read_mesh(mesh, file, options)) {
    throw std::runtime_error("OpenMesh cannot read '" + file +
                             "' (missing file, unknown extension or a parse error; OpenMesh reads .om, .obj, .off, .ply, .stl)");
  }
  positions.reserve(3 * mesh.n_vertices());
  for (auto v : mesh.vertices()) {
    const auto &p = mesh.point(v);
    positions.push_back(p[0]);
    positions.push_back(p[1]);
    positions.push_back(p[2]);
  }
  triangles.reserve(3 * mesh.n_faces());
  for (auto f : mesh.faces()) {
    for (auto v : mesh.fv_range(f)) triangles.push_back(static_cast<uint32_t>(v.idx()));
  }
}

void write_mesh(rust::Str path, rust::Slice<const double> positions, rust::Slice<const uint32_t> triangles, bool binary) {
  const std::string file(path);
  Mesh mesh;
  const std::size_t nv = positions.size() / 3, nf = triangles.size() / 3;
  std::vector<Mesh::VertexHandle> handles;
  handles.reserve(nv);
  for (std::size_t v = 0; v < nv; ++v)
    handles.push_back(mesh.add_vertex(Mesh::Point(positions[3 * v], positions[3 * v + 1], positions[3 * v + 2])));
  for (std::size_t f = 0; f < nf; ++f) {
    auto fh = mesh.add_face(handles[triangles[3 * f]], handles[triangles[3 * f + 1]], handles[triangles[3 * f + 2]]);
    if (!fh.is_valid()) {
      throw std::runtime_error("OpenMesh refuses face " + std::to_string(f) +
                               " (a complex edge or vertex: OpenMesh stores manifold meshes only)");
    }
  }
  OpenMesh::IO::Options options;
  if (binary) options += OpenMesh::IO::Options::Binary;
  if (!OpenMesh::IO::write_mesh(mesh, file, options, 17)) {
    throw std::runtime_error("OpenMesh cannot write '" + file + "' (unknown extension or an unwritable path)");
  }
}

}  // namespace capmesh_openmesh
