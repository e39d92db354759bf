/* capmesh MeshLab plugin — GPL-3.0-or-later (links MeshLab; see ../README.md).
 *
 * capmesh's JSON report turned into the filter's output values: every number and boolean leaf
 * becomes one entry, its key the path joined by '_' (e.g. "radius_search_z_star"). pymeshlab
 * hands this map back to Python as the dict `apply_filter` returns; it converts bool, int,
 * float and arrays only, so strings stay in the log (the whole report is logged). */
#ifndef CAPMESH_MESHLAB_REPORT_VALUES_H
#define CAPMESH_MESHLAB_REPORT_VALUES_H

#include <QVariant>

#include <map>
#include <string>

namespace capmesh_meshlab {

/// Flattened scalar leaves of a JSON document (arrays are skipped: they are per-iteration
/// histories, not results). Throws MLException when `json` is not valid JSON.
std::map<std::string, QVariant> flattenReport(const char* json);

/// The scalar leaves of the last object of the top-level array `arrayKey` (e.g. the highest
/// order of "errors_by_order"), keys prefixed with `prefix` + '_'; empty if there is none.
std::map<std::string, QVariant> lastArrayEntry(const char* json, const QString& arrayKey, const std::string& prefix);

} // namespace capmesh_meshlab

#endif
