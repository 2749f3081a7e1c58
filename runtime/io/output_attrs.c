/* output_attrs.c — the attributes of a run's HDF5 file: how the file was
 * made (the root's provenance and the /params table), what each group
 * describes (rods, joints, muscles), what a probe measures, and the
 * objective's value, penalty and score.
 *
 * Design.  Attributes are scalars, 1-D arrays of doubles or integers, and
 * UTF-8 variable-length strings; every one goes through write_attr() to an
 * swAttrTarget (the object, and the file and object names for messages), so
 * a failure names the attribute and where it was going.  A quantity carries
 * its unit in a sibling attribute NAME_units.  The root group records how
 * the file was made (docs/runtime.md, "Running and output") and a `status`
 * attribute that reads "incomplete" until sw_output_close() (output.c)
 * replaces it with the caller's verdict; a model with an objective also gets
 * its value, penalty and score there (sw_output_objective).  Rod, joint and
 * muscle groups describe themselves once the datasets have made them;
 * muscle groups also carry what a reader needs to normalise their forces
 * (muscle_attrs); a probe is one dataset /probes/NAME [F, 3] whose units
 * follow its kind and whose attributes say what it measures
 * (sw_out_write_probe_attrs). */
#include <hdf5.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sinew.h"
#include "engine/internal.h"
#include "output.h"

/* ---- attributes (scalars, UTF-8 variable-length strings) ---- */

static int write_attr(const swAttrTarget *t, const char *name, hid_t file_type,
                      hid_t mem_type, hid_t space, const void *value) {
  hid_t attr = H5Acreate2(t->obj, name, file_type, space, H5P_DEFAULT, H5P_DEFAULT);
  if (attr < 0)
    return sw_out_fail(t->err, t->errlen, "%s: cannot create attribute '%s' of %s", t->file,
                       name, t->obj_path);
  herr_t wrote = H5Awrite(attr, mem_type, value);
  herr_t closed = H5Aclose(attr);
  if (wrote < 0 || closed < 0)
    return sw_out_fail(t->err, t->errlen, "%s: cannot write attribute '%s' of %s", t->file, name,
                       t->obj_path);
  return SW_OK;
}

hid_t sw_out_utf8_string_type(void) {
  hid_t type = H5Tcopy(H5T_C_S1);
  if (type < 0) return type;
  if (H5Tset_size(type, H5T_VARIABLE) < 0 || H5Tset_cset(type, H5T_CSET_UTF8) < 0) {
    H5Tclose(type);
    return H5I_INVALID_HID;
  }
  return type;
}

/* A 1-D array of strings when count > 0, a scalar string when count == 0. */
int sw_out_attr_strings(const swAttrTarget *t, const char *name, const char *const *values,
                        hsize_t count) {
  hid_t type = sw_out_utf8_string_type();
  hid_t space = count ? H5Screate_simple(1, &count, NULL) : H5Screate(H5S_SCALAR);
  int rc = SW_OK;
  if (type < 0 || space < 0)
    rc = sw_out_fail(t->err, t->errlen, "%s: cannot make the type of attribute '%s' of %s",
                     t->file, name, t->obj_path);
  else
    rc = write_attr(t, name, type, type, space, values);
  if (space >= 0) H5Sclose(space);
  if (type >= 0) H5Tclose(type);
  return rc;
}

int sw_out_attr_string(const swAttrTarget *t, const char *name, const char *value) {
  const char *values[1] = {value ? value : ""};
  return sw_out_attr_strings(t, name, values, 0);
}

int sw_out_attr_scalar(const swAttrTarget *t, const char *name, hid_t file_type,
                       hid_t mem_type, const void *value) {
  hid_t space = H5Screate(H5S_SCALAR);
  if (space < 0)
    return sw_out_fail(t->err, t->errlen, "%s: cannot make the dataspace of attribute '%s' of %s",
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
    return sw_out_fail(t->err, t->errlen, "%s: cannot make the dataspace of attribute '%s' of %s",
                       t->file, name, t->obj_path);
  int rc = write_attr(t, name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, space, values);
  H5Sclose(space);
  return rc;
}

/* A quantity: its value (n > 1: a vector) and its unit in NAME_units. */
static int attr_quantity(const swAttrTarget *t, const char *name, const double *values, int n,
                         const char *units) {
  int rc = n > 1 ? attr_vector(t, name, values, n)
                 : sw_out_attr_scalar(t, name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, values);
  char key[64];
  snprintf(key, sizeof key, "%s_units", name);
  if (rc == SW_OK) rc = sw_out_attr_string(t, key, units);
  return rc;
}

static int attr_int(const swAttrTarget *t, const char *name, int value) {
  return sw_out_attr_scalar(t, name, H5T_STD_I32LE, H5T_NATIVE_INT, &value);
}

/* What a probe measures: `kind` (probe.c's name), its rods (or rod and
 * node), and the averaging window of a mean velocity (s). */
int sw_out_write_probe_attrs(const swAttrTarget *t, const swProbeDesc *p) {
  int rc = sw_out_attr_string(t, "kind", sw_probe_kind_name(p->kind));
  if (rc == SW_OK && p->kind == SW_PROBE_NODE) {
    rc = sw_out_attr_scalar(t, "rod", H5T_STD_I32LE, H5T_NATIVE_INT, &p->rod);
    if (rc == SW_OK) rc = sw_out_attr_scalar(t, "node", H5T_STD_I32LE, H5T_NATIVE_INT, &p->node);
    return rc;
  }
  if (rc == SW_OK) {
    hsize_t n = (hsize_t)p->nrods;
    hid_t space = H5Screate_simple(1, &n, NULL);
    if (space < 0)
      return sw_out_fail(t->err, t->errlen,
                         "%s: cannot make the dataspace of attribute 'rods' of %s", t->file,
                         t->obj_path);
    rc = write_attr(t, "rods", H5T_STD_I32LE, H5T_NATIVE_INT, space, p->rods);
    H5Sclose(space);
  }
  if (rc == SW_OK && p->kind == SW_PROBE_MEAN_VELOCITY)
    rc = attr_quantity(t, "window", &p->window, 1, "s");
  return rc;
}

/* ---- the root: how the file was made ---- */

int sw_out_write_root_attrs(swOutput *o, const swModel *m, const swOutputOptions *opt,
                            char *err, size_t errlen) {
  swAttrTarget t = {o->file, o->path, "/", err, errlen};
  int n_rods = m->nrod;
  int rc = sw_out_attr_string(&t, "sinew_version", SW_VERSION);
  if (rc == SW_OK) rc = sw_out_attr_string(&t, "model_source", opt->model_source);
  if (rc == SW_OK) rc = sw_out_attr_string(&t, "model_sha256", opt->model_sha256);
  if (rc == SW_OK) rc = attr_quantity(&t, "dt", &m->dt, 1, "s");
  if (rc == SW_OK) rc = attr_quantity(&t, "duration", &opt->duration, 1, "s");
  if (rc == SW_OK) rc = attr_quantity(&t, "every", &opt->every, 1, "s");
  if (rc == SW_OK) rc = attr_quantity(&t, "gravity", m->gravity, 3, "m/s^2");
  if (rc == SW_OK)
    rc = sw_out_attr_string(&t, "integrator",
                            m->integrator == SW_PEFRL ? "pefrl"
                            : m->integrator == SW_IMEX ? "imex" : "position-verlet");
  if (rc == SW_OK) rc = sw_out_attr_string(&t, "params", opt->params);
  if (rc == SW_OK) rc = sw_out_attr_scalar(&t, "n_rods", H5T_STD_I32LE, H5T_NATIVE_INT, &n_rods);
  /* Replaced by sw_output_close(); a file that still says this was not closed. */
  if (rc == SW_OK)
    rc = sw_out_attr_string(&t, "status", "incomplete: the run did not close this file");
  return rc;
}

/* ---- groups that describe themselves ---- */

/* Opens group PATH if a dataset made it (a rod, joint or muscle with nothing
 * selected has none); 0 when absent, -1 on error. */
static hid_t open_group(swOutput *o, const char *gpath, char *err, size_t errlen) {
  htri_t exists = H5Lexists(o->file, gpath, H5P_DEFAULT);
  if (exists < 0) {
    sw_out_fail(err, errlen, "%s: cannot look up group %s", o->path, gpath);
    return -1;
  }
  if (!exists) return 0;
  hid_t g = H5Gopen2(o->file, gpath, H5P_DEFAULT);
  if (g < 0) sw_out_fail(err, errlen, "%s: cannot open group %s", o->path, gpath);
  return g;
}

/* A rod: what it is (kind, material, the model line), its rest geometry
 * (elements, length, the radius of each element) and its material
 * constants, each with its unit. */
static int rod_attrs(const swAttrTarget *t, const swModel *m, int r) {
  const swRodInfo *info = &m->rod_info[r];
  const int n = m->rod_nelem[r];
  double *radius = malloc((size_t)n * sizeof *radius);
  if (!radius) return sw_out_fail(t->err, t->errlen, "%s: out of memory", t->file);
  for (int i = 0; i < n; i++) radius[i] = m->radius[m->elem_adr[r] + i];
  int rc = sw_out_attr_string(t, "kind", info->kind ? info->kind : "rod");
  if (rc == SW_OK && info->material) rc = sw_out_attr_string(t, "material", info->material);
  if (rc == SW_OK && info->where) rc = sw_out_attr_string(t, "where", info->where);
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
  int rc = sw_out_attr_string(t, "kind", sw_joint_kind_name(jd->kind));
  if (rc == SW_OK) rc = sw_out_attr_string(t, "rod_a", m->rod_name[jd->rod_a]);
  if (rc == SW_OK)
    rc = attr_int(t, "node_a", jd->node_a < 0 ? m->rod_nelem[jd->rod_a] : jd->node_a);
  if (rc == SW_OK && jd->rod_b >= 0) {
    rc = sw_out_attr_string(t, "rod_b", m->rod_name[jd->rod_b]);
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
  int rc = sw_out_attr_string(t, "kind", "muscle");
  if (rc == SW_OK && info->material) rc = sw_out_attr_string(t, "material", info->material);
  if (rc == SW_OK && info->where) rc = sw_out_attr_string(t, "where", info->where);
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
    if (rc == SW_OK) rc = sw_out_attr_strings(t, "via_rods", rods, (hsize_t)nvia);
  }
  return rc;
}

/* The attributes of every rod, joint and muscle group the datasets made. */
int sw_out_write_group_attrs(swOutput *o, const swModel *m, char *err, size_t errlen) {
  static const char *const kinds[] = {"rods", "joints", "muscles"};
  const int count[] = {m->nrod, m->njoint, m->nmuscle};
  int rc = SW_OK;
  for (int kind = 0; kind < 3 && rc == SW_OK; kind++)
    for (int i = 0; i < count[kind] && rc == SW_OK; i++) {
      const char *name = kind == 0 ? m->rod_name[i] : kind == 1 ? m->joint_name[i]
                                                                 : m->muscle_name[i];
      char *gpath = sw_out_dup_printf("/%s/%s", kinds[kind], name);
      if (!gpath) return sw_out_fail(err, errlen, "%s: out of memory", o->path);
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
int sw_out_write_params(swOutput *o, const swOutputOptions *opt, char *err, size_t errlen) {
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
  hid_t str = sw_out_utf8_string_type();
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
  return ok ? SW_OK : sw_out_fail(err, errlen, "%s: cannot write the table /params", o->path);
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
      return sw_out_fail(NULL, 0, "%s: cannot replace attribute '%s' of /", o->path, names[k]);
  }
  swAttrTarget t = {o->file, o->path, "/", NULL, 0};
  int rc = attr_quantity(&t, "objective", &objective, 1, units);
  if (rc == SW_OK) rc = attr_quantity(&t, "penalty", &penalty, 1, units);
  if (rc == SW_OK) rc = attr_quantity(&t, "score", &score, 1, units);
  if (rc == SW_OK) rc = sw_out_attr_string(&t, "objective_text", text);
  return rc;
}
