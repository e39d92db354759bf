/* capmesh MeshLab plugin — GPL-3.0-or-later (links MeshLab; see ../README.md). */
#include "mesh_views.h"

#include <common/mlexception.h>

#include <vcg/complex/algorithms/update/bounding.h>
#include <vcg/complex/algorithms/update/normal.h>
#include <vcg/complex/allocate.h>

#include <limits>

namespace capmesh_meshlab {

MeshBuffers::MeshBuffers(const CMeshO& mesh)
{
	const size_t none = std::numeric_limits<size_t>::max();
	std::vector<size_t> compact(mesh.vert.size(), none);
	positions.reserve(3 * size_t(mesh.vn));
	source.reserve(size_t(mesh.vn));
	for (size_t i = 0; i < mesh.vert.size(); ++i) {
		if (mesh.vert[i].IsD())
			continue;
		compact[i] = source.size();
		source.push_back(i);
		const auto& p = mesh.vert[i].cP();
		positions.push_back(double(p[0]));
		positions.push_back(double(p[1]));
		positions.push_back(double(p[2]));
	}
	if (source.size() > size_t(std::numeric_limits<uint32_t>::max()))
		throw MLException("Capmesh: the mesh has more vertices than 32-bit indices can address.");
	triangles.reserve(3 * size_t(mesh.fn));
	for (const auto& f : mesh.face) {
		if (f.IsD())
			continue;
		for (int k = 0; k < 3; ++k) {
			const size_t v = compact[size_t(f.cV(k) - &mesh.vert[0])];
			if (v == none)
				throw MLException("Capmesh: a face references a deleted vertex; run "
				                  "'Remove Unreferenced Vertices' / 'Compact' first.");
			triangles.push_back(uint32_t(v));
		}
	}
}

capmesh_v1_mesh_view MeshBuffers::view() const
{
	capmesh_v1_mesh_view v;
	v.positions = positions.data();
	v.vertex_count = vertexCount();
	v.triangles = triangles.data();
	v.face_count = faceCount();
	return v;
}

void fillMesh(const capmesh_v1_mesh* result, CMeshO& out)
{
	fillMesh(capmesh_v1_mesh_positions(result), capmesh_v1_mesh_vertex_count(result),
	         capmesh_v1_mesh_triangles(result), capmesh_v1_mesh_face_count(result), out);
}

void fillMesh(const double* p, size_t nv, const uint32_t* t, size_t nf, CMeshO& out)
{
	if ((nv > 0 && p == nullptr) || (nf > 0 && t == nullptr))
		throw MLException("Capmesh: the result has no arrays (a capmesh bug).");
	for (size_t i = 0; i < 3 * nf; ++i)
		if (t[i] >= nv)
			throw MLException("Capmesh: the result indexes a vertex it does not have (a capmesh bug).");

	out.Clear();
	auto vi = vcg::tri::Allocator<CMeshO>::AddVertices(out, nv);
	for (size_t i = 0; i < nv; ++i, ++vi)
		vi->P() = Point3m(Scalarm(p[3 * i]), Scalarm(p[3 * i + 1]), Scalarm(p[3 * i + 2]));
	auto fi = vcg::tri::Allocator<CMeshO>::AddFaces(out, nf);
	for (size_t i = 0; i < nf; ++i, ++fi)
		for (int k = 0; k < 3; ++k)
			fi->V(k) = &out.vert[t[3 * i + k]];
	vcg::tri::UpdateBounding<CMeshO>::Box(out);
	vcg::tri::UpdateNormal<CMeshO>::PerVertexNormalizedPerFaceNormalized(out);
}

} // namespace capmesh_meshlab
