/* output.c — the HDF5 file of a run, from open to close: creating it (or
 * reopening it to continue a run, --restart), each frame, the checkpoint,
 * the XDMF description beside it, the status it closes with, and the
 * messages of what failed.  Its siblings: output_datasets.c (the table of
 * what is written and the datasets), output_attrs.c (the attributes),
 * output.h (what the three share); restart.c (the checkpoint), xdmf.c (the
 * XDMF text) and compare.c (which reads a golden file) are the other files
 * of the runtime that include hdf5.h.
 *
 * Design.  sw_output_open() creates the file, writes the root's record of
 * how it was made, creates every dataset the table selects (whose groups
 * then describe themselves) and the /params table; sw_output_resume()
 * reopens the file of an earlier run of the same model, params, time step
 * and frame interval, reads its checkpoint into the state and cuts every
 * dataset back to the checkpoint's frames.  sw_output_frame() walks the
 * opened datasets, fills a scratch frame allocated at open time, appends it
 * and flushes the file every 50 ms of wall time or less often (when a
 * flush takes long), so a run that dies
 * later still leaves a readable file of the frames written up to then.  The root's `status` reads
 * "incomplete" until sw_output_close() replaces it with the caller's
 * verdict.  Beside the
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
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "sinew.h"
#include "engine/internal.h"
#include "output.h"
#include "restart.h"
#include "xdmf.h"

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
int sw_out_fail(char *err, size_t errlen, const char *fmt, ...) {
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

char *sw_out_dup_printf(const char *fmt, ...) {
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

/* ---- open ---- */

static int valid_group_name(const char *name) {
  return name && name[0] && !strchr(name, '/') && strcmp(name, ".") && strcmp(name, "..");
}

/* Frames wait in memory, each dataset's in a buffer of one chunk aligned
 * with the file's chunks, and go to the datasets when their chunk is full,
 * at every flush (sw_output_frame) and at the checkpoint and close: one
 * extent and one write per dataset and chunk or flush (output_datasets.c).
 * Written frame by frame, the arm's 179 datasets cost 0.6 ms a frame, more
 * than its 1 ms of simulated time took to compute at 150 us. */
static int alloc_pending(swOutput *o, char *err, size_t errlen) {
  size_t per_frame = 0;
  for (int i = 0; i < o->ndset; i++) per_frame += o->dset[i].frame_len;
  o->pending_len = (per_frame ? per_frame : 1) * (size_t)o->chunk_frames;
  if (!(o->pending = calloc(o->pending_len, sizeof *o->pending)))
    return sw_out_fail(err, errlen, "%s: out of memory", o->path);
  for (int i = 0, off = 0; i < o->ndset; i++) {
    o->dset[i].pending = o->pending + (size_t)off * (size_t)o->chunk_frames;
    off += (int)o->dset[i].frame_len;
  }
  return sw_out_read_partial_chunk(o);
}

/* The frames taken and not yet written into their datasets; a full chunk
 * leaves its buffers zeroed for the next (so that a partly filled chunk's
 * rows past the extent are zeros in the file). */
static int write_pending(swOutput *o) {
  if (o->written == o->frames) return SW_OK;
  for (int i = 0; i < o->ndset; i++) {
    int rc = sw_out_write_frames(o, &o->dset[i], o->frames);
    if (rc != SW_OK) return rc;
  }
  o->written = o->frames;
  if (o->written % o->chunk_frames == 0) memset(o->pending, 0, o->pending_len * sizeof *o->pending);
  return SW_OK;
}

static void release(swOutput *o) {
  for (int i = 0; i < o->ndset; i++) {
    if (o->dset[i].dset >= 0) H5Dclose(o->dset[i].dset);
    free(o->dset[i].path);
  }
  if (o->file >= 0) H5Fclose(o->file);
  free(o->dset);
  free(o->pending);
  free(o->path);
  free(o->xdmf_path);
  free(o->xdmf_rod);
  free(o->frame_time);
  sw_checkpoint_free(o->checkpoint);
  free(o);
}

/* ---- the root's record, read back and replaced (resume, read_run, close) ---- */

/* The root attribute `name` as a string into buf ("" when absent). */
static void read_root_string(hid_t file, const char *name, char *buf, size_t len) {
  buf[0] = '\0';
  if (H5Aexists(file, name) <= 0) return;
  hid_t attr = H5Aopen(file, name, H5P_DEFAULT), type = sw_out_utf8_string_type();
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
    return sw_out_fail(NULL, 0, "%s: cannot replace attribute '%s' of /", o->path, name);
  return sw_out_attr_string(&t, name, value);
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
    return sw_out_fail(err, errlen, "%s was written by another model (model_sha256 %.12s..., this "
                       "model's %.12s...)", o->path, have,
                       opt->model_sha256 ? opt->model_sha256 : "");
  read_root_string(o->file, "params", have, sizeof have);
  if (strcmp(have, opt->params ? opt->params : ""))
    return sw_out_fail(err, errlen, "%s was run with the params %s, this run has %s", o->path, have,
                       opt->params ? opt->params : "");
  double dt = read_root_number(o->file, "dt"), every = read_root_number(o->file, "every");
  if (dt != m->dt)
    return sw_out_fail(err, errlen, "%s was run at dt = %g s, this run at %g s", o->path, dt,
                       m->dt);
  if (every != opt->every)
    return sw_out_fail(err, errlen, "%s was written with a frame every %g s, this run every %g s",
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
 * rewritten whole (about 0.5 kB per rod and frame), so rewriting it at every
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
  char *path = sw_out_dup_printf("/rods/%s/node_radius", m->rod_name[r]);
  if (!node || !path) {
    free(node);
    free(path);
    return sw_out_fail(NULL, 0, "%s: out of memory", o->path);
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
               : sw_out_fail(NULL, 0, "%s: cannot write dataset %s", o->path, path);
  if (rc == SW_OK) {
    swAttrTarget t = {dset, o->path, path, NULL, 0};
    rc = sw_out_attr_string(&t, "units", "m");
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
    return sw_out_fail(NULL, 0, "%s", err);
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
    return sw_out_fail(err, errlen, "%s: out of memory", o->path);
  for (int i = 0; i < o->ndset; i++) {
    const swDataset *ds = &o->dset[i];
    if (ds->field->fill != sw_out_fill_position) continue;
    const int r = ds->item;
    swXdmfRod *x = &o->xdmf_rod[o->nxdmf_rod++];
    *x = (swXdmfRod){m->rod_name[r], m->rod_nelem[r] + 1, 0};
    for (int j = 0; j < o->ndset; j++)
      if (o->dset[j].field->fill == sw_out_fill_velocity && o->dset[j].item == r) x->velocity = 1;
    if (fresh && write_node_radius(o, m, r) != SW_OK)
      return sw_out_fail(err, errlen, "%s", last_error);
  }
  char *xdmf_path = sw_xdmf_path(o->path);
  if (!xdmf_path) return sw_out_fail(err, errlen, "%s: out of memory", o->path);
  if (!o->nxdmf_rod) {   /* nothing to draw: no description, nor a stale one */
    if (remove(xdmf_path) != 0 && errno != ENOENT)
      sw_out_fail(NULL, 0, "%s: cannot remove the stale %s", o->path, xdmf_path);
    free(xdmf_path);
    return SW_OK;
  }
  o->xdmf_path = xdmf_path;
  o->frame_time_cap = o->frames + 64;
  if (!(o->frame_time = malloc((size_t)o->frame_time_cap * sizeof *o->frame_time)))
    return sw_out_fail(err, errlen, "%s: out of memory", o->path);
  /* output_fields[0] is /time, the first dataset opened */
  if (o->frames > 0 && H5Dread(o->dset[0].dset, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL,
                               H5P_DEFAULT, o->frame_time) < 0)
    return sw_out_fail(err, errlen, "%s: cannot read /time", o->path);
  if (xdmf_update(o) != SW_OK) return sw_out_fail(err, errlen, "%s", last_error);
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
    sw_out_fail(err, errlen, "output: no file name or no model");
    return NULL;
  }
  for (int r = 0; r < m->nrod; r++)
    if (!valid_group_name(m->rod_name[r])) {
      sw_out_fail(err, errlen, "%s: rod %d has name '%s', which cannot name an HDF5 group", path, r,
                  m->rod_name[r] ? m->rod_name[r] : "");
      return NULL;
    }
  if (!sw_xdmf_name_ok(path)) {
    sw_out_fail(err, errlen, "%s: the file name has a control character, which the XDMF "
                "description beside it (XML) cannot hold", path);
    return NULL;
  }
  for (int r = 0; r < m->nrod; r++)
    if (!sw_xdmf_name_ok(m->rod_name[r])) {
      sw_out_fail(err, errlen, "%s: rod %d has a control character in its name, which the XDMF "
                  "description (XML) cannot hold", path, r);
      return NULL;
    }
  for (int j = 0; j < m->njoint; j++)
    if (!valid_group_name(m->joint_name[j])) {
      sw_out_fail(err, errlen, "%s: joint %d has name '%s', which cannot name an HDF5 group",
                  path, j, m->joint_name[j] ? m->joint_name[j] : "");
      return NULL;
    }
  for (int i = 0; i < m->nmuscle; i++)
    if (!valid_group_name(m->muscle_name[i])) {
      sw_out_fail(err, errlen, "%s: muscle %d has name '%s', which cannot name an HDF5 group",
                  path, i, m->muscle_name[i] ? m->muscle_name[i] : "");
      return NULL;
    }
  for (int i = 0; i < m->nprobe; i++)
    if (!valid_group_name(m->probe[i].name)) {
      sw_out_fail(err, errlen, "%s: probe %d has name '%s', which cannot name an HDF5 dataset",
                  path, i, m->probe[i].name ? m->probe[i].name : "");
      return NULL;
    }

  swOutput *o = calloc(1, sizeof *o);
  if (!o || !(o->path = sw_out_dup_printf("%s", path))) {
    free(o);
    sw_out_fail(err, errlen, "%s: out of memory", path);
    return NULL;
  }
  o->file = H5I_INVALID_HID;
  o->nrod = m->nrod;
  size_t max_dsets = sw_out_count_datasets(m);
  o->dset = calloc(max_dsets ? max_dsets : 1, sizeof *o->dset);
  if (!o->dset) {
    sw_out_fail(err, errlen, "%s: out of memory", path);
    release(o);
    return NULL;
  }

  o->model = m;
  o->checkpoint = sw_checkpoint_new(m);
  if (!o->checkpoint) {
    sw_out_fail(err, errlen, "%s: out of memory", path);
    release(o);
    return NULL;
  }
  long frames = -1;   /* reopening: the frames to keep */
  int rc = SW_OK;
  if (!d) {
    o->file = H5Fcreate(path, H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
    if (o->file < 0) {
      sw_out_fail(err, errlen, "cannot create HDF5 file %s", path);
      release(o);
      return NULL;
    }
    rc = sw_out_write_root_attrs(o, m, opt, err, errlen);
  } else {
    o->file = H5Fopen(path, H5F_ACC_RDWR, H5P_DEFAULT);
    if (o->file < 0) {
      sw_out_fail(err, errlen, "cannot open HDF5 file %s to continue its run", path);
      release(o);
      return NULL;
    }
    rc = check_resumable(o, m, opt, err, errlen);
    if (rc == SW_OK) rc = sw_checkpoint_read(path, o->file, m, d, x, &frames, err, errlen);
    if (rc == SW_OK) rc = replace_root_string(o, "status", "incomplete: the run did not close this file");
    if (rc == SW_OK && H5Adelete(o->file, "duration") >= 0) {
      swAttrTarget t = {o->file, o->path, "/", err, errlen};
      rc = sw_out_attr_scalar(&t, "duration", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, &opt->duration);
    }
    if (rc == SW_OK && frames >= 0) sw_checkpoint_take(o->checkpoint, m, d, x, frames);
    o->frames = o->written = frames;
  }

  if (rc == SW_OK) rc = sw_out_create_datasets(o, m, opt, frames, err, errlen);
  if (rc == SW_OK && !d) rc = sw_out_write_group_attrs(o, m, err, errlen);
  if (rc == SW_OK && !d) rc = sw_out_write_params(o, opt, err, errlen);
  if (rc == SW_OK) rc = xdmf_open(o, m, !d, err, errlen);
  if (rc == SW_OK) rc = alloc_pending(o, err, errlen);
  if (rc == SW_OK && H5Fflush(o->file, H5F_SCOPE_LOCAL) < 0)
    rc = sw_out_fail(err, errlen, "%s: cannot flush the file", path);
  if (rc != SW_OK) {
    release(o);
    return NULL;
  }
  return o;
}

int sw_output_read_run(const char *path, char *sha256, char *params, size_t len, double *dt,
                       double *every, char *integrator) {
  H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
  hid_t file = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
  if (file < 0) return sw_out_fail(NULL, 0, "cannot open HDF5 file %s", path);
  read_root_string(file, "model_sha256", sha256, 65);
  read_root_string(file, "params", params, len);
  *dt = read_root_number(file, "dt");
  *every = read_root_number(file, "every");
  read_root_string(file, "integrator", integrator, 16);
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
    sw_out_fail(err, errlen, "%s: no state to continue into", path ? path : "output");
    return NULL;
  }
  return open_output(path, m, opt, d, x, err, errlen);
}

/* ---- frames ---- */

/* Seconds of wall time between two flushes of the frames (sw_output_frame),
 * at least, and at least FLUSH_SHARE times the last flush took: a flush
 * writes every dataset's partly filled chunk again, so the flushes take at
 * most 1/FLUSH_SHARE of a run's wall time (at every 50 ms they were 8% of
 * the arm's half-second demo). */
#define FLUSH_EVERY 0.05
#define FLUSH_SHARE 50.0

static int flush_frames(swOutput *o) {
  double start = wall_now();
  int rc = write_pending(o);
  if (rc != SW_OK) return rc;
  if (H5Fflush(o->file, H5F_SCOPE_LOCAL) < 0)
    return sw_out_fail(NULL, 0, "%s: cannot flush the file after frame %ld", o->path, o->written - 1);
  o->flushed_at = wall_now();
  o->flush_wait = FLUSH_SHARE * (o->flushed_at - start);
  if (o->flush_wait < FLUSH_EVERY) o->flush_wait = FLUSH_EVERY;
  o->flushed_frames = o->written;
  return SW_OK;
}

int sw_output_frame(swOutput *o, const swModel *m, swData *d) {
  if (!o || !m || !d) return sw_out_fail(NULL, 0, "output: no file, model or state");
  if (m->nrod != o->nrod)
    return sw_out_fail(NULL, 0, "%s: the model has %d rods but the file was opened for %d", o->path,
                       m->nrod, o->nrod);
  /* the frame's row of each chunk buffer, which starts at frame `start` */
  const long start = o->written - o->written % o->chunk_frames;
  for (int i = 0; i < o->ndset; i++) {
    swDataset *ds = &o->dset[i];
    ds->field->fill(m, d, ds->item, ds->pending + (size_t)(o->frames - start) * ds->frame_len);
  }
  if (o->xdmf_path) {
    if (o->frames == o->frame_time_cap) {
      long cap = 2 * o->frame_time_cap;
      double *grown = realloc(o->frame_time, (size_t)cap * sizeof *grown);
      if (!grown) return sw_out_fail(NULL, 0, "%s: out of memory", o->path);
      o->frame_time = grown;
      o->frame_time_cap = cap;
    }
    o->frame_time[o->frames] = d->time;
  }
  const int first = o->frames == 0;
  o->frames++;
  /* The frames go to their datasets when their chunk is full, and with the
   * metadata on disk (a flush) after the first frame and then at most every
   * flush_wait s of wall time: a run killed outright leaves a valid file of
   * all but its last moment's frames (every failure the run handles, an
   * interrupt included, closes the file, which writes and flushes them
   * all).  At a flush per frame, a scene of many rods written every
   * millisecond spent a third of its run in the flushes (the arm of 43
   * rods: 0.4 s of 1.45). */
  const double now = wall_now();
  if (first || now - o->flushed_at >= o->flush_wait) {
    int rc = flush_frames(o);
    if (rc != SW_OK) return rc;
  } else if (o->frames - start == o->chunk_frames) {
    int rc = write_pending(o);
    if (rc != SW_OK) return rc;
  }
  /* the description follows the flushed file: at the first frame, then
   * every xdmf_wait seconds, and at close */
  if (o->xdmf_path && (o->xdmf_frames == 0 || now - o->xdmf_written >= o->xdmf_wait)) {
    if (o->flushed_frames < o->frames) { /* it lists only flushed frames */
      int rc = flush_frames(o);
      if (rc != SW_OK) return rc;
    }
    return xdmf_update(o);
  }
  return SW_OK;
}

long sw_output_frames(const swOutput *o) { return o ? o->frames : 0; }

/* Seconds of wall time between two writes of the checkpoint: a run killed
 * outright loses at most this much. */
#define CHECKPOINT_EVERY 10.0
/* and between two snapshots of the state in memory, which the close writes
 * (a failed or interrupted run continues from the last one): a copy of the
 * whole state at every frame had been 2.5% of the arm's demo (501 frames of
 * 230 KiB). */
#define CHECKPOINT_TAKE_EVERY 0.25

int sw_output_checkpoint(swOutput *o, const swModel *m, const swData *d, const swExpectRun *x,
                         int last) {
  if (!o || !o->checkpoint || m != o->model) return SW_OK;
  double now = wall_now();
  const int write = now - o->checkpoint_written >= CHECKPOINT_EVERY;
  if (!last && !write && now - o->checkpoint_taken < CHECKPOINT_TAKE_EVERY) return SW_OK;
  sw_checkpoint_take(o->checkpoint, m, d, x, o->frames);
  o->checkpoint_taken = now;
  if (!write) return SW_OK;
  o->checkpoint_written = now;
  int rc = write_pending(o); /* the checkpoint's frames in the file before it */
  if (rc != SW_OK) return rc;
  if (sw_checkpoint_write(o->checkpoint, m, o->file) != SW_OK)
    return sw_out_fail(NULL, 0, "%s: cannot write the checkpoint /restart", o->path);
  return SW_OK;
}

/* ---- close ---- */

int sw_output_close(swOutput *o, const char *status) {
  if (!o) return SW_OK;
  int rc = SW_OK;
  rc = write_pending(o); /* every frame taken, into the file */
  if (rc == SW_OK && o->checkpoint && sw_checkpoint_write(o->checkpoint, o->model, o->file) != SW_OK)
    rc = sw_out_fail(NULL, 0, "%s: cannot write the checkpoint /restart", o->path);
  if (rc == SW_OK) rc = replace_root_string(o, "status", status ? status : "complete");
  for (int i = 0; i < o->ndset; i++) {
    if (o->dset[i].dset >= 0 && H5Dclose(o->dset[i].dset) < 0 && rc == SW_OK)
      rc = sw_out_fail(NULL, 0, "%s: cannot close dataset %s", o->path, o->dset[i].path);
    o->dset[i].dset = H5I_INVALID_HID;
  }
  if (H5Fclose(o->file) < 0 && rc == SW_OK)
    rc = sw_out_fail(NULL, 0, "%s: cannot close the file", o->path);
  o->file = H5I_INVALID_HID;
  /* every frame is in the file: the description lists them all */
  int described = xdmf_update(o);
  if (rc == SW_OK) rc = described;
  release(o);
  return rc;
}
