/* cli_rigidity.c — after a run, the elastic rods that hardly deformed,
 * named as rods the scene could hold rigid, and the muscles whose
 * filaments moved alike, which fewer filaments could stand for.
 *
 * Design.  engine/rigidity.c keeps, per rod, its largest stretch or shear
 * strain and its largest bend along it over the frames written.  A rod
 * whose both stayed within SW_CLI_RIGID_LIKE (strain, and radians end to
 * end) moved as a rigid body would, to that accuracy, in this run; held
 * rigid (`rigid = true`) it would have no elastic waves and no elastic
 * step, which matters most when its own bound is the scene's explicit
 * step, so those rods come first, then by their bound, shortest first.
 * Likewise a muscle whose filaments' motion spread by at most
 * SW_CLI_RIGID_LIKE of its length.  A note each after the run's summary,
 * at most SW_CLI_RIGID_SHOWN rods or muscles named;
 * nothing with --quiet or when no rod qualifies.  Whether holding them
 * rigid changes the scene's observables more than the user accepts is the
 * tradeoff tool's measurement (scripts/sinew-study, docs/tradeoff.md),
 * not this note's. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "sinew.h"
#include "cli.h"
#include "engine/internal.h"

#define SW_CLI_RIGID_LIKE 1e-2 /* strain, and bend end to end in rad (0.57 deg) */
#define SW_CLI_RIGID_SHOWN 6

/* shortest explicit bound first (an implicit rod's bound does not hold its step) */
static double bound_of(const swModel *m, int r) {
  return m->rod_implicit && m->rod_implicit[r] ? INFINITY : m->rod_wave_dt[r];
}

/* rods[0..n) by bound_of, ties in rod order (insertion: n is small, and
 * the order is the same on every machine) */
static void order_by_bound(const swModel *m, int *rods, int n) {
  for (int i = 1; i < n; i++) {
    const int r = rods[i];
    int k = i;
    while (k > 0 && bound_of(m, rods[k - 1]) > bound_of(m, r)) {
      rods[k] = rods[k - 1];
      k--;
    }
    rods[k] = r;
  }
}

/* The muscles whose filaments moved alike within SW_CLI_RIGID_LIKE of
 * the muscle's length (engine/rigidity.c's spread). */
static void muscles_alike(const swCli *c, const swModel *m, const swData *d) {
  int n = 0;
  for (int k = 0; k < m->nmuscle; k++) n += d->muscle_spread_peak[k] <= SW_CLI_RIGID_LIKE;
  if (n == 0) return;
  fprintf(stderr, "%s: note: the filaments of %d muscle%s moved alike within %g of %s length over the "
          "%ld frames (largest spread of their motion over the length):", c->prog, n, n == 1 ? "" : "s",
          SW_CLI_RIGID_LIKE, n == 1 ? "its" : "each one's", d->rigidity_frames);
  for (int k = 0, shown = 0; k < m->nmuscle && shown < SW_CLI_RIGID_SHOWN; k++) {
    if (!(d->muscle_spread_peak[k] <= SW_CLI_RIGID_LIKE)) continue;
    fprintf(stderr, "%s %s (%d filaments, %.3g)", shown++ ? ";" : "", m->muscle_name[k],
            m->muscle_fil_adr[k + 1] - m->muscle_fil_adr[k], d->muscle_spread_peak[k]);
  }
  if (n > SW_CLI_RIGID_SHOWN) fprintf(stderr, "; and %d more", n - SW_CLI_RIGID_SHOWN);
  fprintf(stderr, ". Fewer filaments (`filaments = 1`) would carry the muscle's force with fewer "
          "elements; scripts/sinew-study measures what that costs on the scene's observables.\n");
}

void sw_cli_rigidity_note(const swCli *c, const swModel *m, const swData *d) {
  if (c->quiet || d->rigidity_frames < 2) return;
  muscles_alike(c, m, d);
  if (m->nrod == 0) return;
  int *rods = malloc(sizeof *rods * (size_t)m->nrod);
  if (!rods) return;
  int n = 0;
  for (int r = 0; r < m->nrod; r++)
    if (d->rod_strain_peak[r] <= SW_CLI_RIGID_LIKE && d->rod_bend_peak[r] <= SW_CLI_RIGID_LIKE)
      rods[n++] = r; /* NaN (not sampled) fails both tests */
  if (n == 0) {
    free(rods);
    return;
  }
  order_by_bound(m, rods, n);
  const double scene = sw_stable_dt(m);
  fprintf(stderr, "%s: note: %d rod%s kept %s rest shape within %g over the %ld frames (largest stretch "
          "or shear strain, largest bend end to end):", c->prog, n, n == 1 ? "" : "s",
          n == 1 ? "its" : "their", SW_CLI_RIGID_LIKE, d->rigidity_frames);
  for (int k = 0; k < n && k < SW_CLI_RIGID_SHOWN; k++) {
    const int r = rods[k];
    char t[32];
    fprintf(stderr, "%s %s (%.3g, %.3g rad", k ? ";" : "", m->rod_name[r], d->rod_strain_peak[r],
            d->rod_bend_peak[r]);
    if (bound_of(m, r) == scene)
      fprintf(stderr, "; its elastic waves set the explicit step, %s",
              sw_cli_format_time(t, sizeof t, scene));
    fprintf(stderr, ")");
  }
  if (n > SW_CLI_RIGID_SHOWN) fprintf(stderr, "; and %d more", n - SW_CLI_RIGID_SHOWN);
  fprintf(stderr, ". Held rigid (`rigid = true`), such a rod moves as one body, with no elastic "
          "step of its own; scripts/sinew-study measures what that costs on the scene's observables.\n");
  free(rods);
}
