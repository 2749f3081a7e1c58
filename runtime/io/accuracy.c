/* accuracy.c — SIM --accuracy: how much a run's answer depends on its step.
 * One of the io/ files that read a run's HDF5 file back (h5get.h).
 *
 * Design.  sim/cli_accuracy.c runs the model at dt and at dt/2 (and on,
 * halving) into two files; this compares them.  The two runs share the
 * frame times exactly (a frame every k steps at dt is one every 2k at dt/2,
 * run.c), so the files are compared frame by frame over the frames both
 * have (a run that became unstable has fewer).  Observables are what a user
 * asked to see: each probe, as a vector (the difference is the Euclidean
 * norm of the difference of its rows), and each hinge's angle (a joint whose
 * angle is 0 throughout in both files is not a hinge and is skipped).  Each
 * is held to its own scale: its range over the finer run, max - min of any
 * component, so that a toe that rises 20 mm is judged against 20 mm and not
 * against its height above the origin; an observable that barely moves
 * (range below 1e-9 of its magnitude) is judged against its magnitude.  It
 * "parts" at the first frame whose difference exceeds tol times the scale.
 * The objective, which a model with `maximize` or `minimize` stores as
 * attributes of the root (output_attrs.c), is read from both files. */
#include <hdf5.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sinew.h"
#include "h5get.h"
#include "engine/vec.h"

typedef struct {
  hid_t coarse, fine;
  double tol;
  const double *time;        /* the coarse file's frame times              */
  long frames;
  swAccuracy *a;
} swAcc;

/* One numeric dataset of both files, as [frames][width]; 0 when either is
 * missing or they do not fit. */
static int read_pair(swAcc *c, const char *path, double **x, double **y, size_t *width) {
  *x = *y = NULL;
  if (H5Lexists(c->coarse, path, H5P_DEFAULT) <= 0 || H5Lexists(c->fine, path, H5P_DEFAULT) <= 0)
    return 0;
  hid_t dx = H5Dopen2(c->coarse, path, H5P_DEFAULT), dy = H5Dopen2(c->fine, path, H5P_DEFAULT);
  int rx = 0, ry = 0;
  hsize_t ex[8] = {0}, ey[8] = {0};
  size_t nx = 0, ny = 0;
  if (dx >= 0) *x = sw_h5_read_all(dx, &rx, ex, &nx);
  if (dy >= 0) *y = sw_h5_read_all(dy, &ry, ey, &ny);
  if (dx >= 0) H5Dclose(dx);
  if (dy >= 0) H5Dclose(dy);
  int ok = *x && *y && rx == ry && rx >= 1 && ex[0] >= (hsize_t)c->frames && ey[0] >= (hsize_t)c->frames;
  for (int k = 1; ok && k < rx; k++) ok = ex[k] == ey[k];
  if (ok) *width = ex[0] ? nx / (size_t)ex[0] : 1;
  if (!ok) {
    free(*x);
    free(*y);
    *x = *y = NULL;
  }
  return ok;
}

static void units_of(hid_t file, const char *path, char *buf, size_t len) {
  buf[0] = '\0';
  hid_t ds = H5Dopen2(file, path, H5P_DEFAULT);
  if (ds < 0) return;
  sw_h5_units(ds, buf, len);
  H5Dclose(ds);
}

/* The observable at `path` (width values a frame) into the next item. */
static void observe(swAcc *c, const char *path, const char *label, int skip_zero) {
  double *x, *y;
  size_t w;
  if (!read_pair(c, path, &x, &y, &w)) return;
  const size_t n = (size_t)c->frames;
  double lo[8], hi[8], mag = 0;
  const size_t wk = w < 8 ? w : 8;
  for (size_t k = 0; k < wk; k++) lo[k] = INFINITY, hi[k] = -INFINITY;
  int nonzero = 0;
  for (size_t f = 0; f < n; f++)
    for (size_t k = 0; k < w; k++) {
      const double v = y[f * w + k];
      if (k < wk) lo[k] = sw_min(v, lo[k]), hi[k] = sw_max(v, hi[k]); /* vec.h: not fmin */
      mag = sw_max(fabs(v), mag);
      nonzero |= v != 0 || x[f * w + k] != 0;
    }
  if (skip_zero && !nonzero) {
    free(x);
    free(y);
    return;
  }
  double range = 0;
  for (size_t k = 0; k < wk; k++) range = fmax(range, hi[k] - lo[k]);
  const double scale = range > 1e-9 * mag ? range : mag;
  double worst = 0, part = NAN;
  for (size_t f = 0; f < n; f++) {
    double d2 = 0;
    for (size_t k = 0; k < w; k++) {
      const double d = x[f * w + k] - y[f * w + k];
      d2 += d * d;
    }
    const double d = isnan(d2) ? INFINITY : sqrt(d2);
    worst = fmax(worst, d);
    if (isnan(part) && d > c->tol * scale) part = c->time[f];
  }
  free(x);
  free(y);
  swAccuracy *a = c->a;
  if (a->n == SW_ACCURACY_MAX) {
    a->more++;
    return;
  }
  swAccuracyItem *it = &a->item[a->n++];
  snprintf(it->name, sizeof it->name, "%s", label);
  units_of(c->fine, path, it->units, sizeof it->units);
  it->worst = worst;
  it->scale = scale;
  it->part_time = part;
}

typedef struct {
  swAcc *c;
  const char *group;         /* "probes" or "joints"                       */
} swVisit;

static herr_t each(hid_t g, const char *name, const H5L_info_t *info, void *data) {
  (void)g;
  (void)info;
  swVisit *v = data;
  char path[512], label[128];
  if (!strcmp(v->group, "probes")) {
    snprintf(path, sizeof path, "/probes/%s", name);
    snprintf(label, sizeof label, "probe %s", name);
    observe(v->c, path, label, 0);
  } else {
    snprintf(path, sizeof path, "/joints/%s/angle", name);
    snprintf(label, sizeof label, "joint %s", name);
    observe(v->c, path, label, 1);
  }
  return 0;
}

static void each_in(swAcc *c, const char *group) {
  char path[64];
  snprintf(path, sizeof path, "/%s", group);
  if (H5Lexists(c->coarse, path, H5P_DEFAULT) <= 0) return;
  hid_t g = H5Gopen2(c->coarse, path, H5P_DEFAULT);
  if (g < 0) return;
  swVisit v = {c, group};
  H5Literate(g, H5_INDEX_NAME, H5_ITER_INC, NULL, each, &v);
  H5Gclose(g);
}

/* The root's attribute `name` as a double; 0 when it has none. */
static int root_number(hid_t file, const char *name, double *value) {
  if (H5Aexists(file, name) <= 0) return 0;
  hid_t at = H5Aopen(file, name, H5P_DEFAULT);
  int ok = at >= 0 && H5Aread(at, H5T_NATIVE_DOUBLE, value) >= 0;
  if (at >= 0) H5Aclose(at);
  return ok;
}

static long frames_of(hid_t file, double **time) {
  *time = NULL;
  if (H5Lexists(file, "/time", H5P_DEFAULT) <= 0) return -1;
  hid_t ds = H5Dopen2(file, "/time", H5P_DEFAULT);
  int rank = 0;
  hsize_t dims[8] = {0};
  size_t n = 0;
  *time = ds >= 0 ? sw_h5_read_all(ds, &rank, dims, &n) : NULL;
  if (ds >= 0) H5Dclose(ds);
  return *time && rank == 1 ? (long)n : -1;
}

int sw_accuracy_compare(const char *coarse, const char *fine, double tol, swAccuracy *a,
                        char *err, size_t errlen) {
  memset(a, 0, sizeof *a);
  a->objective[0] = a->objective[1] = NAN;
  H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
  hid_t fc = H5Fopen(coarse, H5F_ACC_RDONLY, H5P_DEFAULT);
  hid_t ff = fc >= 0 ? H5Fopen(fine, H5F_ACC_RDONLY, H5P_DEFAULT) : -1;
  if (fc < 0 || ff < 0) {
    snprintf(err, errlen, "cannot open %s as an HDF5 file", fc < 0 ? coarse : fine);
    if (fc >= 0) H5Fclose(fc);
    return SW_EIO;
  }
  double *tc = NULL, *tf = NULL;
  a->frames_coarse = frames_of(fc, &tc);
  a->frames_fine = frames_of(ff, &tf);
  int rc = SW_OK;
  if (a->frames_coarse < 0 || a->frames_fine < 0) {
    snprintf(err, errlen, "%s has no /time", a->frames_coarse < 0 ? coarse : fine);
    rc = SW_EIO;
  } else {
    a->frames = a->frames_coarse < a->frames_fine ? a->frames_coarse : a->frames_fine;
    /* the frames are at the same times (to the step's round-off) */
    for (long f = 0; f < a->frames && rc == SW_OK; f++)
      if (fabs(tc[f] - tf[f]) > 1e-9 * fmax(1e-9, fabs(tc[f]))) {
        snprintf(err, errlen, "frame %ld is at t = %.9g s in %s and %.9g s in %s: the runs do "
                 "not share their frames", f, tc[f], coarse, tf[f], fine);
        rc = SW_EIO;
      }
  }
  if (rc == SW_OK) {
    swAcc c = {fc, ff, tol, tc, a->frames, a};
    each_in(&c, "probes");
    each_in(&c, "joints");
    a->has_objective = root_number(fc, "objective", &a->objective[0]) |
                       root_number(ff, "objective", &a->objective[1]);
  }
  free(tc);
  free(tf);
  H5Fclose(fc);
  H5Fclose(ff);
  return rc;
}
