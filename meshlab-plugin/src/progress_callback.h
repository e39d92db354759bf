/* capmesh MeshLab plugin — GPL-3.0-or-later (links MeshLab; see ../README.md).
 *
 * capmesh's progress callback forwarded to MeshLab's vcg::CallBackPos (percent + message).
 * MeshLab's callback returns false to ask for cancellation; capmesh's returns nonzero. */
#ifndef CAPMESH_MESHLAB_PROGRESS_CALLBACK_H
#define CAPMESH_MESHLAB_PROGRESS_CALLBACK_H

#include <wrap/callback.h> // vcg::CallBackPos

#include <capmesh.h>

#include <string>

namespace capmesh_meshlab {

struct ProgressTarget
{
	vcg::CallBackPos* cb = nullptr;
	std::string filter;     ///< prefix of every message, e.g. "Capmesh remesh"
	int lastPercent = -1;   ///< MeshLab redraws on every call; skip repeats
	std::string lastMessage;
};

/// A capmesh_v1_progress_fn; `user_data` is a ProgressTarget*.
int32_t forwardProgress(void* user_data, int32_t stage, double fraction, const char* message);

} // namespace capmesh_meshlab

#endif
