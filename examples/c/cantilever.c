/* cantilever.c — the `make demo` scene until the .sinew compiler lands: a
 * Timoshenko cantilever (3 m, r = 0.25 m, E = 1 MPa, G = 10 kPa) clamped at
 * one end, loaded at the tip by a force ramped up over 2 s, relaxed with
 * analytic damping, written to HDF5, and compared with the closed form
 *   delta = F L^3 / (3 E I) + F L / (4/3 G A).
 * It uses only the runtime's public header, as generated simulators will. */
#include <math.h>
#include <stdio.h>
#include "sinew.h"

int main(int argc, char **argv) {
  const char *path = argc > 1 ? argv[1] : "cantilever.h5";
  const double L = 3.0, R = 0.25, E = 1e6, G = 1e4, rho = 1000, F = 0.15, pi = 3.14159265358979;
  const double A = pi * R * R, I = A * R * R / 4;
  swSpec *s = sw_spec_new();
  swRodDesc r;
  sw_rod_desc_init(&r);
  r.name = "beam";
  r.nelem = 100;
  r.direction[0] = 1; r.direction[2] = 0;
  r.normal[0] = 0; r.normal[2] = 1;
  r.length = L;
  r.radius_start = r.radius_end = R;
  r.youngs = E;
  r.shear_modulus = G;
  r.density = rho;
  r.damping = SW_DAMP_ANALYTIC;
  r.gamma = 2 * (1.8751 * 1.8751 / (L * L)) * sqrt(E * I / (rho * A)) * rho * A; /* ~critical */
  int beam = sw_spec_add_rod(s, &r);
  swBCDesc clamp = {.kind = SW_BC_CLAMP, .rod = beam, .end = 0, .signal = sw_signal_const(1)};
  sw_spec_add_bc(s, &clamp);
  swLoadDesc tip = {.kind = SW_LOAD_FORCE, .rod = beam, .index = -1, .vec = {0, -F, 0},
                    .signal = sw_signal_ramp(0, 1, 0, 2.0)};
  sw_spec_add_load(s, &tip);

  char err[512];
  swModel *m = sw_compile(s, err, sizeof err);
  if (!m) { fprintf(stderr, "demo: %s\n", err); return SW_EMODEL; }
  sw_spec_set_dt(s, 0.9 * sw_stable_dt(m));
  sw_model_free(m);
  m = sw_compile(s, err, sizeof err);
  swData *d = sw_data_new(m);
  const double duration = 40.0;
  swOutputOptions oo = {.model_source = "examples/c/cantilever.c", .duration = duration, .velocity = 1};
  swOutput *out = sw_output_open(path, m, &oo, err, sizeof err);
  if (!out) { fprintf(stderr, "demo: %s\n", err); return SW_EIO; }
  printf("demo: Timoshenko cantilever, %d elements, dt = %.3g s (stable estimate %.3g s), %.0f s\n",
         m->rod_nelem[0], m->dt, sw_stable_dt(m), duration);
  swRunOptions ro = {.duration = duration, .every = 0.1};
  int rc = sw_run(m, d, out, &ro);
  double e[3];
  sw_energy(m, d, e);
  sw_output_close(out, rc == SW_OK ? NULL : "stopped early");
  double tip_y = -d->x[3 * 100 + 1];
  double ref = F * L * L * L / (3 * E * I) + F * L / (4.0 / 3.0 * G * A);
  printf("demo: %ld steps, %ld frames written to %s\n", d->step, sw_output_frames(out), path);
  printf("demo: tip deflection %.6e m, Timoshenko %.6e m, relative error %.2e\n", tip_y, ref,
         fabs(tip_y - ref) / ref);
  printf("demo: energy: kinetic %.3e J, elastic %.6e J, work done %.6e J\n", e[0], e[1], e[2]);
  sw_data_free(d);
  sw_model_free(m);
  sw_spec_free(s);
  return rc;
}
