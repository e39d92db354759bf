/* capmesh MeshLab plugin — GPL-3.0-or-later (links MeshLab; see ../README.md). */
#include "filter_capmesh.h"

#include "mesh_views.h"
#include "parameters.h"
#include "progress_callback.h"
#include "report_values.h"
#include "vertex_data.h"

#include <cmath>
#include <memory>

using namespace capmesh_meshlab;

namespace {

struct MeshFree { void operator()(capmesh_v1_mesh* m) const { capmesh_v1_mesh_free(m); } };
struct StringFree { void operator()(char* s) const { capmesh_v1_string_free(s); } };
struct MapFree { void operator()(capmesh_v1_map* m) const { capmesh_v1_map_free(m); } };
using MeshPtr = std::unique_ptr<capmesh_v1_mesh, MeshFree>;
using MapPtr = std::unique_ptr<capmesh_v1_map, MapFree>;
using StringPtr = std::unique_ptr<char, StringFree>;

const char* statusName(capmesh_v1_status s)
{
	switch (s) {
	case CAPMESH_V1_OK: return "ok";
	case CAPMESH_V1_INVALID_ARGUMENT: return "invalid argument";
	case CAPMESH_V1_INVALID_MESH: return "invalid mesh";
	case CAPMESH_V1_NUMERICAL: return "numerical failure";
	case CAPMESH_V1_UNSUPPORTED: return "unsupported";
	case CAPMESH_V1_CANCELLED: return "cancelled";
	case CAPMESH_V1_INTERNAL: return "internal error";
	}
	return "unknown status";
}

/// Throws the MLException MeshLab shows (and pymeshlab raises as PyMeshLabException).
void check(capmesh_v1_status status, const char* what)
{
	if (status == CAPMESH_V1_OK)
		return;
	if (status == CAPMESH_V1_CANCELLED)
		throw MLException(QString("Capmesh %1: cancelled.").arg(what));
	const char* detail = capmesh_v1_last_error();
	throw MLException(QString("Capmesh %1 failed (%2): %3")
		.arg(what, statusName(status), detail != nullptr ? QString::fromUtf8(detail) : QString("no details")));
}

/// The current mesh, checked: capmesh needs triangles.
MeshModel& inputMesh(MeshDocument& md)
{
	MeshModel* m = md.mm();
	if (m == nullptr)
		throw MLException("Capmesh: there is no current mesh.");
	if (m->cm.fn == 0)
		throw MLException("Capmesh: the current mesh has no faces; capmesh needs a triangle mesh.");
	return *m;
}

/// A new layer holding `nv` vertices and `nf` triangles, made current (MeshLab's habit for
/// filters that create meshes).
MeshModel& addLayer(MeshDocument& md, const double* positions, size_t nv, const uint32_t* triangles, size_t nf, const QString& label)
{
	MeshModel* out = md.addNewMesh("", label, true);
	try {
		fillMesh(positions, nv, triangles, nf, out->cm);
	}
	catch (...) {
		md.delMesh(out->id()); // no half-made layer
		throw;
	}
	out->updateBoxAndNormals();
	return *out;
}

/// A new layer holding `result`, made current.
MeshModel& addLayer(MeshDocument& md, const capmesh_v1_mesh* result, const QString& label)
{
	return addLayer(md, capmesh_v1_mesh_positions(result), capmesh_v1_mesh_vertex_count(result),
	                capmesh_v1_mesh_triangles(result), capmesh_v1_mesh_face_count(result), label);
}

/// The report as output values plus the counts of the produced mesh; the report is logged.
std::map<std::string, QVariant> outputs(const FilterPlugin& plugin, const char* json, const MeshModel& out)
{
	std::map<std::string, QVariant> values = flattenReport(json);
	values["vertex_count"] = QVariant(int(out.cm.vn));
	values["face_count"] = QVariant(int(out.cm.fn));
	if (json != nullptr)
		plugin.log(std::string("capmesh report: ") + json);
	return values;
}

/// Per-vertex texture coordinates from the cap: stereographic projection from the south pole,
/// (u, v) = (x, y) / (1 + z), which is capmesh's planar disk, scaled into [0, 1]^2.
void storePlaneTexCoords(MeshModel& out)
{
	CMeshO& cm = out.cm;
	std::vector<Point2m> plane(cm.vert.size());
	Scalarm radius = 0;
	for (size_t i = 0; i < cm.vert.size(); ++i) {
		const Point3m& p = cm.vert[i].cP();
		const Scalarm d = Scalarm(1) + p[2];
		plane[i] = d > Scalarm(1e-12) ? Point2m(p[0] / d, p[1] / d) : Point2m(0, 0);
		if (std::isfinite(plane[i].Norm()))
			radius = std::max(radius, plane[i].Norm());
	}
	if (!(radius > 0))
		return;
	out.updateDataMask(MeshModel::MM_VERTTEXCOORD);
	for (size_t i = 0; i < cm.vert.size(); ++i) {
		cm.vert[i].T().P() = Point2m(0.5, 0.5) + plane[i] * (Scalarm(0.5) / radius);
		cm.vert[i].T().N() = 0;
	}
}

} // namespace

FilterCapmeshPlugin::FilterCapmeshPlugin()
{
	typeList = {FP_PARAMETERIZE, FP_REMESH, FP_HARMONICS};
	for (ActionIDType t : types())
		actionList.push_back(new QAction(filterName(t), this));
}

QString FilterCapmeshPlugin::pluginName() const { return "FilterCapmesh"; }

QString FilterCapmeshPlugin::vendor() const { return "capmesh"; }

QString FilterCapmeshPlugin::filterName(ActionIDType f) const
{
	switch (f) {
	case FP_PARAMETERIZE: return "Capmesh: adaptive area-preserving parameterization";
	case FP_REMESH: return "Capmesh: remesh through the cap";
	case FP_HARMONICS: return "Capmesh: adaptive harmonics reconstruction";
	}
	return QString();
}

QString FilterCapmeshPlugin::pythonFilterName(ActionIDType f) const
{
	switch (f) {
	case FP_PARAMETERIZE: return "capmesh_parameterization";
	case FP_REMESH: return "capmesh_remesh";
	case FP_HARMONICS: return "capmesh_harmonics_reconstruction";
	}
	return QString();
}

QString FilterCapmeshPlugin::filterInfo(ActionIDType f) const
{
	const QString version = QString::fromUtf8(capmesh_v1_version());
	switch (f) {
	case FP_PARAMETERIZE:
		return "Maps a genus-0 triangle mesh (a disk, or a closed surface) onto a spherical cap "
		       "with an area-preserving map; the adaptive domain searches the cap that also keeps "
		       "angles least distorted (Choi et al., adaptive area-preserving parameterization). "
		       "The cap mesh is added as a new layer, or replaces the vertex positions; the planar "
		       "disk coordinates can be stored as per-vertex texture coordinates. capmesh " + version;
	case FP_REMESH:
		return "Remeshes a genus-0 surface through its cap parameterization: a uniform or "
		       "latitude-longitude grid on the cap is pulled back onto the surface, then optimised "
		       "(by default shape+area: well-shaped triangles of near-equal area, every vertex "
		       "on the input surface). The result is a new layer; the input's vertex colour and "
		       "quality are carried onto it, interpolated where each new vertex lies on the input "
		       "(capmesh's inverse map). capmesh " + version;
	case FP_HARMONICS:
		return "Fits a harmonic basis of the cap (the paper's adaptive harmonics, or spherical cap "
		       "harmonics that keep an open surface's boundary loop) to the surface coordinates up "
		       "to order N and adds the reconstructed surface (optionally resampled on a cap grid) "
		       "as a new layer. capmesh " + version;
	}
	return QString();
}

FilterPlugin::FilterClass FilterCapmeshPlugin::getClass(const QAction* a) const
{
	return ID(a) == FP_PARAMETERIZE ? FilterPlugin::Texture : FilterPlugin::Remeshing;
}

FilterPlugin::FilterArity FilterCapmeshPlugin::filterArity(const QAction*) const { return SINGLE_MESH; }

int FilterCapmeshPlugin::getPreConditions(const QAction*) const { return MeshModel::MM_FACENUMBER; }

int FilterCapmeshPlugin::getRequirements(const QAction*) { return MeshModel::MM_NONE; }

int FilterCapmeshPlugin::postCondition(const QAction*) const
{
	// Every filter writes into a new layer, except the parameterization's in-place mode, which
	// sets the postConditionMask at run time.
	return MeshModel::MM_NONE;
}

RichParameterList FilterCapmeshPlugin::initParameterList(const QAction* a, const MeshModel&)
{
	RichParameterList list;
	switch (ID(a)) {
	case FP_PARAMETERIZE:
		addParamOptions(list, capmesh_v1_param_options_default());
		list.addParam(RichBool(
			"NewLayer", true, "Cap as a new layer",
			"Add the cap mesh as a new layer (default). Unchecked, the vertices of the current mesh "
			"are moved onto the cap; this needs the cap to keep every vertex (no welded duplicates)."));
		list.addParam(RichBool(
			"PlaneTexCoords", true, "Store disk coordinates as texture coordinates",
			"Per-vertex texture coordinates: the stereographic projection of the cap, i.e. "
			"capmesh's planar disk, scaled into the unit square."));
		list.addParam(RichBool(
			"InputTexCoords", false, "Set the map as texture coordinates of the input",
			"Per-vertex texture coordinates on the current (input) mesh: each vertex's point of the "
			"map's disk scaled into the unit square, as capmesh's `param --uv` writes them, so a "
			"checkerboard texture shows the map on the surface."));
		break;
	case FP_REMESH: addRemeshOptions(list, capmesh_v1_remesh_options_default()); break;
	case FP_HARMONICS: addHarmonicsOptions(list, capmesh_v1_harmonics_options_default()); break;
	default: wrongActionCalled(a);
	}
	return list;
}

std::map<std::string, QVariant> FilterCapmeshPlugin::applyFilter(
	const QAction* action, const RichParameterList& par, MeshDocument& md, unsigned int& postConditionMask,
	vcg::CallBackPos* cb)
{
	switch (ID(action)) {
	case FP_PARAMETERIZE: {
		auto values = parameterize(par, md, cb);
		postConditionMask = par.getBool("NewLayer")
			? (par.getBool("InputTexCoords") ? int(MeshModel::MM_VERTTEXCOORD) : int(MeshModel::MM_NONE))
			: (MeshModel::MM_VERTCOORD | MeshModel::MM_VERTNORMAL | MeshModel::MM_FACENORMAL
			   | MeshModel::MM_VERTTEXCOORD);
		return values;
	}
	case FP_REMESH: return remesh(par, md, cb);
	case FP_HARMONICS: return harmonics(par, md, cb);
	default: wrongActionCalled(action);
	}
	return {};
}

std::map<std::string, QVariant> FilterCapmeshPlugin::parameterize(
	const RichParameterList& par, MeshDocument& md, vcg::CallBackPos* cb)
{
	MeshModel& in = inputMesh(md);
	const capmesh_v1_param_options options = readParamOptions(par);
	const bool newLayer = par.getBool("NewLayer");
	const MeshBuffers buffers(in.cm);
	const capmesh_v1_mesh_view view = buffers.view();
	ProgressTarget progress{cb, "Capmesh parameterization"};
	capmesh_v1_map* map = nullptr;
	char* json = nullptr;
	const capmesh_v1_status status = capmesh_v1_parameterize_map(&view, &options, forwardProgress, &progress, &map, &json);
	MapPtr mapOwner(map);
	StringPtr jsonOwner(json);
	check(status, "parameterization");
	const size_t capVertices = capmesh_v1_map_vertex_count(map);
	if (capVertices != buffers.vertexCount())
		throw MLException(QString("Capmesh: the map has %1 vertices, the mesh %2 (a capmesh bug).")
			.arg(capVertices).arg(buffers.vertexCount()));
	// Texture coordinates on the input first: a new layer becomes the current mesh.
	if (par.getBool("InputTexCoords"))
		setTexCoordsFromMap(capmesh_v1_map_uv(map), buffers, in);

	MeshModel* out = nullptr;
	if (newLayer) {
		const std::vector<uint32_t>& t = buffers.triangleIndices();
		out = &addLayer(md, capmesh_v1_map_cap_positions(map), capVertices, t.data(), t.size() / 3, in.label() + " cap");
	}
	else {
		const double* p = capmesh_v1_map_cap_positions(map);
		const auto& source = buffers.sourceVertex();
		for (size_t i = 0; i < source.size(); ++i)
			in.cm.vert[source[i]].P() = Point3m(Scalarm(p[3 * i]), Scalarm(p[3 * i + 1]), Scalarm(p[3 * i + 2]));
		in.updateBoxAndNormals();
		out = &in;
	}
	if (par.getBool("PlaneTexCoords"))
		storePlaneTexCoords(*out);
	return outputs(*this, json, *out);
}

std::map<std::string, QVariant> FilterCapmeshPlugin::remesh(
	const RichParameterList& par, MeshDocument& md, vcg::CallBackPos* cb)
{
	MeshModel& in = inputMesh(md);
	const capmesh_v1_remesh_options options = readRemeshOptions(par);
	const MeshBuffers buffers(in.cm);
	const capmesh_v1_mesh_view view = buffers.view();
	ProgressTarget progress{cb, "Capmesh remesh"};
	capmesh_v1_mesh* mesh = nullptr;
	char* json = nullptr;
	// located: each new vertex's input triangle and weights, to carry colour and quality.
	const capmesh_v1_status status = capmesh_v1_remesh_located(&view, &options, forwardProgress, &progress, &mesh, &json);
	MeshPtr meshOwner(mesh);
	StringPtr jsonOwner(json);
	check(status, "remesh");
	const QString grid = options.grid == 0 ? QString("uniform %1").arg(options.faces)
	                                       : QString("lat-long %1x%2").arg(options.rings).arg(options.sectors);
	MeshModel& out = addLayer(md, mesh, in.label() + " capmesh " + grid);
	const int carried = carryVertexData(in, buffers, mesh, out);
	auto values = outputs(*this, json, out);
	values["carried_vertex_color"] = QVariant((carried & MeshModel::MM_VERTCOLOR) != 0);
	values["carried_vertex_quality"] = QVariant((carried & MeshModel::MM_VERTQUALITY) != 0);
	return values;
}

std::map<std::string, QVariant> FilterCapmeshPlugin::harmonics(
	const RichParameterList& par, MeshDocument& md, vcg::CallBackPos* cb)
{
	MeshModel& in = inputMesh(md);
	const capmesh_v1_harmonics_options options = readHarmonicsOptions(par);
	const MeshBuffers buffers(in.cm);
	const capmesh_v1_mesh_view view = buffers.view();
	ProgressTarget progress{cb, "Capmesh harmonics"};
	capmesh_v1_mesh* mesh = nullptr;
	char* json = nullptr;
	const capmesh_v1_status status = capmesh_v1_harmonics(&view, &options, forwardProgress, &progress, &mesh, &json);
	MeshPtr meshOwner(mesh);
	StringPtr jsonOwner(json);
	check(status, "harmonics");
	MeshModel& out = addLayer(md, mesh, in.label() + QString(" harmonics N=%1").arg(options.order));
	auto values = outputs(*this, json, out);
	// the reconstruction error at order N: error_mean_relative, error_max_distance, ...
	for (auto& [key, value] : lastArrayEntry(json, "errors_by_order", "error"))
		values[key] = value;
	return values;
}

MESHLAB_PLUGIN_NAME_EXPORTER(FilterCapmeshPlugin)
