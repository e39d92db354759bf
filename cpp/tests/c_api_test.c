/* The C ABI from plain C99: read an OBJ, remesh it, cancel, and misuse the API; the cap map
 * handle gives the input vertices back from their cap points (open and closed surfaces).
 * Usage: capmesh_c_test MESH_DIR */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "capmesh.h"

static int failures = 0;
#define CHECK(cond)                                                        \
  do {                                                                     \
    if (!(cond)) {                                                         \
      fprintf(stderr, "%s:%d: CHECK failed: %s\n", __FILE__, __LINE__, #cond); \
      failures++;                                                          \
    }                                                                      \
  } while (0)

typedef struct {
  double *positions;
  size_t nv, cap_v;
  uint32_t *triangles;
  size_t nf, cap_f;
} obj_mesh;

/* Minimal OBJ reader: "v x y z" and triangular "f a b c" (a, a/b, a/b/c, a//c). */
static int read_obj(const char *path, obj_mesh *m) {
  FILE *f = fopen(path, "r");
  char line[512];
  memset(m, 0, sizeof *m);
  if (!f) return 0;
  while (fgets(line, sizeof line, f)) {
    if (line[0] == 'v' && line[1] == ' ') {
      if (m->nv == m->cap_v) {
        m->cap_v = m->cap_v ? 2 * m->cap_v : 1024;
        m->positions = realloc(m->positions, 3 * m->cap_v * sizeof(double));
      }
      if (sscanf(line + 2, "%lf %lf %lf", &m->positions[3 * m->nv], &m->positions[3 * m->nv + 1],
                 &m->positions[3 * m->nv + 2]) != 3) {
        fclose(f);
        return 0;
      }
      m->nv++;
    } else if (line[0] == 'f' && line[1] == ' ') {
      char *p = line + 2;
      int k;
      if (m->nf == m->cap_f) {
        m->cap_f = m->cap_f ? 2 * m->cap_f : 1024;
        m->triangles = realloc(m->triangles, 3 * m->cap_f * sizeof(uint32_t));
      }
      for (k = 0; k < 3; k++) {
        char *end;
        long idx = strtol(p, &end, 10);
        if (end == p || idx < 1) {
          fclose(f);
          return 0;
        }
        m->triangles[3 * m->nf + k] = (uint32_t)(idx - 1);
        p = end;
        while (*p && *p != ' ' && *p != '\t') p++;
      }
      m->nf++;
    }
  }
  fclose(f);
  return m->nv > 0 && m->nf > 0;
}

static int calls = 0;
static int32_t cancel_on_third(void *user, int32_t stage, double fraction, const char *message) {
  (void)user;
  (void)stage;
  (void)message;
  CHECK(fraction >= 0.0 && fraction <= 1.0);
  return ++calls >= 3;
}

/* Parameterize `m` into a map handle, invert its cap vertices and check that the input
 * vertices come back (within 1e-9 of the bounding-box diagonal), that a point off the cap is
 * reported, and that the forward map sends the surface points back to the cap vertices. */
static void map_round_trip(const obj_mesh *m, const char *name) {
  capmesh_v1_mesh_view view;
  capmesh_v1_map *map = NULL;
  const double *cap;
  double *pos, *bary, *fwd, lo[3], hi[3], diag = 0.0, worst = 0.0, worst_fwd = 0.0;
  double off[6] = {0.0, 0.0, 1.0, 0.0, 0.0, 3.0};
  uint32_t *faces;
  int32_t *located, off_status[2] = {-1, -1};
  size_t i, k, nv, count = 0;
  capmesh_v1_status s;

  view.positions = m->positions;
  view.vertex_count = m->nv;
  view.triangles = m->triangles;
  view.face_count = m->nf;
  s = capmesh_v1_parameterize_map(&view, NULL, NULL, NULL, &map, NULL);
  CHECK(s == CAPMESH_V1_OK);
  if (s != CAPMESH_V1_OK) {
    fprintf(stderr, "%s: %s\n", name, capmesh_v1_last_error());
    return;
  }
  nv = capmesh_v1_map_vertex_count(map);
  CHECK(nv == m->nv);
  CHECK(capmesh_v1_map_face_count(map) == m->nf);
  cap = capmesh_v1_map_cap_positions(map);
  CHECK(cap != NULL && capmesh_v1_map_uv(map) != NULL);
  pos = malloc(3 * nv * sizeof(double));
  bary = malloc(3 * nv * sizeof(double));
  fwd = malloc(3 * nv * sizeof(double));
  faces = malloc(nv * sizeof(uint32_t));
  located = malloc(nv * sizeof(int32_t));
  s = capmesh_v1_map_inverse(map, cap, nv, pos, faces, bary, located, &count);
  CHECK(s == CAPMESH_V1_OK);
  CHECK(count == nv);
  for (k = 0; k < 3; k++) lo[k] = hi[k] = m->positions[k];
  for (i = 0; i < nv; i++)
    for (k = 0; k < 3; k++) {
      double x = m->positions[3 * i + k];
      lo[k] = x < lo[k] ? x : lo[k];
      hi[k] = x > hi[k] ? x : hi[k];
    }
  for (k = 0; k < 3; k++) diag += (hi[k] - lo[k]) * (hi[k] - lo[k]);
  diag = sqrt(diag);
  for (i = 0; i < nv; i++) {
    double d = 0.0;
    CHECK(located[i] == CAPMESH_V1_POINT_LOCATED);
    CHECK(faces[i] < m->nf);
    for (k = 0; k < 3; k++) d += (pos[3 * i + k] - m->positions[3 * i + k]) * (pos[3 * i + k] - m->positions[3 * i + k]);
    worst = sqrt(d) > worst ? sqrt(d) : worst;
  }
  printf("%s: %zu cap vertices inverted, worst distance to the input vertex %.3g (diagonal %.3g)\n", name, nv, worst, diag);
  CHECK(worst <= 1e-9 * diag);
  /* Forward map of the located surface points: the cap vertices again. */
  s = capmesh_v1_map_forward(map, faces, bary, nv, fwd);
  CHECK(s == CAPMESH_V1_OK);
  for (i = 0; i < 3 * nv; i++) worst_fwd = fabs(fwd[i] - cap[i]) > worst_fwd ? fabs(fwd[i] - cap[i]) : worst_fwd;
  CHECK(worst_fwd < 1e-6);
  /* The north pole is on the cap, (0, 0, 3) is not: reported, not guessed. */
  s = capmesh_v1_map_inverse(map, off, 2, NULL, NULL, NULL, off_status, &count);
  CHECK(s == CAPMESH_V1_OK && count == 1);
  CHECK(off_status[0] == CAPMESH_V1_POINT_LOCATED && off_status[1] == CAPMESH_V1_POINT_OFF_CAP);
  /* Misuse: no status array; NULL map. */
  s = capmesh_v1_map_inverse(map, off, 2, NULL, NULL, NULL, NULL, NULL);
  CHECK(s == CAPMESH_V1_INVALID_ARGUMENT && strstr(capmesh_v1_last_error(), "out_located") != NULL);
  s = capmesh_v1_map_inverse(NULL, off, 2, NULL, NULL, NULL, off_status, NULL);
  CHECK(s == CAPMESH_V1_INVALID_ARGUMENT && strstr(capmesh_v1_last_error(), "map is NULL") != NULL);
  free(pos);
  free(bary);
  free(fwd);
  free(faces);
  free(located);
  capmesh_v1_map_free(map);
}

int main(int argc, char **argv) {
  char path[1024];
  obj_mesh m;
  capmesh_v1_mesh_view view, bad;
  capmesh_v1_remesh_options opt = capmesh_v1_remesh_options_default();
  capmesh_v1_mesh *out = NULL;
  char *report = NULL;
  capmesh_v1_status s;
  size_t nf;
  uint32_t saved;

  if (argc < 2) return 2;
  snprintf(path, sizeof path, "%s/open_meg_helmet_babysquid_mne.obj", argv[1]);
  CHECK(read_obj(path, &m));
  view.positions = m.positions;
  view.vertex_count = m.nv;
  view.triangles = m.triangles;
  view.face_count = m.nf;
  printf("capmesh %s, input %zu vertices %zu faces\n", capmesh_v1_version(), m.nv, m.nf);

  /* Remesh into about 1000 faces. */
  opt.faces = 1000;
  s = capmesh_v1_remesh(&view, &opt, NULL, NULL, &out, &report);
  CHECK(s == CAPMESH_V1_OK);
  CHECK(strcmp(capmesh_v1_last_error(), "") == 0);
  nf = capmesh_v1_mesh_face_count(out);
  printf("remeshed: %zu faces, %zu vertices\n", nf, capmesh_v1_mesh_vertex_count(out));
  CHECK(nf >= 900 && nf <= 1100);
  CHECK(report != NULL && strstr(report, "\"d_face_relative\"") != NULL);
  /* The default optimisation is shape+area. */
  CHECK(opt.optimize == CAPMESH_V1_OPTIMIZE_SHAPE_AND_AREA);
  CHECK(strstr(report, "\"optimize\":\"shape+area\"") != NULL);
  CHECK(capmesh_v1_mesh_positions(out) != NULL && capmesh_v1_mesh_triangles(out) != NULL);
  capmesh_v1_mesh_free(out);
  capmesh_v1_string_free(report);

  /* Cancel from the callback. */
  out = (capmesh_v1_mesh *)&opt; /* garbage: must be reset to NULL */
  s = capmesh_v1_remesh(&view, &opt, cancel_on_third, NULL, &out, NULL);
  CHECK(s == CAPMESH_V1_CANCELLED);
  CHECK(out == NULL);
  CHECK(calls == 3);
  CHECK(strlen(capmesh_v1_last_error()) > 0);

  /* Misuse: NULL view, NULL output, out-of-range index, vertex_count too small. */
  s = capmesh_v1_remesh(NULL, &opt, NULL, NULL, &out, NULL);
  CHECK(s == CAPMESH_V1_INVALID_ARGUMENT && strlen(capmesh_v1_last_error()) > 0);
  s = capmesh_v1_remesh(&view, &opt, NULL, NULL, NULL, NULL);
  CHECK(s == CAPMESH_V1_INVALID_ARGUMENT && strstr(capmesh_v1_last_error(), "out_mesh") != NULL);
  saved = m.triangles[5];
  m.triangles[5] = (uint32_t)m.nv;
  s = capmesh_v1_remesh(&view, &opt, NULL, NULL, &out, NULL);
  CHECK(s == CAPMESH_V1_INVALID_MESH && strstr(capmesh_v1_last_error(), "triangle 1") != NULL);
  m.triangles[5] = saved;
  bad = view;
  bad.vertex_count = 10;
  s = capmesh_v1_parameterize(&bad, NULL, NULL, NULL, &out, NULL);
  CHECK(s == CAPMESH_V1_INVALID_MESH && strlen(capmesh_v1_last_error()) > 0);
  CHECK(out == NULL);

  /* The map handle: the cap vertices give the input vertices back. */
  map_round_trip(&m, "open_meg_helmet_babysquid_mne");
  free(m.positions);
  free(m.triangles);
  snprintf(path, sizeof path, "%s/closed_bunny_npm.obj", argv[1]);
  CHECK(read_obj(path, &m));
  map_round_trip(&m, "closed_bunny_npm");
  free(m.positions);
  free(m.triangles);
  printf("%s\n", failures ? "FAILED" : "all C checks passed");
  return failures ? 1 : 0;
}
