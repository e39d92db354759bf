/* capmesh MeshLab plugin — GPL-3.0-or-later (links MeshLab; see ../README.md).
 *
 * The MeshLab FilterPlugin: three filters that hand the current mesh to capmesh's C ABI and
 * put the result in a new layer. It only translates — parameters to capmesh's options
 * structs, progress to vcg::CallBackPos, capmesh's status and error text to MLException,
 * capmesh's JSON report to the filter's output values and the log. */
#ifndef CAPMESH_MESHLAB_FILTER_CAPMESH_H
#define CAPMESH_MESHLAB_FILTER_CAPMESH_H

#include <common/plugins/interfaces/filter_plugin.h>

#include <capmesh.h>

class FilterCapmeshPlugin : public QObject, public FilterPlugin
{
	Q_OBJECT
	MESHLAB_PLUGIN_IID_EXPORTER(FILTER_PLUGIN_IID)
	Q_INTERFACES(FilterPlugin)

public:
	enum { FP_PARAMETERIZE, FP_REMESH, FP_HARMONICS };

	FilterCapmeshPlugin();

	QString pluginName() const override;
	QString vendor() const override;

	QString filterName(ActionIDType filter) const override;
	QString pythonFilterName(ActionIDType filter) const override;
	QString filterInfo(ActionIDType filter) const override;
	FilterClass getClass(const QAction* a) const override;
	FilterArity filterArity(const QAction*) const override;
	int getPreConditions(const QAction*) const override;
	int getRequirements(const QAction*) override;
	int postCondition(const QAction*) const override;
	RichParameterList initParameterList(const QAction* a, const MeshModel& m) override;
	std::map<std::string, QVariant> applyFilter(
		const QAction* action,
		const RichParameterList& parameters,
		MeshDocument& md,
		unsigned int& postConditionMask,
		vcg::CallBackPos* cb) override;

private:
	std::map<std::string, QVariant> parameterize(const RichParameterList& par, MeshDocument& md, vcg::CallBackPos* cb);
	std::map<std::string, QVariant> remesh(const RichParameterList& par, MeshDocument& md, vcg::CallBackPos* cb);
	std::map<std::string, QVariant> harmonics(const RichParameterList& par, MeshDocument& md, vcg::CallBackPos* cb);
};

#endif
