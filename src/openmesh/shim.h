// C++ side of capmesh's OpenMesh bridge (src/openmesh/bridge.rs): reading and writing meshes
// through OpenMesh::IO with double-precision points.
#pragma once
#include <cstdint>

#include "rust/cxx.h"

namespace capmesh_openmesh {

// Throws std::runtime_error when OpenMesh cannot read the file.
void read_mesh(rust::Str path, rust::Vec<double> &positions, rust::Vec<uint32_t> &triangles);

// Throws std::runtime_error when OpenMesh refuses a face or cannot write the file.
void write_mesh(rust::Str path, rust::Slice<const double> positions, rust::Slice<const uint32_t> triangles, bool binary);

}  // namespace capmesh_openmesh
