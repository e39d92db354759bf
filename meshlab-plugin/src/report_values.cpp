/* capmesh MeshLab plugin — GPL-3.0-or-later (links MeshLab; see ../README.md). */
#include "report_values.h"

#include <common/mlexception.h>

#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QJsonValue>

#include <limits>

namespace capmesh_meshlab {

namespace {

/// Integers of the report (counts, iterations) stay integers: Qt keeps a JSON literal without
/// fraction as a 64-bit integer; pymeshlab converts int, so narrow it when it fits.
QVariant number(const QJsonValue& v)
{
	const QVariant raw = v.toVariant();
	if (raw.type() == QVariant::LongLong) {
		const qlonglong i = raw.toLongLong();
		if (i >= std::numeric_limits<int>::min() && i <= std::numeric_limits<int>::max())
			return QVariant(int(i));
	}
	return QVariant(v.toDouble());
}

void flatten(const QJsonObject& object, const std::string& prefix, std::map<std::string, QVariant>& out)
{
	for (auto it = object.begin(); it != object.end(); ++it) {
		const std::string key = prefix.empty() ? it.key().toStdString() : prefix + "_" + it.key().toStdString();
		const QJsonValue v = it.value();
		if (v.isObject())
			flatten(v.toObject(), key, out);
		else if (v.isDouble())
			out[key] = number(v);
		else if (v.isBool())
			out[key] = QVariant(v.toBool());
	}
}

QJsonObject parse(const char* json)
{
	if (json == nullptr)
		return QJsonObject();
	QJsonParseError error;
	const QJsonDocument doc = QJsonDocument::fromJson(QByteArray(json), &error);
	if (doc.isNull())
		throw MLException("Capmesh: the report is not valid JSON (" + error.errorString() + ").");
	return doc.object();
}

} // namespace

std::map<std::string, QVariant> flattenReport(const char* json)
{
	std::map<std::string, QVariant> out;
	flatten(parse(json), std::string(), out);
	return out;
}

std::map<std::string, QVariant> lastArrayEntry(const char* json, const QString& arrayKey, const std::string& prefix)
{
	std::map<std::string, QVariant> out;
	const QJsonArray array = parse(json).value(arrayKey).toArray();
	if (!array.isEmpty() && array.last().isObject())
		flatten(array.last().toObject(), prefix, out);
	return out;
}

} // namespace capmesh_meshlab
