/* fluid.c — a fluid acting on the elements of its rods: slender-body Stokes
 * drag or quadratic (Morison-type) drag, a uniform background flow, and
 * buoyancy.
 *
 * Design.  Each fluid acts element by element; the load of an element is
 * computed from the element's relative velocity w = (v_a + v_b)/2 - u (v_a,
 * v_b the velocities of its two nodes, u the flow) and its current tangent
 * t = (x_b - x_a) / l, and is shared half and half by the two nodes.
 * The fluid's coefficients lie in planes over the element slots (zero off
 * its rods), so that the loads are two vector loops over the slots its rods
 * span: every element's load, then every node's two halves (on the wing,
 * 12,823 elements, this made the step 16% faster than a loop over a list of
 * elements, whose scatter to shared nodes does not vectorize).
 *
 *   Stokes (Zhang et al. 2019, Suppl. Note 3, eq. 1; slender-body theory of
 *   Cox, J. Fluid Mech. 44 (1970) 791): a force per unit length
 *     f = -c (I - t t^T / 2) w,   c = 4 pi mu / ln(L / r),
 *   integrated over the element as c l (I - t t^T / 2) w.  L is the body
 *   length (the description's, or the rod's rest length), r the element's
 *   radius.  A rod moving broadside feels c per unit length, one moving
 *   along its axis c / 2.
 *
 *   Quadratic (Zhang et al. 2019, Suppl. Note 5.2, eq. 2):
 *     F = -(1/2) rho_f C_d A |w| w,
 *   with A one of three areas per element (swFluidArea, the fluid's `area`).
 *
 *   Silhouette (the default): A is the area the element shows to the
 *   relative flow, the silhouette of a cylinder seen along w,
 *   2 r l |sin a| + (caps) pi r^2 |cos a|, a the angle between t and w.
 *   Only the two ends of a rod are caps the fluid can see (the faces between
 *   elements are inside the rod), and a whole cylinder seen along w shows
 *   one cap's worth, pi r^2 |cos a| (two half-ellipses), so each end element
 *   carries pi r^2 / 2 of it.  With
 *   |w| sin a = |w - (t.w) t| and |w| cos a = |t.w| the force needs no angle:
 *     F = -(1/2) rho_f C_d (2 r l |w_n| + cap |t.w|) w.
 *   Why this area and not the reference's "cross-sectional area of each
 *   filament": read as pi r^2 per element it would make the drag on a rod
 *   grow with the number of elements it is cut into, and read as pi r^2 per
 *   rod it is the area seen along the axis only, orders of magnitude below
 *   the broadside silhouette 2 r L that sets the drag of a barb or a limb
 *   moving sideways.  The projected area is what the drag coefficient of a
 *   cylinder (C_d = 1.2 in the reference, for cross flow) is defined
 *   against; one C_d serves every direction, which is this model's
 *   approximation (a real cylinder in axial flow has another C_d).
 *
 *   Cross section: A = pi r^2 per element, the supplement's words as they
 *   stand, for comparing with eq. 2 read literally: F = -(1/2) rho_f C_d
 *   pi r^2 |w| w whatever the direction of w, so a rod's drag is n pi r^2
 *   worth for n elements (the objection above).
 *
 *   Broadside: A = 2 r l per element whatever the direction of w, the
 *   diameter times the element's current length.  This is what the
 *   reference's released C++ code does for the wing's barbs (GitHub
 *   mattialab/elastica, source/ExternalContact.h): the drag of a node is
 *   one half air density times C_d times the squared speed times "3.0" times
 *   the length of the element after it, along minus its velocity, and 3.0 is
 *   the barbs' diameter in mm (radius 1.5 mm, source/Wing.cpp).  There the
 *   drag acts on each node's own velocity; here, as for the other areas, on
 *   the element's mean velocity, half to each node.  A rod's broadside drag
 *   equals its silhouette's when the flow meets it side on, and exceeds it
 *   once the flow is more than about pi r / L rad off that (lengthwise
 *   2 r L against the end caps' pi r^2).
 *
 *   Buoyancy: -rho_f V g on each element, V = pi r^2 l^ its rest volume (the
 *   rod model keeps each element's volume as it stretches, Gazzola et al.
 *   2018, sec. 2), g the scene's gravity.
 *
 * Which length: the drag is a density along the centreline as it is, so an
 * element's drag is its force per unit length times its current length l
 * (slender-body theory integrates over the deformed body's arc length; a
 * stretched muscle filament shows the fluid more of itself).  The radius is
 * the rest radius, as everywhere in the runtime.  Which velocity: the mean
 * of the element's nodes, so an element is dragged as a whole; a zig-zag of
 * neighbouring nodes (the rod's fastest elastic mode) feels no drag, which
 * keeps the drag out of the elastic waves' step limit (below).
 *
 * All three loads are external: they go into d->ext_force (whose work the
 * kick books) and d->force, so kinetic + elastic - work stays constant and
 * the work column shows what the fluid took out.
 *
 * Step limit.  Explicit drag is a damper; a kick of length h multiplies the
 * velocity of a mode with damping rate c by a factor that grows past 1 in
 * size once h c passes the scheme's limit for a pure damper, S = 2 for
 * position Verlet (1 - h c) and 2.34 for PEFRL (the limit of
 * sw_integrator_stability_limit as the damping ratio goes to infinity).  The
 * Stokes drag is linear in the node velocities, with the symmetric matrix
 * c l / 4 [[P, P], [P, P]] per element (P = I - t t^T / 2, |P| = 1) on its
 * two nodes; the largest rate of the mass-scaled matrix is bounded by its
 * Gershgorin rows, rate_i = sum over node i's elements of c l^ / (2 m_i)
 * (plus the rod's own linear damping gamma D^ / m_i), which is the exact
 * rate c / (rho A) of a uniform rod moving broadside.  The bound is
 * h < 0.95 S / max rate_i (sw_fluid_stable_dt), at rest length: an element
 * stretched by e drags e times harder (the default step is half the
 * estimate).  Quadratic drag's Jacobian on an element's relative velocity
 * has norm rho_f C_d A |w| (twice the secant) for an area that does not
 * depend on w (cross section, broadside); the silhouette's does, and its
 * Jacobian's norm is at most rho_f C_d sqrt((2 r l)^2 + cap^2) |w|, the
 * broadside figure on every element but a rod's two ends.  So node i's rate
 * is at most sum over its elements of rho_f C_d A_e |w_e| / (2 m_i), with
 * A_e = pi r^2 (cross section), 2 r l (broadside) or
 * sqrt((2 r l)^2 + cap^2) (silhouette), and the step is stable below a
 * relative speed |w| ~ 2 S m_i / (h rho_f C_d sum A_e).  On a uniform rod's
 * inner node (m_i = rho pi r^2 l) that is S rho pi r / (2 h rho_f C_d) for
 * the silhouette and broadside, and S rho l / (h rho_f C_d) for the cross
 * section, 2 l / (pi r) times higher.  The bound holds on the Jacobian, so
 * it is conservative: above that speed a kick overshoots (the relative
 * velocity changes sign), and the velocity grows, faster than
 * exponentially, only once h times the secant rate rho_f C_d A |w| / (2 m)
 * (m an element's mass) of a rod moving as a whole passes S, at twice that
 * speed (position Verlet's kick multiplies that velocity by
 * 1 - h rho_f C_d A |w| / (2 m)).  The speed a scene will reach is not
 * known when it is compiled, so whichever the area quadratic drag adds no
 * term to the estimate; the instability check (stability.c) reports a run
 * that passes it within a few steps (test_fluid's
 * test_quadratic_speed_limit measures both speeds for each area).  For the
 * reference's wing (barbs r = 0.6 mm, 2.5 kg/m^3, air, C_d = 1.2) the
 * first speed is 2 / (611 h) m/s, 3 km/s at h = 1 us, broadside or
 * silhouette (2 / (244 h) with the released code's r = 1.5 mm).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "sinew.h"
#include "vec.h"
#include "internal.h"
#include "model.h"



/* The scheme's limit on h c for a pure damper dv/dt = -c v: the damped
 * oscillator's limit on h w times 2 zeta, at a damping ratio so large that
 * the spring no longer matters: at zeta = 1e4 it is within 1e-8 of the
 * limit (2 for Verlet, 2.3414576 for PEFRL).  Much larger zeta does worse:
 * the slow mode's eigenvalue, 1 - h w / (2 zeta), comes within the
 * stability test's 1e-12 of 1 and rounding decides. */
static double damper_limit(swIntegrator integ) {
  const double zeta = 1e4;
  return 2.0 * zeta * sw_integrator_stability_limit(integ, zeta);
}

int sw_fluid_setup(swModel *m, char *err, size_t errlen) {
  const size_t S = (size_t)m->stride, P = (size_t)(m->nfluid ? m->nfluid : 1) * S;
  m->fluid_on = sw_dalloc(P);
  m->fluid_stokes = sw_dalloc(P);
  m->fluid_cap = sw_dalloc(P);
  m->fluid_displaced = sw_dalloc(P);
  m->fluid_span = calloc(2 * (size_t)(m->nfluid ? m->nfluid : 1), sizeof(int));
  double *rate = calloc((size_t)m->nslot, sizeof(double)); /* Stokes damping rate per node slot */
  if (!m->fluid_on || !m->fluid_stokes || !m->fluid_cap || !m->fluid_displaced || !m->fluid_span ||
      !rate) {
    free(rate);
    return sw_fail(err, errlen, "out of memory while building the fluids");
  }
  for (int k = 0; k < m->nfluid; k++) {
    const swFluidDesc *f = &m->fluid[k];
    double *on = m->fluid_on + k * S, *stokes = m->fluid_stokes + k * S;
    double *cap = m->fluid_cap + k * S, *displaced = m->fluid_displaced + k * S;
    int *span = m->fluid_span + 2 * k;
    span[0] = m->stride;
    span[1] = 0;
    for (int q = 0; q < f->nrods; q++) {
      const int r = f->rods[q], n = m->rod_nelem[r], ea = m->elem_adr[r], na = m->node_adr[r];
      if (na < span[0]) span[0] = na;
      if (na + n + 1 > span[1]) span[1] = na + n + 1;
      double L = f->body_length;
      if (L == 0)
        for (int i = 0; i < n; i++) L += m->rest_len[ea + i];
      for (int i = 0; i < n; i++) {
        const int e = ea + i;
        const double rad = m->radius[e], area = SW_PI * rad * rad;
        on[e] += 1;
        if (f->model == SW_FLUID_STOKES) {
          /* Zhang 2019, Suppl. eq. 1: c = 4 pi mu / ln(L / r) */
          if (!(L > rad)) {
            free(rate);
            return sw_fail(err, errlen,
                        "fluid '%s': slender-body drag on rod '%s' needs the body length "
                        "(%g m) to exceed the radius of element %d (%g m)",
                        f->name, m->rod_name[r], L, i, rad);
          }
          double c = 4.0 * SW_PI * f->viscosity / log(L / rad);
          stokes[e] = c;
          double half = 0.5 * c * m->rest_len[e];
          rate[na + i] += half * m->inv_mass[na + i];
          rate[na + i + 1] += half * m->inv_mass[na + i + 1];
        } else if (f->area == SW_FLUID_SILHOUETTE) {
          /* the rod's two end caps, half a cap's silhouette each (above) */
          cap[e] = 0.5 * area * ((i == 0) + (i == n - 1));
        }
        if (f->buoyancy) displaced[e] = f->density * area * m->rest_len[e];
      }
    }
    if (span[1] < span[0]) span[0] = span[1] = 0;
  }
  /* Gershgorin bound of the drag's damping rate (header), with the rods'
   * own linear damping, which damps the same translations */
  double worst = 0;
  for (int r = 0; r < m->nrod; r++) {
    const int na = m->node_adr[r], n = m->rod_nelem[r];
    for (int i = na; i <= na + n; i++) {
      if (!(rate[i] > 0)) continue;
      double c = rate[i];
      if (m->rod_damping[r] == SW_DAMP_LINEAR) c += m->node_gamma[i] * m->inv_mass[i];
      if (c > worst) worst = c;
    }
  }
  free(rate);
  m->fluid_dt = worst > 0 ? 0.95 * damper_limit(m->integrator) / worst : INFINITY;
  return 1;
}

void sw_fluid_free(swModel *m) {
  free(m->fluid_on); free(m->fluid_stokes); free(m->fluid_cap); free(m->fluid_displaced);
  free(m->fluid_span);
  m->fluid_on = m->fluid_stokes = m->fluid_cap = m->fluid_displaced = NULL;
  m->fluid_span = NULL;
}

double sw_fluid_stable_dt(const swModel *m) { return m->nfluid ? m->fluid_dt : INFINITY; }

/* Element e's load from fluid k (the header's laws, Suppl. eqs. 1 and 2,
 * and buoyancy), `on` times: 0 off the fluid's rods.  `stokes` and `area`
 * are the fluid's, passed as constants so that each kernel below has one law
 * and its loop no branch. */
static inline sw3 element_load(const swModel *m, const swData *d, const swFluidDesc *fl, int k,
                               int stokes, int area, double g_scale, int e) {
  const size_t S = (size_t)m->stride, K = (size_t)k * S;
  const sw3 xa = sw3_load(d->x, S, e), xb = sw3_load(d->x, S, e + 1);
  const sw3 va = sw3_load(d->v, S, e), vb = sw3_load(d->v, S, e + 1);
  const sw3 u = {fl->velocity[0], fl->velocity[1], fl->velocity[2]};
  const sw3 dx = sw3_sub(xb, xa);
  const double l = sqrt(sw3_dot(dx, dx));
  const sw3 t = sw3_scale(dx, 1.0 / l);
  const sw3 w = sw3_sub(sw3_scale(sw3_add(va, vb), 0.5), u);   /* relative velocity */
  const double wt = sw3_dot(w, t);
  sw3 load;
  if (stokes) {
    /* -c l (I - t t^T / 2) w  (Suppl. eq. 1 over the element) */
    const double cl = m->fluid_stokes[K + e] * l;
    load = sw3_scale(sw3_sub(w, sw3_scale(t, 0.5 * wt)), -cl);
  } else {
    /* -(1/2) rho C_d A |w| w  (Suppl. eq. 2) */
    const double rad = m->radius[e], speed = sqrt(sw3_dot(w, w));
    double area_speed; /* A |w| */
    if (area == SW_FLUID_CROSS_SECTION) {
      area_speed = SW_PI * rad * rad * speed;
    } else if (area == SW_FLUID_BROADSIDE) {
      area_speed = 2.0 * rad * l * speed;
    } else { /* silhouette: A |w| = 2 r l |w_n| + cap |t.w| */
      const sw3 wn = sw3_sub(w, sw3_scale(t, wt));
      area_speed = 2.0 * rad * l * sqrt(sw3_dot(wn, wn)) + m->fluid_cap[K + e] * fabs(wt);
    }
    load = sw3_scale(w, -0.5 * fl->density * fl->drag_coefficient * area_speed);
  }
  /* buoyancy: -rho_f V g */
  const double dm = m->fluid_displaced[K + e] * g_scale;
  load = sw3_sub(load, (sw3){dm * m->gravity[0], dm * m->gravity[1], dm * m->gravity[2]});
  const double on = m->fluid_on[K + e];
  return sw3_select(on != 0.0, sw3_scale(load, on), (sw3){0, 0, 0});
}

/* Fluid k on slots [lo, hi) (this thread's, internal.h, sw_owned_slots):
 * every element's load into d->scratch_f (free after the rod's gather), one
 * vector loop; then half of it to each of the element's nodes, node i taking
 * the halves of elements i - 1 and i (a rod's first node has none before it
 * in its rod, and slot i - 1 is then the last node of another rod, off the
 * fluid), another.  A thread's slots start where its chunks do, often in the
 * middle of a rod: with `before` (lo inside the fluid's span) node lo also
 * takes element lo - 1's half, which the thread before computes for its own
 * node lo - 1 and this one computes again, to the same bits (the same
 * operations on the same state), so that the node gets the one-thread sum
 * 0.5 (L[lo - 1] + L[lo]).  Without it the node lost that half on 2 or more
 * threads (the wing's --threads 2 parted from 1 thread). */
static inline void fluid_slots(const swModel *m, swData *d, int k, int stokes, int area,
                               double g_scale, int lo, int hi, int before) {
  const size_t S = (size_t)m->stride;
  const swFluidDesc *fl = &m->fluid[k];
  double *restrict L = d->scratch_f;
#pragma omp simd
  for (int e = lo; e < hi; e++) sw3_store(L, S, e, element_load(m, d, fl, k, stokes, area, g_scale, e));
  const sw3 b = before ? element_load(m, d, fl, k, stokes, area, g_scale, lo - 1) : (sw3){0, 0, 0};
  const double prev[3] = {b.x, b.y, b.z};
  for (int q = 0; q < 3; q++) {
    const double *restrict Lq = L + q * S;
    double *restrict ef = d->ext_force + q * S, *restrict F = d->force + q * S;
    const double first = before ? 0.5 * (prev[q] + Lq[lo]) : 0.5 * Lq[lo]; /* node lo */
    ef[lo] += first;
    F[lo] += first;
#pragma omp simd
    for (int i = lo + 1; i < hi; i++) {
      const double h = 0.5 * (Lq[i - 1] + Lq[i]);
      ef[i] += h;
      F[i] += h;
    }
  }
}

void sw_fluid_loads(const swModel *m, swData *d, int lo, int hi) {
  const double gs = sw_signal_eval(&m->gravity_signal, d->time); /* gravity's scale now */
  for (int k = 0; k < m->nfluid; k++) {
    const int a = lo > m->fluid_span[2 * k] ? lo : m->fluid_span[2 * k];
    const int b = hi < m->fluid_span[2 * k + 1] ? hi : m->fluid_span[2 * k + 1];
    if (a >= b) continue;
    const int before = a > m->fluid_span[2 * k]; /* a thread's first slot, inside the span */
    /* one kernel per law */
    if (m->fluid[k].model == SW_FLUID_STOKES) fluid_slots(m, d, k, 1, SW_FLUID_SILHOUETTE, gs, a, b, before);
    else if (m->fluid[k].area == SW_FLUID_CROSS_SECTION)
      fluid_slots(m, d, k, 0, SW_FLUID_CROSS_SECTION, gs, a, b, before);
    else if (m->fluid[k].area == SW_FLUID_BROADSIDE)
      fluid_slots(m, d, k, 0, SW_FLUID_BROADSIDE, gs, a, b, before);
    else fluid_slots(m, d, k, 0, SW_FLUID_SILHOUETTE, gs, a, b, before);
  }
}
