/* capmesh MeshLab plugin — GPL-3.0-or-later (links MeshLab; see ../README.md). */
#include "report_values.h"

#include <common/mlexception.h>

#include <QJsonDocument>
#include <QJsonObject>
#include <QJsonValue>

namespace capmesh_meshlab {

namespace {

void flatten(const QJsonObject& object, const std::string& prefix, std::map<std::string, QVariant>& out)
{
	for (auto it = object.begin(); it != object.end(); ++it) {
		const std::string key = prefix.empty() ? it.key().toStdString() : prefix + "_" + it.key().toStdString();
		const QJsonValue v = it.value();
		if (v.isObject())
			flatten(v.toObject(), key, out);
		else if (v.isDouble())
			out[key] = QVariant(v.toDouble());
		else if (v.isBool())
			out[key] = QVariant(v.toBool());
	}
}

} // namespace

std::map<std::string, QVariant> flattenReport(const char* json)
{
	std::map<std::string, QVariant> out;
	if (json == nullptr)
		return out;
	QJsonParseError error;
	const QJsonDocument doc = QJsonDocument::fromJson(QByteArray(json), &error);
	if (doc.isNull())
		throw MLException("Capmesh: the report is not valid JSON (" + error.errorString() + ").");
	if (doc.isObject())
		flatten(doc.object(), std::string(), out);
	return out;
}

} // namespace capmesh_meshlab
