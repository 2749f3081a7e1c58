/* output.c — HDF5 output of a run; with compare.c (which reads a golden
 * file) and restart.c (the checkpoint), the only files of the runtime that
 * include hdf5.h.
 *
 * Design.  What is written is described by one table, output_fields[]: a
 * dataset path, whether it exists once, once per rod, per joint (or hinge),
 * per muscle or per probe, its shape per frame (with symbolic extents for
 * "nodes of this rod" and "elements of this rod"), its units, optional
 * column names, the option that enables it and the function that fills one
 * frame from the state.  sw_output_open() walks the table once and creates
 * every dataset (doubles, first dimension unlimited, chunked by up to 64
 * frames) with its `units` attribute; sw_output_frame() walks the opened
 * datasets, fills a scratch frame allocated at open time, appends it and
 * flushes the file, so a run that dies later still leaves a readable file of
 * every frame written so far.  Adding an output is one line of the table
 * plus, if the quantity is new, a four-line fill function.  Muscle groups
 * also carry what a reader needs to normalise their forces
 * (write_muscle_attrs); a probe is one dataset /probes/NAME [F, 3] whose
 * units follow its kind and whose attributes say what it measures
 * (write_probe_attrs).  The root group records how the file was made
 * (docs/runtime.md, "Running and output") and a `status` attribute that reads "incomplete"
 * until sw_output_close() replaces it with the caller's verdict; a model
 * with an objective also gets its value, penalty and score there
 * (sw_output_objective).  Beside the
 * file, RUN.xdmf describes the rods' frames for ParaView (xdmf.c); it is
 * rewritten from the frames written (at open, after the first frame, every
 * second of wall time or less often when rewriting it takes long, at close),
 * so it never lists a frame the file has
 * not flushed, and each rod whose positions are written gets the static
 * /rods/NAME/node_radius it draws tubes with.  HDF5's own
 * error printing is switched off; every call is checked and the failure is
 * reported once, in our words, naming the file and the object, with HDF5's
 * innermost reason appended. */
#include <errno.h>
#include <hdf5.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "sinew.h"
#include "engine/internal.h"
#include "restart.h"
#include "xdmf.h"

/* ---- the output table ---- */

/* Symbolic per-frame extents, resolved for each rod at open time. */
enum { EXTENT_NODES = -1, EXTENT_ELEMS = -2, EXTENT_FILAMENTS = -3, EXTENT_VORONOI = -4 };
enum { SCOPE_ROOT, SCOPE_ROD, SCOPE_JOINT, SCOPE_MUSCLE, SCOPE_PROBE };
#define MAX_FRAME_RANK 3

/* Fill one frame of a field (contiguous, row-major) from the state; `item`
 * is the rod or the joint. */
typedef void (*swFillFn)(const swModel *m, swData *d, int item, double *frame);

typedef struct {
  const char *path;          /* under "/", "/rods/NAME" or "/joints/NAME";
                                "" for the probe's own dataset /probes/NAME  */
  int scope;                 /* SCOPE_ROOT, SCOPE_ROD or SCOPE_JOINT           */
  int rank;                  /* rank of one frame                              */
  int extent[MAX_FRAME_RANK];/* count, EXTENT_NODES or EXTENT_ELEMS            */
  const char *units;         /* NULL: the item's own (probes)                  */
  const char *const *columns;/* names along the last dimension, or NULL        */
  unsigned bit;              /* the SW_OUT_* selection bit; 0: always written  */
  swFillFn fill;
} swField;

static void fill_time(const swModel *m, swData *d, int rod, double *frame) {
  (void)m, (void)rod;
  frame[0] = d->time;
}

static void fill_energy(const swModel *m, swData *d, int rod, double *frame) {
  (void)rod;
  sw_energy(m, d, frame);
}

/* Slots [first, first + count) of a planar array of `planes` planes
 * (sinew.h, "Layout") as a row-major [count][planes] frame: row i holds
 * component k of slot first + i at column k. */
static void gather_rows(const swModel *m, const double *a, int first, int count, int planes,
                        double *frame) {
  for (int i = 0; i < count; i++)
    for (int k = 0; k < planes; k++)
      frame[(size_t)planes * (size_t)i + (size_t)k] = SW_AT(m, a, first + i, k);
}

static void fill_position(const swModel *m, swData *d, int rod, double *frame) {
  gather_rows(m, d->x, m->node_adr[rod], m->rod_nelem[rod] + 1, 3, frame);
}

static void fill_velocity(const swModel *m, swData *d, int rod, double *frame) {
  gather_rows(m, d->v, m->node_adr[rod], m->rod_nelem[rod] + 1, 3, frame);
}

/* Rows d1, d2, d3 of each element's frame, lab components (sinew.h): the
 * nine planes of Q are the row-major entries, so each element's row of the
 * frame is its matrix in row-major order. */
static void fill_directors(const swModel *m, swData *d, int rod, double *frame) {
  gather_rows(m, d->Q, m->elem_adr[rod], m->rod_nelem[rod], 9, frame);
}

static void fill_angular_velocity(const swModel *m, swData *d, int rod, double *frame) {
  gather_rows(m, d->omega, m->elem_adr[rod], m->rod_nelem[rod], 3, frame);
}

/* Strains, curvatures and internal loads are scratch of a step (sinew.h,
 * swData): recomputed from the state being written, as sw_energy does. */
static void fill_strain(const swModel *m, swData *d, int rod, double *frame) {
  sw_internal_loads(m, d);
  gather_rows(m, d->sigma, m->elem_adr[rod], m->rod_nelem[rod], 3, frame);
}

static void fill_curvature(const swModel *m, swData *d, int rod, double *frame) {
  sw_internal_loads(m, d);
  gather_rows(m, d->kappa, m->vor_adr[rod], m->rod_nelem[rod] - 1, 3, frame);
}

static void fill_internal_force(const swModel *m, swData *d, int rod, double *frame) {
  sw_internal_loads(m, d);
  gather_rows(m, d->stress, m->elem_adr[rod], m->rod_nelem[rod], 3, frame);
}

static void fill_internal_couple(const swModel *m, swData *d, int rod, double *frame) {
  sw_internal_loads(m, d);
  gather_rows(m, d->couple, m->vor_adr[rod], m->rod_nelem[rod] - 1, 3, frame);
}

/* Joint force on rod a (lab) and hinge angle, of the state being written
 * (d->joint_* hold those of the last force evaluation, half a step away). */
static void fill_joint_force(const swModel *m, swData *d, int joint, double *frame) {
  sw_joint_measure(m, d, joint);
  memcpy(frame, d->joint_force + 3 * (size_t)joint, 3 * sizeof *frame);
}

static void fill_joint_limit_torque(const swModel *m, swData *d, int joint, double *frame) {
  sw_joint_measure(m, d, joint);
  memcpy(frame, d->joint_limit_torque + 3 * (size_t)joint, 3 * sizeof *frame);
}

static void fill_joint_angle(const swModel *m, swData *d, int joint, double *frame) {
  sw_joint_measure(m, d, joint);
  frame[0] = d->joint_angle[joint];
}

/* Muscles (muscle.c): the bundle's tension is the sum of its filaments'
 * (they pull in parallel), of the last force evaluation; its stretch is the
 * muscle's length over its rest length, the end-to-end distance of each
 * filament (a slack, unrecruited filament bows and keeps its arc length,
 * which is what its own law uses) averaged by cross-section; its activation
 * is the mean weighted by peak force. */
static void fill_muscle_force(const swModel *m, swData *d, int mu, double *frame) {
  frame[0] = sw_muscle_ops(m)->force(m, d, mu);
}

static void fill_muscle_stretch(const swModel *m, swData *d, int mu, double *frame) {
  frame[0] = sw_muscle_ops(m)->stretch(m, d, mu);
}

static void fill_muscle_activation(const swModel *m, swData *d, int mu, double *frame) {
  double s = 0, w = 0;
  for (int f = m->muscle_fil_adr[mu]; f < m->muscle_fil_adr[mu + 1]; f++) {
    s += m->fil_fmax[f] * d->fil_activation[f];
    w += m->fil_fmax[f];
  }
  frame[0] = s / w;
}

static void fill_filament_force(const swModel *m, swData *d, int mu, double *frame) {
  const int f0 = m->muscle_fil_adr[mu];
  memcpy(frame, d->fil_tension + f0, (size_t)(m->muscle_fil_adr[mu + 1] - f0) * sizeof *frame);
}

/* Probes (probe.c): the row of /probes/NAME. */
static void fill_probe(const swModel *m, swData *d, int probe, double *frame) {
  sw_probe_measure(m, d, probe, frame);
}

/* Must match the order sw_energy() returns. */
static const char *const energy_columns[] = {"kinetic", "elastic", "work_done", NULL};
/* Vectors in the material frame of each element (or Voronoi domain). */
static const char *const material_columns[] = {"d1", "d2", "d3", NULL};

/* Rods' fields that need strains refuse rigid rods (item_enabled). */
#define SW_OUT_STRAINS (SW_OUT_STRAIN | SW_OUT_CURVATURE | SW_OUT_INTERNAL_FORCE | \
                        SW_OUT_INTERNAL_COUPLE)

static const swField output_fields[] = {
  /* path                 scope        rank extent per frame        units    columns           bit                      source */
  {"time",                SCOPE_ROOT,  0, {0},                      "s",     NULL,             0,                       fill_time},
  {"position",            SCOPE_ROD,   2, {EXTENT_NODES, 3},        "m",     NULL,             SW_OUT_POSITION,         fill_position},
  {"velocity",            SCOPE_ROD,   2, {EXTENT_NODES, 3},        "m/s",   NULL,             SW_OUT_VELOCITY,         fill_velocity},
  {"directors",           SCOPE_ROD,   3, {EXTENT_ELEMS, 3, 3},     "-",     NULL,             SW_OUT_DIRECTORS,        fill_directors},
  {"angular_velocity",    SCOPE_ROD,   2, {EXTENT_ELEMS, 3},        "rad/s", material_columns, SW_OUT_ANGULAR_VELOCITY, fill_angular_velocity},
  {"strain",              SCOPE_ROD,   2, {EXTENT_ELEMS, 3},        "-",     material_columns, SW_OUT_STRAIN,           fill_strain},
  {"curvature",           SCOPE_ROD,   2, {EXTENT_VORONOI, 3},      "rad/m", material_columns, SW_OUT_CURVATURE,        fill_curvature},
  {"internal_force",      SCOPE_ROD,   2, {EXTENT_ELEMS, 3},        "N",     material_columns, SW_OUT_INTERNAL_FORCE,   fill_internal_force},
  {"internal_couple",     SCOPE_ROD,   2, {EXTENT_VORONOI, 3},      "N m",   material_columns, SW_OUT_INTERNAL_COUPLE,  fill_internal_couple},
  {"force",               SCOPE_JOINT, 1, {3},                      "N",     NULL,             SW_OUT_JOINT_FORCE,      fill_joint_force},
  {"angle",               SCOPE_JOINT, 0, {0},                      "rad",   NULL,             SW_OUT_ANGLE,            fill_joint_angle},
  {"limit_torque",        SCOPE_JOINT, 1, {3},                      "N m",   NULL,             SW_OUT_LIMIT_TORQUE,     fill_joint_limit_torque},
  {"force",               SCOPE_MUSCLE,0, {0},                      "N",     NULL,             SW_OUT_MUSCLE_FORCE,     fill_muscle_force},
  {"stretch",             SCOPE_MUSCLE,0, {0},                      "-",     NULL,             SW_OUT_STRETCH,          fill_muscle_stretch},
  {"activation",          SCOPE_MUSCLE,0, {0},                      "-",     NULL,             SW_OUT_ACTIVATION,       fill_muscle_activation},
  {"filament_force",      SCOPE_MUSCLE,1, {EXTENT_FILAMENTS},       "N",     NULL,             SW_OUT_FILAMENT_FORCE,   fill_filament_force},
  {"",                    SCOPE_PROBE, 1, {3},                      NULL,    NULL,             0,                       fill_probe},
  {"diagnostics/energy",  SCOPE_ROOT,  1, {3},                      "J",     energy_columns,   0,                       fill_energy},
};
#define NFIELDS (sizeof output_fields / sizeof output_fields[0])

/* ---- the open file ---- */

#define CHUNK_FRAMES 64                  /* frames per chunk, at most        */
#define CHUNK_BYTES (1u << 20)           /* and about this many bytes        */

typedef struct {
  const swField *field;
  int item;                              /* rod or joint; -1 for root fields */
  hid_t dset;
  int rank;                              /* 1 + field rank                   */
  hsize_t dims[1 + MAX_FRAME_RANK];      /* dims[0] = frames written         */
  size_t frame_len;                      /* doubles per frame                */
  char *path;                            /* "/rods/arm/position"             */
} swDataset;

struct swOutput {
  hid_t file;
  char *path;                            /* file name, for messages          */
  int nrod;
  long frames;
  int ndset;
  swDataset *dset;
  double *frame;                         /* scratch, the largest frame       */
  swCheckpoint *checkpoint;              /* the last scheduled frame's state */
  const swModel *model;                  /* the model it was taken of        */
  double checkpoint_written;             /* wall clock of its last write, s  */
  /* The XDMF description beside the file (xdmf.c); xdmf_path is NULL when
   * no rod's positions are written. */
  char *xdmf_path;
  swXdmfRod *xdmf_rod;
  int nxdmf_rod;
  double *frame_time;                    /* (frame_time_cap) time of each frame */
  long frame_time_cap;
  long xdmf_frames;                      /* frames it listed when last written */
  double xdmf_written;                   /* wall clock of its last write, s  */
  double xdmf_wait;                      /* s until the next may be written  */
};

/* ---- errors ---- */

static _Thread_local char last_error[512];

const char *sw_output_error(void) { return last_error; }

static herr_t innermost_reason(unsigned n, const H5E_error2_t *e, void *data) {
  char *reason = data;
  (void)n;
  if (reason[0] || !e->desc || !e->desc[0]) return 0;
  /* File-driver errors carry the C library's message; prefer it. */
  const char *msg = strstr(e->desc, "error message = '");
  if (msg) {
    msg += strlen("error message = '");
    size_t len = strcspn(msg, "'");
    if (len > 255) len = 255;
    memcpy(reason, msg, len);
    reason[len] = '\0';
  } else {
    snprintf(reason, 256, "%s", e->desc);
  }
  return 0;
}

/* Format the message, append HDF5's innermost reason (if the stack holds
 * one), store it as the last error and copy it into err.  Returns SW_EIO. */
static int fail(char *err, size_t errlen, const char *fmt, ...) {
  char reason[256] = "";
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(last_error, sizeof last_error, fmt, ap);
  va_end(ap);
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_UPWARD, innermost_reason, reason);
  H5Eclear2(H5E_DEFAULT);
  if (reason[0]) {
    size_t used = strlen(last_error);
    snprintf(last_error + used, sizeof last_error - used, " (%s)", reason);
  }
  if (err && errlen) snprintf(err, errlen, "%s", last_error);
  return SW_EIO;
}

static char *dup_printf(const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  int len = vsnprintf(NULL, 0, fmt, ap);
  va_end(ap);
  if (len < 0) return NULL;
  char *s = malloc((size_t)len + 1);
  if (!s) return NULL;
  va_start(ap, fmt);
  vsnprintf(s, (size_t)len + 1, fmt, ap);
  va_end(ap);
  return s;
}

/* ---- attributes (scalars, UTF-8 variable-length strings) ---- */

typedef struct {                         /* where an attribute goes          */
  hid_t obj;
  const char *file;                      /* for messages                     */
  const char *obj_path;
  char *err;
  size_t errlen;
} swAttrTarget;

static int write_attr(const swAttrTarget *t, const char *name, hid_t file_type,
                      hid_t mem_type, hid_t space, const void *value) {
  hid_t attr = H5Acreate2(t->obj, name, file_type, space, H5P_DEFAULT, H5P_DEFAULT);
  if (attr < 0)
    return fail(t->err, t->errlen, "%s: cannot create attribute '%s' of %s", t->file,
                name, t->obj_path);
  herr_t wrote = H5Awrite(attr, mem_type, value);
  herr_t closed = H5Aclose(attr);
  if (wrote < 0 || closed < 0)
    return fail(t->err, t->errlen, "%s: cannot write attribute '%s' of %s", t->file, name,
                t->obj_path);
  return SW_OK;
}

static hid_t utf8_string_type(void) {
  hid_t type = H5Tcopy(H5T_C_S1);
  if (type < 0) return type;
  if (H5Tset_size(type, H5T_VARIABLE) < 0 || H5Tset_cset(type, H5T_CSET_UTF8) < 0) {
    H5Tclose(type);
    return H5I_INVALID_HID;
  }
  return type;
}

/* A 1-D array of strings when count > 0, a scalar string when count == 0. */
static int attr_strings(const swAttrTarget *t, const char *name, const char *const *values,
                        hsize_t count) {
  hid_t type = utf8_string_type();
  hid_t space = count ? H5Screate_simple(1, &count, NULL) : H5Screate(H5S_SCALAR);
  int rc = SW_OK;
  if (type < 0 || space < 0)
    rc = fail(t->err, t->errlen, "%s: cannot make the type of attribute '%s' of %s",
              t->file, name, t->obj_path);
  else
    rc = write_attr(t, name, type, type, space, values);
  if (space >= 0) H5Sclose(space);
  if (type >= 0) H5Tclose(type);
  return rc;
}

static int attr_string(const swAttrTarget *t, const char *name, const char *value) {
  const char *values[1] = {value ? value : ""};
  return attr_strings(t, name, values, 0);
}

static int attr_scalar(const swAttrTarget *t, const char *name, hid_t file_type,
                       hid_t mem_type, const void *value) {
  hid_t space = H5Screate(H5S_SCALAR);
  if (space < 0)
    return fail(t->err, t->errlen, "%s: cannot make the dataspace of attribute '%s' of %s",
                t->file, name, t->obj_path);
  int rc = write_attr(t, name, file_type, mem_type, space, value);
  H5Sclose(space);
  return rc;
}

/* A 1-D array of doubles. */
static int attr_vector(const swAttrTarget *t, const char *name, const double *values, int n) {
  hsize_t count = (hsize_t)n;
  hid_t space = H5Screate_simple(1, &count, NULL);
  if (space < 0)
    return fail(t->err, t->errlen, "%s: cannot make the dataspace of attribute '%s' of %s",
                t->file, name, t->obj_path);
  int rc = write_attr(t, name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, space, values);
  H5Sclose(space);
  return rc;
}

/* A quantity: its value (n > 1: a vector) and its unit in NAME_units. */
static int attr_quantity(const swAttrTarget *t, const char *name, const double *values, int n,
                         const char *units) {
  int rc = n > 1 ? attr_vector(t, name, values, n)
                 : attr_scalar(t, name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, values);
  char key[64];
  snprintf(key, sizeof key, "%s_units", name);
  if (rc == SW_OK) rc = attr_string(t, key, units);
  return rc;
}

static int attr_int(const swAttrTarget *t, const char *name, int value) {
  return attr_scalar(t, name, H5T_STD_I32LE, H5T_NATIVE_INT, &value);
}

/* What a probe measures: `kind` (probe.c's name), its rods (or rod and
 * node), and the averaging window of a mean velocity (s). */
static int write_probe_attrs(const swAttrTarget *t, const swProbeDesc *p) {
  int rc = attr_string(t, "kind", sw_probe_kind_name(p->kind));
  if (rc == SW_OK && p->kind == SW_PROBE_NODE) {
    rc = attr_scalar(t, "rod", H5T_STD_I32LE, H5T_NATIVE_INT, &p->rod);
    if (rc == SW_OK) rc = attr_scalar(t, "node", H5T_STD_I32LE, H5T_NATIVE_INT, &p->node);
    return rc;
  }
  if (rc == SW_OK) {
    hsize_t n = (hsize_t)p->nrods;
    hid_t space = H5Screate_simple(1, &n, NULL);
    if (space < 0)
      return fail(t->err, t->errlen, "%s: cannot make the dataspace of attribute 'rods' of %s",
                  t->file, t->obj_path);
    rc = write_attr(t, "rods", H5T_STD_I32LE, H5T_NATIVE_INT, space, p->rods);
    H5Sclose(space);
  }
  if (rc == SW_OK && p->kind == SW_PROBE_MEAN_VELOCITY)
    rc = attr_quantity(t, "window", &p->window, 1, "s");
  return rc;
}

/* ---- open ---- */

static int valid_group_name(const char *name) {
  return name && name[0] && !strchr(name, '/') && strcmp(name, ".") && strcmp(name, "..");
}

/* How many datasets field f can make. */
static int field_items(const swField *f, const swModel *m) {
  return f->scope == SCOPE_ROD      ? m->nrod
         : f->scope == SCOPE_JOINT  ? m->njoint
         : f->scope == SCOPE_MUSCLE ? m->nmuscle
         : f->scope == SCOPE_PROBE  ? m->nprobe
                                    : 1;
}

/* The SW_OUT_* bits selected for item k of a scope: the options' arrays, or
 * the defaults (positions, plus velocity and directors when asked, and every
 * quantity of joints and muscles). */
static unsigned selected(const swOutputOptions *opt, int scope, int k) {
  switch (scope) {
  case SCOPE_ROD:
    if (opt->rod_out) return opt->rod_out[k];
    return SW_OUT_POSITION | (opt->velocity ? SW_OUT_VELOCITY : 0u) |
           (opt->directors ? SW_OUT_DIRECTORS : 0u);
  case SCOPE_JOINT: return opt->joint_out ? opt->joint_out[k] : ~0u;
  case SCOPE_MUSCLE: return opt->muscle_out ? opt->muscle_out[k] : ~0u;
  default: return ~0u;
  }
}

/* Whether item k gets a dataset of field f: selected, and meaningful for it
 * (an angle for hinges only; strains for elastic rods, and curvatures for
 * rods of two elements or more). */
static int item_enabled(const swField *f, const swModel *m, const swOutputOptions *opt,
                        int k) {
  if (f->bit && !(selected(opt, f->scope, k) & f->bit)) return 0;
  if (f->bit == SW_OUT_ANGLE) return m->joint[k].kind == SW_JOINT_HINGE;
  if (f->bit == SW_OUT_LIMIT_TORQUE) return sw_joint_limited(&m->joint[k]);
  if (f->bit & SW_OUT_STRAINS) {
    if (m->rod_rigid && m->rod_rigid[k] >= 0) return 0;
    if (f->extent[0] == EXTENT_VORONOI && m->rod_nelem[k] < 2) return 0;
  }
  return 1;
}

/* A continued run (sw_output_resume): the dataset the first part made, cut
 * back to `frames` frames; its shape per frame must be this model's. */
static int reopen_dataset(swOutput *o, swDataset *ds, long frames, char *err, size_t errlen) {
  ds->dset = H5Dopen2(o->file, ds->path, H5P_DEFAULT);
  if (ds->dset < 0)
    return fail(err, errlen, "%s: no dataset %s: the file was written by another model or "
                "another output selection", o->path, ds->path);
  hsize_t have[1 + MAX_FRAME_RANK];
  hid_t space = H5Dget_space(ds->dset);
  int rank = space >= 0 ? H5Sget_simple_extent_dims(space, have, NULL) : -1;
  if (space >= 0) H5Sclose(space);
  int same = rank == ds->rank;
  for (int k = 1; same && k < rank; k++) same = have[k] == ds->dims[k];
  if (!same || have[0] < (hsize_t)frames)
    return fail(err, errlen, "%s: dataset %s does not have the shape this model writes",
                o->path, ds->path);
  ds->dims[0] = (hsize_t)frames;
  if (H5Dset_extent(ds->dset, ds->dims) < 0)
    return fail(err, errlen, "%s: cannot cut dataset %s back to %ld frames", o->path,
                ds->path, frames);
  return SW_OK;
}

/* Create the dataset of field f (for rod or joint `item`, or -1) with its
 * attributes. */
static int create_dataset(swOutput *o, swDataset *ds, const swField *f, const swModel *m,
                          int item, hid_t lcpl, long reopen_frames, char *err, size_t errlen) {
  hsize_t maxdims[1 + MAX_FRAME_RANK], chunk[1 + MAX_FRAME_RANK];
  const int rod = f->scope == SCOPE_ROD ? item : -1;
  ds->field = f;
  ds->item = item;
  ds->dset = H5I_INVALID_HID;
  ds->rank = 1 + f->rank;
  ds->path = f->scope == SCOPE_ROD      ? dup_printf("/rods/%s/%s", m->rod_name[item], f->path)
             : f->scope == SCOPE_JOINT  ? dup_printf("/joints/%s/%s", m->joint_name[item], f->path)
             : f->scope == SCOPE_MUSCLE ? dup_printf("/muscles/%s/%s", m->muscle_name[item], f->path)
             : f->scope == SCOPE_PROBE  ? dup_printf("/probes/%s%s%s", m->probe[item].name,
                                                     f->path[0] ? "/" : "", f->path)
                                        : dup_printf("/%s", f->path);
  if (!ds->path) return fail(err, errlen, "%s: out of memory", o->path);

  ds->dims[0] = 0;
  maxdims[0] = H5S_UNLIMITED;
  ds->frame_len = 1;
  for (int k = 0; k < f->rank; k++) {
    int e = f->extent[k];
    if (e == EXTENT_NODES) e = m->rod_nelem[rod] + 1;
    else if (e == EXTENT_ELEMS) e = m->rod_nelem[rod];
    else if (e == EXTENT_VORONOI) e = m->rod_nelem[rod] - 1;
    else if (e == EXTENT_FILAMENTS) e = m->muscle_fil_adr[item + 1] - m->muscle_fil_adr[item];
    ds->dims[1 + k] = maxdims[1 + k] = chunk[1 + k] = (hsize_t)e;
    ds->frame_len *= (size_t)e;
  }
  size_t frame_bytes = ds->frame_len * sizeof(double);
  size_t frames_per_chunk = frame_bytes ? CHUNK_BYTES / frame_bytes : CHUNK_FRAMES;
  if (frames_per_chunk > CHUNK_FRAMES) frames_per_chunk = CHUNK_FRAMES;
  if (frames_per_chunk < 1) frames_per_chunk = 1;
  chunk[0] = frames_per_chunk;

  if (reopen_frames >= 0) return reopen_dataset(o, ds, reopen_frames, err, errlen);
  hid_t space = H5Screate_simple(ds->rank, ds->dims, maxdims);
  hid_t dcpl = H5Pcreate(H5P_DATASET_CREATE);
  if (space < 0 || dcpl < 0 || H5Pset_chunk(dcpl, ds->rank, chunk) < 0) {
    if (space >= 0) H5Sclose(space);
    if (dcpl >= 0) H5Pclose(dcpl);
    return fail(err, errlen, "%s: cannot describe dataset %s", o->path, ds->path);
  }
  ds->dset = H5Dcreate2(o->file, ds->path, H5T_IEEE_F64LE, space, lcpl, dcpl, H5P_DEFAULT);
  H5Sclose(space);
  H5Pclose(dcpl);
  if (ds->dset < 0) return fail(err, errlen, "%s: cannot create dataset %s", o->path, ds->path);

  swAttrTarget t = {ds->dset, o->path, ds->path, err, errlen};
  int rc = attr_string(&t, "units", f->units ? f->units : sw_probe_units(m->probe[item].kind));
  if (rc == SW_OK && f->scope == SCOPE_PROBE) rc = write_probe_attrs(&t, &m->probe[item]);
  if (rc == SW_OK && f->columns) {
    hsize_t ncol = 0;
    while (f->columns[ncol]) ncol++;
    rc = attr_strings(&t, "columns", f->columns, ncol);
  }
  return rc;
}

static int write_root_attrs(swOutput *o, const swModel *m, const swOutputOptions *opt,
                            char *err, size_t errlen) {
  swAttrTarget t = {o->file, o->path, "/", err, errlen};
  int n_rods = m->nrod;
  int rc = attr_string(&t, "sinew_version", SW_VERSION);
  if (rc == SW_OK) rc = attr_string(&t, "model_source", opt->model_source);
  if (rc == SW_OK) rc = attr_string(&t, "model_sha256", opt->model_sha256);
  if (rc == SW_OK) rc = attr_quantity(&t, "dt", &m->dt, 1, "s");
  if (rc == SW_OK) rc = attr_quantity(&t, "duration", &opt->duration, 1, "s");
  if (rc == SW_OK) rc = attr_quantity(&t, "every", &opt->every, 1, "s");
  if (rc == SW_OK) rc = attr_quantity(&t, "gravity", m->gravity, 3, "m/s^2");
  if (rc == SW_OK)
    rc = attr_string(&t, "integrator",
                     m->integrator == SW_PEFRL ? "pefrl"
                     : m->integrator == SW_IMEX ? "imex" : "position-verlet");
  if (rc == SW_OK) rc = attr_string(&t, "params", opt->params);
  if (rc == SW_OK) rc = attr_scalar(&t, "n_rods", H5T_STD_I32LE, H5T_NATIVE_INT, &n_rods);
  /* Replaced by sw_output_close(); a file that still says this was not closed. */
  if (rc == SW_OK) rc = attr_string(&t, "status", "incomplete: the run did not close this file");
  return rc;
}

/* ---- groups that describe themselves ---- */

/* Opens group PATH if a dataset made it (a rod, joint or muscle with nothing
 * selected has none); 0 when absent, -1 on error. */
static hid_t open_group(swOutput *o, const char *gpath, char *err, size_t errlen) {
  htri_t exists = H5Lexists(o->file, gpath, H5P_DEFAULT);
  if (exists < 0) {
    fail(err, errlen, "%s: cannot look up group %s", o->path, gpath);
    return -1;
  }
  if (!exists) return 0;
  hid_t g = H5Gopen2(o->file, gpath, H5P_DEFAULT);
  if (g < 0) fail(err, errlen, "%s: cannot open group %s", o->path, gpath);
  return g;
}

/* A rod: what it is (kind, material, the model line), its rest geometry
 * (elements, length, the radius of each element) and its material
 * constants, each with its unit. */
static int rod_attrs(const swAttrTarget *t, const swModel *m, int r) {
  const swRodInfo *info = &m->rod_info[r];
  const int n = m->rod_nelem[r];
  double *radius = malloc((size_t)n * sizeof *radius);
  if (!radius) return fail(t->err, t->errlen, "%s: out of memory", t->file);
  for (int i = 0; i < n; i++) radius[i] = m->radius[m->elem_adr[r] + i];
  int rc = attr_string(t, "kind", info->kind ? info->kind : "rod");
  if (rc == SW_OK && info->material) rc = attr_string(t, "material", info->material);
  if (rc == SW_OK && info->where) rc = attr_string(t, "where", info->where);
  if (rc == SW_OK) rc = attr_int(t, "rigid", m->rod_rigid && m->rod_rigid[r] >= 0);
  if (rc == SW_OK) rc = attr_int(t, "elements", n);
  if (rc == SW_OK) rc = attr_quantity(t, "length", &info->length, 1, "m");
  if (rc == SW_OK) rc = attr_quantity(t, "radius", radius, n, "m");
  if (rc == SW_OK) rc = attr_quantity(t, "density", &info->density, 1, "kg/m^3");
  if (rc == SW_OK) rc = attr_quantity(t, "E", &info->youngs, 1, "Pa");
  if (rc == SW_OK) rc = attr_quantity(t, "G", &info->shear_modulus, 1, "Pa");
  free(radius);
  return rc;
}

/* A joint: its kind, the rods and nodes it ties (an anchored joint has no
 * rod_b but an anchor), the hinge's axis, its stiffnesses and its limits. */
static int joint_attrs(const swAttrTarget *t, const swModel *m, int j) {
  const swJointDesc *jd = &m->joint[j];
  int rc = attr_string(t, "kind", sw_joint_kind_name(jd->kind));
  if (rc == SW_OK) rc = attr_string(t, "rod_a", m->rod_name[jd->rod_a]);
  if (rc == SW_OK)
    rc = attr_int(t, "node_a", jd->node_a < 0 ? m->rod_nelem[jd->rod_a] : jd->node_a);
  if (rc == SW_OK && jd->rod_b >= 0) {
    rc = attr_string(t, "rod_b", m->rod_name[jd->rod_b]);
    if (rc == SW_OK)
      rc = attr_int(t, "node_b", jd->node_b < 0 ? m->rod_nelem[jd->rod_b] : jd->node_b);
  } else if (rc == SW_OK) {
    rc = attr_quantity(t, "anchor", jd->anchor, 3, "m");
  }
  if (rc == SW_OK && jd->kind == SW_JOINT_HINGE) rc = attr_quantity(t, "axis", jd->axis, 3, "-");
  if (rc == SW_OK) rc = attr_quantity(t, "stiffness", &jd->stiffness, 1, "N/m");
  if (rc == SW_OK && jd->kind != SW_JOINT_SPHERICAL)
    rc = attr_quantity(t, "rot_stiffness", &jd->rot_stiffness, 1, "N m/rad");
  if (rc == SW_OK && jd->kind == SW_JOINT_HINGE && jd->has_range) {
    rc = attr_quantity(t, "angle_min", &jd->angle_min, 1, "rad");
    if (rc == SW_OK) rc = attr_quantity(t, "angle_max", &jd->angle_max, 1, "rad");
  }
  if (rc == SW_OK && jd->kind == SW_JOINT_SPHERICAL && jd->cone > 0)
    rc = attr_quantity(t, "cone", &jd->cone, 1, "rad");
  if (rc == SW_OK && sw_joint_limited(jd)) {
    rc = attr_quantity(t, "limit_stiffness", &jd->limit_stiffness, 1, "N m/rad");
    if (rc == SW_OK) rc = attr_quantity(t, "limit_damping", &jd->limit_damping, 1, "N m s/rad");
  }
  return rc;
}

/* What a reader needs to normalise a muscle's output: F_max (N, the sum of
 * its filaments' peak forces), l0 (m), its filament count, and per filament
 * the peak force, the rest cross-section and the number of muscle fibres;
 * its material and model line are its first filament's. */
static int muscle_attrs(const swAttrTarget *t, const swModel *m, int mu) {
  const int f0 = m->muscle_fil_adr[mu], nf = m->muscle_fil_adr[mu + 1] - f0;
  const swRodInfo *info = &m->rod_info[m->fil_rod[f0]];
  double fmax = 0;
  for (int f = f0; f < f0 + nf; f++) fmax += m->fil_fmax[f];
  int rc = attr_string(t, "kind", "muscle");
  if (rc == SW_OK && info->material) rc = attr_string(t, "material", info->material);
  if (rc == SW_OK && info->where) rc = attr_string(t, "where", info->where);
  if (rc == SW_OK) rc = attr_quantity(t, "F_max", &fmax, 1, "N");
  if (rc == SW_OK) rc = attr_quantity(t, "l0", &m->fil_l0[f0], 1, "m");
  if (rc == SW_OK) rc = attr_int(t, "filaments", nf);
  if (rc == SW_OK) rc = attr_quantity(t, "filament_F_max", m->fil_fmax + f0, nf, "N");
  if (rc == SW_OK) rc = attr_quantity(t, "filament_area", m->fil_area + f0, nf, "m^2");
  if (rc == SW_OK) rc = attr_vector(t, "filament_fibres", m->fil_fibres + f0, nf);
  /* via points (muscle_via.c): where each was at t = 0, row by row, and the
   * rod that carries it ("space": fixed) */
  const int nvia = m->muscle_nvia ? m->muscle_nvia[mu] : 0;
  if (rc == SW_OK && nvia > 0) {
    const char *rods[SW_MUSCLE_MAX_VIA];
    for (int k = 0; k < nvia; k++) {
      const int e = m->ring_elem[m->fil_ring_adr[f0] + k];
      rods[k] = "space";
      for (int r = 0; e >= 0 && r < m->nrod; r++)
        if (m->elem_adr[r] <= e && e < m->elem_adr[r] + m->rod_nelem[r]) rods[k] = m->rod_name[r];
    }
    rc = attr_quantity(t, "via", m->muscle_via + 3 * SW_MUSCLE_MAX_VIA * mu, 3 * nvia, "m");
    if (rc == SW_OK) rc = attr_strings(t, "via_rods", rods, (hsize_t)nvia);
  }
  return rc;
}

/* The attributes of every rod, joint and muscle group the datasets made. */
static int write_group_attrs(swOutput *o, const swModel *m, char *err, size_t errlen) {
  static const char *const kinds[] = {"rods", "joints", "muscles"};
  const int count[] = {m->nrod, m->njoint, m->nmuscle};
  int rc = SW_OK;
  for (int kind = 0; kind < 3 && rc == SW_OK; kind++)
    for (int i = 0; i < count[kind] && rc == SW_OK; i++) {
      const char *name = kind == 0 ? m->rod_name[i] : kind == 1 ? m->joint_name[i]
                                                                 : m->muscle_name[i];
      char *gpath = dup_printf("/%s/%s", kinds[kind], name);
      if (!gpath) return fail(err, errlen, "%s: out of memory", o->path);
      hid_t g = open_group(o, gpath, err, errlen);
      if (g < 0) rc = SW_EIO;
      if (g > 0) {
        swAttrTarget t = {g, o->path, gpath, err, errlen};
        rc = kind == 0 ? rod_attrs(&t, m, i) : kind == 1 ? joint_attrs(&t, m, i)
                                                         : muscle_attrs(&t, m, i);
        H5Gclose(g);
      }
      free(gpath);
    }
  return rc;
}

/* /params: a table of (name, value, unit, default), one row per param. */
static int write_params(swOutput *o, const swOutputOptions *opt, char *err, size_t errlen) {
  if (opt->nparam <= 0) return SW_OK;
  typedef struct {
    const char *name;
    double value;
    const char *unit;
    double dflt;
  } swParamRow;
  hsize_t n = (hsize_t)opt->nparam;
  swParamRow rows[opt->nparam];
  for (int i = 0; i < opt->nparam; i++)
    rows[i] = (swParamRow){opt->param_name[i], opt->param_value[i],
                           opt->param_unit[i] ? opt->param_unit[i] : "", opt->param_default[i]};
  hid_t str = utf8_string_type();
  hid_t type = H5Tcreate(H5T_COMPOUND, sizeof(swParamRow));
  hid_t space = H5Screate_simple(1, &n, NULL);
  int ok = str >= 0 && type >= 0 && space >= 0 &&
           H5Tinsert(type, "name", HOFFSET(swParamRow, name), str) >= 0 &&
           H5Tinsert(type, "value", HOFFSET(swParamRow, value), H5T_NATIVE_DOUBLE) >= 0 &&
           H5Tinsert(type, "unit", HOFFSET(swParamRow, unit), str) >= 0 &&
           H5Tinsert(type, "default", HOFFSET(swParamRow, dflt), H5T_NATIVE_DOUBLE) >= 0;
  hid_t dset = ok ? H5Dcreate2(o->file, "/params", type, space, H5P_DEFAULT, H5P_DEFAULT,
                               H5P_DEFAULT)
                  : H5I_INVALID_HID;
  ok = ok && dset >= 0 && H5Dwrite(dset, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, rows) >= 0;
  if (dset >= 0) H5Dclose(dset);
  if (space >= 0) H5Sclose(space);
  if (type >= 0) H5Tclose(type);
  if (str >= 0) H5Tclose(str);
  return ok ? SW_OK : fail(err, errlen, "%s: cannot write the table /params", o->path);
}

static void release(swOutput *o) {
  for (int i = 0; i < o->ndset; i++) {
    if (o->dset[i].dset >= 0) H5Dclose(o->dset[i].dset);
    free(o->dset[i].path);
  }
  if (o->file >= 0) H5Fclose(o->file);
  free(o->dset);
  free(o->frame);
  free(o->path);
  free(o->xdmf_path);
  free(o->xdmf_rod);
  free(o->frame_time);
  sw_checkpoint_free(o->checkpoint);
  free(o);
}

/* The root attribute `name` as a string into buf ("" when absent). */
static void read_root_string(hid_t file, const char *name, char *buf, size_t len) {
  buf[0] = '\0';
  if (H5Aexists(file, name) <= 0) return;
  hid_t attr = H5Aopen(file, name, H5P_DEFAULT), type = utf8_string_type();
  char *value = NULL;
  if (attr >= 0 && type >= 0 && H5Aread(attr, type, &value) >= 0 && value) {
    snprintf(buf, len, "%s", value);
    H5free_memory(value);
  }
  if (type >= 0) H5Tclose(type);
  if (attr >= 0) H5Aclose(attr);
}

/* Replaces (or adds) a root string attribute. */
static int replace_root_string(swOutput *o, const char *name, const char *value) {
  swAttrTarget t = {o->file, o->path, "/", NULL, 0};
  htri_t had = H5Aexists(o->file, name);
  if (had < 0 || (had > 0 && H5Adelete(o->file, name) < 0))
    return fail(NULL, 0, "%s: cannot replace attribute '%s' of /", o->path, name);
  return attr_string(&t, name, value);
}

/* A root attribute that is a number (-1 when absent). */
static double read_root_number(hid_t file, const char *name) {
  double value = -1;
  hid_t attr = H5Aexists(file, name) > 0 ? H5Aopen(file, name, H5P_DEFAULT) : -1;
  if (attr >= 0) {
    if (H5Aread(attr, H5T_NATIVE_DOUBLE, &value) < 0) value = -1;
    H5Aclose(attr);
  }
  return value;
}

/* A continued run's file: the model that wrote it (by hash) and the params,
 * time step and frame interval it ran with must be this run's. */
static int check_resumable(swOutput *o, const swModel *m, const swOutputOptions *opt, char *err,
                           size_t errlen) {
  char have[4096];
  read_root_string(o->file, "model_sha256", have, sizeof have);
  if (strcmp(have, opt->model_sha256 ? opt->model_sha256 : ""))
    return fail(err, errlen, "%s was written by another model (model_sha256 %.12s..., this "
                "model's %.12s...)", o->path, have, opt->model_sha256 ? opt->model_sha256 : "");
  read_root_string(o->file, "params", have, sizeof have);
  if (strcmp(have, opt->params ? opt->params : ""))
    return fail(err, errlen, "%s was run with the params %s, this run has %s", o->path, have,
                opt->params ? opt->params : "");
  double dt = read_root_number(o->file, "dt"), every = read_root_number(o->file, "every");
  if (dt != m->dt)
    return fail(err, errlen, "%s was run at dt = %g s, this run at %g s", o->path, dt, m->dt);
  if (every != opt->every)
    return fail(err, errlen, "%s was written with a frame every %g s, this run every %g s",
                o->path, every, opt->every);
  return SW_OK;
}

static double wall_now(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* ---- the XDMF description (xdmf.c) ---- */

/* Seconds of wall time between two rewrites of the description during a
 * run, at least, and at least this many times the last rewrite took: it is
 * rewritten whole (about 1 kB per rod and frame), so rewriting it at every
 * frame would cost the square of the frame count, and a long run's rewrites
 * take at most 1/XDMF_SHARE of its wall time. */
#define XDMF_EVERY 1.0
#define XDMF_SHARE 20.0

/* /rods/NAME/node_radius [n + 1] (m): the rest radius at each node, the
 * mean of the elements on either side (an end node takes its element's),
 * for ParaView's Tube filter, which varies radius over points. */
static int write_node_radius(swOutput *o, const swModel *m, int r) {
  const int n = m->rod_nelem[r];
  const double *radius = m->radius + m->elem_adr[r];
  double *node = malloc(((size_t)n + 1) * sizeof *node); /* not on the stack: n is unbounded */
  char *path = dup_printf("/rods/%s/node_radius", m->rod_name[r]);
  if (!node || !path) {
    free(node);
    free(path);
    return fail(NULL, 0, "%s: out of memory", o->path);
  }
  for (int i = 0; i <= n; i++)
    node[i] = i == 0 ? radius[0] : i == n ? radius[n - 1] : 0.5 * (radius[i - 1] + radius[i]);
  hsize_t count = (hsize_t)n + 1;
  hid_t space = H5Screate_simple(1, &count, NULL);
  hid_t dset = space < 0 ? H5I_INVALID_HID
                         : H5Dcreate2(o->file, path, H5T_IEEE_F64LE, space, H5P_DEFAULT,
                                      H5P_DEFAULT, H5P_DEFAULT);
  int rc = dset >= 0 && H5Dwrite(dset, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT,
                                 node) >= 0
               ? SW_OK
               : fail(NULL, 0, "%s: cannot write dataset %s", o->path, path);
  if (rc == SW_OK) {
    swAttrTarget t = {dset, o->path, path, NULL, 0};
    rc = attr_string(&t, "units", "m");
  }
  if (dset >= 0) H5Dclose(dset);
  if (space >= 0) H5Sclose(space);
  free(path);
  free(node);
  return rc;
}

/* Rewrites the description to list the frames written so far. */
static int xdmf_update(swOutput *o) {
  if (!o->xdmf_path) return SW_OK;
  char err[512];
  double start = wall_now();
  if (sw_xdmf_write(o->xdmf_path, o->path, o->xdmf_rod, o->nxdmf_rod, o->frame_time, o->frames,
                    err, sizeof err) != SW_OK)
    return fail(NULL, 0, "%s", err);
  double now = wall_now();
  o->xdmf_frames = o->frames;
  o->xdmf_wait = XDMF_SHARE * (now - start);
  if (o->xdmf_wait < XDMF_EVERY) o->xdmf_wait = XDMF_EVERY;
  o->xdmf_written = now;
  return SW_OK;
}

/* The rods whose positions the file holds, their node radii (a new file),
 * the times of the frames it keeps (a continued one: the description lists
 * them again), and a first description. */
static int xdmf_open(swOutput *o, const swModel *m, int fresh, char *err, size_t errlen) {
  if (!(o->xdmf_rod = calloc((size_t)m->nrod + 1, sizeof *o->xdmf_rod)))
    return fail(err, errlen, "%s: out of memory", o->path);
  for (int i = 0; i < o->ndset; i++) {
    const swDataset *ds = &o->dset[i];
    if (ds->field->fill != fill_position) continue;
    const int r = ds->item;
    swXdmfRod *x = &o->xdmf_rod[o->nxdmf_rod++];
    *x = (swXdmfRod){m->rod_name[r], m->rod_nelem[r] + 1, 0};
    for (int j = 0; j < o->ndset; j++)
      if (o->dset[j].field->fill == fill_velocity && o->dset[j].item == r) x->velocity = 1;
    if (fresh && write_node_radius(o, m, r) != SW_OK)
      return fail(err, errlen, "%s", last_error);
  }
  char *xdmf_path = sw_xdmf_path(o->path);
  if (!xdmf_path) return fail(err, errlen, "%s: out of memory", o->path);
  if (!o->nxdmf_rod) {   /* nothing to draw: no description, nor a stale one */
    if (remove(xdmf_path) != 0 && errno != ENOENT)
      fail(NULL, 0, "%s: cannot remove the stale %s", o->path, xdmf_path);
    free(xdmf_path);
    return SW_OK;
  }
  o->xdmf_path = xdmf_path;
  o->frame_time_cap = o->frames + 64;
  if (!(o->frame_time = malloc((size_t)o->frame_time_cap * sizeof *o->frame_time)))
    return fail(err, errlen, "%s: out of memory", o->path);
  /* output_fields[0] is /time, the first dataset opened */
  if (o->frames > 0 && H5Dread(o->dset[0].dset, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL,
                               H5P_DEFAULT, o->frame_time) < 0)
    return fail(err, errlen, "%s: cannot read /time", o->path);
  if (xdmf_update(o) != SW_OK) return fail(err, errlen, "%s", last_error);
  return SW_OK;
}

/* sw_output_open and sw_output_resume: d == NULL creates the file, else it
 * reopens it and puts its checkpoint into d and x. */
static swOutput *open_output(const char *path, const swModel *m, const swOutputOptions *opt,
                             swData *d, swExpectRun *x, char *err, size_t errlen) {
  static const swOutputOptions no_options;
  if (!opt) opt = &no_options;
  H5Eset_auto2(H5E_DEFAULT, NULL, NULL);   /* our messages, not HDF5's stack dump */
  if (!path || !path[0] || !m) {
    fail(err, errlen, "output: no file name or no model");
    return NULL;
  }
  for (int r = 0; r < m->nrod; r++)
    if (!valid_group_name(m->rod_name[r])) {
      fail(err, errlen, "%s: rod %d has name '%s', which cannot name an HDF5 group", path, r,
           m->rod_name[r] ? m->rod_name[r] : "");
      return NULL;
    }
  if (!sw_xdmf_name_ok(path)) {
    fail(err, errlen, "%s: the file name has a control character, which the XDMF "
         "description beside it (XML) cannot hold", path);
    return NULL;
  }
  for (int r = 0; r < m->nrod; r++)
    if (!sw_xdmf_name_ok(m->rod_name[r])) {
      fail(err, errlen, "%s: rod %d has a control character in its name, which the XDMF "
           "description (XML) cannot hold", path, r);
      return NULL;
    }
  for (int j = 0; j < m->njoint; j++)
    if (!valid_group_name(m->joint_name[j])) {
      fail(err, errlen, "%s: joint %d has name '%s', which cannot name an HDF5 group", path, j,
           m->joint_name[j] ? m->joint_name[j] : "");
      return NULL;
    }
  for (int i = 0; i < m->nmuscle; i++)
    if (!valid_group_name(m->muscle_name[i])) {
      fail(err, errlen, "%s: muscle %d has name '%s', which cannot name an HDF5 group", path, i,
           m->muscle_name[i] ? m->muscle_name[i] : "");
      return NULL;
    }
  for (int i = 0; i < m->nprobe; i++)
    if (!valid_group_name(m->probe[i].name)) {
      fail(err, errlen, "%s: probe %d has name '%s', which cannot name an HDF5 dataset", path, i,
           m->probe[i].name ? m->probe[i].name : "");
      return NULL;
    }

  swOutput *o = calloc(1, sizeof *o);
  if (!o || !(o->path = dup_printf("%s", path))) {
    free(o);
    fail(err, errlen, "%s: out of memory", path);
    return NULL;
  }
  o->file = H5I_INVALID_HID;
  o->nrod = m->nrod;
  size_t max_dsets = 0;
  for (size_t f = 0; f < NFIELDS; f++) max_dsets += (size_t)field_items(&output_fields[f], m);
  o->dset = calloc(max_dsets ? max_dsets : 1, sizeof *o->dset);
  if (!o->dset) {
    fail(err, errlen, "%s: out of memory", path);
    release(o);
    return NULL;
  }

  o->model = m;
  o->checkpoint = sw_checkpoint_new(m);
  if (!o->checkpoint) {
    fail(err, errlen, "%s: out of memory", path);
    release(o);
    return NULL;
  }
  long frames = -1;   /* reopening: the frames to keep */
  int rc = SW_OK;
  if (!d) {
    o->file = H5Fcreate(path, H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
    if (o->file < 0) {
      fail(err, errlen, "cannot create HDF5 file %s", path);
      release(o);
      return NULL;
    }
    rc = write_root_attrs(o, m, opt, err, errlen);
  } else {
    o->file = H5Fopen(path, H5F_ACC_RDWR, H5P_DEFAULT);
    if (o->file < 0) {
      fail(err, errlen, "cannot open HDF5 file %s to continue its run", path);
      release(o);
      return NULL;
    }
    rc = check_resumable(o, m, opt, err, errlen);
    if (rc == SW_OK) rc = sw_checkpoint_read(path, o->file, m, d, x, &frames, err, errlen);
    if (rc == SW_OK) rc = replace_root_string(o, "status", "incomplete: the run did not close this file");
    if (rc == SW_OK && H5Adelete(o->file, "duration") >= 0) {
      swAttrTarget t = {o->file, o->path, "/", err, errlen};
      rc = attr_scalar(&t, "duration", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, &opt->duration);
    }
    if (rc == SW_OK && frames >= 0) sw_checkpoint_take(o->checkpoint, m, d, x, frames);
    o->frames = frames;
  }

  /* Groups /rods/NAME, /joints/NAME and /diagnostics come into being with
   * their datasets. */
  hid_t lcpl = H5Pcreate(H5P_LINK_CREATE);
  if (rc == SW_OK && (lcpl < 0 || H5Pset_create_intermediate_group(lcpl, 1) < 0))
    rc = fail(err, errlen, "%s: cannot make a link creation property list", path);
  size_t max_frame = 1;
  for (size_t f = 0; f < NFIELDS && rc == SW_OK; f++) {
    const swField *field = &output_fields[f];
    int nrep = field_items(field, m);
    for (int k = 0; k < nrep && rc == SW_OK; k++) {
      if (field->scope != SCOPE_ROOT && !item_enabled(field, m, opt, k)) continue;
      swDataset *ds = &o->dset[o->ndset++];
      rc = create_dataset(o, ds, field, m, field->scope == SCOPE_ROOT ? -1 : k, lcpl, frames,
                          err, errlen);
      if (ds->frame_len > max_frame) max_frame = ds->frame_len;
    }
  }
  if (lcpl >= 0) H5Pclose(lcpl);
  if (rc == SW_OK && !d) rc = write_group_attrs(o, m, err, errlen);
  if (rc == SW_OK && !d) rc = write_params(o, opt, err, errlen);
  if (rc == SW_OK) rc = xdmf_open(o, m, !d, err, errlen);
  if (rc == SW_OK && !(o->frame = malloc(max_frame * sizeof *o->frame)))
    rc = fail(err, errlen, "%s: out of memory", path);
  if (rc == SW_OK && H5Fflush(o->file, H5F_SCOPE_LOCAL) < 0)
    rc = fail(err, errlen, "%s: cannot flush the file", path);
  if (rc != SW_OK) {
    release(o);
    return NULL;
  }
  return o;
}

int sw_output_read_run(const char *path, char *sha256, char *params, size_t len, double *dt,
                       double *every) {
  H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
  hid_t file = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
  if (file < 0) return fail(NULL, 0, "cannot open HDF5 file %s", path);
  read_root_string(file, "model_sha256", sha256, 65);
  read_root_string(file, "params", params, len);
  *dt = read_root_number(file, "dt");
  *every = read_root_number(file, "every");
  H5Fclose(file);
  return SW_OK;
}

swOutput *sw_output_open(const char *path, const swModel *m, const swOutputOptions *opt,
                         char *err, size_t errlen) {
  return open_output(path, m, opt, NULL, NULL, err, errlen);
}

swOutput *sw_output_resume(const char *path, const swModel *m, const swOutputOptions *opt,
                           swData *d, swExpectRun *x, char *err, size_t errlen) {
  if (!d) {
    fail(err, errlen, "%s: no state to continue into", path ? path : "output");
    return NULL;
  }
  return open_output(path, m, opt, d, x, err, errlen);
}

/* ---- frames ---- */

static int append_frame(swOutput *o, swDataset *ds, const double *frame) {
  hsize_t start[1 + MAX_FRAME_RANK] = {0}, count[1 + MAX_FRAME_RANK];
  ds->dims[0] = (hsize_t)o->frames + 1;
  if (H5Dset_extent(ds->dset, ds->dims) < 0) {
    ds->dims[0] = (hsize_t)o->frames;
    return fail(NULL, 0, "%s: cannot extend dataset %s to %ld frames", o->path, ds->path,
                o->frames + 1);
  }
  start[0] = (hsize_t)o->frames;
  count[0] = 1;
  for (int k = 1; k < ds->rank; k++) count[k] = ds->dims[k];
  hid_t file_space = H5Dget_space(ds->dset);
  hid_t mem_space = H5Screate_simple(ds->rank, count, NULL);
  int ok = file_space >= 0 && mem_space >= 0 &&
           H5Sselect_hyperslab(file_space, H5S_SELECT_SET, start, NULL, count, NULL) >= 0 &&
           H5Dwrite(ds->dset, H5T_NATIVE_DOUBLE, mem_space, file_space, H5P_DEFAULT, frame) >= 0;
  if (mem_space >= 0) H5Sclose(mem_space);
  if (file_space >= 0) H5Sclose(file_space);
  if (!ok)
    return fail(NULL, 0, "%s: cannot write frame %ld of dataset %s", o->path, o->frames,
                ds->path);
  return SW_OK;
}

int sw_output_frame(swOutput *o, const swModel *m, swData *d) {
  if (!o || !m || !d) return fail(NULL, 0, "output: no file, model or state");
  if (m->nrod != o->nrod)
    return fail(NULL, 0, "%s: the model has %d rods but the file was opened for %d", o->path,
                m->nrod, o->nrod);
  for (int i = 0; i < o->ndset; i++) {
    swDataset *ds = &o->dset[i];
    ds->field->fill(m, d, ds->item, o->frame);
    int rc = append_frame(o, ds, o->frame);
    if (rc != SW_OK) return rc;
  }
  /* Metadata on disk after every frame: a run that dies leaves a valid file. */
  if (H5Fflush(o->file, H5F_SCOPE_LOCAL) < 0)
    return fail(NULL, 0, "%s: cannot flush the file after frame %ld", o->path, o->frames);
  if (o->xdmf_path) {
    if (o->frames == o->frame_time_cap) {
      long cap = 2 * o->frame_time_cap;
      double *grown = realloc(o->frame_time, (size_t)cap * sizeof *grown);
      if (!grown) return fail(NULL, 0, "%s: out of memory", o->path);
      o->frame_time = grown;
      o->frame_time_cap = cap;
    }
    o->frame_time[o->frames] = d->time;
  }
  o->frames++;
  /* the description follows the flushed file: at the first frame, then
   * every xdmf_wait seconds, and at close */
  if (o->xdmf_path && (o->xdmf_frames == 0 || wall_now() - o->xdmf_written >= o->xdmf_wait))
    return xdmf_update(o);
  return SW_OK;
}

long sw_output_frames(const swOutput *o) { return o ? o->frames : 0; }

/* Seconds of wall time between two writes of the checkpoint: a run killed
 * outright loses at most this much. */
#define CHECKPOINT_EVERY 10.0

int sw_output_checkpoint(swOutput *o, const swModel *m, const swData *d, const swExpectRun *x) {
  if (!o || !o->checkpoint || m != o->model) return SW_OK;
  sw_checkpoint_take(o->checkpoint, m, d, x, o->frames);
  double now = wall_now();
  if (now - o->checkpoint_written < CHECKPOINT_EVERY) return SW_OK;
  o->checkpoint_written = now;
  if (sw_checkpoint_write(o->checkpoint, m, o->file) != SW_OK)
    return fail(NULL, 0, "%s: cannot write the checkpoint /restart", o->path);
  return SW_OK;
}

/* ---- the objective (evaluate.c computes it, cli.c hands it here) ---- */

int sw_output_objective(swOutput *o, const char *text, double objective, double penalty,
                        double score, const char *units) {
  if (!o) return SW_OK;
  static const char *const names[] = {"objective", "penalty", "score", "objective_units",
                                      "penalty_units", "score_units", "objective_text"};
  for (size_t k = 0; k < sizeof names / sizeof names[0]; k++) {
    htri_t had = H5Aexists(o->file, names[k]);
    if (had < 0 || (had > 0 && H5Adelete(o->file, names[k]) < 0))
      return fail(NULL, 0, "%s: cannot replace attribute '%s' of /", o->path, names[k]);
  }
  swAttrTarget t = {o->file, o->path, "/", NULL, 0};
  int rc = attr_quantity(&t, "objective", &objective, 1, units);
  if (rc == SW_OK) rc = attr_quantity(&t, "penalty", &penalty, 1, units);
  if (rc == SW_OK) rc = attr_quantity(&t, "score", &score, 1, units);
  if (rc == SW_OK) rc = attr_string(&t, "objective_text", text);
  return rc;
}

/* ---- close ---- */

int sw_output_close(swOutput *o, const char *status) {
  if (!o) return SW_OK;
  int rc = SW_OK;
  if (o->checkpoint && sw_checkpoint_write(o->checkpoint, o->model, o->file) != SW_OK)
    rc = fail(NULL, 0, "%s: cannot write the checkpoint /restart", o->path);
  if (rc == SW_OK) rc = replace_root_string(o, "status", status ? status : "complete");
  for (int i = 0; i < o->ndset; i++) {
    if (o->dset[i].dset >= 0 && H5Dclose(o->dset[i].dset) < 0 && rc == SW_OK)
      rc = fail(NULL, 0, "%s: cannot close dataset %s", o->path, o->dset[i].path);
    o->dset[i].dset = H5I_INVALID_HID;
  }
  if (H5Fclose(o->file) < 0 && rc == SW_OK)
    rc = fail(NULL, 0, "%s: cannot close the file", o->path);
  o->file = H5I_INVALID_HID;
  /* every frame is in the file: the description lists them all */
  int described = xdmf_update(o);
  if (rc == SW_OK) rc = described;
  release(o);
  return rc;
}
