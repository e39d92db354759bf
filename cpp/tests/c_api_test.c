/* The C ABI from plain C99: read an OBJ, remesh it, cancel, and misuse the API.
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

  free(m.positions);
  free(m.triangles);
  printf("%s\n", failures ? "FAILED" : "all C checks passed");
  return failures ? 1 : 0;
}
