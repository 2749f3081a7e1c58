/* xdmf.h — the XDMF description written beside a run's HDF5 file (xdmf.c),
 * shared with output.c, which owns the file and knows what it holds. */
#ifndef SINEW_XDMF_H
#define SINEW_XDMF_H

/* A rod as the XDMF describes it: /rods/NAME/position [F, nodes, 3] and the
 * static /rods/NAME/node_radius [nodes], plus velocity [F, nodes, 3] when
 * the file has it. */
typedef struct {
  const char *name;
  int nodes;                 /* n + 1 */
  int velocity;              /* /rods/NAME/velocity is written */
} swXdmfRod;

/* The XDMF path beside the HDF5 file `h5_path` (RUN.h5 -> RUN.xdmf; a name
 * without the .h5 ending gets .xdmf appended); malloc'd, NULL when out of
 * memory. */
char *sw_xdmf_path(const char *h5_path);
/* Whether XML can carry a name (no control characters, which XML 1.0 cannot
 * hold even escaped). */
int sw_xdmf_name_ok(const char *name);
/* Writes the description of the first `frames` frames (times time[0..]) of
 * the HDF5 file h5_path to xdmf_path, through a temporary file renamed over
 * it, so that a reader sees the old description or the new one, never half
 * of one.  The HDF5 file is named by its base name, so the pair can be moved
 * together.  SW_OK, or SW_EIO with the reason in err. */
int sw_xdmf_write(const char *xdmf_path, const char *h5_path, const swXdmfRod *rods, int nrod,
                  const double *time, long frames, char *err, size_t errlen);
#endif
