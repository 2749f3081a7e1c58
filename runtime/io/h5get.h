/* h5get.h — reading a run's HDF5 file back: what compare.c (--compare) and
 * accuracy.c (--accuracy) share.  Internal to io/.
 *
 * Design.  Two readers, written once in compare.c: a numeric dataset whole,
 * as doubles, and its `units` attribute. */
#ifndef SINEW_H5GET_H
#define SINEW_H5GET_H
#include <hdf5.h>
#include <stddef.h>

/* All of a numeric dataset as doubles, with its rank and extents (at most
 * 8); NULL on failure.  The caller frees it. */
double *sw_h5_read_all(hid_t ds, int *rank, hsize_t dims[8], size_t *count);
/* The dataset's `units` attribute into buf, or "". */
void sw_h5_units(hid_t ds, char *buf, size_t len);

#endif
