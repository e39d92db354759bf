/* capmesh MeshLab plugin — GPL-3.0-or-later (see ../README.md).
 *
 * The progress bridge without MeshLab: capmesh's remesh of a small planar grid (an open disk)
 * reports through forwardProgress into a vcg::CallBackPos that records percents, then one that
 * refuses (MeshLab's "cancel") must stop capmesh with CAPMESH_V1_CANCELLED. Run by
 * tests/test_plugin.py; prints "ok" and exits 0 on success. */
#include "progress_callback.h"

#include <capmesh.h>

#include <cstdio>
#include <vector>

namespace {

std::vector<int> percents;
int calls = 0;

bool record(const int pos, const char*) { percents.push_back(pos); ++calls; return true; }
bool refuse(const int, const char*) { ++calls; return false; }

int fail(const char* what)
{
	std::printf("FAILED: %s (%s)\n", what, capmesh_v1_last_error());
	return 1;
}

} // namespace

int main()
{
	const int n = 12; // (n + 1)^2 vertices on the unit square
	std::vector<double> positions;
	std::vector<uint32_t> triangles;
	for (int j = 0; j <= n; ++j)
		for (int i = 0; i <= n; ++i) {
			positions.push_back(double(i) / n);
			positions.push_back(double(j) / n);
			positions.push_back(0.1 * double(i * j) / (n * n));
		}
	for (int j = 0; j < n; ++j)
		for (int i = 0; i < n; ++i) {
			const uint32_t a = uint32_t(j * (n + 1) + i), b = a + 1, c = a + uint32_t(n + 1), d = c + 1;
			triangles.insert(triangles.end(), {a, b, d, a, d, c});
		}
	const capmesh_v1_mesh_view view{positions.data(), positions.size() / 3, triangles.data(), triangles.size() / 3};
	capmesh_v1_remesh_options options = capmesh_v1_remesh_options_default();
	options.faces = 200;

	capmesh_meshlab::ProgressTarget progress{record, "test"};
	capmesh_v1_mesh* mesh = nullptr;
	char* json = nullptr;
	if (capmesh_v1_remesh(&view, &options, capmesh_meshlab::forwardProgress, &progress, &mesh, &json) != CAPMESH_V1_OK)
		return fail("remesh");
	capmesh_v1_mesh_free(mesh);
	capmesh_v1_string_free(json);
	if (percents.size() < 3)
		return fail("too few progress calls");
	for (size_t i = 1; i < percents.size(); ++i)
		if (percents[i] < percents[i - 1])
			return fail("progress went back");
	if (percents.front() != 0 || percents.back() < 90 || percents.back() > 100)
		return fail("progress does not span the bar");

	calls = 0;
	capmesh_meshlab::ProgressTarget cancelling{refuse, "test"};
	mesh = nullptr;
	json = nullptr;
	const capmesh_v1_status s = capmesh_v1_remesh(&view, &options, capmesh_meshlab::forwardProgress, &cancelling, &mesh, &json);
	if (s != CAPMESH_V1_CANCELLED)
		return fail("a refusing callback did not cancel");
	if (mesh != nullptr || json != nullptr)
		return fail("a cancelled call returned results");
	if (calls != 1)
		return fail("capmesh went on calling after the cancel");
	std::printf("ok: %zu progress calls, last %d%%; cancelled after 1 call\n", percents.size(), percents.back());
	return 0;
}
