/* capmesh MeshLab plugin — GPL-3.0-or-later (links MeshLab; see ../README.md). */
#include "vertex_data.h"

#include <common/mlexception.h>

#include <algorithm>
#include <cmath>

namespace capmesh_meshlab {

int carryVertexData(const MeshModel& in, const MeshBuffers& buffers, const capmesh_v1_mesh* located, MeshModel& out)
{
	const bool colour = in.hasDataMask(MeshModel::MM_VERTCOLOR);
	const bool quality = in.hasDataMask(MeshModel::MM_VERTQUALITY);
	if (!colour && !quality)
		return MeshModel::MM_NONE;
	const size_t nv = capmesh_v1_mesh_vertex_count(located);
	const uint32_t* faces = capmesh_v1_mesh_source_faces(located);
	const double* weights = capmesh_v1_mesh_source_barycentrics(located);
	if (faces == nullptr || weights == nullptr || out.cm.vert.size() != nv)
		throw MLException("Capmesh: the remesh did not say where its vertices lie on the input (a capmesh bug).");
	const std::vector<uint32_t>& triangles = buffers.triangleIndices();
	const std::vector<size_t>& source = buffers.sourceVertex();
	int mask = MeshModel::MM_NONE;
	if (colour) {
		out.updateDataMask(MeshModel::MM_VERTCOLOR);
		mask |= MeshModel::MM_VERTCOLOR;
	}
	if (quality) {
		out.updateDataMask(MeshModel::MM_VERTQUALITY);
		mask |= MeshModel::MM_VERTQUALITY;
	}
	for (size_t v = 0; v < nv; ++v) {
		const size_t f = faces[v];
		if (3 * f + 2 >= triangles.size())
			throw MLException(QString("Capmesh: remesh vertex %1 lies on input face %2, which does not exist (a capmesh bug).").arg(v).arg(f));
		double rgba[4] = {0, 0, 0, 0};
		double q = 0;
		for (int k = 0; k < 3; ++k) {
			const auto& corner = in.cm.vert[source[triangles[3 * f + k]]];
			const double w = weights[3 * v + k];
			for (int c = 0; c < 4; ++c)
				rgba[c] += w * double(corner.cC()[c]);
			q += w * double(corner.cQ());
		}
		auto& target = out.cm.vert[v];
		if (colour)
			for (int c = 0; c < 4; ++c)
				target.C()[c] = static_cast<unsigned char>(std::clamp(std::lround(rgba[c]), 0L, 255L));
		if (quality)
			target.Q() = Scalarm(q);
	}
	return mask;
}

void setTexCoordsFromMap(const double* uv, const MeshBuffers& buffers, MeshModel& mesh)
{
	if (uv == nullptr)
		throw MLException("Capmesh: the map has no texture coordinates (a capmesh bug).");
	mesh.updateDataMask(MeshModel::MM_VERTTEXCOORD);
	const auto& source = buffers.sourceVertex();
	for (size_t i = 0; i < source.size(); ++i) {
		auto& v = mesh.cm.vert[source[i]];
		v.T().P() = vcg::Point2<Scalarm>(Scalarm(uv[2 * i]), Scalarm(uv[2 * i + 1]));
		v.T().N() = 0;
	}
}

} // namespace capmesh_meshlab
