/* contact.c — rod-rod contact: elements whose centrelines come closer than
 * the sum of their radii push apart (Zhang et al. 2019, Suppl. Table 4,
 * stiffness k_c and damping gamma_c).
 *
 * Design.  Each element is the segment x_i..x_{i+1} of its rod, a cylinder
 * of radius r around it.  For a pair of elements a, b the narrow phase finds
 * the closest points p = a0 + s (a1 - a0), q = b0 + t (b1 - b0) of the two
 * segments (s, t in [0, 1]: the box-constrained minimum of |p - q|^2,
 * Ericson, Real-Time Collision Detection, 2005, sec. 5.1.9, with parallel
 * segments meeting at the middle of their common stretch), the distance
 * D = |p - q|, the normal n = (p - q) / D and the overlap
 *   delta = r_a + r_b - D.
 * A pair with delta > 0 stores U = k_c delta^2 / 2.  Since the closest
 * points minimise the distance, dD/da0 = (1 - s) n, dD/da1 = s n,
 * dD/db0 = -(1 - t) n, dD/db1 = -t n (Danskin's theorem: the minimiser's
 * own variation does not count), so the spring force -dU/dx is
 *   f = k_c delta n  on a, split (1 - s, s) over a0, a1,
 *  -f                on b, split (1 - t, t) over b0, b1,
 * the exact gradient of U: with gamma_c = 0 the contact is conservative, and
 * its energy is reported with the elastic energy (sw_contact_energy).  The
 * damper adds gamma_c times the approach speed of the contact points,
 * -(v_p - v_q) . n with v_p = (1 - s) v_a0 + s v_a1 (likewise v_q), to the
 * normal force, which is never let become attractive: the damper's part is
 * max(gamma_c * approach, -k_c delta).  It goes into ext_force as well as
 * force, so that integrate.c's kick books the energy it takes.
 *
 * Friction (mu_s > 0): the obstacles' elastic-Coulomb law (friction.c;
 * Cundall & Strack 1979) between two rods.  When a pair first touches it
 * records its anchor: on each element the point of its surface that
 * touches, the centreline point s (t) plus the arm -r_a n (r_b n), the arm
 * kept in the element's material frame, so that the anchor moves, turns and
 * rolls with its element.  At each evaluation the anchors' separation
 * u = p_a - p_b and relative velocity w (v_s + omega x arm, each side), their
 * tangential parts, give friction.c's capped force F on a, -F on b.  Each
 * force acts at its anchor: split (1 - s, s) over the element's nodes at
 * the centreline point, with the couple arm x F on the element.  The pair
 * is then re-anchored at the touching surface points with the spring's
 * tangential stretch kept (sw_friction_reanchor): u_t while stuck, the
 * places s, t kept; -F / k_t when slipping, at the current closest points
 * (where F then acts), b's point moved so that the spring alone gives F.
 * So a stuck rod that rolls keeps its anchor where it touches: kept as a
 * material point, the anchor would ride up the rod's side while the spring,
 * which sees only u_t, let it, and the rod would roll about a point off its
 * bottom (test_obstacle_roll measured it on an obstacle).  Forces
 * and couples are then the gradient of k_t |u_t|^2 / 2 in the positions and
 * rotations (n held), and since the two anchors are apart only by the
 * overlap along n and the spring's stretch, the part of the energy's change
 * that holding n misses is second order: the law is passive (a hairpin's
 * self-contact friction never does positive work; test_rod_friction.c).
 * Anchored on the centrelines instead, the points would be r_a + r_b apart
 * along n, and the turning of n under that lever fed energy in (9 % of
 * the kinetic energy in the same hairpin).  The pair of forces is equal and
 * opposite: momentum is kept to round-off; angular momentum up to the
 * moment of the pair about their separation (the overlap), small.  The
 * whole tangential force and its couples go into ext_force, ext_torque as
 * well: the kick books their work as obstacle.c's.  The anchors are a table
 * of rows in the state (d->contact_anchor, keyed by the pair's two rows,
 * ordered), rebuilt at each evaluation: the grid meets pairs in no
 * particular order, so a pair's old row is found by bisection and the new
 * table sorted once written (friction.c).  It holds contact_maxanchor rows,
 * four per element of the contacts with friction; pairs beyond it are
 * frictionless, counted in d->friction_full, of which the run warns.  The
 * table is state: checkpoints save it.
 *
 * Which pairs.  Every pair of elements of different rods of the
 * description's set; with `self`, also pairs of one rod whose rest arc
 * length strictly between them (the "gap") is at least pi (r_a + r_b) / 2:
 * the arc of the tightest hairpin, a half circle whose diameter r_a + r_b
 * brings its two legs into touch.  Closer neighbours are never paired (two
 * elements sharing a node are always at distance 0), and a rest shape that
 * turns no tighter than that hairpin is contact-free (the chord of an arc
 * g <= pi R of a circle of radius R is at least 2 g / pi >= r_a + r_b).
 *
 * Broad phase.  A uniform grid of cubic cells of side h = the longest
 * current element + twice the largest radius, hashed into a fixed number of
 * buckets (a power of two, at least twice the elements of the set), rebuilt
 * at every evaluation by a counting sort of the elements by the bucket of
 * the cell of their midpoint.  Two elements can touch only if their
 * midpoints are within (l_a + l_b) / 2 + r_a + r_b <= h, so only the same
 * cell and the 26 around it hold candidates; each element looks in its own
 * cell (partners after it) and in the 13 cells of one half of the
 * neighbourhood, so each pair is seen once, and a bucket's elements of
 * another cell (hash collisions) are passed over.  A bit set of the
 * non-empty buckets (small enough to stay in the L1 cache) and the cells
 * copied in bucket order keep most look-ups off main memory, which is what
 * the loop waits on (bench/bench_contact.c).  The cost is linear in the
 * elements plus the candidate pairs; the sizes are fixed when the model and
 * the state are made, so nothing is allocated in the step.  The brute force
 * n^2 loop is kept for tests and the benchmark (SW_CONTACT_BRUTE).
 *
 * The step limit (sw_contact_stable_dt) is derived in docs/physics.md,
 * "Rod-rod contact".
 */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "sinew.h"
#include "vec.h"
#include "internal.h"

/* ---- setup ---- */

/* The rows of contact c are its elements, rod by rod, each rod once. */
int sw_contact_setup(swModel *m) {
  int rows = 0, widest = 0;
  for (int c = 0; c < m->ncontact; c++)
    for (int k = 0; k < m->contact[c].nrods; k++) rows += m->rod_nelem[m->contact[c].rods[k]];
  size_t R = (size_t)(rows ? rows : 1);
  m->contact_row_adr = calloc((size_t)m->ncontact + 1, sizeof(int));
  m->contact_elem = calloc(R, sizeof(int));
  m->contact_rod = calloc(R, sizeof(int));
  m->contact_arc = calloc(R, sizeof(double));
  int *seen = calloc((size_t)(m->nrod ? m->nrod : 1), sizeof(int));
  if (!m->contact_row_adr || !m->contact_elem || !m->contact_rod || !m->contact_arc || !seen) {
    free(seen);
    return 0;
  }
  int row = 0;
  for (int c = 0; c < m->ncontact; c++) {
    m->contact_row_adr[c] = row;
    for (int k = 0; k < m->contact[c].nrods; k++) {
      int r = m->contact[c].rods[k];
      if (seen[r] == c + 1) continue; /* a rod listed twice is one rod */
      seen[r] = c + 1;
      double arc = 0;
      for (int i = 0; i < m->rod_nelem[r]; i++, row++) {
        int e = m->elem_adr[r] + i;
        m->contact_elem[row] = e;
        m->contact_rod[row] = r;
        m->contact_arc[row] = arc;
        arc += m->rest_len[e];
      }
    }
    if (row - m->contact_row_adr[c] > widest) widest = row - m->contact_row_adr[c];
  }
  m->contact_row_adr[m->ncontact] = row;
  free(seen);
  int nb = 16;
  while (nb < 2 * widest) nb *= 2;
  m->contact_nbucket = nb;
  m->contact_maxrows = widest;
  /* friction's anchors: up to four touching pairs per element of the
   * contacts with friction (rods lying along each other touch three) */
  long room = 0;
  for (int c = 0; c < m->ncontact; c++)
    if (m->contact[c].static_friction > 0) room += 4L * (m->contact_row_adr[c + 1] - m->contact_row_adr[c]);
  m->contact_maxanchor = room ? (int)(room + 64) : 0;
  return 1;
}

void sw_contact_free(swModel *m) {
  free(m->contact_row_adr);
  free(m->contact_elem);
  free(m->contact_rod);
  free(m->contact_arc);
  m->contact_row_adr = m->contact_elem = m->contact_rod = NULL;
  m->contact_arc = NULL;
}

int sw_contact_data_new(const swModel *m, swData *d) {
  size_t R = (size_t)(m->contact_maxrows ? m->contact_maxrows : 1);
  d->contact_cell = calloc(3 * R, sizeof(int));
  d->contact_bucket = calloc(R, sizeof(int));
  d->contact_sorted = calloc(R, sizeof(int));
  d->contact_start = calloc((size_t)m->contact_nbucket + 1, sizeof(int));
  d->contact_occupied = calloc((size_t)m->contact_nbucket / 64 + 1, sizeof(unsigned long long));
  d->contact_sorted_cell = calloc(3 * R, sizeof(int));
  if (m->contact_maxanchor) {
    const size_t anchors = 1 + (size_t)m->contact_maxanchor * SW_CONTACT_ANCHOR_ROW;
    d->contact_anchor = calloc(anchors, sizeof(double));
    d->contact_anchor_old = calloc(anchors, sizeof(double));
    if (!d->contact_anchor || !d->contact_anchor_old) return 0;
  }
  return d->contact_cell && d->contact_bucket && d->contact_sorted && d->contact_start &&
         d->contact_occupied && d->contact_sorted_cell;
}

/* ---- narrow phase ---- */

/* Closest points of the segments a0 + s da and b0 + t db, s, t in [0, 1]
 * (Ericson 2005, sec. 5.1.9; obstacle.c's capsules use it too).  Parallel segments (sin of their angle below
 * 1e-7) meet at the middle of the stretch of a that faces b, or at a's end
 * nearest to b when none does.  Returns |p - q|^2 and the difference p - q. */
double sw_segment_closest(const double *a0, const double *da, const double *b0, const double *db,
                          double *s_out, double *t_out, double *pq) {
  double r[3];
  sw_v3_sub(r, a0, b0);
  const double aa = sw_v3_dot(da, da), bb = sw_v3_dot(db, db), ab = sw_v3_dot(da, db);
  const double ar = sw_v3_dot(da, r), br = sw_v3_dot(db, r);
  double s, t;
  if (aa <= 0 && bb <= 0) { /* two points */
    s = t = 0;
  } else if (aa <= 0) {
    s = 0;
    t = sw_clamp01(br / bb);
  } else if (bb <= 0) {
    t = 0;
    s = sw_clamp01(-ar / aa);
  } else {
    const double denom = aa * bb - ab * ab; /* |da x db|^2 >= 0 */
    if (denom > 1e-14 * aa * bb) {
      s = sw_clamp01((ab * br - ar * bb) / denom);
    } else {
      /* b's ends projected on a's line: s = (b_end - a0) . da / aa */
      double u0 = -ar / aa, u1 = (ab - ar) / aa;
      double lo = fmax(0.0, fmin(u0, u1)), hi = fmin(1.0, fmax(u0, u1));
      if (lo <= hi) s = 0.5 * (lo + hi);   /* the middle of the common stretch */
      else s = fmax(u0, u1) < 0 ? 0 : 1;   /* b lies wholly before or after a */
    }
    /* the point of b nearest to p(s); if it is clamped, p nearest to it */
    t = (ab * s + br) / bb;
    if (t < 0) {
      t = 0;
      s = sw_clamp01(-ar / aa);
    } else if (t > 1) {
      t = 1;
      s = sw_clamp01((ab - ar) / aa);
    }
  }
  for (int k = 0; k < 3; k++) pq[k] = r[k] + s * da[k] - t * db[k];
  *s_out = s;
  *t_out = t;
  return sw_v3_dot(pq, pq);
}

/* A unit vector normal to the segment direction da (for centrelines that
 * cross exactly, where p - q is zero): along da x db, or any normal of da. */
static void crossing_normal(double *n, const double *da, const double *db) {
  sw_v3_cross(n, da, db);
  double len = sw_v3_norm(n);
  if (!(len > 0)) {
    const double ex[3] = {1, 0, 0}, ey[3] = {0, 1, 0};
    sw_v3_cross(n, da, fabs(da[0]) < 0.9 * sw_v3_norm(da) ? ex : ey);
    len = sw_v3_norm(n);
  }
  if (len > 0) sw_v3_scale(n, n, 1.0 / len);
  else n[0] = 1, n[1] = 0, n[2] = 0;
}

/* Contact of the elements of rows ra, rb of description c: adds the loads
 * (when force != NULL) and returns the overlap (<= 0: none). */
typedef struct {
  double *force, *ext_force, *torque, *ext_torque; /* NULL: energy only */
  double energy, max_overlap;
  int pairs;
  /* friction: the previous anchors (old, old_rows), the new table (rows
   * written, room), the stuck and slipping */
  const double *old;
  int old_rows;
  double *anchor;
  int rows, room;
  int stuck, slipping, full; /* full: pairs beyond the table */
} Sums;

/* ---- friction: the anchor of a touching pair (see the design) ---- */

/* One side of a touching pair: friction.c's swFrictionSide (the element,
 * the closest point's place, the radius; once anchored, the anchor's place
 * and arm), whose anchored surface point sw_side_point places. */
typedef swFrictionSide Side;

/* The tangential force F on side a of the pair (a, b) of key `key` (a the
 * lower row), touching with the normal n from b to a and the normal force
 * N; the sides' anchors filled, the pair's new anchor row appended to
 * sum->anchor.  Returns 0 without friction. */
static int friction_force(const swModel *m, const swData *d, const swContactDesc *cd, double key,
                          Side *a, Side *b, const double n[3], double N, Sums *sum, double F[3]) {
  if (!(cd->static_friction > 0) || !sum->anchor) return 0;
  if (sum->rows >= sum->room) { /* beyond the table: frictionless, counted */
    sum->full++;
    return 0;
  }
  const double *row = sw_anchor_find(sum->old, sum->old_rows, SW_CONTACT_ANCHOR_ROW, key);
  double ya[3], yb[3], off[3];
  if (row) {
    memcpy(ya, row + 3, sizeof ya);
    memcpy(yb, row + 6, sizeof yb);
  } else { /* the surface points that touch: a's towards b, b's towards a */
    sw_v3_scale(off, n, -a->radius);
    sw_side_arm(m, d, a, off, ya);
    sw_v3_scale(off, n, b->radius);
    sw_side_arm(m, d, b, off, yb);
  }
  /* the two material points, their separation and relative velocity,
   * tangential parts */
  double pa[3], pb[3], va[3], vb[3], u[3], w[3];
  sw_side_point(m, d, a, row ? row[1] : a->at, ya, pa, va);
  sw_side_point(m, d, b, row ? row[2] : b->at, yb, pb, vb);
  for (int q = 0; q < 3; q++) u[q] = pa[q] - pb[q], w[q] = va[q] - vb[q];
  const double un = sw_v3_dot(u, n), wn = sw_v3_dot(w, n);
  for (int q = 0; q < 3; q++) u[q] -= un * n[q], w[q] -= wn * n[q];
  const double kt = cd->tangential_stiffness > 0 ? cd->tangential_stiffness : cd->stiffness;
  const int stuck = sw_coulomb_cap(u, w, kt, cd->damping, cd->static_friction, cd->kinetic_friction, N, F);
  /* re-anchored at the touching surface points (friction.c), the places
   * kept while stuck, the spring's tangential stretch kept: a's arm -r_a n,
   * b's r_b n plus the tangential part of the centreline points' offset
   * less the stretch, so that p_a - p_b has the tangential part `stretch`
   * (a stuck rod that rolls keeps its anchor where it touches instead of
   * carrying it up its side).  F acts at the anchors it came from while
   * stuck, at the new ones when slipping. */
  double stretch[3], ca[3], cb[3], rel[3];
  const double at_a = sw_friction_reanchor(a, stuck, u, F, kt, stretch);
  const double at_b = sw_friction_reanchor(b, stuck, u, F, kt, stretch);
  sw_side_centre(m, d->x, a, at_a, ca);
  sw_side_centre(m, d->x, b, at_b, cb);
  sw_v3_sub(rel, ca, cb);
  const double reln = sw_v3_dot(rel, n);
  sw_v3_scale(off, n, -a->radius);
  sw_side_arm(m, d, a, off, ya);
  for (int q = 0; q < 3; q++) off[q] = b->radius * n[q] + rel[q] - reln * n[q] - stretch[q];
  sw_side_arm(m, d, b, off, yb);
  if (!stuck) {
    sw_side_point(m, d, a, at_a, ya, pa, va);
    sw_side_point(m, d, b, at_b, yb, pb, vb);
  }
  double *out = sum->anchor + SW_CONTACT_ANCHOR_ROW * sum->rows++;
  out[0] = key, out[1] = at_a, out[2] = at_b;
  memcpy(out + 3, ya, sizeof ya);
  memcpy(out + 6, yb, sizeof yb);
  out[9] = stuck;
  if (stuck) sum->stuck++;
  else sum->slipping++;
  return 1;
}

static void pair_contact(const swModel *m, const swData *d, const swContactDesc *cd, int ra,
                         int rb, Sums *sum) {
  const int ea = m->contact_elem[ra], eb = m->contact_elem[rb];
  const int rod_a = m->contact_rod[ra], rod_b = m->contact_rod[rb];
  const int ia = m->node_adr[rod_a] + (ea - m->elem_adr[rod_a]);
  const int ib = m->node_adr[rod_b] + (eb - m->elem_adr[rod_b]);
  const double rsum = d->radius_now[ea] + d->radius_now[eb];
  if (rod_a == rod_b) {
    double gap = ra < rb ? m->contact_arc[rb] - m->contact_arc[ra] - m->rest_len[ea]
                         : m->contact_arc[ra] - m->contact_arc[rb] - m->rest_len[eb];
    if (!cd->self || gap < 0.5 * SW_PI * rsum) return;
  }
  double a0[3], a1[3], b0[3], b1[3];
  sw_get3(m, d->x, ia, a0);
  sw_get3(m, d->x, ia + 1, a1);
  sw_get3(m, d->x, ib, b0);
  sw_get3(m, d->x, ib + 1, b1);
  double da[3], db[3], pq[3], n[3], s, t;
  sw_v3_sub(da, a1, a0);
  sw_v3_sub(db, b1, b0);
  /* the midpoints are within half of each length plus the radii, or no
   * points are within the radii */
  double mid[3], reach = 0.5 * (sw_v3_norm(da) + sw_v3_norm(db)) + rsum;
  for (int k = 0; k < 3; k++) mid[k] = 0.5 * (a0[k] + a1[k] - b0[k] - b1[k]);
  if (sw_v3_dot(mid, mid) > reach * reach) return;
  const double dist2 = sw_segment_closest(a0, da, b0, db, &s, &t, pq);
  if (!(dist2 < rsum * rsum)) return;
  const double dist = sqrt(dist2), delta = rsum - dist;
  if (dist > 0) sw_v3_scale(n, pq, 1.0 / dist);
  else crossing_normal(n, da, db);
  sum->energy += 0.5 * cd->stiffness * delta * delta;
  sum->pairs++;
  if (delta > sum->max_overlap) sum->max_overlap = delta;
  if (!sum->force) return;
  /* approach speed of the contact points, > 0 when they close in */
  double va0[3], va1[3], vb0[3], vb1[3];
  sw_get3(m, d->v, ia, va0);
  sw_get3(m, d->v, ia + 1, va1);
  sw_get3(m, d->v, ib, vb0);
  sw_get3(m, d->v, ib + 1, vb1);
  double approach = 0;
  for (int k = 0; k < 3; k++)
    approach -= ((1 - s) * va0[k] + s * va1[k] - (1 - t) * vb0[k] - t * vb1[k]) * n[k];
  const double spring = cd->stiffness * delta;
  const double damper = fmax(cd->damping * approach, -spring); /* never attractive */
  const double w[4] = {1 - s, s, -(1 - t), -t};
  const int node[4] = {ia, ia + 1, ib, ib + 1};
  for (int j = 0; j < 4; j++)
    for (int k = 0; k < 3; k++) {
      SW_AT(m, sum->force, node[j], k) += w[j] * (spring + damper) * n[k];
      SW_AT(m, sum->ext_force, node[j], k) += w[j] * damper * n[k];
    }
  /* friction: the side of the lower row first, so that a pair's anchor is
   * the same whichever way the broad phase met it; n from its partner to it */
  Side sa = {ia, ea, s, d->radius_now[ea], 0, {0, 0, 0}};
  Side sb = {ib, eb, t, d->radius_now[eb], 0, {0, 0, 0}};
  const int lower = ra < rb;
  const double nrows = m->contact_row_adr[m->ncontact];
  const double key = lower ? ra * nrows + rb : rb * nrows + ra;
  Side *first = lower ? &sa : &sb, *second = lower ? &sb : &sa;
  double nf[3], F[3], G[3];
  sw_v3_scale(nf, n, lower ? 1.0 : -1.0);
  if (!friction_force(m, d, cd, key, first, second, nf, spring + damper, sum, F)) return;
  sw_v3_scale(G, F, -1.0);
  sw_side_apply(m, d, first, F, sum->force, sum->ext_force, sum->torque, sum->ext_torque);
  sw_side_apply(m, d, second, G, sum->force, sum->ext_force, sum->torque, sum->ext_torque);
}

/* ---- broad phase ---- */

/* Cell coordinates of a point, clamped so that the int conversion is
 * defined even for a run that is blowing up (stability.c reports it). */
static int cell_of(double x, double inv_h) {
  double c = floor(x * inv_h);
  if (!(c > -1e9)) return -1000000000; /* NaN too */
  return c < 1e9 ? (int)c : 1000000000;
}

static int bucket_of(const int *cell, int mask) {
  unsigned h = (unsigned)cell[0] * 73856093u ^ (unsigned)cell[1] * 19349663u ^
               (unsigned)cell[2] * 83492791u; /* Teschner et al. 2003, spatial hashing */
  return (int)(h & (unsigned)mask);
}

/* The 13 cells of one half of the neighbourhood (offsets whose first
 * nonzero coordinate is positive). */
static const int HALF[13][3] = {{1, -1, -1}, {1, -1, 0}, {1, -1, 1}, {1, 0, -1}, {1, 0, 0},
                                {1, 0, 1},   {1, 1, -1}, {1, 1, 0},  {1, 1, 1},  {0, 1, -1},
                                {0, 1, 0},   {0, 1, 1},  {0, 0, 1}};

static void grid_pairs(const swModel *m, const swData *d, int c, Sums *sum) {
  const int r0 = m->contact_row_adr[c], nrow = m->contact_row_adr[c + 1] - r0;
  const int nb = m->contact_nbucket, mask = nb - 1;
  double longest2 = 0, widest = 0; /* from the positions: valid whoever calls */
  for (int i = 0; i < nrow; i++) {
    int row = r0 + i, e = m->contact_elem[row], rod = m->contact_rod[row];
    const int a = m->node_adr[rod] + (e - m->elem_adr[rod]);
    double xa[3], xb[3], dx[3];
    sw_get3(m, d->x, a, xa);
    sw_get3(m, d->x, a + 1, xb);
    sw_v3_sub(dx, xb, xa);
    longest2 = sw_max(sw_v3_dot(dx, dx), longest2); /* vec.h: not fmax */
    widest = sw_max(d->radius_now[e], widest);
  }
  const double longest = sqrt(longest2);
  const double h = longest + 2 * widest;
  if (!(h > 0)) return;
  const double inv_h = 1.0 / h;
  int *cell = d->contact_cell, *bucket = d->contact_bucket, *sorted = d->contact_sorted;
  int *start = d->contact_start, *sorted_cell = d->contact_sorted_cell;
  unsigned long long *occupied = d->contact_occupied;
  memset(start, 0, sizeof(int) * ((size_t)nb + 1));
  memset(occupied, 0, sizeof(unsigned long long) * ((size_t)nb / 64 + 1));
  for (int i = 0; i < nrow; i++) {
    int row = r0 + i, e = m->contact_elem[row], rod = m->contact_rod[row];
    const int a = m->node_adr[rod] + (e - m->elem_adr[rod]);
    for (int k = 0; k < 3; k++)
      cell[3 * i + k] = cell_of(0.5 * (SW_AT(m, d->x, a, k) + SW_AT(m, d->x, a + 1, k)), inv_h);
    bucket[i] = bucket_of(cell + 3 * i, mask);
    start[bucket[i] + 1]++;
    occupied[bucket[i] >> 6] |= (unsigned long long)1 << (bucket[i] & 63);
  }
  for (int b = 0; b < nb; b++) start[b + 1] += start[b];
  for (int i = 0; i < nrow; i++) { /* start[b] ends at b+1's */
    int q = start[bucket[i]]++;
    sorted[q] = i;
    memcpy(sorted_cell + 3 * q, cell + 3 * i, 3 * sizeof(int)); /* a bucket's cells together */
  }
  for (int b = nb; b > 0; b--) start[b] = start[b - 1];
  start[0] = 0;
  for (int i = 0; i < nrow; i++) {
    const int *ci = cell + 3 * i;
    for (int o = -1; o < 13; o++) {
      int cj[3];
      for (int k = 0; k < 3; k++) cj[k] = ci[k] + (o < 0 ? 0 : HALF[o][k]);
      int b = o < 0 ? bucket[i] : bucket_of(cj, mask);
      if (!(occupied[b >> 6] >> (b & 63) & 1)) continue; /* most are empty: no cache miss */
      for (int q = start[b]; q < start[b + 1]; q++) {
        const int *cq = sorted_cell + 3 * q;
        if (cq[0] != cj[0] || cq[1] != cj[1] || cq[2] != cj[2]) continue; /* a hash collision */
        int j = sorted[q];
        if (o < 0 && j <= i) continue; /* own cell: partners after it */
        pair_contact(m, d, &m->contact[c], r0 + i, r0 + j, sum);
      }
    }
  }
}

static void brute_pairs(const swModel *m, const swData *d, int c, Sums *sum) {
  const int r0 = m->contact_row_adr[c], r1 = m->contact_row_adr[c + 1];
  for (int i = r0; i < r1; i++)
    for (int j = i + 1; j < r1; j++) pair_contact(m, d, &m->contact[c], i, j, sum);
}

/* ---- the kernels ---- */

void sw_contact_loads_with(const swModel *m, swData *d, swContactPhase phase) {
  Sums sum;
  memset(&sum, 0, sizeof sum);
  sum.force = d->force, sum.ext_force = d->ext_force;
  sum.torque = d->torque, sum.ext_torque = d->ext_torque;
  if (m->contact_maxanchor) {
    /* the last evaluation's anchors become the old ones, found by bisection */
    double *old = d->contact_anchor;
    d->contact_anchor = d->contact_anchor_old;
    d->contact_anchor_old = old;
    sum.old = old + 1, sum.old_rows = (int)old[0];
    sum.anchor = d->contact_anchor + 1, sum.room = m->contact_maxanchor;
  }
  for (int c = 0; c < m->ncontact; c++) {
    if (phase == SW_CONTACT_BRUTE) brute_pairs(m, d, c, &sum);
    else grid_pairs(m, d, c, &sum);
  }
  if (m->contact_maxanchor) {
    sw_anchor_sort(sum.anchor, sum.rows, SW_CONTACT_ANCHOR_ROW);
    d->contact_anchor[0] = sum.rows;
  }
  d->contact_pairs = sum.pairs;
  d->contact_max_overlap = sum.max_overlap;
  d->contact_stuck = sum.stuck;
  d->contact_slipping = sum.slipping;
  d->friction_full += sum.full;
}

void sw_contact_loads(const swModel *m, swData *d) { sw_contact_loads_with(m, d, SW_CONTACT_GRID); }

/* The energy of the contact springs at the current positions.  The grid's
 * scratch is written through the state's pointers (its contents are not
 * part of the state). */
double sw_contact_energy(const swModel *m, const swData *d) {
  Sums sum;
  memset(&sum, 0, sizeof sum);
  for (int c = 0; c < m->ncontact; c++) grid_pairs(m, d, c, &sum);
  return sum.energy;
}

/* Node i of a contact's rod is pressed by at most 3 pairs with full weight
 * from a neighbouring rod lying along it (docs/physics.md, "Rod-rod
 * contact"), each a spring k_c to a node that moves too: with the rod's own
 * transverse row (joint_node_dt in stability.c), Gershgorin gives
 *   w^2 = (2 sum_elements max(EA, 4GA/3) / l + 2 * 3 k_c) / m_i,
 * and the damper the rate c = 2 * 3 gamma_c / m_i.  With friction k_c is
 * max(k_c, k_t): the tangential spring presses the same nodes across the
 * normal one, and its couples turn an element no faster (w^2 <= 4 k_t / m_e). */
double sw_contact_stable_dt(const swModel *m) {
  double dt = INFINITY;
  for (int c = 0; c < m->ncontact; c++) {
    const swContactDesc *cd = &m->contact[c];
    /* the tangential spring acts across the normal one: the larger counts */
    const double stiff = cd->static_friction > 0 ? fmax(cd->stiffness, cd->tangential_stiffness) : cd->stiffness;
    for (int row = m->contact_row_adr[c]; row < m->contact_row_adr[c + 1]; row++) {
      int e = m->contact_elem[row], rod = m->contact_rod[row];
      int i = m->node_adr[rod] + (e - m->elem_adr[rod]); /* the element's first node */
      for (int side = 0; side < 2; side++) {
        int node = i + side;
        double ksum = 0;
        if (!sw_rod_is_rigid(m, rod)) {
          int first = m->elem_adr[rod], last = first + m->rod_nelem[rod];
          for (int q = e - 1 + side; q <= e + side; q++) { /* the node's elements */
            if (q < first || q >= last) continue;
            ksum += fmax(SW_AT(m, m->shear_stiff, q, 2), SW_AT(m, m->shear_stiff, q, 0)) *
                    m->inv_rest_len[q];
          }
        }
        double w = sqrt((2 * ksum + 6 * stiff) * m->inv_mass[node]);
        double rate = 6 * cd->damping * m->inv_mass[node];
        if (m->rod_damping[rod] == SW_DAMP_LINEAR) rate += m->node_gamma[node] * m->inv_mass[node];
        dt = fmin(dt, 0.95 * sw_integrator_stability_limit(m->integrator, rate / (2 * w)) / w);
      }
    }
  }
  return dt;
}
