/* capmesh MeshLab plugin — GPL-3.0-or-later (links MeshLab; see ../README.md).
 *
 * Per-vertex data of the input carried onto capmesh's results: vertex colour and quality
 * through the remesh (each new vertex is a point of an input triangle with barycentric
 * weights, capmesh_v1_remesh_located, found by capmesh's inverse map), and the map's texture
 * coordinates (capmesh_v1_map_uv, as `capmesh param --uv`) on the input's vertices. */
#ifndef CAPMESH_MESHLAB_VERTEX_DATA_H
#define CAPMESH_MESHLAB_VERTEX_DATA_H

#include <common/ml_document/mesh_model.h>

#include <capmesh.h>

#include "mesh_views.h"

namespace capmesh_meshlab {

/// Sets `out`'s vertex colour and quality, when `in` has them, from `located` (a
/// capmesh_v1_remesh_located result whose vertices are `out`'s): each channel interpolated
/// with the vertex's barycentric weights on its input triangle (`buffers`, the compact copy
/// of `in` capmesh read). Returns the MeshModel::MM_* mask of what was set.
int carryVertexData(const MeshModel& in, const MeshBuffers& buffers, const capmesh_v1_mesh* located, MeshModel& out);

/// Sets `mesh`'s per-vertex texture coordinates from the map's `uv` (2 per compact vertex of
/// `buffers`).
void setTexCoordsFromMap(const double* uv, const MeshBuffers& buffers, MeshModel& mesh);

} // namespace capmesh_meshlab

#endif
