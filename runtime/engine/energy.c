/* energy.c — kinetic and elastic energy of the rods, and the work balance.
 *
 * Design.  Energies are diagnostics, evaluated only when a frame is written,
 * so clarity beats speed here: the strains are recomputed from the current
 * state by the same kernel the step uses (rod.c), then summed.
 *   kinetic  = sum_nodes m |v|^2 / 2 + sum_elements w . (J^ / e) w / 2
 *              (J^ alone on the rods of the variational law, rod.c)
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
  /* rod by rod over the real nodes, elements and domains (no ghosts), in
   * rod order r = 0, 1, ...: the order of the sums is that of the global
   * indices before slots were grouped (sinew.h, "Layout") */
  for (int r = 0; r < m->nrod; r++)
    for (int i = m->node_adr[r]; i <= m->node_adr[r] + m->rod_nelem[r]; i++) {
      double v[3];
      sw_get3(m, d->v, i, v);
      kin += 0.5 * d->mass_now[i] * sw_v3_dot(v, v);
    }
  for (int r = 0; r < m->nrod; r++)
    for (int e = m->elem_adr[r]; e < m->elem_adr[r] + m->rod_nelem[r]; e++)
      for (int k = 0; k < 3; k++) {
        double w = SW_AT(m, d->omega, e, k);
        double ds = SW_AT(m, d->sigma, e, k) - SW_AT(m, m->rest_sigma, e, k);
        kin += 0.5 * SW_AT(m, d->inertia_now, e, k) / sw_inertia_dilatation(m, d, e) * w * w;
        ela += 0.5 * m->rest_len[e] * SW_AT(m, d->shear_now, e, k) * ds * ds;
      }
  for (int r = 0; r < m->nrod; r++)
    for (int j = m->vor_adr[r]; j < m->vor_adr[r] + m->rod_nelem[r] - 1; j++)
      for (int k = 0; k < 3; k++) {
        double dk = SW_AT(m, d->kappa, j, k) - SW_AT(m, d->kappa0_now, j, k);
        ela += 0.5 * m->rest_vor_len[j] * SW_AT(m, d->bend_now, j, k) * dk * dk;
      }
  ela += sw_bc_energy(m, d); /* clamp domains */
  if (m->njoint) ela += sw_joint_energy(m, d);
  if (sw_has_env(m)) ela += sw_env_ops(m)->energy(m, d);
  out[0] = kin;
  out[1] = ela;
  out[2] = d->work;
}
