/* h5read.h — reading attributes of an HDF5 file back in tests: one copy for
 * the runtime's output tests, the simulator command-line tests and the
 * end-to-end tests.  Include after <cmocka.h> (it asserts) and <hdf5.h>. */
#ifndef SINEW_TEST_H5READ_H
#define SINEW_TEST_H5READ_H

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* A scalar string attribute of obj_path, fixed or variable length; caller frees. */
static inline char *read_string_attr(hid_t file, const char *obj_path, const char *name) {
  if (H5Aexists_by_name(file, obj_path, name, H5P_DEFAULT) <= 0) {
    fprintf(stderr, "# %s has no attribute '%s'\n", obj_path, name);
    fail();
  }
  hid_t attr = H5Aopen_by_name(file, obj_path, name, H5P_DEFAULT, H5P_DEFAULT);
  assert_true(attr >= 0);
  hid_t type = H5Aget_type(attr);
  assert_int_equal(H5Tget_class(type), H5T_STRING);
  char *copy;
  if (H5Tis_variable_str(type) > 0) {
    char *value = NULL;
    hid_t mem = H5Tget_native_type(type, H5T_DIR_ASCEND);
    assert_true(H5Aread(attr, mem, &value) >= 0);
    copy = strdup(value ? value : "");
    H5free_memory(value);
    H5Tclose(mem);
  } else {
    size_t size = H5Tget_size(type);
    copy = calloc(size + 1, 1);
    assert_true(H5Aread(attr, type, copy) >= 0);
  }
  H5Tclose(type);
  H5Aclose(attr);
  return copy;
}

/* A scalar double attribute of obj_path (a group or a dataset). */
static inline double read_double_attr_of(hid_t file, const char *obj_path, const char *name) {
  double value = NAN;
  hid_t attr = H5Aopen_by_name(file, obj_path, name, H5P_DEFAULT, H5P_DEFAULT);
  assert_true(attr >= 0);
  assert_true(H5Aread(attr, H5T_NATIVE_DOUBLE, &value) >= 0);
  H5Aclose(attr);
  return value;
}

/* A scalar double attribute of the root group. */
static inline double read_double_attr(hid_t file, const char *name) {
  return read_double_attr_of(file, "/", name);
}

#endif
