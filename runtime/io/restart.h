/* restart.h — the checkpoint's file side, shared by output.c (which owns the
 * file) and restart.c; with output.h, the io/ headers that include hdf5.h.  The
 * in-memory side is declared first: a snapshot of every array of the state
 * at a scheduled frame, kept in memory by the run loop and written into the
 * output file. */
#ifndef SINEW_RESTART_H
#define SINEW_RESTART_H
#include <hdf5.h>
#include "sinew.h"

typedef struct swCheckpoint swCheckpoint;
swCheckpoint *sw_checkpoint_new(const swModel *m);
void sw_checkpoint_free(swCheckpoint *c);
/* Copies d (and the expectations' state x, may be NULL) as the state of the
 * file's frame `frames` - 1. */
void sw_checkpoint_take(swCheckpoint *c, const swModel *m, const swData *d,
                        const swExpectRun *x, long frames);

/* Writes the snapshot to /restart of the file if it changed since it was
 * last written; SW_OK or SW_EIO. */
int sw_checkpoint_write(swCheckpoint *c, const swModel *m, hid_t file);
/* Reads /restart of `file` (named `path` in messages) into d and x (x may be
 * NULL); *frames is how many frames the file held at the snapshot.  SW_OK,
 * SW_EIO (no checkpoint, unreadable) or SW_EMODEL (another model's). */
int sw_checkpoint_read(const char *path, hid_t file, const swModel *m, swData *d,
                       swExpectRun *x, long *frames, char *err, size_t errlen);
#endif
