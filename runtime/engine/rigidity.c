/* rigidity.c — how far each elastic rod strays from its rest shape over a
 * run, so that the simulator can name the rods a scene could hold rigid.
 *
 * Design.  A stiff bone or tendon that hardly deforms costs an elastic
 * rod's step all the same, and often sets the scene's explicit step
 * (docs/benchmarks.md, "Time to solution").  Held rigid (`rigid = true`) it
 * moves as one body and has no elastic waves.  Whether that is faithful
 * depends on the scene's loads, so it is measured, not guessed: at every
 * frame sw_run writes to a file (a study's evaluations write none and are
 * not sampled), each elastic rod's two deformations are taken from the
 * state written,
 *   stretch and shear  s = max_i max_k |sigma_i,k - sigma0_i,k|,
 *                      sigma_i = Q_i (x_{i+1} - x_i) / l^_i - d3
 *                      (Gazzola et al. 2018, eq. 3.7), dimensionless;
 *   bend and twist     b = sum_j |log(Q_{j+1} Q_j^T) - kappa0_j D^_j|,
 *                      the turns between neighbouring elements beyond
 *                      their rest turns, summed along the rod: a bound on
 *                      how far its last element's frame has turned from
 *                      where a rigid rod would carry it (rad),
 * and their largest values over the frames are kept.  For a muscle of
 * several filaments, likewise the largest spread of their motion,
 *   p = max_i max_f |u_f,i - mean_g u_g,i| / L,   u_f,i = x_f,i - x_f,i(t = 0),
 * node i of every filament f (all of one element count) moved from where
 * it started, against the filaments' mean, over the muscle's rest length L
 * (its first filament's): filaments that move alike within a small p could
 * be one filament carrying their force.  After the run's
 * summary, sim/cli_rigidity.c names the rods whose largest s and b stayed
 * within SW_CLI_RIGID_LIKE (0.01); the tradeoff tool then measures what
 * holding them rigid costs on the scene's observables (docs/tradeoff.md).  Rods that cannot
 * be held rigid are not sampled: muscle filaments, kinematic followers and
 * swelling rods (whose rest shape moves).  No allocation here: the peaks
 * live in swData (data.c). */
#include <math.h>
#include <string.h>
#include "sinew.h"
#include "vec.h"
#include "internal.h"
#include "model.h"

/* Whether muscle k has several filaments, all of one element count. */
static int muscle_alike_candidate(const swModel *m, int k) {
  const int f0 = m->muscle_fil_adr[k], f1 = m->muscle_fil_adr[k + 1];
  if (f1 - f0 < 2) return 0;
  for (int f = f0 + 1; f < f1; f++)
    if (m->rod_nelem[m->fil_rod[f]] != m->rod_nelem[m->fil_rod[f0]]) return 0;
  return 1;
}

/* The peaks start at 0 on the rods that could be held rigid and at NaN
 * (not sampled) on the others: rigid rods, muscle filaments, kinematic
 * followers, swelling rods. */
static void not_sampled(swData *d, int r) { d->rod_strain_peak[r] = d->rod_bend_peak[r] = NAN; }

void sw_rigidity_reset(const swModel *m, swData *d) {
  /* one store to each slot: written as 0 then NaN in one iteration, GCC 12.2
   * at -O3 -march=native kept the 0 of the strain peak (test_rigidity) */
  for (int r = 0; r < m->nrod; r++)
    d->rod_strain_peak[r] = d->rod_bend_peak[r] = m->nrigid && m->rod_rigid[r] >= 0 ? NAN : 0.0;
  for (int g = 0; g < m->nfil; g++) not_sampled(d, m->fil_rod[g]);
  for (int j = 0; j < m->nkinematic; j++) not_sampled(d, m->kinematic[j].follower_rod);
  for (int k = 0; k < m->nswell; k++) not_sampled(d, m->swell_rod[k]);
  for (int k = 0; k < m->nmuscle; k++) d->muscle_spread_peak[k] = muscle_alike_candidate(m, k) ? 0.0 : NAN;
  d->rigidity_frames = 0;
}

/* The largest |sigma - sigma0| component of rod r's elements (header). */
static double strain_of(const swModel *m, const swData *d, int r) {
  const int first = m->elem_adr[r], n = m->rod_nelem[r];
  double peak = 0;
  for (int e = first; e < first + n; e++) {
    double Q[9], x0[3], x1[3], dx[3], s[3];
    sw_getQ(m, d->Q, e, Q);
    sw_get3(m, d->x, e, x0);
    sw_get3(m, d->x, e + 1, x1);
    sw_v3_sub(dx, x1, x0);
    sw_mat_vec(s, Q, dx);
    for (int k = 0; k < 3; k++) {
      const double sigma = s[k] / m->rest_len[e] - (k == 2);
      peak = fmax(peak, fabs(sigma - SW_AT(m, m->rest_sigma, e, k)));
    }
  }
  return peak;
}

/* The sum of the turns beyond rest between rod r's neighbouring elements
 * (header), in radians. */
static double bend_of(const swModel *m, const swData *d, int r) {
  const int first = m->elem_adr[r], n = m->rod_nelem[r];
  double sum = 0;
  for (int j = first; j + 1 < first + n; j++) {
    double Qa[9], Qb[9], phi[3], dphi[3];
    sw_getQ(m, d->Q, j, Qa);
    sw_getQ(m, d->Q, j + 1, Qb);
    sw_frame_log(phi, Qa, Qb);
    for (int k = 0; k < 3; k++) dphi[k] = phi[k] - SW_AT(m, m->rest_kappa, j, k) * m->rest_vor_len[j];
    sum += sw_v3_norm(dphi);
  }
  return sum;
}

/* The spread p of muscle k's filaments' motion now (header). */
static double spread_of(const swModel *m, const swData *d, int k) {
  const int f0 = m->muscle_fil_adr[k], f1 = m->muscle_fil_adr[k + 1], nf = f1 - f0;
  const int r0 = m->fil_rod[f0], nn = m->rod_nelem[r0] + 1;
  double L = 0;
  for (int e = m->elem_adr[r0]; e < m->elem_adr[r0] + nn - 1; e++) L += m->rest_len[e];
  double peak = 0;
  for (int i = 0; i < nn; i++) {
    double mean[3] = {0, 0, 0};
    for (int f = f0; f < f1; f++) {
      const int a = m->node_adr[m->fil_rod[f]] + i;
      for (int c = 0; c < 3; c++) mean[c] += (SW_AT(m, d->x, a, c) - SW_AT(m, m->x0, a, c)) / nf;
    }
    for (int f = f0; f < f1; f++) {
      const int a = m->node_adr[m->fil_rod[f]] + i;
      double dev[3];
      for (int c = 0; c < 3; c++) dev[c] = SW_AT(m, d->x, a, c) - SW_AT(m, m->x0, a, c) - mean[c];
      peak = fmax(peak, sw_v3_norm(dev));
    }
  }
  return peak / L;
}

void sw_rigidity_sample(const swModel *m, swData *d) {
  for (int k = 0; k < m->nmuscle; k++)
    if (!isnan(d->muscle_spread_peak[k]))
      d->muscle_spread_peak[k] = fmax(d->muscle_spread_peak[k], spread_of(m, d, k));
  for (int r = 0; r < m->nrod; r++) {
    if (isnan(d->rod_strain_peak[r])) continue; /* not a candidate (sw_rigidity_reset) */
    d->rod_strain_peak[r] = fmax(d->rod_strain_peak[r], strain_of(m, d, r));
    d->rod_bend_peak[r] = fmax(d->rod_bend_peak[r], bend_of(m, d, r));
  }
  d->rigidity_frames++;
}
