/* capmesh MeshLab plugin — GPL-3.0-or-later (links MeshLab; see ../README.md). */
#include "parameters.h"

#include <common/mlexception.h>

#include <algorithm>
#include <limits>

namespace capmesh_meshlab {

namespace {

const QStringList domainNames = {
	"Adaptive cap (radius search)", "Unit disk", "Hemisphere", "Sphere", "Cap of fixed radius"};
const QStringList gridNames = {"Uniform", "Latitude-longitude"};
// In the order of CAPMESH_V1_OPTIMIZE_SHAPE_AND_AREA, _AREA, _NONE (0, 1, 2).
const QStringList optimizeNames = {"shape+area", "area", "none"};
// In the order of CAPMESH_V1_SIZING_*.
const QStringList sizingNames = {"uniform", "surface", "curvature"};
// In the order of CAPMESH_V1_CREASES_AUTO, _KEEP, _OFF (0, 1, 2).
const QStringList creaseNames = {"auto", "keep", "off"};
// Index i: basis and boundary of capmesh_v1_harmonics_options (0: AH; 1..3: SCHA with
// boundary i - 1).
const QStringList basisNames = {
	"adaptive harmonics (paper)", "cap harmonics, Neumann", "cap harmonics, Dirichlet", "cap harmonics, mixed"};

uint32_t positive(const RichParameterList& list, const char* name)
{
	const int v = list.getInt(name);
	if (v <= 0)
		throw MLException(QString("Capmesh: parameter %1 must be a positive integer, got %2.").arg(name).arg(v));
	return uint32_t(v);
}

uint32_t nonNegative(const RichParameterList& list, const char* name)
{
	const int v = list.getInt(name);
	if (v < 0)
		throw MLException(QString("Capmesh: parameter %1 must be a non-negative integer, got %2.").arg(name).arg(v));
	return uint32_t(v);
}

int clampToInt(uint32_t v)
{
	return int(std::min<uint32_t>(v, uint32_t(std::numeric_limits<int>::max())));
}

} // namespace

void addParamOptions(RichParameterList& list, const capmesh_v1_param_options& d)
{
	list.addParam(RichEnum(
		"Domain", d.domain, domainNames, "Target domain",
		"Adaptive (the paper's method): searches the spherical cap Z >= Z* whose area-preserving "
		"map has the least angle distortion. Unit disk, Hemisphere and Sphere are the fixed-domain "
		"baselines; 'Cap of fixed radius' uses the disk radius given below."));
	list.addParam(RichFloat(
		"Radius", Scalarm(d.radius), "Disk radius (fixed-radius domain)",
		"Only for the 'Cap of fixed radius' domain: the planar disk of this radius is mapped onto "
		"the cap Z >= (1 - r^2) / (1 + r^2) of the unit sphere (r = 1 is the hemisphere); r in "
		"[0.05, 20], the range of the adaptive search."));
	list.addParam(RichFloat(
		"Lambda", Scalarm(d.lambda), "Quasi-conformal factor (closed surfaces)",
		"Closed surfaces: the stretch-energy map of the punctured surface is composed with the "
		"quasi-conformal map of lambda * mu, in [0, 1]. In Python the keyword is lambda_."));
	list.addParam(RichFloat(
		"Smoothing", Scalarm(d.smoothing), "Smoothing of the centroid map",
		"Regularisation of the final transport map; a negative value chooses it automatically, "
		"0 is the paper's plain centroid map."));
}

capmesh_v1_param_options readParamOptions(const RichParameterList& list)
{
	capmesh_v1_param_options o = capmesh_v1_param_options_default();
	o.domain = int32_t(list.getEnum("Domain"));
	o.radius = double(list.getFloat("Radius"));
	o.lambda = double(list.getFloat("Lambda"));
	o.smoothing = double(list.getFloat("Smoothing"));
	if (o.domain < 0 || o.domain >= domainNames.size())
		throw MLException(QString("Capmesh: unknown domain %1.").arg(o.domain));
	return o;
}

void addRemeshOptions(RichParameterList& list, const capmesh_v1_remesh_options& d)
{
	list.addParam(RichEnum(
		"Grid", d.grid, gridNames, "Grid on the cap",
		"Uniform: a near-uniform triangulation of the cap with about 'Target faces' faces. "
		"Latitude-longitude: 'Rings' x 'Sectors' quads split into triangles, with a pole fan."));
	list.addParam(RichInt(
		"Faces", clampToInt(d.faces), "Target faces (uniform grid)",
		"Approximate face count of the uniform grid."));
	list.addParam(RichInt("Rings", clampToInt(d.rings), "Rings (lat-long grid)", "Number of latitude rings."));
	list.addParam(RichInt("Sectors", clampToInt(d.sectors), "Sectors (lat-long grid)", "Number of longitude sectors."));
	list.addParam(RichEnum(
		"Optimize", d.optimize, optimizeNames, "Optimize",
		"What is optimised after the cap grid is pulled back onto the surface. shape+area "
		"(default): edge flips, tangential relaxation and a joint area and shape polish on the "
		"surface, then the area equalization: well-shaped triangles of near-equal area. area: "
		"the area equalization alone, keeping the cap grid's connectivity (thin triangles where "
		"the map stretches). none: the paper's plain pull-back. The latitude-longitude grid keeps "
		"its grid lines and gets the area equalization only."));
	list.addParam(RichInt(
		"RelaxIterations", clampToInt(d.relax_iterations), "Relaxation iterations (shape+area)",
		"Iterations of edge flips and tangential relaxation on the surface in the shape stage."));
	list.addParam(RichInt(
		"PolishIterations", clampToInt(d.polish_iterations), "Polish iterations (shape+area)",
		"Iterations of the joint area and shape polish in the shape stage."));
	list.addParam(RichFloat(
		"PolishTolerance", Scalarm(d.polish_tolerance), "Polish tolerance (shape+area)",
		"The polish stops early, after its global area steps, once an iteration flips no edge "
		"and moves the vertices by less than this root mean square, in edge lengths (>= 0; 0: "
		"every polish iteration runs)."));
	list.addParam(RichInt(
		"AreaSteps", clampToInt(d.area_steps), "Global area steps (shape+area)",
		"Gauss-Newton steps of the area term over all vertices at once, one every 5 polish "
		"iterations from the first (0: none): they remove the smooth part of the area error."));
	list.addParam(RichFloat(
		"ShapeWeight", Scalarm(d.shape_weight), "Shape weight (shape+area)",
		"Weight of the shape term against the area term in the polish, >= 0: larger gives better "
		"angles and less equal areas."));
	list.addParam(RichBool(
		"Resample", d.resample != 0, "Split and collapse edges (shape+area)",
		"Also split long and collapse short edges in the shape stage: better angles on smooth "
		"surfaces, slivers where thin parts fold at the remesh's scale."));
	list.addParam(RichEnum(
		"Sizing", d.sizing, sizingNames, "Sizing (shape+area)",
		"How the faces are sized. uniform (default): equal areas. surface: equal surface areas "
		"covered through the map, a uniform vertex density on the surface: closer to an input "
		"folded finer than the faces (a cortex's sulci, a thin edge), less equal face areas. "
		"curvature: smaller faces where the surface is curved ('Curvature strength'), for a "
		"smaller distance to the input at the same face count."));
	list.addParam(RichFloat(
		"SizingStrength", Scalarm(d.sizing_strength), "Curvature strength (curvature sizing)",
		"Strength > 0 of the curvature sizing: the density is 1 + S k L (3 is the command "
		"line's --sizing curvature)."));
	list.addParam(RichEnum(
		"Creases", d.creases, creaseNames, "Creases (shape+area)",
		"Whether vertices are put on the input's sharp edges (faces bent by more than the crease "
		"angle, also at the remesh's scale) and joined by edges: a smaller distance to the input "
		"on surfaces with real sharp edges, worse angles where a finely remeshed segmentation's "
		"steps count too. auto (default): with curvature sizing only."));
	list.addParam(RichFloat(
		"CreaseAngle", Scalarm(d.crease_deg), "Crease angle (shape+area)",
		"Degrees, strictly between 0 and 180: input edges bent more are creases, and no edge flip "
		"bends a pair of faces more (60 by default)."));
	list.addParam(RichBool(
		"VerticesOnSurface", d.placement == CAPMESH_V1_PLACEMENT_ON_SURFACE, "Vertices on the surface",
		"Leave the vertices on the input surface. Off by default: they are moved along their "
		"normals so that the faces fit the input in the least-squares sense (a smaller mean "
		"distance to it; the faces of a remesh on the surface are chords, inside convex parts)."));
	list.addParam(RichBool(
		"FillHoles", d.fill_holes != 0, "Fill holes",
		"Fill each hole of an open surface with a fan of faces and remesh the closed surface: for "
		"a closed surface with a few faces missing (a segmentation cut by the volume's edge), "
		"which a disk's map squeezes. Off by default: an open surface is remeshed open."));
	list.addParam(RichBool(
		"SubdivideCoarse", d.subdivide_coarse != 0, "Subdivide a coarse input",
		"Map an input with fewer faces than the remesh through a copy with every face split into "
		"4 (up to 3 times), and split its edges longer than three times the remesh's (a decimated long "
		"bone's shaft): the same surface, its map resolved at the remesh's scale. On by default; "
		"off maps the input as it is."));
	list.addParam(RichBool(
		"CoarseMap", d.coarse_map != 0, "Map a fine input at the remesh's detail",
		"With the shape stage (shape and area, uniform grid), map a closed input of many more "
		"vertices than the remesh needs through a decimated copy of 1.2 times the remesh's faces "
		"in vertices (at least 6000), prolonged to every vertex: faster, the same remesh, a higher "
		"mean |d_area|. On by default; off (and always without the shape stage) maps it at the "
		"detail the multilevel options ask for."));
	addParamOptions(list, d.param);
}

capmesh_v1_remesh_options readRemeshOptions(const RichParameterList& list)
{
	capmesh_v1_remesh_options o = capmesh_v1_remesh_options_default();
	o.grid = int32_t(list.getEnum("Grid"));
	if (o.grid < 0 || o.grid >= gridNames.size())
		throw MLException(QString("Capmesh: unknown grid %1.").arg(o.grid));
	o.faces = positive(list, "Faces");
	o.rings = positive(list, "Rings");
	o.sectors = positive(list, "Sectors");
	o.optimize = int32_t(list.getEnum("Optimize"));
	if (o.optimize < 0 || o.optimize >= optimizeNames.size())
		throw MLException(QString("Capmesh: unknown optimization %1.").arg(o.optimize));
	o.relax_iterations = nonNegative(list, "RelaxIterations");
	o.polish_iterations = nonNegative(list, "PolishIterations");
	o.polish_tolerance = double(list.getFloat("PolishTolerance"));
	if (!(o.polish_tolerance >= 0.0))
		throw MLException(QString("Capmesh: parameter PolishTolerance must be >= 0, got %1.").arg(o.polish_tolerance));
	o.area_steps = nonNegative(list, "AreaSteps");
	o.shape_weight = double(list.getFloat("ShapeWeight"));
	o.resample = list.getBool("Resample") ? 1 : 0;
	o.sizing = int32_t(list.getEnum("Sizing"));
	if (o.sizing < 0 || o.sizing >= sizingNames.size())
		throw MLException(QString("Capmesh: unknown sizing %1.").arg(o.sizing));
	o.sizing_strength = double(list.getFloat("SizingStrength"));
	o.creases = int32_t(list.getEnum("Creases"));
	if (o.creases < 0 || o.creases >= creaseNames.size())
		throw MLException(QString("Capmesh: unknown crease handling %1.").arg(o.creases));
	o.crease_deg = double(list.getFloat("CreaseAngle"));
	o.placement = list.getBool("VerticesOnSurface") ? CAPMESH_V1_PLACEMENT_ON_SURFACE : CAPMESH_V1_PLACEMENT_FITTED;
	o.fill_holes = list.getBool("FillHoles") ? 1 : 0;
	o.subdivide_coarse = list.getBool("SubdivideCoarse") ? 1 : 0;
	o.coarse_map = list.getBool("CoarseMap") ? 1 : 0;
	o.param = readParamOptions(list);
	return o;
}

void addHarmonicsOptions(RichParameterList& list, const capmesh_v1_harmonics_options& d)
{
	list.addParam(RichInt(
		"Order", clampToInt(d.order), "Order N",
		"Largest order N of the adaptive harmonic fit: (N + 1)^2 basis functions on the cap, so "
		"the mesh needs at least that many vertices. Higher orders reproduce finer detail. "
		"The 'Unit disk' domain is refused here."));
	const int basis = d.basis == CAPMESH_V1_BASIS_SCHA ? 1 + d.boundary : 0;
	list.addParam(RichEnum(
		"Basis", basis, basisNames, "Harmonic basis",
		"adaptive harmonics: the paper's basis (it maps an open surface's whole boundary loop to "
		"one point). cap harmonics: spherical cap harmonics on the true polar angle, Legendre "
		"functions of non-integer degree with a Neumann (keeps the boundary loop; recommended), "
		"Dirichlet (boundary to the origin) or mixed rim condition (Haines' set; rank deficient "
		"on closed surfaces)."));
	list.addParam(RichInt(
		"ResampleFaces", clampToInt(d.resample_faces), "Resample on a cap grid (faces)",
		"0: the reconstruction keeps the input's connectivity. N > 0: the reconstructed surface "
		"is evaluated on a uniform cap mesh of about N faces (a smooth remesh)."));
	addParamOptions(list, d.param);
}

capmesh_v1_harmonics_options readHarmonicsOptions(const RichParameterList& list)
{
	capmesh_v1_harmonics_options o = capmesh_v1_harmonics_options_default();
	const int order = list.getInt("Order");
	if (order < 0)
		throw MLException(QString("Capmesh: the order must be >= 0, got %1.").arg(order));
	o.order = uint32_t(order);
	const int basis = list.getEnum("Basis");
	if (basis < 0 || basis >= basisNames.size())
		throw MLException(QString("Capmesh: unknown harmonic basis %1.").arg(basis));
	o.basis = basis == 0 ? CAPMESH_V1_BASIS_AH : CAPMESH_V1_BASIS_SCHA;
	o.boundary = basis == 0 ? CAPMESH_V1_BOUNDARY_NEUMANN : int32_t(basis - 1);
	const int faces = list.getInt("ResampleFaces");
	if (faces < 0)
		throw MLException(QString("Capmesh: the resampling face count must be >= 0, got %1.").arg(faces));
	o.resample_faces = uint32_t(faces);
	o.param = readParamOptions(list);
	return o;
}

} // namespace capmesh_meshlab
