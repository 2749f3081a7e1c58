/* output.h — what the three files of a run's HDF5 output share: output.c
 * (the file's life), output_datasets.c (the table of what is written, its
 * datasets and their rows) and output_attrs.c (the attributes that describe
 * the file, its groups and its datasets).  Internal to io/; the public side
 * is sinew_io.h.
 *
 * Design.  One open file is one swOutput, defined here so that each of the
 * three can reach the file, its datasets and its path for messages;
 * output.c alone creates and frees it.  A row of the table (swField) is
 * declared here because a dataset (swDataset) points at its row and
 * output.c fills frames through it.  Every failure, in whichever file, is
 * reported through sw_out_fail, which keeps the message for
 * sw_output_error(). */
#ifndef SINEW_OUTPUT_H
#define SINEW_OUTPUT_H
#include <hdf5.h>
#include <stddef.h>

#include "sinew.h"
#include "restart.h"
#include "xdmf.h"

/* ---- a row of the output table (output_datasets.c) ---- */

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

/* ---- the open file ---- */

typedef struct {
  const swField *field;
  int item;                              /* rod or joint; -1 for root fields */
  hid_t dset;
  int rank;                              /* 1 + field rank                   */
  hsize_t dims[1 + MAX_FRAME_RANK];      /* dims[0] = frames written         */
  size_t frame_len;                      /* doubles per frame                */
  double *pending;                       /* its chunk buffer: chunk_frames of
                                            frame_len each (in o->pending), the
                                            frames from the chunk's start    */
  char *path;                            /* "/rods/arm/position"             */
} swDataset;

struct swOutput {
  hid_t file;
  char *path;                            /* file name, for messages          */
  int nrod;
  long frames;                           /* frames taken                     */
  long written;                          /* of them, in the datasets         */
  int chunk_frames;                      /* frames of every dataset's chunks */
  int direct;                            /* chunks written as stored         */
  int ndset;
  swDataset *dset;
  double *pending;                       /* every dataset's chunk buffer     */
  size_t pending_len;                    /* its doubles                      */
  swCheckpoint *checkpoint;              /* the last scheduled frame's state */
  const swModel *model;                  /* the model it was taken of        */
  double checkpoint_written;             /* wall clock of its last write, s  */
  double checkpoint_taken;               /* and of its last snapshot, s      */
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
  double flushed_at;                     /* wall clock of the last flush, s  */
  double flush_wait;                     /* s until the next may be made     */
  long flushed_frames;                   /* frames on disk at that flush     */
};

/* Where an attribute goes (output_attrs.c's helpers write to it). */
typedef struct {
  hid_t obj;
  const char *file;                      /* for messages                     */
  const char *obj_path;
  char *err;
  size_t errlen;
} swAttrTarget;

/* ---- errors and strings (output.c) ---- */

/* Formats the message, appends HDF5's innermost reason, keeps it for
 * sw_output_error() and copies it into err (may be NULL); returns SW_EIO. */
int sw_out_fail(char *err, size_t errlen, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));
/* A malloc'd printf; NULL when out of memory. */
char *sw_out_dup_printf(const char *fmt, ...) __attribute__((format(printf, 1, 2)));

/* ---- attributes (output_attrs.c) ---- */

/* A variable-length UTF-8 string type (close it with H5Tclose); < 0 on error. */
hid_t sw_out_utf8_string_type(void);
/* A 1-D array of `count` strings, or a scalar string when count == 0. */
int sw_out_attr_strings(const swAttrTarget *t, const char *name, const char *const *values,
                        hsize_t count);
/* A scalar string (NULL writes ""). */
int sw_out_attr_string(const swAttrTarget *t, const char *name, const char *value);
/* A scalar of file_type, read from *value as mem_type. */
int sw_out_attr_scalar(const swAttrTarget *t, const char *name, hid_t file_type,
                       hid_t mem_type, const void *value);
/* What probe p measures, on its dataset /probes/NAME. */
int sw_out_write_probe_attrs(const swAttrTarget *t, const swProbeDesc *p);
/* The root's record of how the file was made, and status "incomplete". */
int sw_out_write_root_attrs(swOutput *o, const swModel *m, const swOutputOptions *opt,
                            char *err, size_t errlen);
/* The description of every rod, joint and muscle group the datasets made. */
int sw_out_write_group_attrs(swOutput *o, const swModel *m, char *err, size_t errlen);
/* The table /params (nothing when the model has no params). */
int sw_out_write_params(swOutput *o, const swOutputOptions *opt, char *err, size_t errlen);

/* ---- datasets (output_datasets.c) ---- */

/* The fill functions of /rods/NAME/position and velocity, which the XDMF
 * description looks for among the datasets opened. */
void sw_out_fill_position(const swModel *m, swData *d, int rod, double *frame);
void sw_out_fill_velocity(const swModel *m, swData *d, int rod, double *frame);
/* How many datasets the table can make for model m, at the most. */
size_t sw_out_count_datasets(const swModel *m);
/* Creates (reopen_frames < 0) or reopens every dataset the options select
 * into o->dset, all chunked by o->chunk_frames frames (set here, with
 * o->direct). */
int sw_out_create_datasets(swOutput *o, const swModel *m, const swOutputOptions *opt,
                           long reopen_frames, char *err, size_t errlen);
/* Extends dataset ds to `upto` frames and writes those after o->written
 * from its chunk buffer. */
int sw_out_write_frames(swOutput *o, swDataset *ds, long upto);
/* A continued run: the frames of the file's last, partly filled chunk back
 * into the chunk buffers. */
int sw_out_read_partial_chunk(swOutput *o);
#endif
