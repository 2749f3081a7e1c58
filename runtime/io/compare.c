/* compare.c — SIM --compare GOLDEN.h5: a run against a stored one, dataset
 * by dataset.  One of the io/ files that include hdf5.h: this one reads a
 * golden file, output.c and its siblings write a run's, restart.c its
 * checkpoint.
 *
 * Design.  Every numeric dataset of the golden file but the checkpoint
 * /restart (the simulator's state, not a result) must exist in the run's
 * file with the same shape, and its values must agree within rtol of the
 * dataset's largest magnitude in the golden file:
 *   max |run - golden| <= rtol * max |golden|
 * a scale per dataset, so that a position of metres and a force of
 * kilonewtons are each held to their own size, and a value that crosses
 * zero is not held to a relative error it cannot have (the measure of
 * scripts/compare_h5.py).  NaN matches nothing.  Datasets the run has and the
 * golden file has not are listed, not failed (a newer sinew writes more);
 * string datasets are skipped.  The report names each dataset that differs,
 * with the largest difference in its `units`, that difference over the
 * dataset's scale, and the first frame where it exceeds the tolerance. */
#include <hdf5.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sinew.h"
#include "h5get.h"

typedef struct {
  hid_t run;          /* the run's file                      */
  double rtol;
  FILE *f;
  const char *prog;
  int matched, differ, missing, read_errors;
} swCompare;

void sw_h5_units(hid_t ds, char *buf, size_t len) {
  buf[0] = 0;
  if (H5Aexists(ds, "units") <= 0) return;
  hid_t a = H5Aopen(ds, "units", H5P_DEFAULT);
  if (a < 0) return;
  hid_t t = H5Aget_type(a);
  if (t >= 0 && H5Tget_class(t) == H5T_STRING) {
    if (H5Tis_variable_str(t) > 0) {
      char *s = NULL;
      hid_t mt = H5Tcopy(H5T_C_S1);
      H5Tset_size(mt, H5T_VARIABLE);
      H5Tset_cset(mt, H5Tget_cset(t));
      if (H5Aread(a, mt, &s) >= 0 && s) {
        snprintf(buf, len, "%s", s);
        H5free_memory(s);
      }
      H5Tclose(mt);
    } else {
      size_t n = H5Tget_size(t);
      char *s = calloc(n + 1, 1);
      if (s && H5Aread(a, t, s) >= 0) snprintf(buf, len, "%s", s);
      free(s);
    }
  }
  if (t >= 0) H5Tclose(t);
  H5Aclose(a);
}

double *sw_h5_read_all(hid_t ds, int *rank, hsize_t dims[8], size_t *count) {
  hid_t space = H5Dget_space(ds);
  if (space < 0) return NULL;
  int r = H5Sget_simple_extent_ndims(space);
  if (r < 0 || r > 8) {
    H5Sclose(space);
    return NULL;
  }
  H5Sget_simple_extent_dims(space, dims, NULL);
  H5Sclose(space);
  size_t n = 1;
  for (int k = 0; k < r; k++) n *= (size_t)dims[k];
  double *v = malloc((n ? n : 1) * sizeof *v);
  if (v && n && H5Dread(ds, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v) < 0) {
    free(v);
    return NULL;
  }
  *rank = r;
  *count = n;
  return v;
}

static void dims_text(char *buf, size_t len, int rank, const hsize_t *dims) {
  size_t used = (size_t)snprintf(buf, len, "[");
  for (int k = 0; k < rank && used < len; k++)
    used += (size_t)snprintf(buf + used, len - used, "%s%llu", k ? ", " : "",
                             (unsigned long long)dims[k]);
  if (used < len) snprintf(buf + used, len - used, "]");
}

static void compare_dataset(swCompare *c, const char *name, hid_t golden) {
  hid_t t = H5Dget_type(golden);
  H5T_class_t cls = t >= 0 ? H5Tget_class(t) : H5T_NO_CLASS;
  if (t >= 0) H5Tclose(t);
  if (cls != H5T_FLOAT && cls != H5T_INTEGER) return; /* strings and the like */
  if (H5Lexists(c->run, name, H5P_DEFAULT) <= 0) {
    fprintf(c->f, "    FAILED /%s: not in the run's file\n", name);
    c->missing++;
    return;
  }
  hid_t run = H5Dopen2(c->run, name, H5P_DEFAULT);
  int rg = 0, rr = 0;
  hsize_t dg[8] = {0}, dr[8] = {0};
  size_t ng = 0, nr = 0;
  double *g = sw_h5_read_all(golden, &rg, dg, &ng);
  double *r = run >= 0 ? sw_h5_read_all(run, &rr, dr, &nr) : NULL;
  char units[64] = "";
  sw_h5_units(golden, units, sizeof units);
  if (!g || !r) {
    fprintf(c->f, "    FAILED /%s: cannot be read\n", name);
    c->read_errors++;
  } else if (rg != rr || memcmp(dg, dr, (size_t)rg * sizeof *dg)) {
    char a[96], b[96];
    dims_text(a, sizeof a, rg, dg);
    dims_text(b, sizeof b, rr, dr);
    fprintf(c->f, "    FAILED /%s: shape %s, the golden file's %s\n", name, b, a);
    c->differ++;
  } else {
    double scale = 0, worst = 0;
    for (size_t i = 0; i < ng; i++) scale = fmax(scale, fabs(g[i]));
    size_t per_frame = rg > 0 && dg[0] ? ng / (size_t)dg[0] : 1, first_bad = (size_t)-1;
    for (size_t i = 0; i < ng; i++) {
      double diff = fabs(r[i] - g[i]);
      if (!(diff <= worst)) worst = isnan(diff) ? INFINITY : fmax(worst, diff);
      if (!(diff <= c->rtol * scale) && first_bad == (size_t)-1) first_bad = i;
    }
    const char *sp = units[0] && strcmp(units, "-") ? " " : "";
    const char *u = units[0] && strcmp(units, "-") ? units : "";
    if (first_bad == (size_t)-1) {
      c->matched++;
    } else {
      fprintf(c->f, "    FAILED /%s: differs by up to %.3g%s%s (%.3g of its largest value, "
              "%.3g%s%s), first at frame %zu\n", name, worst, sp, u,
              scale > 0 ? worst / scale : INFINITY, scale, sp, u,
              per_frame ? first_bad / per_frame : 0);
      c->differ++;
    }
  }
  free(g);
  free(r);
  if (run >= 0) H5Dclose(run);
}

static herr_t visit(hid_t obj, const char *name, const H5O_info_t *info, void *data) {
  if (info->type != H5O_TYPE_DATASET) return 0;
  /* the checkpoint (restart.c) is the simulator's, not a result */
  if (!strncmp(name, "restart/", 8)) return 0;
  hid_t ds = H5Dopen2(obj, name, H5P_DEFAULT);
  if (ds < 0) return 0;
  compare_dataset((swCompare *)data, name, ds);
  H5Dclose(ds);
  return 0;
}

int sw_compare_files(const char *run_path, const char *golden_path, double rtol, FILE *f,
                     const char *prog) {
  H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
  hid_t golden = H5Fopen(golden_path, H5F_ACC_RDONLY, H5P_DEFAULT);
  if (golden < 0) {
    fprintf(f, "%s: --compare: cannot open '%s' as an HDF5 file\n", prog, golden_path);
    return -1;
  }
  hid_t run = H5Fopen(run_path, H5F_ACC_RDONLY, H5P_DEFAULT);
  if (run < 0) {
    fprintf(f, "%s: --compare: cannot open the run's file '%s'\n", prog, run_path);
    H5Fclose(golden);
    return -1;
  }
  swCompare c = {run, rtol, f, prog, 0, 0, 0, 0};
  fprintf(f, "%s: compare with %s (rtol %g of each dataset's largest value):\n", prog,
          golden_path, rtol);
  H5Ovisit2(golden, H5_INDEX_NAME, H5_ITER_INC, visit, &c, H5O_INFO_BASIC);
  int bad = c.differ + c.missing + c.read_errors;
  fprintf(f, "%s: compare: %d dataset%s match, %d differ%s\n", prog, c.matched,
          c.matched == 1 ? "" : "s", bad, bad == 1 ? "s" : "");
  fflush(f);
  H5Fclose(run);
  H5Fclose(golden);
  return bad;
}
