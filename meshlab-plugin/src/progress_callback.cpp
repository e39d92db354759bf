/* capmesh MeshLab plugin — GPL-3.0-or-later (links MeshLab; see ../README.md). */
#include "progress_callback.h"

#include <algorithm>
#include <cmath>

namespace capmesh_meshlab {

namespace {

struct Band { double from, to; };

Band bandOf(int32_t stage)
{
	switch (stage) {
	case CAPMESH_V1_STAGE_VALIDATE: return {0, 5};
	case CAPMESH_V1_STAGE_FLATTEN: return {5, 25};
	case CAPMESH_V1_STAGE_RADIUS_SEARCH:
	case CAPMESH_V1_STAGE_TRANSPORT: return {25, 85};
	case CAPMESH_V1_STAGE_PROJECT: return {85, 90};
	case CAPMESH_V1_STAGE_REMESH:
	case CAPMESH_V1_STAGE_HARMONICS: return {90, 100};
	}
	return {-1, -1};
}

} // namespace

int overallPercent(ProgressTarget& target, int32_t stage, double fraction)
{
	if (stage == CAPMESH_V1_STAGE_RADIUS_SEARCH)
		target.radiusSearch = true;
	if (stage == CAPMESH_V1_STAGE_TRANSPORT && target.radiusSearch)
		return -1;
	const Band band = bandOf(stage);
	if (band.from < 0)
		return -1;
	const double f = std::isfinite(fraction) ? std::clamp(fraction, 0.0, 1.0) : 0.0;
	return int(std::lround(band.from + f * (band.to - band.from)));
}

int32_t forwardProgress(void* user_data, int32_t stage, double fraction, const char* message)
{
	auto* target = static_cast<ProgressTarget*>(user_data);
	if (target == nullptr || target->cb == nullptr)
		return 0;
	const int percent = overallPercent(*target, stage, fraction);
	const int shown = std::max(target->percent, percent);
	std::string text = target->filter;
	if (message != nullptr && message[0] != '\0')
		text += ": " + std::string(message);
	if (shown == target->percent && text == target->lastMessage)
		return 0;
	target->percent = shown;
	target->lastMessage = text;
	return (*target->cb)(shown, text.c_str()) ? 0 : 1;
}

} // namespace capmesh_meshlab
