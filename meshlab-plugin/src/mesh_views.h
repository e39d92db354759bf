/* capmesh MeshLab plugin — GPL-3.0-or-later (links MeshLab; see ../README.md).
 *
 * Conversion between MeshLab's CMeshO and capmesh's C ABI: a compact copy of the live
 * (non-deleted) vertices and faces as the f64 / u32 view capmesh reads, and a capmesh result
 * written into a MeshLab mesh layer. */
#ifndef CAPMESH_MESHLAB_MESH_VIEWS_H
#define CAPMESH_MESHLAB_MESH_VIEWS_H

#include <common/ml_document/cmesh.h>

#include <capmesh.h>

#include <cstdint>
#include <vector>

namespace capmesh_meshlab {

/// The live part of a CMeshO, compacted: deleted vertices and faces are skipped and the face
/// indices renumbered. `view()` points into this object, so keep it alive while capmesh runs.
class MeshBuffers
{
public:
	explicit MeshBuffers(const CMeshO& mesh);

	capmesh_v1_mesh_view view() const;
	size_t vertexCount() const { return positions.size() / 3; }
	size_t faceCount() const { return triangles.size() / 3; }
	/// The compact triangles: three compact vertex indices each.
	const std::vector<uint32_t>& triangleIndices() const { return triangles; }
	/// Index in `mesh.vert` of each compact vertex (to write per-vertex data back).
	const std::vector<size_t>& sourceVertex() const { return source; }

private:
	std::vector<double> positions;
	std::vector<uint32_t> triangles;
	std::vector<size_t> source;
};

/// Replaces the content of `out` by the vertices and triangles of a capmesh result.
/// Throws MLException when the result indexes a vertex it does not have.
void fillMesh(const capmesh_v1_mesh* result, CMeshO& out);

/// Replaces the content of `out` by `nv` vertices `positions` (xyz each) and `nf` triangles.
/// Throws MLException when a triangle indexes a vertex that does not exist.
void fillMesh(const double* positions, size_t nv, const uint32_t* triangles, size_t nf, CMeshO& out);

} // namespace capmesh_meshlab

#endif
