/* restart.c — the checkpoint a run keeps in its output file, and the
 * continuation of a run from it (SIM --restart RUN.h5).
 *
 * Design.  A continued run must give the datasets an uninterrupted run gives,
 * bit for bit.  Two things make that hold.  First, the checkpoint holds every
 * array of swData a step can read before writing it, not only positions and
 * velocities: the state proper (x, v, Q, omega, the dilatation, rigid bodies,
 * muscle activation), what a step carries over (a pending kick's work per
 * slot and per chunk, the unwrapped hinge angles, the probes' rings of
 * samples, the implicit joints' system, the friction anchors of obstacles
 * and of rod-rod contact)
 * and the scratch arrays as well, since copying them costs little and
 * leaves nothing to argue about; the scalars
 * (time, step, work, the pending kick, whether the last step's half drift
 * is held) go as attributes, and so do the expectations' running minima and
 * maxima (expect.c).  Second, a checkpoint is taken of the held state at a
 * frame of the run's schedule (a multiple of `every` steps, or the end;
 * integrate.c, "Held steps"): continuing from there, the next step fuses
 * the held half drift as the uninterrupted run does.
 *
 * The run loop copies the state into an in-memory snapshot at each scheduled
 * frame (a memcpy of the arrays: cheap beside writing the frame) and the
 * snapshot is written to /restart in the file at most every few seconds of
 * wall time and when the file is closed, whatever the status: after Ctrl-C
 * or an unstable step the snapshot is the last scheduled frame's, never the
 * state the run stopped in.  /restart records how many frames the file held
 * at the snapshot; a continued run cuts every dataset back to that many
 * before it appends, so an off-schedule last frame (Ctrl-C writes one) does
 * not stay in the file. */
#include <hdf5.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sinew.h"
#include "engine/internal.h"
#include "restart.h"

/* ---- what is saved ---- */

enum { PER_SLOT, PER_CHUNK, PER_BC, PER_JOINT, PER_FIL, PER_BODY, PER_PROBE_RING, RIGID_SYS, PER_RING,
       IMPLICIT_SYS, OBSTACLE_ANCHORS, CONTACT_ANCHORS };

typedef struct {
  const char *name;
  size_t offset;        /* of the double * in swData */
  int per;              /* what it is counted in      */
  int count;            /* that many per item (planes per slot) */
} swSaved;

#define SAVED(field, per, count) {#field, offsetof(swData, field), per, count}
static const swSaved saved[] = {
    SAVED(x, PER_SLOT, 3),            SAVED(v, PER_SLOT, 3),
    SAVED(Q, PER_SLOT, 9),            SAVED(omega, PER_SLOT, 3),
    SAVED(dilatation, PER_SLOT, 1),   SAVED(length, PER_SLOT, 1),
    SAVED(sigma, PER_SLOT, 3),        SAVED(stress, PER_SLOT, 3),
    SAVED(vor_dilatation, PER_SLOT, 1), SAVED(kappa, PER_SLOT, 3),
    SAVED(couple, PER_SLOT, 3),       SAVED(force, PER_SLOT, 3),
    SAVED(torque, PER_SLOT, 3),       SAVED(ext_force, PER_SLOT, 3),
    SAVED(ext_torque, PER_SLOT, 3),   SAVED(scratch_f, PER_SLOT, 3),
    SAVED(scratch_h, PER_SLOT, 3),    SAVED(scratch_flag, PER_SLOT, 1),
    SAVED(scratch_phi, PER_SLOT, 3),  SAVED(chunk_sum, PER_CHUNK, 1),
    SAVED(bc_work, PER_BC, 1),        SAVED(bc_free, PER_BC, 1),
    SAVED(joint_scratch, PER_JOINT, SW_JOINT_ROW),
    SAVED(joint_force, PER_JOINT, 3), SAVED(joint_angle, PER_JOINT, 1),
    SAVED(rigid_X, PER_BODY, 3),      SAVED(rigid_V, PER_BODY, 3),
    SAVED(rigid_R, PER_BODY, 9),      SAVED(rigid_L, PER_BODY, 3),
    SAVED(rigid_load, PER_BODY, 6),   SAVED(rigid_omega, PER_BODY, 3),
    SAVED(rigid_sys, RIGID_SYS, 1),   SAVED(fil_activation, PER_FIL, 1),
    SAVED(fil_stretch, PER_FIL, 1),   SAVED(fil_rate, PER_FIL, 1),
    SAVED(fil_tension, PER_FIL, 1),   SAVED(probe_ring, PER_PROBE_RING, 4),
    SAVED(ring_row, PER_RING, SW_RING_ROW),
    SAVED(implicit_sys, IMPLICIT_SYS, 1), /* the implicit rods' kept factorisations */
    SAVED(obstacle_anchor, OBSTACLE_ANCHORS, 1), /* the friction's anchors (obstacle.c) */
    SAVED(contact_anchor, CONTACT_ANCHORS, 1),   /* and rod-rod contact's (contact.c) */
};
#define NSAVED (sizeof saved / sizeof saved[0])

static size_t saved_len(const swModel *m, const swSaved *s) {
  size_t n = 0;
  switch (s->per) {
  case PER_SLOT: n = (size_t)m->stride; break;
  case PER_CHUNK: n = (size_t)sw_nchunk(m, m->stride); break;
  case PER_BC: n = (size_t)m->nbc; break;
  case PER_JOINT: n = (size_t)m->njoint; break;
  case PER_FIL: n = (size_t)m->nfil; break;
  case PER_BODY: n = (size_t)m->nrigid; break;
  case PER_PROBE_RING: n = (size_t)m->nprobe * SW_PROBE_RING; break;
  case RIGID_SYS: n = sw_rigid_joints_scratch(m); break;
  case PER_RING: n = (size_t)m->nring; break;
  case IMPLICIT_SYS: n = sw_implicit_scratch(m); break;
  case OBSTACLE_ANCHORS:
    n = m->nobstacle ? 1 + (size_t)m->obstacle_maxcontact * SW_OBSTACLE_ANCHOR_ROW : 0;
    break;
  case CONTACT_ANCHORS:
    n = m->contact_maxanchor ? 1 + (size_t)m->contact_maxanchor * SW_CONTACT_ANCHOR_ROW : 0;
    break;
  }
  return n * (size_t)s->count;
}

static double *saved_array(const swData *d, const swSaved *s) {
  return *(double *const *)((const char *)d + s->offset);
}

/* The scalars, and per probe its ring's head and count, per expectation its
 * count, last step, minimum, maximum, last value and trapezoidal sum, as doubles (exact: steps and counts
 * are far below 2^53). */
static size_t scalars_len(const swModel *m) {
  return 7 + 2 * (size_t)m->nprobe + SW_EXPECT_SAVED * (size_t)m->nexpect;
}

struct swCheckpoint {
  long frames;          /* frames in the file at the snapshot; -1: none yet */
  double *data;         /* the saved arrays, one after another              */
  double *scalars;
  size_t len;
  int dirty;            /* taken since it was last written                  */
};

swCheckpoint *sw_checkpoint_new(const swModel *m) {
  swCheckpoint *c = calloc(1, sizeof *c);
  if (!c) return NULL;
  for (size_t i = 0; i < NSAVED; i++) c->len += saved_len(m, &saved[i]);
  c->data = malloc((c->len ? c->len : 1) * sizeof *c->data);
  c->scalars = malloc(scalars_len(m) * sizeof *c->scalars);
  c->frames = -1;
  if (!c->data || !c->scalars) {
    sw_checkpoint_free(c);
    return NULL;
  }
  return c;
}

void sw_checkpoint_free(swCheckpoint *c) {
  if (!c) return;
  free(c->data);
  free(c->scalars);
  free(c);
}

void sw_checkpoint_take(swCheckpoint *c, const swModel *m, const swData *d,
                        const swExpectRun *x, long frames) {
  double *p = c->data;
  for (size_t i = 0; i < NSAVED; i++) {
    size_t n = saved_len(m, &saved[i]);
    if (n) memcpy(p, saved_array(d, &saved[i]), n * sizeof *p);
    p += n;
  }
  double *s = c->scalars;
  *s++ = d->time;
  *s++ = (double)d->step;
  *s++ = d->work;
  *s++ = d->kick_pending;
  *s++ = d->kick_h;
  *s++ = (double)frames;
  *s++ = d->held;
  for (int k = 0; k < m->nprobe; k++) {
    *s++ = d->probe_head[k];
    *s++ = d->probe_count[k];
  }
  sw_expect_run_save(m, x, s);
  c->frames = frames;
  c->dirty = 1;
}

/* Puts the snapshot back into d and x. */
static void checkpoint_put(const swCheckpoint *c, const swModel *m, swData *d, swExpectRun *x) {
  const double *p = c->data;
  for (size_t i = 0; i < NSAVED; i++) {
    size_t n = saved_len(m, &saved[i]);
    if (n) memcpy(saved_array(d, &saved[i]), p, n * sizeof *p);
    p += n;
  }
  const double *s = c->scalars;
  d->time = s[0];
  d->step = (long)s[1];
  d->work = s[2];
  d->kick_pending = (int)s[3];
  d->kick_h = s[4];
  d->held = (int)s[6];
  d->whole = 0;
  s += 7;
  for (int k = 0; k < m->nprobe; k++) {
    d->probe_head[k] = (int)*s++;
    d->probe_count[k] = (int)*s++;
  }
  if (x) sw_expect_run_load(m, x, s);
}

/* ---- on disk: /restart/state, /restart/scalars ---- */

static int write_vector(hid_t g, const char *name, const double *v, size_t n) {
  hsize_t dims = n;
  htri_t exists = H5Lexists(g, name, H5P_DEFAULT);
  hid_t dset;
  if (exists > 0) {
    dset = H5Dopen2(g, name, H5P_DEFAULT);
  } else {
    hid_t space = H5Screate_simple(1, &dims, NULL);
    if (space < 0) return -1;
    dset = H5Dcreate2(g, name, H5T_IEEE_F64LE, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    H5Sclose(space);
  }
  if (dset < 0) return -1;
  herr_t rc = n ? H5Dwrite(dset, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v) : 0;
  H5Dclose(dset);
  return rc < 0 ? -1 : 0;
}

int sw_checkpoint_write(swCheckpoint *c, const swModel *m, hid_t file) {
  if (c->frames < 0 || !c->dirty) return SW_OK;
  htri_t exists = H5Lexists(file, "/restart", H5P_DEFAULT);
  hid_t g = exists > 0 ? H5Gopen2(file, "/restart", H5P_DEFAULT)
                       : H5Gcreate2(file, "/restart", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  if (g < 0) return SW_EIO;
  int rc = write_vector(g, "state", c->data, c->len) == 0 &&
                   write_vector(g, "scalars", c->scalars, scalars_len(m)) == 0
               ? SW_OK
               : SW_EIO;
  H5Gclose(g);
  if (rc == SW_OK) c->dirty = 0;
  return rc;
}

static int read_vector(hid_t g, const char *name, double *v, size_t n, char *err,
                       size_t errlen, const char *path) {
  hid_t dset = H5Dopen2(g, name, H5P_DEFAULT);
  if (dset < 0) {
    snprintf(err, errlen, "%s: no /restart/%s: the file has no checkpoint", path, name);
    return SW_EIO;
  }
  hid_t space = H5Dget_space(dset);
  hssize_t have = space >= 0 ? H5Sget_simple_extent_npoints(space) : -1;
  if (space >= 0) H5Sclose(space);
  int rc = SW_OK;
  if (have != (hssize_t)n) {
    snprintf(err, errlen, "%s: /restart/%s holds %lld numbers, this model's state %zu: the "
             "file is of another model", path, name, (long long)have, n);
    rc = SW_EMODEL;
  } else if (n && H5Dread(dset, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v) < 0) {
    snprintf(err, errlen, "%s: cannot read /restart/%s", path, name);
    rc = SW_EIO;
  }
  H5Dclose(dset);
  return rc;
}

int sw_checkpoint_read(const char *path, hid_t file, const swModel *m, swData *d,
                       swExpectRun *x, long *frames, char *err, size_t errlen) {
  swCheckpoint *c = sw_checkpoint_new(m);
  if (!c) {
    snprintf(err, errlen, "out of memory");
    return SW_EMODEL;
  }
  hid_t g = H5Lexists(file, "/restart", H5P_DEFAULT) > 0
                ? H5Gopen2(file, "/restart", H5P_DEFAULT)
                : H5I_INVALID_HID;
  int rc;
  if (g < 0) {
    snprintf(err, errlen, "%s has no checkpoint (/restart): it was not written by a run that "
             "reached a frame", path);
    rc = SW_EIO;
  } else {
    rc = read_vector(g, "state", c->data, c->len, err, errlen, path);
    if (rc == SW_OK) rc = read_vector(g, "scalars", c->scalars, scalars_len(m), err, errlen, path);
    H5Gclose(g);
  }
  if (rc == SW_OK) {
    checkpoint_put(c, m, d, x);
    *frames = (long)c->scalars[5];
  }
  sw_checkpoint_free(c);
  return rc;
}
