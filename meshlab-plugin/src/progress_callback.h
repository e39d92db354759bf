/* capmesh MeshLab plugin — GPL-3.0-or-later (links MeshLab; see ../README.md).
 *
 * capmesh's progress callback forwarded to MeshLab's vcg::CallBackPos (percent + message).
 * capmesh reports a fraction per stage; MeshLab shows one bar, so each stage gets a band of
 * it (checking 0-5 %, flattening 5-25 %, radius search 25-85 %, projection 85-90 %, remeshing
 * or harmonics fit 90-100 %). The transport solves run inside the radius search and only
 * update the message then; with a fixed domain they fill the radius search's band. The bar
 * never goes back. MeshLab's callback returns false to ask for cancellation; capmesh's
 * returns nonzero. */
#ifndef CAPMESH_MESHLAB_PROGRESS_CALLBACK_H
#define CAPMESH_MESHLAB_PROGRESS_CALLBACK_H

#include <wrap/callback.h> // vcg::CallBackPos

#include <capmesh.h>

#include <string>

namespace capmesh_meshlab {

struct ProgressTarget
{
	vcg::CallBackPos* cb = nullptr;
	std::string filter;      ///< prefix of every message, e.g. "Capmesh remesh"
	int percent = 0;         ///< last percent shown
	bool radiusSearch = false; ///< the radius search has started (transport is nested in it)
	std::string lastMessage;
};

/// The overall percent for `fraction` of `stage`, or -1 to keep the current one.
int overallPercent(ProgressTarget& target, int32_t stage, double fraction);

/// A capmesh_v1_progress_fn; `user_data` is a ProgressTarget*.
int32_t forwardProgress(void* user_data, int32_t stage, double fraction, const char* message);

} // namespace capmesh_meshlab

#endif
