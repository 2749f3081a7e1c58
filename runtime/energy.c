/* energy.c — kinetic and elastic energy of the rods, and the work balance.
 *
 * Design.  Energies are diagnostics, evaluated only when a frame is written,
 * so clarity beats speed here: the strains are recomputed from the current
 * state by the same kernel the step uses (rod.c), then summed.
 *   kinetic  = sum_nodes m |v|^2 / 2 + sum_elements w . (J^ / e) w / 2
 *   elastic  = sum_elements l^ (s - s0) . S^ (s - s0) / 2
 *            + sum_voronoi  D^ (k - k0) . B^ (k - k0) / 2
 * (Gazzola et al. 2018, eq. 2.5 discretised; the same sums as PyElastica's
 * energy diagnostics), plus the clamp domains (boundary.c) and the joint
 * springs (joint.c), which are elastic energy too.  The third value is the work done on the rods by
 * loads, gravity, boundaries and dissipation since t = 0 (integrate.c), so
 * kinetic + elastic - work stays constant for an exact integration.
 */
#include "sinew.h"
#include "vec.h"
#include "internal.h"

void sw_energy(const swModel *m, swData *d, double out[3]) {
  sw_internal_loads(m, d); /* refresh strains; force/torque are scratch */
  double kin = 0, ela = 0;
  for (int i = 0; i < m->nnode; i++) kin += 0.5 * m->mass[i] * sw_v3_dot(d->v + 3 * i, d->v + 3 * i);
  for (int e = 0; e < m->nelem; e++)
    for (int k = 0; k < 3; k++) {
      double w = d->omega[3 * e + k], ds = d->sigma[3 * e + k] - m->rest_sigma[3 * e + k];
      kin += 0.5 * m->inertia[3 * e + k] / d->dilatation[e] * w * w;
      ela += 0.5 * m->rest_len[e] * m->shear_stiff[3 * e + k] * ds * ds;
    }
  for (int j = 0; j < m->nvor; j++)
    for (int k = 0; k < 3; k++) {
      double dk = d->kappa[3 * j + k] - m->rest_kappa[3 * j + k];
      ela += 0.5 * m->rest_vor_len[j] * m->bend_stiff[3 * j + k] * dk * dk;
    }
  ela += sw_bc_energy(m, d); /* clamp domains */
  if (m->njoint) ela += sw_joint_energy(m, d);
  if (sw_has_env(m)) ela += sw_env_energy(m, d);
  out[0] = kin;
  out[1] = ela;
  out[2] = d->work;
}
