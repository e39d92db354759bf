/* capmesh MeshLab plugin — GPL-3.0-or-later (links MeshLab; see ../README.md).
 *
 * MeshLab RichParameters <-> capmesh options structs. The parameter names are what pymeshlab
 * users pass as keyword arguments (lowercased: "Domain" -> domain, "Lambda" -> lambda_ since
 * `lambda` is a Python keyword). Defaults are capmesh's own (capmesh_v1_*_options_default). */
#ifndef CAPMESH_MESHLAB_PARAMETERS_H
#define CAPMESH_MESHLAB_PARAMETERS_H

#include <common/parameters/rich_parameter_list.h>

#include <capmesh.h>

namespace capmesh_meshlab {

/// Domain, Radius, Lambda, Smoothing: the parameterization options every filter shares.
void addParamOptions(RichParameterList& list, const capmesh_v1_param_options& defaults);
capmesh_v1_param_options readParamOptions(const RichParameterList& list);

/// Grid, Faces, Rings, Sectors, Optimize, RelaxIterations, PolishIterations, PolishTolerance,
/// AreaSteps, ShapeWeight, Resample, Sizing, SizingStrength, Creases, CreaseAngle,
/// VerticesOnSurface,
/// FillHoles, SubdivideCoarse, CoarseMap, then the parameterization options.
void addRemeshOptions(RichParameterList& list, const capmesh_v1_remesh_options& defaults);
capmesh_v1_remesh_options readRemeshOptions(const RichParameterList& list);

/// Order, then the parameterization options.
void addHarmonicsOptions(RichParameterList& list, const capmesh_v1_harmonics_options& defaults);
capmesh_v1_harmonics_options readHarmonicsOptions(const RichParameterList& list);

} // namespace capmesh_meshlab

#endif
