/* capmesh MeshLab plugin — GPL-3.0-or-later (links MeshLab; see ../README.md). */
#include "progress_callback.h"

#include <algorithm>
#include <cmath>

namespace capmesh_meshlab {

int32_t forwardProgress(void* user_data, int32_t /*stage*/, double fraction, const char* message)
{
	auto* target = static_cast<ProgressTarget*>(user_data);
	if (target == nullptr || target->cb == nullptr)
		return 0;
	const double f = std::isfinite(fraction) ? std::clamp(fraction, 0.0, 1.0) : 0.0;
	const int percent = int(std::lround(100.0 * f));
	std::string text = target->filter;
	if (message != nullptr && message[0] != '\0')
		text += ": " + std::string(message);
	if (percent == target->lastPercent && text == target->lastMessage)
		return 0;
	target->lastPercent = percent;
	target->lastMessage = text;
	return (*target->cb)(percent, text.c_str()) ? 0 : 1;
}

} // namespace capmesh_meshlab
