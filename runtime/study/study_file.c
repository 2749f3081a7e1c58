/* study_file.c — the HDF5 file of a sweep or an optimisation: every
 * evaluation as it arrives, the best design, the optimiser's path, and what
 * --resume needs to continue.  With output.c, compare.c and restart.c, the
 * only files of the runtime that include hdf5.h.
 *
 * Design.  One row per evaluation, at the evaluation's index (its place in
 * the deterministic sequence of designs), so that results arriving from
 * several ranks in any order land where a serial run puts them: the files of
 * `-np 1` and `-np 2` hold the same values in every dataset but the two that
 * say how the work was done (wall_time, rank).  Rows not yet evaluated hold
 * the fill values: status `pending`, NaN, -1.  Params are stored twice: in
 * the units the model shows them in (`params`, its `units` attribute), for
 * the reader, and in SI (`params_si`), the values evaluated bit for bit,
 * which a quotient by a unit's scale need not give back, for --replay and
 * --start; a file written before params_si still reads (the values shown,
 * converted), and --resume fills it in from the designs it regenerates and
 * checks against the stored ones.  The study's settings are
 * root attributes, and `status` reads "running" until the study ends.  The
 * file is flushed after every row, so an interrupted or killed study keeps
 * every result that arrived (docs/optimisation.md, "The study file").  Once the
 * study is complete, /recheck holds its best designs evaluated again at dt/2
 * (study_recheck.c), rewritten whole each time, columns of a few rows.  Object
 * modification times are not recorded, so two studies of the same results
 * differ only where their timings do. */
#include <hdf5.h>
#include <inttypes.h>
#include <math.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sinew.h"
#include "study_file.h"

#define CHUNK_ROWS 64

struct swStudyFile {
  hid_t file;
  int nparam;
  hid_t status_type;                    /* the enum of swEvalStatus          */
};

static int fail(char *err, size_t len, const char *fmt, ...) __attribute__((format(printf, 3, 4)));
static int fail(char *err, size_t len, const char *fmt, ...) {
  if (err && len) {
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(err, len, fmt, ap);
    va_end(ap);
  }
  return SW_EIO;
}

static const char *const status_names[] = {"pending", "ok", "unstable", "invalid", "failed"};

const char *sw_eval_status_name(int s) {
  return s >= 0 && s < (int)(sizeof status_names / sizeof *status_names) ? status_names[s] : "?";
}

static hid_t make_status_type(void) {
  hid_t t = H5Tenum_create(H5T_NATIVE_INT);
  for (int i = 0; i < 5; i++) H5Tenum_insert(t, status_names[i], &i);
  return t;
}

/* ---- attributes ---- */

static hid_t string_type(void) {
  hid_t t = H5Tcopy(H5T_C_S1);
  H5Tset_size(t, H5T_VARIABLE);
  H5Tset_cset(t, H5T_CSET_UTF8);
  return t;
}

static int put_attr(hid_t obj, const char *name, hid_t ftype, hid_t mtype, const void *v) {
  if (H5Aexists(obj, name) > 0 && H5Adelete(obj, name) < 0) return -1;
  hid_t space = H5Screate(H5S_SCALAR);
  hid_t a = H5Acreate2(obj, name, ftype, space, H5P_DEFAULT, H5P_DEFAULT);
  int ok = a >= 0 && H5Awrite(a, mtype, v) >= 0;
  if (a >= 0) H5Aclose(a);
  H5Sclose(space);
  return ok ? 0 : -1;
}

static int put_string(hid_t obj, const char *name, const char *value) {
  hid_t t = string_type();
  const char *v = value ? value : "";
  int rc = put_attr(obj, name, t, t, &v);
  H5Tclose(t);
  return rc;
}

static int put_double(hid_t obj, const char *name, double v) {
  return put_attr(obj, name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, &v);
}

static int put_long(hid_t obj, const char *name, long v) {
  long long x = v;
  return put_attr(obj, name, H5T_STD_I64LE, H5T_NATIVE_LLONG, &x);
}

static int get_string(hid_t obj, const char *name, char *buf, size_t len) {
  buf[0] = 0;
  if (H5Aexists(obj, name) <= 0) return -1;
  hid_t a = H5Aopen(obj, name, H5P_DEFAULT), t = string_type();
  char *v = NULL;
  int ok = a >= 0 && H5Aread(a, t, &v) >= 0 && v;
  if (ok) snprintf(buf, len, "%s", v);
  if (v) H5free_memory(v);
  H5Tclose(t);
  if (a >= 0) H5Aclose(a);
  return ok ? 0 : -1;
}

static int get_number(hid_t obj, const char *name, hid_t mtype, void *v) {
  if (H5Aexists(obj, name) <= 0) return -1;
  hid_t a = H5Aopen(obj, name, H5P_DEFAULT);
  int ok = a >= 0 && H5Aread(a, mtype, v) >= 0;
  if (a >= 0) H5Aclose(a);
  return ok ? 0 : -1;
}

/* The 1-D string attribute `name` of n values (a param's names, units). */
static int put_string_list(hid_t obj, const char *name, const char *const *values, hsize_t n) {
  hid_t st = string_type(), sp = H5Screate_simple(1, &n, NULL);
  hid_t a = H5Acreate2(obj, name, st, sp, H5P_DEFAULT, H5P_DEFAULT);
  int ok = a >= 0 && H5Awrite(a, st, values) >= 0;
  if (a >= 0) H5Aclose(a);
  H5Sclose(sp);
  H5Tclose(st);
  return ok ? 0 : -1;
}

/* ---- datasets: rows of `width` values, first axis unlimited ---- */

static int make_rows(hid_t loc, const char *name, hid_t ftype, int width, const void *fill,
                     hid_t mtype, const char *units) {
  hsize_t dims[2] = {0, (hsize_t)width}, max[2] = {H5S_UNLIMITED, (hsize_t)width};
  hsize_t chunk[2] = {CHUNK_ROWS, (hsize_t)(width > 0 ? width : 1)};
  int rank = width > 0 ? 2 : 1;
  hid_t space = H5Screate_simple(rank, dims, max);
  hid_t dcpl = H5Pcreate(H5P_DATASET_CREATE);
  H5Pset_chunk(dcpl, rank, chunk);
  H5Pset_fill_value(dcpl, mtype, fill);
  H5Pset_obj_track_times(dcpl, 0);
  hid_t ds = H5Dcreate2(loc, name, ftype, space, H5P_DEFAULT, dcpl, H5P_DEFAULT);
  int ok = ds >= 0 && (!units || put_string(ds, "units", units) == 0);
  if (ds >= 0) H5Dclose(ds);
  H5Pclose(dcpl);
  H5Sclose(space);
  return ok ? 0 : -1;
}

/* Writes row `row` (width values; 0: a scalar row) of dataset `name`,
 * growing it to at least row + 1 rows. */
static int put_row(hid_t loc, const char *name, long row, int width, hid_t mtype,
                   const void *v) {
  hid_t ds = H5Dopen2(loc, name, H5P_DEFAULT);
  if (ds < 0) return -1;
  int rank = width > 0 ? 2 : 1;
  hsize_t dims[2], start[2] = {(hsize_t)row, 0}, count[2] = {1, (hsize_t)width};
  hid_t fs = H5Dget_space(ds);
  H5Sget_simple_extent_dims(fs, dims, NULL);
  H5Sclose(fs);
  int ok = 1;
  if (dims[0] < (hsize_t)row + 1) {
    dims[0] = (hsize_t)row + 1;
    ok = H5Dset_extent(ds, dims) >= 0;
  }
  fs = H5Dget_space(ds);
  hid_t ms = H5Screate_simple(rank, count, NULL);
  ok = ok && H5Sselect_hyperslab(fs, H5S_SELECT_SET, start, NULL, count, NULL) >= 0 &&
       H5Dwrite(ds, mtype, ms, fs, H5P_DEFAULT, v) >= 0;
  H5Sclose(ms);
  H5Sclose(fs);
  H5Dclose(ds);
  return ok ? 0 : -1;
}

/* Reads row `row` (width values; 0: a scalar row) of dataset `name`. */
static int get_row(hid_t loc, const char *name, long row, int width, hid_t mtype, void *v) {
  hid_t ds = H5Dopen2(loc, name, H5P_DEFAULT);
  if (ds < 0) return -1;
  int rank = width > 0 ? 2 : 1;
  hsize_t dims[2] = {0, 0}, start[2] = {(hsize_t)row, 0}, count[2] = {1, (hsize_t)width};
  hid_t fs = H5Dget_space(ds), ms = H5Screate_simple(rank, count, NULL);
  int ok = H5Sget_simple_extent_ndims(fs) == rank && H5Sget_simple_extent_dims(fs, dims, NULL) ==
           rank && row >= 0 && dims[0] > (hsize_t)row && (rank == 1 || dims[1] == count[1]) &&
           H5Sselect_hyperslab(fs, H5S_SELECT_SET, start, NULL, count, NULL) >= 0 &&
           H5Dread(ds, mtype, ms, fs, H5P_DEFAULT, v) >= 0;
  H5Sclose(ms);
  H5Sclose(fs);
  H5Dclose(ds);
  return ok ? 0 : -1;
}

/* Reads the whole dataset (rows x width) into a new buffer of `size` bytes
 * per value; *rows its length. */
static void *get_rows(hid_t loc, const char *name, hid_t mtype, size_t size, long *rows) {
  hid_t ds = H5Dopen2(loc, name, H5P_DEFAULT);
  if (ds < 0) return NULL;
  hid_t fs = H5Dget_space(ds);
  hsize_t dims[2] = {0, 1};
  int rank = H5Sget_simple_extent_dims(fs, dims, NULL);
  H5Sclose(fs);
  size_t n = (size_t)dims[0] * (rank == 2 ? (size_t)dims[1] : 1);
  void *buf = malloc(n * size + size);
  if (buf && n && H5Dread(ds, mtype, H5S_ALL, H5S_ALL, H5P_DEFAULT, buf) < 0) {
    free(buf);
    buf = NULL;
  }
  H5Dclose(ds);
  *rows = (long)dims[0];
  return buf;
}

/* ---- create, open, write ---- */

static hid_t new_group(hid_t loc, const char *name) {
  hid_t gcpl = H5Pcreate(H5P_GROUP_CREATE);
  H5Pset_obj_track_times(gcpl, 0);
  hid_t g = H5Gcreate2(loc, name, H5P_DEFAULT, gcpl, H5P_DEFAULT);
  H5Pclose(gcpl);
  return g;
}

static const char *const kind_names[] = {"grid", "lhs", "cmaes"};

/* /evaluations/params_si: as params, in SI, its `units` the SI units. */
static int make_params_si(hid_t ev, const swStudyOptions *o) {
  const double nan = NAN;
  const int np = o->nparam;
  const char **si = malloc(((size_t)np + 1) * sizeof *si);
  int bad = !si || make_rows(ev, "params_si", H5T_IEEE_F64LE, np, &nan, H5T_NATIVE_DOUBLE, NULL);
  hid_t ds = bad ? -1 : H5Dopen2(ev, "params_si", H5P_DEFAULT);
  for (int i = 0; si && i < np; i++) si[i] = o->si_unit && o->si_unit[i] ? o->si_unit[i] : "";
  bad |= ds < 0 || put_string_list(ds, "names", o->name, (hsize_t)np) ||
         put_string_list(ds, "units", si, (hsize_t)np);
  if (ds >= 0) H5Dclose(ds);
  free(si);
  return bad ? -1 : 0;
}

/* The handle of an opened file (file < 0: it could not be opened). */
static swStudyFile *new_handle(hid_t file, const swStudyOptions *o, const char *what, char *err,
                               size_t errlen) {
  if (file < 0) {
    fail(err, errlen, "cannot %s the study file %s", what, o->path);
    return NULL;
  }
  swStudyFile *f = calloc(1, sizeof *f);
  if (!f) {
    H5Fclose(file);
    fail(err, errlen, "out of memory");
    return NULL;
  }
  f->file = file;
  f->nparam = o->nparam;
  f->status_type = make_status_type();
  return f;
}

/* Opens without HDF5's file lock: under mpirun every rank reads a resumed
 * study's settings while rank 0 opens it for writing (only rank 0 writes). */
static hid_t open_unlocked(const char *path, unsigned flags) {
  hid_t fapl = H5Pcreate(H5P_FILE_ACCESS);
  H5Pset_file_locking(fapl, 0, 1);
  hid_t f = H5Fopen(path, flags, fapl);
  H5Pclose(fapl);
  return f;
}

static int write_settings(hid_t f, const swStudyFileInfo *in) {
  const swStudyOptions *o = in->o;
  int bad = 0;
  bad |= put_string(f, "kind", kind_names[o->kind]);
  bad |= put_string(f, "seed", in->seed_text);
  bad |= put_long(f, "levels", o->levels);
  bad |= put_long(f, "samples", o->samples);
  bad |= put_long(f, "popsize", o->popsize);
  bad |= put_long(f, "restarts", o->restarts);
  bad |= put_double(f, "sigma", o->sigma);
  bad |= put_string(f, "model", o->model_name);
  bad |= put_string(f, "model_sha256", o->model_sha256);
  bad |= put_string(f, "run_settings", o->run_settings);
  bad |= put_string(f, "start", in->start_text);
  bad |= put_string(f, "varied", in->varied_text);
  bad |= put_string(f, "objective", o->objective_text);
  bad |= put_string(f, "objective_units", o->objective_unit);
  bad |= put_string(f, "sense", o->sense > 0 ? "maximize" : "minimize");
  bad |= put_string(f, "status", "running");
  return bad ? -1 : 0;
}

swStudyFile *sw_study_file_create(const swStudyFileInfo *in, char *err, size_t errlen) {
  const swStudyOptions *o = in->o;
  H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
  hid_t fcpl = H5Pcreate(H5P_FILE_CREATE);
  H5Pset_obj_track_times(fcpl, 0);
  hid_t file = H5Fcreate(o->path, H5F_ACC_TRUNC, fcpl, H5P_DEFAULT);
  H5Pclose(fcpl);
  swStudyFile *f = new_handle(file, o, "create", err, errlen);
  if (!f) return NULL;
  int bad = write_settings(file, in);
  /* the design space: the varied params' names, bounds and units */
  hid_t design = new_group(file, "design");
  hid_t ev = new_group(file, "evaluations");
  bad |= design < 0 || ev < 0;
  if (!bad) {
    const double nan = NAN;
    const int minus1 = -1, pending = SW_EVAL_PENDING;
    bad |= make_rows(ev, "params", H5T_IEEE_F64LE, o->nparam, &nan, H5T_NATIVE_DOUBLE, NULL);
    bad |= make_rows(ev, "objective", H5T_IEEE_F64LE, 0, &nan, H5T_NATIVE_DOUBLE,
                     o->objective_unit);
    bad |= make_rows(ev, "penalty", H5T_IEEE_F64LE, 0, &nan, H5T_NATIVE_DOUBLE,
                     o->objective_unit);
    bad |= make_rows(ev, "score", H5T_IEEE_F64LE, 0, &nan, H5T_NATIVE_DOUBLE,
                     o->objective_unit);
    bad |= make_rows(ev, "status", f->status_type, 0, &pending, f->status_type, NULL);
    bad |= make_rows(ev, "generation", H5T_STD_I32LE, 0, &minus1, H5T_NATIVE_INT, NULL);
    bad |= make_rows(ev, "sim_time", H5T_IEEE_F64LE, 0, &nan, H5T_NATIVE_DOUBLE, "s");
    bad |= make_rows(ev, "wall_time", H5T_IEEE_F64LE, 0, &nan, H5T_NATIVE_DOUBLE, "s");
    bad |= make_rows(ev, "rank", H5T_STD_I32LE, 0, &minus1, H5T_NATIVE_INT, NULL);
    /* the params' names and units, one per column */
    hid_t ds = H5Dopen2(ev, "params", H5P_DEFAULT);
    bad |= ds < 0 || put_string_list(ds, "names", o->name, (hsize_t)o->nparam) ||
           put_string_list(ds, "units", o->unit, (hsize_t)o->nparam);
    if (ds >= 0) H5Dclose(ds);
    bad |= make_params_si(ev, o);
    /* /design: one row per varied param */
    const double *lo = in->design_lo, *hi = in->design_hi;
    hsize_t nv = (hsize_t)in->nvar;
    hid_t vs = H5Screate_simple(1, &nv, NULL), s2 = string_type();
    hid_t dn = H5Dcreate2(design, "name", s2, vs, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    bad |= dn < 0 || H5Dwrite(dn, s2, H5S_ALL, H5S_ALL, H5P_DEFAULT, in->design_name) < 0;
    hid_t du = H5Dcreate2(design, "units", s2, vs, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    bad |= du < 0 || H5Dwrite(du, s2, H5S_ALL, H5S_ALL, H5P_DEFAULT, in->design_unit) < 0;
    hid_t dl = H5Dcreate2(design, "lo", H5T_IEEE_F64LE, vs, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    bad |= dl < 0 || H5Dwrite(dl, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, lo) < 0;
    hid_t dh = H5Dcreate2(design, "hi", H5T_IEEE_F64LE, vs, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    bad |= dh < 0 || H5Dwrite(dh, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, hi) < 0;
    const hid_t made[4] = {dn, du, dl, dh};
    for (int k = 0; k < 4; k++)
      if (made[k] >= 0) H5Dclose(made[k]);
    H5Tclose(s2);
    H5Sclose(vs);
    if (o->kind == SW_STUDY_CMAES) {
      hid_t cm = new_group(file, "cmaes");
      bad |= cm < 0;
      if (cm >= 0) {
        bad |= make_rows(cm, "sigma", H5T_IEEE_F64LE, 0, &nan, H5T_NATIVE_DOUBLE, NULL);
        bad |= make_rows(cm, "mean", H5T_IEEE_F64LE, in->nvar, &nan, H5T_NATIVE_DOUBLE, NULL);
        bad |= make_rows(cm, "best_score", H5T_IEEE_F64LE, 0, &nan, H5T_NATIVE_DOUBLE,
                         o->objective_unit);
        bad |= make_rows(cm, "evaluations", H5T_STD_I64LE, 0, &minus1, H5T_NATIVE_INT, NULL);
        H5Gclose(cm);
      }
    }
  }
  if (design >= 0) H5Gclose(design);
  if (ev >= 0) H5Gclose(ev);
  if (bad || H5Fflush(file, H5F_SCOPE_LOCAL) < 0) {
    fail(err, errlen, "cannot write the study file %s", o->path);
    sw_study_file_close(f, NULL);
    return NULL;
  }
  return f;
}

int sw_study_file_settings(const char *path, swStudySettings *s, char *err, size_t errlen) {
  memset(s, 0, sizeof *s);
  H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
  hid_t file = open_unlocked(path, H5F_ACC_RDONLY);
  if (file < 0) return fail(err, errlen, "cannot open the study file %s", path);
  char kind[32], seed[32];
  long long levels = 0, samples = 0, popsize = 0, restarts = 0;
  int bad = get_string(file, "kind", kind, sizeof kind) || get_string(file, "seed", seed, sizeof seed) ||
            get_number(file, "levels", H5T_NATIVE_LLONG, &levels) ||
            get_number(file, "samples", H5T_NATIVE_LLONG, &samples) ||
            get_number(file, "popsize", H5T_NATIVE_LLONG, &popsize) ||
            get_number(file, "restarts", H5T_NATIVE_LLONG, &restarts) ||
            get_number(file, "sigma", H5T_NATIVE_DOUBLE, &s->sigma) ||
            get_string(file, "model_sha256", s->model_sha256, sizeof s->model_sha256) ||
            get_string(file, "run_settings", s->run_settings, sizeof s->run_settings) ||
            get_string(file, "start", s->fixed, sizeof s->fixed) ||
            get_string(file, "varied", s->varied, sizeof s->varied);
  H5Fclose(file);
  if (bad) return fail(err, errlen, "%s is not a sinew study file (or is damaged)", path);
  s->kind = (swStudyKind)-1;
  for (int k = 0; k < 3; k++)
    if (!strcmp(kind, kind_names[k])) s->kind = (swStudyKind)k;
  char *end;
  s->seed = strtoull(seed, &end, 10);
  if ((int)s->kind < 0 || *end) return fail(err, errlen, "%s: unknown study kind '%s'", path, kind);
  s->levels = (long)levels;
  s->samples = (long)samples;
  s->popsize = (long)popsize;
  s->restarts = (long)restarts;
  return SW_OK;
}

/* The strings of the 1-D attribute `attr` of dataset `ds`, n of them, into
 * out[] (H5free_memory each); 0 if it is not that. */
static int get_string_list(hid_t ds, const char *attr, char **out, hsize_t n) {
  if (H5Aexists(ds, attr) <= 0) return 0;
  hid_t a = H5Aopen(ds, attr, H5P_DEFAULT), sp = a >= 0 ? H5Aget_space(a) : -1;
  hsize_t len = 0;
  int ok = sp >= 0 && H5Sget_simple_extent_ndims(sp) == 1 &&
           H5Sget_simple_extent_dims(sp, &len, NULL) == 1 && len == n;
  hid_t t = string_type();
  ok = ok && H5Aread(a, t, out) >= 0;
  H5Tclose(t);
  if (sp >= 0) H5Sclose(sp);
  if (a >= 0) H5Aclose(a);
  return ok;
}

/* Param k of the file (its unit u) as param i of this model (unit[i],
 * scale[i]): the SI value of one of the file's units in *s_file, or -1 with
 * err when u is of another dimension. */
static int file_unit(const char *path, const char *pname, const char *u, const char *here,
                     double scale_here, double *s_file, char *err, size_t errlen) {
  *s_file = scale_here;
  if (!strcmp(u, here)) return 0;
  /* another unit of the same dimension (a model may show a param in mm that
   * another showed in cm) */
  char q[96], why[160];
  signed char dim_file[SW_NDIM], dim_here[SW_NDIM];
  double s_here;
  snprintf(q, sizeof q, "1 %s", u);
  int bad = sw_parse_quantity(q, s_file, dim_file, why, sizeof why);
  snprintf(q, sizeof q, "1 %s", here);
  bad = bad || sw_parse_quantity(q, &s_here, dim_here, why, sizeof why) ||
        memcmp(dim_file, dim_here, sizeof dim_here);
  if (bad)
    fail(err, errlen, "%s holds %s in '%s', which is not a unit of this model's %s (%s%s%s)", path,
         pname, u[0] ? u : "no unit", pname, here[0] ? "shown in '" : "dimensionless", here,
         here[0] ? "'" : "");
  return bad ? -1 : 0;
}

int sw_study_file_design(const char *path, long index, int nparam, const char *const *name,
                         const char *const *unit, const double *scale, double *value,
                         int *found, swStudyDesign *d, char *err, size_t errlen) {
  H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
  memset(d, 0, sizeof *d);
  d->objective = d->penalty = d->score = NAN;
  for (int i = 0; i < nparam; i++) found[i] = 0;
  hid_t file = open_unlocked(path, H5F_ACC_RDONLY);
  if (file < 0) return fail(err, errlen, "cannot open the study file %s", path);
  int rc = SW_OK;
  hsize_t n = 0;
  char **names = NULL, **units = NULL;
  double *shown = NULL, *si = NULL;
  hid_t ev = H5Gopen2(file, "evaluations", H5P_DEFAULT);
  hid_t ds = ev >= 0 ? H5Dopen2(ev, "params", H5P_DEFAULT) : -1;
  hid_t sp = ds >= 0 ? H5Dget_space(ds) : -1;
  hsize_t dims[2] = {0, 0};
  if (sp < 0 || H5Sget_simple_extent_ndims(sp) != 2 ||
      H5Sget_simple_extent_dims(sp, dims, NULL) != 2 || !(n = dims[1])) {
    rc = fail(err, errlen, "%s is not a sinew study file (or is damaged)", path);
    goto done;
  }
  d->rows = (long)dims[0];
  names = calloc(n, sizeof *names), units = calloc(n, sizeof *units);
  shown = malloc(n * sizeof *shown), si = malloc(n * sizeof *si);
  if (!names || !units || !shown || !si || !get_string_list(ds, "names", names, n) ||
      !get_string_list(ds, "units", units, n)) {
    rc = fail(err, errlen, "%s: the params' names and units cannot be read", path);
    goto done;
  }
  if (index < 0) {   /* the best */
    long long idx = -1;
    hid_t bg = H5Lexists(file, "best", H5P_DEFAULT) > 0 ? H5Gopen2(file, "best", H5P_DEFAULT) : -1;
    int have = bg >= 0 && !get_number(bg, "index", H5T_NATIVE_LLONG, &idx);
    if (bg >= 0) H5Gclose(bg);
    if (!have) {
      fail(err, errlen, "%s has no best design: none of its evaluations has succeeded yet", path);
      rc = SW_EUSAGE;
      goto done;
    }
    index = (long)idx;
  }
  if (index >= d->rows) {
    fail(err, errlen, "%s holds %ld evaluation%s (0 to %ld): there is no evaluation %ld", path,
         d->rows, d->rows == 1 ? "" : "s", d->rows - 1, index);
    rc = SW_EUSAGE;
    goto done;
  }
  d->index = index;
  if (get_row(ev, "params", index, (int)n, H5T_NATIVE_DOUBLE, shown) ||
      get_row(ev, "status", index, 0, H5T_NATIVE_INT, &d->status) ||
      get_row(ev, "objective", index, 0, H5T_NATIVE_DOUBLE, &d->objective) ||
      get_row(ev, "penalty", index, 0, H5T_NATIVE_DOUBLE, &d->penalty) ||
      get_row(ev, "score", index, 0, H5T_NATIVE_DOUBLE, &d->score)) {
    rc = fail(err, errlen, "%s: evaluation %ld cannot be read", path, index);
    goto done;
  }
  /* a file of before params_si, or a row it lacks: the values shown */
  d->exact = H5Lexists(ev, "params_si", H5P_DEFAULT) > 0 &&
             !get_row(ev, "params_si", index, (int)n, H5T_NATIVE_DOUBLE, si) && !isnan(si[0]);
  for (int i = 0; i < nparam && rc == SW_OK; i++)
    for (hsize_t k = 0; k < n; k++) {
      if (!names[k] || strcmp(names[k], name[i])) continue;
      double s_file;
      if (file_unit(path, name[i], units[k] ? units[k] : "", unit[i], scale[i], &s_file, err,
                    errlen))
        rc = SW_EIO;
      value[i] = d->exact ? si[k] : shown[k] * s_file;
      found[i] = 1;
      break;
    }
done:
  for (hsize_t k = 0; k < n; k++) {
    if (names && names[k]) H5free_memory(names[k]);
    if (units && units[k]) H5free_memory(units[k]);
  }
  free(names);
  free(units);
  free(shown);
  free(si);
  if (sp >= 0) H5Sclose(sp);
  if (ds >= 0) H5Dclose(ds);
  if (ev >= 0) H5Gclose(ev);
  H5Fclose(file);
  return rc;
}

/* ---- /recheck: the best designs at dt/2 ---- */

/* The columns of /recheck: name, file and memory types, offset in a row,
 * unit (NULL: none; "=": the objective's). */
typedef struct {
  const char *name;
  hid_t ftype, mtype;
  size_t offset;
  const char *units;
} swRecheckColumn;

static int recheck_columns(const swStudyFile *f, swRecheckColumn col[9]) {
  const swRecheckColumn c[9] = {
    {"index", H5T_STD_I64LE, H5T_NATIVE_LONG, offsetof(swStudyRecheck, index), NULL},
    {"dt", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, offsetof(swStudyRecheck, dt), "s"},
    {"objective", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, offsetof(swStudyRecheck, objective), "="},
    {"score", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, offsetof(swStudyRecheck, score), "="},
    {"status_half", f->status_type, f->status_type, offsetof(swStudyRecheck, status_half), NULL},
    {"objective_half", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE,
     offsetof(swStudyRecheck, objective_half), "="},
    {"score_half", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, offsetof(swStudyRecheck, score_half), "="},
    {"difference", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, offsetof(swStudyRecheck, difference), NULL},
    {"sensitive", H5T_STD_I8LE, H5T_NATIVE_INT, offsetof(swStudyRecheck, sensitive), NULL},
  };
  memcpy(col, c, sizeof c);
  return 9;
}

/* Column `c` of n rows between the structs and a buffer of its values. */
static void recheck_gather(const swStudyRecheck *rows, long n, const swRecheckColumn *c,
                           unsigned char *buf) {
  size_t size = H5Tget_size(c->mtype);
  for (long i = 0; i < n; i++)
    memcpy(buf + (size_t)i * size, (const unsigned char *)&rows[i] + c->offset, size);
}

static void recheck_scatter(swStudyRecheck *rows, long n, const swRecheckColumn *c,
                            const unsigned char *buf) {
  size_t size = H5Tget_size(c->mtype);
  for (long i = 0; i < n; i++)
    memcpy((unsigned char *)&rows[i] + c->offset, buf + (size_t)i * size, size);
}

/* The file's /recheck into rows->recheck, if it has one that reads. */
static void read_recheck(swStudyFile *f, swStudyRows *rows) {
  if (H5Lexists(f->file, "recheck", H5P_DEFAULT) <= 0) return;
  hid_t g = H5Gopen2(f->file, "recheck", H5P_DEFAULT);
  swRecheckColumn col[9];
  int ncol = recheck_columns(f, col);
  long n = -1;
  swStudyRecheck *r = NULL;
  int ok = g >= 0;
  for (int k = 0; k < ncol && ok; k++) {
    long len = 0;
    unsigned char *buf = H5Lexists(g, col[k].name, H5P_DEFAULT) > 0 ?
        get_rows(g, col[k].name, col[k].mtype, H5Tget_size(col[k].mtype), &len) : NULL;
    if (k == 0) {
      n = len;
      r = calloc((size_t)n + 1, sizeof *r);
    }
    ok = buf && r && len == n;
    if (ok) recheck_scatter(r, n, &col[k], buf);
    free(buf);
  }
  if (g >= 0) H5Gclose(g);
  if (!ok) {
    free(r);
    return;
  }
  rows->recheck = r;
  rows->nrecheck = n;
}

int sw_study_file_recheck(swStudyFile *f, const swStudyRecheck *rows, long n, double tolerance,
                          double floor) {
  char units[64];
  if (get_string(f->file, "objective_units", units, sizeof units)) units[0] = 0;
  if (H5Lexists(f->file, "recheck", H5P_DEFAULT) > 0 && H5Ldelete(f->file, "recheck",
                                                                 H5P_DEFAULT) < 0)
    return SW_EIO;
  if (n <= 0) return H5Fflush(f->file, H5F_SCOPE_LOCAL) < 0 ? SW_EIO : SW_OK;
  hid_t g = new_group(f->file, "recheck");
  if (g < 0) return SW_EIO;
  int bad = put_double(g, "tolerance", tolerance) || put_double(g, "floor", floor) ||
            put_double(g, "dt_scale", 0.5) ||
            put_string(g, "description", "the study's best designs (best first) evaluated again "
                       "with the time step halved, all else the same; sensitive: the objective "
                       "moved by more than tolerance times max(|objective|, floor), or the "
                       "design failed at dt/2");
  swRecheckColumn col[9];
  int ncol = recheck_columns(f, col);
  unsigned char *buf = malloc((size_t)n * sizeof(double));
  hsize_t len = (hsize_t)n;
  hid_t space = H5Screate_simple(1, &len, NULL);
  hid_t dcpl = H5Pcreate(H5P_DATASET_CREATE);
  H5Pset_obj_track_times(dcpl, 0);
  bad |= !buf;
  for (int k = 0; k < ncol && !bad; k++) {
    recheck_gather(rows, n, &col[k], buf);
    hid_t ds = H5Dcreate2(g, col[k].name, col[k].ftype, space, H5P_DEFAULT, dcpl, H5P_DEFAULT);
    bad |= ds < 0 || H5Dwrite(ds, col[k].mtype, H5S_ALL, H5S_ALL, H5P_DEFAULT, buf) < 0 ||
           (col[k].units && put_string(ds, "units", col[k].units[0] == '=' ? units
                                                                           : col[k].units));
    if (ds >= 0) H5Dclose(ds);
  }
  H5Pclose(dcpl);
  H5Sclose(space);
  free(buf);
  H5Gclose(g);
  return bad || H5Fflush(f->file, H5F_SCOPE_LOCAL) < 0 ? SW_EIO : SW_OK;
}

swStudyFile *sw_study_file_reopen(const swStudyFileInfo *in, swStudyRows *rows, char *err,
                                  size_t errlen) {
  const swStudyOptions *o = in->o;
  memset(rows, 0, sizeof *rows);
  H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
  hid_t file = open_unlocked(o->path, H5F_ACC_RDWR);
  swStudyFile *f = new_handle(file, o, "open for writing", err, errlen);
  if (!f) return NULL;
  hid_t ev = H5Gopen2(file, "evaluations", H5P_DEFAULT);
  long n[6] = {0};
  int bad = ev < 0;
  const size_t row = sizeof(double) * (size_t)o->nparam;
  if (ev >= 0) {
    rows->P = get_rows(ev, "params", H5T_NATIVE_DOUBLE, row, &n[0]);
    rows->status = get_rows(ev, "status", H5T_NATIVE_INT, sizeof(int), &n[1]);
    rows->objective = get_rows(ev, "objective", H5T_NATIVE_DOUBLE, sizeof(double), &n[2]);
    rows->penalty = get_rows(ev, "penalty", H5T_NATIVE_DOUBLE, sizeof(double), &n[3]);
    rows->score = get_rows(ev, "score", H5T_NATIVE_DOUBLE, sizeof(double), &n[4]);
    /* params_si: up to as many rows (NaN beyond); a file without it gets it */
    if (H5Lexists(ev, "params_si", H5P_DEFAULT) > 0) {
      double *si = get_rows(ev, "params_si", H5T_NATIVE_DOUBLE, row, &n[5]);
      rows->Psi = si && n[5] <= n[0] ? realloc(si, (size_t)n[0] * row + row) : NULL;
      if (!rows->Psi) free(si);
      bad |= !rows->Psi;
      for (long k = n[5] * o->nparam; rows->Psi && k < n[0] * o->nparam; k++) rows->Psi[k] = NAN;
    } else {
      bad |= make_params_si(ev, o);
    }
    H5Gclose(ev);
  }
  if (bad || !rows->P || !rows->status || !rows->objective || !rows->penalty || !rows->score ||
      n[1] != n[0] || n[2] != n[0] || n[3] != n[0] || n[4] != n[0]) {
    fail(err, errlen, "%s: the evaluations cannot be read (or their lengths differ)", o->path);
    sw_study_rows_free(rows);
    sw_study_file_close(f, NULL);
    return NULL;
  }
  rows->n = n[0];
  read_recheck(f, rows);
  put_string(file, "status", "running");
  put_long(file, "samples", o->samples);   /* a budget given again may have grown */
  return f;
}

void sw_study_rows_free(swStudyRows *rows) {
  free(rows->recheck);
  free(rows->P);
  free(rows->Psi);
  free(rows->status);
  free(rows->objective);
  free(rows->penalty);
  free(rows->score);
  memset(rows, 0, sizeof *rows);
}

int sw_study_file_write(swStudyFile *f, long index, int generation, const double *Pshown,
                        const double *Psi, const swStudyEval *r, double shown_scale) {
  hid_t ev = H5Gopen2(f->file, "evaluations", H5P_DEFAULT);
  if (ev < 0) return SW_EIO;
  double objective = r->objective / shown_scale, penalty = r->penalty / shown_scale;
  double score = r->status == SW_EVAL_OK ? r->score / shown_scale : -INFINITY;
  int status = r->status;
  int bad = put_row(ev, "params", index, f->nparam, H5T_NATIVE_DOUBLE, Pshown) ||
            put_row(ev, "params_si", index, f->nparam, H5T_NATIVE_DOUBLE, Psi) ||
            put_row(ev, "objective", index, 0, H5T_NATIVE_DOUBLE, &objective) ||
            put_row(ev, "penalty", index, 0, H5T_NATIVE_DOUBLE, &penalty) ||
            put_row(ev, "score", index, 0, H5T_NATIVE_DOUBLE, &score) ||
            put_row(ev, "status", index, 0, f->status_type, &status) ||
            put_row(ev, "generation", index, 0, H5T_NATIVE_INT, &generation) ||
            put_row(ev, "sim_time", index, 0, H5T_NATIVE_DOUBLE, &r->sim_time) ||
            put_row(ev, "wall_time", index, 0, H5T_NATIVE_DOUBLE, &r->wall) ||
            put_row(ev, "rank", index, 0, H5T_NATIVE_INT, &r->rank);
  H5Gclose(ev);
  if (bad || H5Fflush(f->file, H5F_SCOPE_LOCAL) < 0) return SW_EIO;
  return SW_OK;
}

int sw_study_file_params_si(swStudyFile *f, long index, const double *Psi) {
  hid_t ev = H5Gopen2(f->file, "evaluations", H5P_DEFAULT);
  if (ev < 0) return SW_EIO;
  int bad = put_row(ev, "params_si", index, f->nparam, H5T_NATIVE_DOUBLE, Psi);
  H5Gclose(ev);
  return bad ? SW_EIO : SW_OK;
}

int sw_study_file_best(swStudyFile *f, long index, const double *Pshown, double score,
                       double objective, double penalty) {
  hid_t g = H5Gopen2(f->file, "best", H5P_DEFAULT);
  if (g < 0) g = new_group(f->file, "best");
  if (g < 0) return SW_EIO;
  int bad = put_long(g, "index", index) || put_double(g, "score", score) ||
            put_double(g, "objective", objective) || put_double(g, "penalty", penalty);
  if (H5Lexists(g, "params", H5P_DEFAULT) <= 0) {
    hsize_t n = (hsize_t)f->nparam;
    hid_t sp = H5Screate_simple(1, &n, NULL);
    hid_t ds = H5Dcreate2(g, "params", H5T_IEEE_F64LE, sp, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    H5Sclose(sp);
    if (ds < 0) bad = 1;
    else H5Dclose(ds);
  }
  hid_t ds = H5Dopen2(g, "params", H5P_DEFAULT);
  bad |= ds < 0 || H5Dwrite(ds, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, Pshown) < 0;
  if (ds >= 0) H5Dclose(ds);
  H5Gclose(g);
  return bad || H5Fflush(f->file, H5F_SCOPE_LOCAL) < 0 ? SW_EIO : SW_OK;
}

int sw_study_file_generation(swStudyFile *f, long g, double sigma, const double *mean, int nvar,
                             double best_score, long evaluations) {
  hid_t cm = H5Gopen2(f->file, "cmaes", H5P_DEFAULT);
  if (cm < 0) return SW_EIO;
  int ev = (int)evaluations;
  int bad = put_row(cm, "sigma", g, 0, H5T_NATIVE_DOUBLE, &sigma) ||
            put_row(cm, "mean", g, nvar, H5T_NATIVE_DOUBLE, mean) ||
            put_row(cm, "best_score", g, 0, H5T_NATIVE_DOUBLE, &best_score) ||
            put_row(cm, "evaluations", g, 0, H5T_NATIVE_INT, &ev);
  H5Gclose(cm);
  return bad || H5Fflush(f->file, H5F_SCOPE_LOCAL) < 0 ? SW_EIO : SW_OK;
}

int sw_study_file_attr(swStudyFile *f, const char *name, const char *value) {
  return put_string(f->file, name, value) ? SW_EIO : SW_OK;
}

int sw_study_file_close(swStudyFile *f, const char *status) {
  if (!f) return SW_OK;
  int bad = 0;
  if (status) bad |= put_string(f->file, "status", status);
  if (f->status_type >= 0) H5Tclose(f->status_type);
  bad |= H5Fclose(f->file) < 0;
  free(f);
  return bad ? SW_EIO : SW_OK;
}
