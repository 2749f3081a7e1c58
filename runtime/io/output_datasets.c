/* output_datasets.c — the datasets of a run's HDF5 file: the table of what
 * is written for the root, rods, joints, muscles and probes, the functions
 * that fill one frame of each from the state, the datasets' creation (or
 * reopening, for --restart) and their extension by one frame.
 *
 * Design.  What is written is described by one table, output_fields[]: a
 * dataset path, whether it exists once, once per rod, per joint (or hinge),
 * per muscle or per probe, its shape per frame (with symbolic extents for
 * "nodes of this rod" and "elements of this rod"), its units, optional
 * column names, the option that enables it and the function that fills one
 * frame from the state.  sw_out_create_datasets() walks the table once, at
 * open, and creates every dataset the options select (doubles, first
 * dimension unlimited, all chunked by the same number of frames, up to 64)
 * with its `units` attribute (and a probe's, output_attrs.c); a continued
 * run reopens them instead and cuts them back to the checkpoint's frames.
 * At each frame output.c fills the frame's row of each dataset's chunk
 * buffer (one chunk, aligned with the file's chunks) and
 * sw_out_write_frames() extends the dataset and writes the chunk as it is
 * stored (H5Dwrite_chunk: no selection, no chunk cache; the arm's 179
 * datasets had spent a fifth of their output time in HDF5's cache and
 * selections), or, where the file's chunks are not this run's (a file of
 * an older sinew continued) or doubles are not little-endian here, the new
 * frames by a selection.
 * Adding an output is one line of the table plus, if the quantity is new, a
 * four-line fill function.  The shared types are in output.h. */
#include <hdf5.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sinew.h"
#include "engine/internal.h"
#include "output.h"

/* ---- the output table ---- */

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

void sw_out_fill_position(const swModel *m, swData *d, int rod, double *frame) {
  gather_rows(m, d->x, m->node_adr[rod], m->rod_nelem[rod] + 1, 3, frame);
}

void sw_out_fill_velocity(const swModel *m, swData *d, int rod, double *frame) {
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
  {"position",            SCOPE_ROD,   2, {EXTENT_NODES, 3},        "m",     NULL,             SW_OUT_POSITION,         sw_out_fill_position},
  {"velocity",            SCOPE_ROD,   2, {EXTENT_NODES, 3},        "m/s",   NULL,             SW_OUT_VELOCITY,         sw_out_fill_velocity},
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

/* ---- creating the datasets ---- */

#define CHUNK_FRAMES 64                  /* frames per chunk, at most        */
#define CHUNK_BYTES (1u << 20)           /* and about this many bytes        */

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
    return sw_out_fail(err, errlen, "%s: no dataset %s: the file was written by another model or "
                       "another output selection", o->path, ds->path);
  hsize_t have[1 + MAX_FRAME_RANK];
  hid_t space = H5Dget_space(ds->dset);
  int rank = space >= 0 ? H5Sget_simple_extent_dims(space, have, NULL) : -1;
  if (space >= 0) H5Sclose(space);
  int same = rank == ds->rank;
  for (int k = 1; same && k < rank; k++) same = have[k] == ds->dims[k];
  if (!same || have[0] < (hsize_t)frames)
    return sw_out_fail(err, errlen, "%s: dataset %s does not have the shape this model writes",
                       o->path, ds->path);
  ds->dims[0] = (hsize_t)frames;
  if (H5Dset_extent(ds->dset, ds->dims) < 0)
    return sw_out_fail(err, errlen, "%s: cannot cut dataset %s back to %ld frames", o->path,
                       ds->path, frames);
  return SW_OK;
}

/* Dataset ds of field f for `item` (rod, joint, muscle or probe; -1 for the
 * root's): its path, rank, per-frame extents and frame length. */
static int describe_dataset(swDataset *ds, const swField *f, const swModel *m, int item) {
  const int rod = f->scope == SCOPE_ROD ? item : -1;
  ds->field = f;
  ds->item = item;
  ds->dset = H5I_INVALID_HID;
  ds->rank = 1 + f->rank;
  ds->path =
      f->scope == SCOPE_ROD      ? sw_out_dup_printf("/rods/%s/%s", m->rod_name[item], f->path)
      : f->scope == SCOPE_JOINT  ? sw_out_dup_printf("/joints/%s/%s", m->joint_name[item], f->path)
      : f->scope == SCOPE_MUSCLE ? sw_out_dup_printf("/muscles/%s/%s", m->muscle_name[item],
                                                     f->path)
      : f->scope == SCOPE_PROBE  ? sw_out_dup_printf("/probes/%s%s%s", m->probe[item].name,
                                                     f->path[0] ? "/" : "", f->path)
                                 : sw_out_dup_printf("/%s", f->path);
  ds->dims[0] = 0;
  ds->frame_len = 1;
  for (int k = 0; k < f->rank; k++) {
    int e = f->extent[k];
    if (e == EXTENT_NODES) e = m->rod_nelem[rod] + 1;
    else if (e == EXTENT_ELEMS) e = m->rod_nelem[rod];
    else if (e == EXTENT_VORONOI) e = m->rod_nelem[rod] - 1;
    else if (e == EXTENT_FILAMENTS) e = m->muscle_fil_adr[item + 1] - m->muscle_fil_adr[item];
    ds->dims[1 + k] = (hsize_t)e;
    ds->frame_len *= (size_t)e;
  }
  return ds->path ? SW_OK : SW_EIO;
}

/* The frames of one chunk, the same for every dataset of the file so that
 * one chunk buffer per dataset holds the frames since the last chunk
 * boundary: CHUNK_FRAMES, fewer when the largest frame would make a chunk
 * of more than CHUNK_BYTES or all the buffers more than BUFFER_BYTES. */
#define BUFFER_BYTES (4u << 20)
static int chunk_frames(const swOutput *o) {
  size_t largest = 1, all = 0;
  for (int i = 0; i < o->ndset; i++) {
    size_t bytes = o->dset[i].frame_len * sizeof(double);
    if (bytes > largest) largest = bytes;
    all += bytes;
  }
  size_t frames = CHUNK_FRAMES;
  if (CHUNK_BYTES / largest < frames) frames = CHUNK_BYTES / largest;
  if (all && BUFFER_BYTES / all < frames) frames = BUFFER_BYTES / all;
  return frames < 1 ? 1 : (int)frames;
}

/* The frames of a reopened dataset's chunks (0 if it is not chunked). */
static hsize_t stored_chunk_frames(hid_t dset) {
  hsize_t chunk[1 + MAX_FRAME_RANK] = {0};
  hid_t dcpl = H5Dget_create_plist(dset);
  if (dcpl < 0) return 0;
  int rank = H5Pget_layout(dcpl) == H5D_CHUNKED ? H5Pget_chunk(dcpl, 1 + MAX_FRAME_RANK, chunk) : 0;
  H5Pclose(dcpl);
  return rank > 0 ? chunk[0] : 0;
}

/* Create (or reopen, reopen_frames >= 0) dataset ds, described, with its
 * attributes. */
static int create_dataset(swOutput *o, swDataset *ds, const swModel *m, hid_t lcpl,
                          long reopen_frames, char *err, size_t errlen) {
  hsize_t maxdims[1 + MAX_FRAME_RANK], chunk[1 + MAX_FRAME_RANK];
  const swField *f = ds->field;
  const int item = ds->item;
  maxdims[0] = H5S_UNLIMITED;
  chunk[0] = (hsize_t)o->chunk_frames;
  for (int k = 1; k < ds->rank; k++) maxdims[k] = chunk[k] = ds->dims[k];

  if (reopen_frames >= 0) {
    int rc = reopen_dataset(o, ds, reopen_frames, err, errlen);
    if (rc == SW_OK && stored_chunk_frames(ds->dset) != chunk[0]) o->direct = 0;
    return rc;
  }
  hid_t space = H5Screate_simple(ds->rank, ds->dims, maxdims);
  hid_t dcpl = H5Pcreate(H5P_DATASET_CREATE);
  /* No fill: every frame inside the extent is written before the extent
   * is read (sw_out_write_frames extends by the frames it writes), so
   * filling a new chunk first would only be a memset of it (a tenth of a
   * short run's output time). */
  if (space < 0 || dcpl < 0 || H5Pset_chunk(dcpl, ds->rank, chunk) < 0 ||
      H5Pset_fill_time(dcpl, H5D_FILL_TIME_NEVER) < 0) {
    if (space >= 0) H5Sclose(space);
    if (dcpl >= 0) H5Pclose(dcpl);
    return sw_out_fail(err, errlen, "%s: cannot describe dataset %s", o->path, ds->path);
  }
  ds->dset = H5Dcreate2(o->file, ds->path, H5T_IEEE_F64LE, space, lcpl, dcpl, H5P_DEFAULT);
  H5Sclose(space);
  H5Pclose(dcpl);
  if (ds->dset < 0)
    return sw_out_fail(err, errlen, "%s: cannot create dataset %s", o->path, ds->path);

  swAttrTarget t = {ds->dset, o->path, ds->path, err, errlen};
  int rc = sw_out_attr_string(&t, "units",
                              f->units ? f->units : sw_probe_units(m->probe[item].kind));
  if (rc == SW_OK && f->scope == SCOPE_PROBE) rc = sw_out_write_probe_attrs(&t, &m->probe[item]);
  if (rc == SW_OK && f->columns) {
    hsize_t ncol = 0;
    while (f->columns[ncol]) ncol++;
    rc = sw_out_attr_strings(&t, "columns", f->columns, ncol);
  }
  return rc;
}

/* How many datasets the table can make for model m, at the most: the size
 * of the swOutput's array. */
size_t sw_out_count_datasets(const swModel *m) {
  size_t max_dsets = 0;
  for (size_t f = 0; f < NFIELDS; f++) max_dsets += (size_t)field_items(&output_fields[f], m);
  return max_dsets;
}

/* Every dataset of the table the options select, in the table's order (so
 * /time is the first): created with its attributes, or (reopen_frames >= 0)
 * reopened and cut back to that many frames. */
int sw_out_create_datasets(swOutput *o, const swModel *m, const swOutputOptions *opt,
                           long reopen_frames, char *err, size_t errlen) {
  int rc = SW_OK;
  for (size_t f = 0; f < NFIELDS && rc == SW_OK; f++) {
    const swField *field = &output_fields[f];
    int nrep = field_items(field, m);
    for (int k = 0; k < nrep && rc == SW_OK; k++) {
      if (field->scope != SCOPE_ROOT && !item_enabled(field, m, opt, k)) continue;
      if (describe_dataset(&o->dset[o->ndset++], field, m, field->scope == SCOPE_ROOT ? -1 : k))
        rc = sw_out_fail(err, errlen, "%s: out of memory", o->path);
    }
  }
  o->chunk_frames = chunk_frames(o);
  /* chunks written as stored need the file's doubles to be this machine's */
  o->direct = H5Tequal(H5T_NATIVE_DOUBLE, H5T_IEEE_F64LE) > 0;
  /* Groups /rods/NAME, /joints/NAME and /diagnostics come into being with
   * their datasets. */
  hid_t lcpl = H5Pcreate(H5P_LINK_CREATE);
  if (rc == SW_OK && (lcpl < 0 || H5Pset_create_intermediate_group(lcpl, 1) < 0))
    rc = sw_out_fail(err, errlen, "%s: cannot make a link creation property list", o->path);
  for (int i = 0; i < o->ndset && rc == SW_OK; i++)
    rc = create_dataset(o, &o->dset[i], m, lcpl, reopen_frames, err, errlen);
  if (lcpl >= 0) H5Pclose(lcpl);
  return rc;
}

/* ---- one frame more ---- */

/* Frames [first, first + count) of dataset ds written from (write) or read
 * into buf, count rows of its frame_len doubles, by a selection.  Returns
 * whether HDF5 did it. */
static int frames_io(swDataset *ds, long first, long count, double *buf, int write) {
  hsize_t at[1 + MAX_FRAME_RANK] = {(hsize_t)first}, n[1 + MAX_FRAME_RANK];
  n[0] = (hsize_t)count;
  for (int k = 1; k < ds->rank; k++) n[k] = ds->dims[k];
  hid_t file_space = H5Dget_space(ds->dset);
  hid_t mem_space = H5Screate_simple(ds->rank, n, NULL);
  int ok = file_space >= 0 && mem_space >= 0 &&
           H5Sselect_hyperslab(file_space, H5S_SELECT_SET, at, NULL, n, NULL) >= 0;
  if (ok)
    ok = (write ? H5Dwrite(ds->dset, H5T_NATIVE_DOUBLE, mem_space, file_space, H5P_DEFAULT, buf)
                : H5Dread(ds->dset, H5T_NATIVE_DOUBLE, mem_space, file_space, H5P_DEFAULT, buf)) >= 0;
  if (mem_space >= 0) H5Sclose(mem_space);
  if (file_space >= 0) H5Sclose(file_space);
  return ok;
}

/* Frames [o->written, upto) of dataset ds, all in its chunk buffer, which
 * holds the chunk from frame start = o->written rounded down to a chunk:
 * the dataset extended to upto frames, then the whole chunk written as
 * stored (its rows past upto, zeros or frames of this chunk not yet
 * written, lie outside the extent and are written again with the chunk),
 * or the new frames by a selection. */
int sw_out_write_frames(swOutput *o, swDataset *ds, long upto) {
  const long start = o->written - o->written % o->chunk_frames;
  ds->dims[0] = (hsize_t)upto;
  if (H5Dset_extent(ds->dset, ds->dims) < 0) {
    ds->dims[0] = (hsize_t)o->written;
    return sw_out_fail(NULL, 0, "%s: cannot extend dataset %s to %ld frames", o->path, ds->path,
                       upto);
  }
  int ok;
  if (o->direct) {
    hsize_t offset[1 + MAX_FRAME_RANK] = {(hsize_t)start};
    size_t bytes = (size_t)o->chunk_frames * ds->frame_len * sizeof(double);
    ok = H5Dwrite_chunk(ds->dset, H5P_DEFAULT, 0, offset, bytes, ds->pending) >= 0;
  } else {
    ok = frames_io(ds, o->written, upto - o->written,
                   ds->pending + (size_t)(o->written - start) * ds->frame_len, 1);
  }
  if (!ok) { /* frames not written are not filled either: take them back */
    ds->dims[0] = (hsize_t)o->written;
    H5Dset_extent(ds->dset, ds->dims);
    return sw_out_fail(NULL, 0, "%s: cannot write frames %ld to %ld of dataset %s", o->path,
                       o->written, upto - 1, ds->path);
  }
  return SW_OK;
}

/* A continued run's chunk buffers: the frames of the last chunk the file
 * holds, from its start to o->written, read back, so that the chunk is
 * written whole again when it fills. */
int sw_out_read_partial_chunk(swOutput *o) {
  const long start = o->written - o->written % o->chunk_frames;
  if (!o->direct || start == o->written) return SW_OK;
  for (int i = 0; i < o->ndset; i++) {
    swDataset *ds = &o->dset[i];
    if (!frames_io(ds, start, o->written - start, ds->pending, 0))
      return sw_out_fail(NULL, 0, "%s: cannot read frames %ld to %ld of dataset %s back", o->path,
                         start, o->written - 1, ds->path);
  }
  return SW_OK;
}
