/* obstacle.c — rigid obstacles: spheres, capsules, infinite cylinders, boxes
 * and ellipsoids, fixed in the lab or carried by a rod element (a bone),
 * pushing back the elements of rods that touch them.
 *
 * Design.  Each element is the segment a0..a1 between its nodes, a capsule
 * of radius r around it (as in contact.c), so a thin rod cannot slip
 * between two nodes through a small obstacle.  The narrow phase works in
 * the shape's own frame (centre c, orthonormal axes e1 = normal, e2 =
 * axis x normal, e3 = axis; a point y is q_k = e_k . (y - c)): it finds the
 * point p = a0 + s (a1 - a0), s in [0, 1], of the segment whose signed
 * distance D to the shape's surface is least, and the outward unit normal n
 * of the surface there.  The element touches when its penetration
 * p_e = r - D > 0, and stores U = k p_e^2 / 2.  Because s minimises D,
 * dD/da0 = (1 - s) n and dD/da1 = s n (Danskin's theorem, as in contact.c),
 * so the spring's force k p_e n split (1 - s, s) over the two nodes is the
 * exact gradient of U: with damping 0 the contact is conservative, and U is
 * reported with the elastic energy (sw_obstacle_energy), as the ground's
 * penalty is.  The damper adds gamma times the approach speed of p and the
 * obstacle's material point there, never letting the normal force pull:
 * max(gamma approach, -k p_e), into ext_force as well, so the kick books the
 * energy it takes (as the ground and rod-rod contact do).
 *
 * The distance per shape (docs/physics.md, "Rigid obstacles"):
 *  - sphere (radius R): p is the point of the segment nearest to c (the
 *    projection of c, clamped), D = |q| - R, n = q / |q|;
 *  - infinite cylinder (radius R along e3): the segment's point nearest to
 *    the axis line, from the segment's part across the axis (q1, q2),
 *    D = |(q1, q2)| - R, n = (q1, q2, 0) / |.|; parallel to the axis: the
 *    middle of the element;
 *  - capsule (radius R around the axis segment from -L/2 to L/2 along e3):
 *    the closest points of two segments (Ericson 2005, sec. 5.1.9,
 *    contact.c's sw_segment_closest), D = |p - q_axis| - R;
 *  - box (half sizes h): the signed distance of a point to a box (Quilez,
 *    "distance functions": outside |max(|q| - h, 0)|, inside
 *    max_k(|q_k| - h_k)), n its gradient;
 *  - ellipsoid (semi-axes a): the closest surface point by Eberly's
 *    bisection on the Lagrange multiplier ("Distance from a point to an
 *    ellipse, an ellipsoid, or a hyperellipsoid", Geometric Tools 2013),
 *    n = (x_k / a_k^2) normalised at that point.
 * For the box and the ellipsoid the distance along the segment, a convex
 * function of s (the signed distance to a convex body is convex), is
 * minimised by golden-section search to 1e-12 of the segment; an element
 * that meets it equally at both ends (lying along a face) takes its middle,
 * the ground's point for the same plane.
 *
 * A carried obstacle's centre and axes live in the material frame of its
 * carrier element, the centre measured from the carrier node (a joint's arm,
 * joint.c): at time t, c = x_node + Q^T o and e_k = Q^T e_k^mat.  It takes
 * the opposite of each contact force, at the node, with the couple
 * (p - x_node) x (-f) on the element (in its material frame): force and
 * couple about any point balance those on the rods, and both are the
 * gradient of U in the carrier's position and rotation, so the pair stays
 * conservative.  Its material point at p moves at v_node + w x (p - x_node).
 *
 * Friction (mu_s > 0): an elastic-Coulomb law with a spring anchor, the
 * tangential "spring and slider" of Cundall & Strack, Geotechnique 29 (1979)
 * 47, eqs. 5-7, as DEM codes (LIGGGHTS' tangential_history) keep it, with
 * anchors at the touching surfaces as rod-rod contact has them (contact.c;
 * friction.c holds what both use).  When element e first touches obstacle
 * k, the pair records its anchor: on the rod the touching surface point,
 * the centreline point s0 = s plus the arm -r n kept in the element's
 * material frame (so it moves, turns and rolls with the element); on the
 * obstacle its touching surface point p - D n, y0 in the obstacle's frame
 * (so it moves with a carried obstacle).  At each evaluation the two
 * anchors' separation u = p_a - p_o and relative velocity w (v_s + omega x
 * arm on the rod), their tangential parts u_t = u - (u.n) n, w_t, give the
 * trial force
 *   F = -k_t u_t - gamma w_t.
 * If |F| <= mu_s N (N the normal force, spring plus damper) the contact is
 * stuck; otherwise it slips and F becomes mu_k N F / |F| (friction.c's
 * sw_coulomb_cap).  F acts on the rod at its anchor, split (1 - s0, s0)
 * over the nodes with the couple arm x F on the element; a carried obstacle
 * takes -F at its node and (p_a - x_node) x (-F) on its element, so force
 * and moment balance exactly.  The pair is then re-anchored at the touching
 * surface points of the current closest point with the spring's tangential
 * stretch kept: u_t while stuck (the rod's place s0 kept), -F / k_t when
 * slipping (the place moved to s, and F applied at the new anchor), so that
 * the spring alone gives F.  A constant load thus finds a static
 * equilibrium (the spring holds exactly, no creep), a stuck rod rolls as a
 * cylinder should (its anchor stays where it touches instead of riding up
 * its side, which the spring, blind to u . n, would let it do), and since
 * the anchors are apart only by the depth along n, the law is passive (the
 * part of the energy's change that holding n misses is proportional to
 * u . n).  Anchored on the centreline instead, the friction tied the rod's
 * axis to the obstacle: a rod could not roll (test_obstacle_roll).  The
 * whole tangential force and its couples go into ext_force, ext_torque as
 * well, so the kick books their work (the spring's stored energy and what
 * slip dissipates) as external work, as ground.c books its friction:
 * kinetic + elastic - work stays constant.  Anchors live in
 * d->obstacle_anchor, a table of rows (key, s0, arm, y0, stuck) ordered by
 * the key (obstacle, place of the element in the obstacle's rod list),
 * rebuilt at each evaluation by a merge with the previous one (no
 * allocation, no search); a pair that stops touching loses its anchor.
 * The table holds obstacle_maxcontact rows; contacts beyond it (never with
 * the default room, one row per listed element up to 4 per element of the
 * model) are frictionless, counted in d->friction_full, of which the run
 * warns.  The table is state: checkpoints save it.
 *
 * Broad phase.  Rods are cut into chunks of SW_OBSTACLE_CHUNK elements,
 * whose boxes (nodes +- the largest radius) and each rod's box (their
 * union) are taken once per evaluation; an obstacle's lab box (its frame
 * box turned into the lab: centre +- sum_k |e_k| h_k; unbounded along a
 * cylinder's axis) is tested against the box of each of its rods, then of
 * the chunks of a rod it overlaps, and only the elements of chunks that
 * overlap it reach the narrow phase.  The cost is obstacles x rods box
 * tests, chunks of the rods near an obstacle, and the elements near it
 * (bench/bench_obstacle.c).  Nothing is allocated
 * in the step; the brute force loop over all pairs is kept for tests and
 * the benchmark (SW_OBSTACLE_BRUTE).
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "sinew.h"
#include "vec.h"
#include "internal.h"

/* ---- setup ---- */

/* Unit e3 along axis, e1 the part of normal across it (or any normal to
 * it), e2 = e3 x e1: rows of E. */
static void frame_of(const swObstacleDesc *o, double E[9]) {
  double e3[3], e1[3], e2[3];
  sw_v3_scale(e3, o->axis, 1.0 / sw_v3_norm(o->axis));
  double along = sw_v3_dot(o->normal, e3);
  for (int k = 0; k < 3; k++) e1[k] = o->normal[k] - along * e3[k];
  if (!(sw_v3_norm(e1) > 1e-9 * sw_v3_norm(o->normal))) {
    const double ex[3] = {1, 0, 0}, ey[3] = {0, 1, 0};
    sw_v3_cross(e1, e3, fabs(e3[0]) < 0.9 ? ex : ey);
  }
  sw_v3_scale(e1, e1, 1.0 / sw_v3_norm(e1));
  sw_v3_cross(e2, e3, e1);
  memcpy(E, e1, sizeof e1);
  memcpy(E + 3, e2, sizeof e2);
  memcpy(E + 6, e3, sizeof e3);
}

int sw_obstacle_setup(swModel *m) {
  const int K = m->nobstacle;
  size_t k1 = (size_t)(K ? K : 1);
  m->obstacle_node = calloc(k1, sizeof(int));
  m->obstacle_elem = calloc(k1, sizeof(int));
  m->obstacle_arm = calloc(3 * k1, sizeof(double));
  m->obstacle_axes = calloc(9 * k1, sizeof(double));
  m->obstacle_extent = calloc(3 * k1, sizeof(double));
  m->obstacle_chunk_adr = calloc((size_t)m->nrod + 1, sizeof(int));
  if (!m->obstacle_node || !m->obstacle_elem || !m->obstacle_arm || !m->obstacle_axes ||
      !m->obstacle_extent || !m->obstacle_chunk_adr)
    return 0;
  long listed = 0;
  for (int k = 0; k < K; k++) {
    const swObstacleDesc *o = &m->obstacle[k];
    double E[9], *ext = m->obstacle_extent + 3 * k;
    frame_of(o, E);
    switch (o->shape) {
    case SW_OBSTACLE_SPHERE: ext[0] = ext[1] = ext[2] = o->radius; break;
    case SW_OBSTACLE_CAPSULE: ext[0] = ext[1] = o->radius, ext[2] = 0.5 * o->length + o->radius; break;
    case SW_OBSTACLE_CYLINDER: ext[0] = ext[1] = o->radius, ext[2] = INFINITY; break;
    default: memcpy(ext, o->half, 3 * sizeof(double)); break;
    }
    m->obstacle_node[k] = m->obstacle_elem[k] = -1;
    if (o->carrier_rod >= 0) {
      /* in the carrier element's material frame at t = 0: o = Q0 (c - x0) */
      const int r = o->carrier_rod, n = m->rod_nelem[r];
      const int node = o->carrier_node < 0 ? n : o->carrier_node;
      const int slot = m->node_adr[r] + node, e = m->elem_adr[r] + (node < n ? node : n - 1);
      double Q0[9], x0[3], rel[3];
      sw_getQ(m, m->Q0, e, Q0);
      sw_get3(m, m->x0, slot, x0);
      sw_v3_sub(rel, o->centre, x0);
      sw_mat_vec(m->obstacle_arm + 3 * k, Q0, rel);
      for (int a = 0; a < 3; a++) sw_mat_vec(m->obstacle_axes + 9 * k + 3 * a, Q0, E + 3 * a);
      m->obstacle_node[k] = slot;
      m->obstacle_elem[k] = e;
    } else {
      memcpy(m->obstacle_arm + 3 * k, o->centre, 3 * sizeof(double));
      memcpy(m->obstacle_axes + 9 * k, E, sizeof E);
    }
    for (int j = 0; j < o->nrods; j++) listed += m->rod_nelem[o->rods[j]];
  }
  int chunks = 0;
  for (int r = 0; r < m->nrod; r++) {
    m->obstacle_chunk_adr[r] = chunks;
    chunks += (m->rod_nelem[r] + SW_OBSTACLE_CHUNK - 1) / SW_OBSTACLE_CHUNK;
  }
  m->obstacle_chunk_adr[m->nrod] = chunks;
  m->obstacle_nchunk = chunks;
  /* records: every listed element once in contact, at most four each */
  long room = 4L * m->nelem + 64;
  m->obstacle_maxcontact = (int)(listed < room ? listed : room);
  return 1;
}

void sw_obstacle_free(swModel *m) {
  free(m->obstacle_node);
  free(m->obstacle_elem);
  free(m->obstacle_arm);
  free(m->obstacle_axes);
  free(m->obstacle_extent);
  free(m->obstacle_chunk_adr);
  m->obstacle_node = m->obstacle_elem = m->obstacle_chunk_adr = NULL;
  m->obstacle_arm = m->obstacle_axes = m->obstacle_extent = NULL;
}

int sw_obstacle_data_new(const swModel *m, swData *d) {
  if (!m->nobstacle) return 1;
  d->obstacle_contact = calloc((size_t)(m->obstacle_maxcontact ? m->obstacle_maxcontact : 1),
                               sizeof *d->obstacle_contact);
  d->obstacle_box = calloc(6 * ((size_t)m->obstacle_nchunk + (size_t)m->nrod + 1), sizeof(double));
  const size_t anchors = 1 + (size_t)m->obstacle_maxcontact * SW_OBSTACLE_ANCHOR_ROW;
  d->obstacle_anchor = calloc(anchors, sizeof(double));
  d->obstacle_anchor_old = calloc(anchors, sizeof(double));
  return d->obstacle_contact && d->obstacle_box && d->obstacle_anchor && d->obstacle_anchor_old;
}

/* ---- where an obstacle is ---- */

typedef struct {
  double c[3], E[9];  /* centre and axis rows, lab                         */
  double v[3], w[3];  /* velocity of the centre and angular velocity, lab  */
  double anchor[3];   /* the carrier node (carried only)                   */
  int carried;
} swPose;

/* Obstacle k's pose in the state x, Q (and v, omega when not NULL). */
static swPose pose_of(const swModel *m, const double *x, const double *v, const double *Q,
                      const double *omega, int k) {
  swPose P;
  memset(&P, 0, sizeof P);
  const double *arm = m->obstacle_arm + 3 * k, *axes = m->obstacle_axes + 9 * k;
  if (m->obstacle_node[k] < 0) {
    memcpy(P.c, arm, sizeof P.c);
    memcpy(P.E, axes, sizeof P.E);
    return P;
  }
  const int node = m->obstacle_node[k], e = m->obstacle_elem[k];
  double Qe[9], r[3];
  sw_getQ(m, Q, e, Qe);
  sw_get3(m, x, node, P.anchor);
  sw_matT_vec(r, Qe, arm);
  sw_v3_add(P.c, P.anchor, r);
  for (int a = 0; a < 3; a++) sw_matT_vec(P.E + 3 * a, Qe, axes + 3 * a);
  if (v) {
    double wm[3], wr[3];
    sw_get3(m, omega, e, wm);
    sw_matT_vec(P.w, Qe, wm);
    sw_get3(m, v, node, P.v);
    sw_v3_cross(wr, P.w, r);
    sw_v3_add(P.v, P.v, wr);
  }
  P.carried = 1;
  return P;
}

static void to_local(double q[3], const swPose *P, const double y[3]) {
  double rel[3];
  sw_v3_sub(rel, y, P->c);
  for (int k = 0; k < 3; k++) q[k] = sw_v3_dot(P->E + 3 * k, rel);
}

/* The narrow phase, the signed distance of a segment to each shape, is
 * obstacle_shape.c's sw_obstacle_segment_distance. */

/* ---- one element against one obstacle ---- */

typedef struct {
  double *force, *ext_force, *torque, *ext_torque; /* NULL: energy only */
  swObstacleContact *rec;
  int room;
  double energy, max_depth;
  int contacts;
  long tests;
  /* friction: the previous anchors (old, rows), the cursor in them, the
   * new table (rows written), the pair's key, the stuck and slipping */
  const double *old;
  int old_rows, cursor;
  double *anchor;
  int rows;
  double key;
  int stuck, slipping, full; /* full: contacts beyond the table */
} Sums;

/* ---- friction: the anchor of a touching pair (see the design) ---- */

/* The tangential force F on the rod's side `rod` of the pair sum->key,
 * touching obstacle k at pose P: the element's centreline point p at s,
 * distance D from the surface, normal n, normal force N.  The rod's anchor
 * is left in `rod` (place and arm, for sw_side_apply), the pair's new
 * anchor row appended to sum->anchor, its record (when kept) filled.
 * Returns 0 without friction. */
static int friction_force(const swModel *m, const swData *d, int k, const swPose *P,
                          swFrictionSide *rod, const double p[3], double D, const double n[3],
                          double N, Sums *sum, double F[3], swObstacleContact *rec) {
  const swObstacleDesc *o = &m->obstacle[k];
  if (!(o->static_friction > 0) || !sum->anchor) return 0;
  if (sum->rows >= m->obstacle_maxcontact) { /* beyond the table: frictionless, counted */
    sum->full++;
    return 0;
  }
  /* the previous anchor of this pair (rows ordered by key) or a new one:
   * the two touching surface points, the rod's p - r n (its arm -r n) and
   * the obstacle's p - D n */
  while (sum->cursor < sum->old_rows && sum->old[SW_OBSTACLE_ANCHOR_ROW * sum->cursor] < sum->key)
    sum->cursor++;
  const double *row = sum->old + SW_OBSTACLE_ANCHOR_ROW * sum->cursor;
  const int known = sum->cursor < sum->old_rows && row[0] == sum->key;
  double ya[3], y0[3], off[3], po[3];
  if (known) {
    memcpy(ya, row + 2, sizeof ya);
    memcpy(y0, row + 5, sizeof y0);
  } else {
    sw_v3_scale(off, n, -rod->radius);
    sw_side_arm(m, d, rod, off, ya);
    for (int q = 0; q < 3; q++) po[q] = p[q] - D * n[q];
    to_local(y0, P, po);
  }
  /* the two material points, their separation and relative velocity,
   * tangential parts */
  double pa[3], va[3], u[3], w[3], vo[3] = {0, 0, 0};
  sw_side_point(m, d, rod, known ? row[1] : rod->at, ya, pa, va);
  for (int q = 0; q < 3; q++) po[q] = P->c[q];
  for (int j = 0; j < 3; j++)
    for (int q = 0; q < 3; q++) po[q] += y0[j] * P->E[3 * j + q];
  if (P->carried) {
    double rel[3];
    sw_v3_sub(rel, po, P->c);
    sw_v3_cross(vo, P->w, rel);
    sw_v3_add(vo, vo, P->v);
  }
  for (int q = 0; q < 3; q++) u[q] = pa[q] - po[q], w[q] = va[q] - vo[q];
  const double un = sw_v3_dot(u, n), wn = sw_v3_dot(w, n);
  for (int q = 0; q < 3; q++) u[q] -= un * n[q], w[q] -= wn * n[q];
  const double kt = o->tangential_stiffness > 0 ? o->tangential_stiffness : o->stiffness;
  /* Coulomb's cap (friction.c): stuck below mu_s N, else slipping at mu_k N */
  const int stuck = sw_coulomb_cap(u, w, kt, o->damping, o->static_friction, o->kinetic_friction, N, F);
  /* re-anchored at the touching surface points (friction.c), the rod's
   * place kept while stuck, the spring's tangential stretch kept, the
   * obstacle's point moved by it: a stuck rod that rolls keeps its anchor
   * where it touches instead of carrying it up its side.  F acts at the
   * anchor it came from while stuck, at the new one when slipping. */
  double stretch[3], ya_new[3];
  const double at = sw_friction_reanchor(rod, stuck, u, F, kt, stretch);
  sw_v3_scale(off, n, -rod->radius);
  sw_side_arm(m, d, rod, off, ya_new);
  sw_side_centre(m, d->x, rod, at, po);
  for (int q = 0; q < 3; q++) po[q] -= D * n[q] + stretch[q];
  to_local(y0, P, po);
  if (!stuck) sw_side_point(m, d, rod, at, ya_new, pa, va);
  double *out = sum->anchor + SW_OBSTACLE_ANCHOR_ROW * sum->rows++;
  out[0] = sum->key;
  out[1] = at;
  memcpy(out + 2, ya_new, sizeof ya_new);
  memcpy(out + 5, y0, sizeof y0);
  out[8] = stuck;
  if (stuck) sum->stuck++;
  else sum->slipping++;
  if (rec) {
    memcpy(rec->anchor, y0, sizeof y0);
    rec->s_anchor = at;
    memcpy(rec->friction, F, 3 * sizeof(double));
    rec->stuck = stuck;
  }
  return 1;
}

/* A carried obstacle's share of a force f on the rod at the point pt (its
 * part fe external): -f at its node, the couple (pt - x_node) x (-f) on its
 * element (material frame). */
static void carrier_takes(const swModel *m, const swData *d, int k, const swPose *P, const double pt[3],
                          const double f[3], const double fe[3], Sums *sum) {
  const int node = m->obstacle_node[k], ec = m->obstacle_elem[k];
  double lever[3], c[3], ce[3], Q[9], cm[3], cem[3];
  sw_v3_sub(lever, pt, P->anchor);
  sw_v3_cross(c, f, lever); /* (pt - x_node) x (-f) */
  sw_v3_cross(ce, fe, lever);
  sw_getQ(m, d->Q, ec, Q);
  sw_mat_vec(cm, Q, c);
  sw_mat_vec(cem, Q, ce);
  for (int q = 0; q < 3; q++) {
    SW_AT(m, sum->force, node, q) -= f[q];
    SW_AT(m, sum->ext_force, node, q) -= fe[q];
    SW_AT(m, sum->torque, ec, q) += cm[q];
    SW_AT(m, sum->ext_torque, ec, q) += cem[q];
  }
}

/* A contact force a dir on the element of nodes ia, ia + 1, at the point
 * pt = a0 + s (a1 - a0), split (1 - s, s); its part b dir external too (the
 * kick books its work); a carried obstacle takes the opposite at its node
 * and its couple (pt - x_node) x (-a dir) on its element. */
static void apply(const swModel *m, const swData *d, int k, const swPose *P, int ia, double s,
                  const double pt[3], const double dir[3], double a, double b, Sums *sum) {
  const double w[2] = {1 - s, s};
  for (int j = 0; j < 2; j++)
    for (int q = 0; q < 3; q++) {
      SW_AT(m, sum->force, ia + j, q) += w[j] * a * dir[q];
      SW_AT(m, sum->ext_force, ia + j, q) += w[j] * b * dir[q];
    }
  if (!P->carried) return;
  double f[3], fe[3];
  sw_v3_scale(f, dir, a);
  sw_v3_scale(fe, dir, b);
  carrier_takes(m, d, k, P, pt, f, fe, sum);
}

/* Element i (nodes ia, ia + 1, element slot e) of a rod against obstacle k
 * at pose P: the loads on both sides (when sum->force), the energy. */
static void element_contact(const swModel *m, const swData *d, int k, const swPose *P, int ia, int e,
                            Sums *sum) {
  const swObstacleDesc *o = &m->obstacle[k];
  sum->tests++;
  double x0[3], x1[3], a[3], b[3], dl[3];
  sw_get3(m, d->x, ia, x0);
  sw_get3(m, d->x, ia + 1, x1);
  to_local(a, P, x0);
  to_local(b, P, x1);
  sw_v3_sub(dl, b, a);
  const double r = d->radius_now[e];
  /* the shape lies within its frame box, which the element's ball about
   * its middle must reach (a cylinder: across its axis only) */
  const double *ext = m->obstacle_extent + 3 * k, half = 0.5 * sw_v3_norm(dl) + r;
  for (int j = 0; j < 3; j++)
    if (fabs(0.5 * (a[j] + b[j])) > ext[j] + half) return;
  double s = r, nl[3];
  const double D = sw_obstacle_segment_distance(o, a, dl, &s, nl);
  const double depth = r - D;
  if (!(depth > 0)) return;
  sum->energy += 0.5 * o->stiffness * depth * depth;
  if (depth > sum->max_depth) sum->max_depth = depth;
  sum->contacts++;
  if (!sum->force) return;
  double n[3] = {0, 0, 0}, p[3];
  for (int j = 0; j < 3; j++)
    for (int q = 0; q < 3; q++) n[q] += nl[j] * P->E[3 * j + q];
  for (int q = 0; q < 3; q++) p[q] = x0[q] + s * (x1[q] - x0[q]);
  /* approach speed of the element's point and the obstacle's point at p */
  double v0[3], v1[3], vo[3] = {0, 0, 0};
  sw_get3(m, d->v, ia, v0);
  sw_get3(m, d->v, ia + 1, v1);
  if (P->carried) {
    double rel[3];
    sw_v3_sub(rel, p, P->c);
    sw_v3_cross(vo, P->w, rel);
    sw_v3_add(vo, vo, P->v);
  }
  double approach = 0;
  for (int q = 0; q < 3; q++) approach -= ((1 - s) * v0[q] + s * v1[q] - vo[q]) * n[q];
  const double spring = o->stiffness * depth;
  const double damper = fmax(o->damping * approach, -spring); /* never pulls */
  apply(m, d, k, P, ia, s, p, n, spring + damper, damper, sum);
  swObstacleContact *rec = NULL;
  if (sum->contacts <= sum->room) {
    rec = &sum->rec[sum->contacts - 1];
    memset(rec, 0, sizeof *rec);
    rec->obstacle = k;
    rec->elem = e;
    rec->s = s;
    rec->depth = depth;
    memcpy(rec->normal, n, sizeof n);
    rec->force = spring + damper;
  }
  /* friction at the touching surfaces: F on the rod at its anchor (with
   * its couple), -F on a carried obstacle there */
  swFrictionSide side = {ia, e, s, r, s, {0, 0, 0}};
  double F[3];
  if (friction_force(m, d, k, P, &side, p, D, n, spring + damper, sum, F, rec)) {
    sw_side_apply(m, d, &side, F, sum->force, sum->ext_force, sum->torque, sum->ext_torque);
    if (P->carried) {
      double pa[3];
      sw_side_centre(m, d->x, &side, side.anchor_at, pa);
      sw_v3_add(pa, pa, side.arm);
      carrier_takes(m, d, k, P, pa, F, F, sum);
    }
  }
}

/* ---- broad phase ---- */

/* The boxes of every chunk of every rod (nodes +- the chunk's widest
 * radius), and after them each rod's (their union), written through the
 * state's scratch pointer. */
static void chunk_boxes(const swModel *m, const swData *d) {
  for (int r = 0; r < m->nrod; r++) {
    const int n = m->rod_nelem[r], na = m->node_adr[r], ea = m->elem_adr[r];
    double *whole = d->obstacle_box + 6 * (m->obstacle_nchunk + r);
    for (int q = 0; q < 3; q++) whole[q] = INFINITY, whole[3 + q] = -INFINITY;
    for (int c = 0, i0 = 0; i0 < n; c++, i0 += SW_OBSTACLE_CHUNK) {
      const int i1 = i0 + SW_OBSTACLE_CHUNK < n ? i0 + SW_OBSTACLE_CHUNK : n;
      double *box = d->obstacle_box + 6 * (m->obstacle_chunk_adr[r] + c), wide = 0;
      for (int q = 0; q < 3; q++) {
        double lo = INFINITY, hi = -INFINITY;
        for (int i = i0; i <= i1; i++) {
          const double y = SW_AT(m, d->x, na + i, q);
          lo = sw_min(lo, y);
          hi = sw_max(hi, y);
        }
        box[q] = lo, box[3 + q] = hi;
      }
      for (int i = i0; i < i1; i++) wide = sw_max(wide, d->radius_now[ea + i]);
      for (int q = 0; q < 3; q++) {
        box[q] -= wide, box[3 + q] += wide;
        whole[q] = sw_min(whole[q], box[q]), whole[3 + q] = sw_max(whole[3 + q], box[3 + q]);
      }
    }
  }
}

static int boxes_apart(const double *a, const double *b) {
  int apart = 0;
  for (int q = 0; q < 3; q++) apart |= a[q] > b[3 + q] || a[3 + q] < b[q];
  return apart;
}

/* Obstacle k's lab box at pose P: c +- sum_j |e_j| h_j (an unbounded
 * extent counts only along the lab directions its axis has a part in). */
static void obstacle_box(const swModel *m, int k, const swPose *P, double box[6]) {
  const double *ext = m->obstacle_extent + 3 * k;
  for (int q = 0; q < 3; q++) {
    double reach = 0;
    for (int j = 0; j < 3; j++) {
      const double e = fabs(P->E[3 * j + q]);
      reach += isinf(ext[j]) ? (e > 0 ? INFINITY : 0.0) : e * ext[j];
    }
    box[q] = P->c[q] - reach;
    box[3 + q] = P->c[q] + reach;
  }
}

static void visit(const swModel *m, const swData *d, swObstaclePhase phase, Sums *sum) {
  if (phase == SW_OBSTACLE_GRID) chunk_boxes(m, d);
  for (int k = 0; k < m->nobstacle; k++) {
    const swObstacleDesc *o = &m->obstacle[k];
    const swPose P = pose_of(m, d->x, d->v, d->Q, d->omega, k);
    double box[6];
    obstacle_box(m, k, &P, box);
    /* the pairs' keys, increasing in the order of the visit: obstacle k's
     * listed elements are at most nelem */
    double base = (double)k * (m->nelem + 1);
    for (int j = 0; j < o->nrods; j++) {
      const int r = o->rods[j], n = m->rod_nelem[r], na = m->node_adr[r], ea = m->elem_adr[r];
      const double first = base;
      base += n;
      if (r == o->carrier_rod) continue; /* a bone does not touch what it carries */
      const int grid = phase == SW_OBSTACLE_GRID;
      if (grid && boxes_apart(d->obstacle_box + 6 * (m->obstacle_nchunk + r), box)) continue;
      for (int c = 0, i0 = 0; i0 < n; c++, i0 += SW_OBSTACLE_CHUNK) {
        const int i1 = i0 + SW_OBSTACLE_CHUNK < n ? i0 + SW_OBSTACLE_CHUNK : n;
        if (grid && boxes_apart(d->obstacle_box + 6 * (m->obstacle_chunk_adr[r] + c), box)) continue;
        for (int i = i0; i < i1; i++) {
          sum->key = first + i;
          element_contact(m, d, k, &P, na + i, ea + i, sum);
        }
      }
    }
  }
}

/* ---- the kernels ---- */

void sw_obstacle_loads_with(const swModel *m, swData *d, swObstaclePhase phase) {
  /* the last evaluation's anchors become the old ones, read by the merge */
  double *old = d->obstacle_anchor;
  d->obstacle_anchor = d->obstacle_anchor_old;
  d->obstacle_anchor_old = old;
  Sums sum;
  memset(&sum, 0, sizeof sum);
  sum.force = d->force, sum.ext_force = d->ext_force, sum.torque = d->torque;
  sum.ext_torque = d->ext_torque, sum.rec = d->obstacle_contact, sum.room = m->obstacle_maxcontact;
  sum.old = old + 1, sum.old_rows = (int)old[0], sum.anchor = d->obstacle_anchor + 1;
  visit(m, d, phase, &sum);
  d->obstacle_anchor[0] = sum.rows;
  d->obstacle_stuck = sum.stuck;
  d->obstacle_slipping = sum.slipping;
  d->friction_full += sum.full;
  d->obstacle_contacts = sum.contacts;
  d->obstacle_max_depth = sum.max_depth;
  d->obstacle_tests = sum.tests;
}

void sw_obstacle_loads(const swModel *m, swData *d) { sw_obstacle_loads_with(m, d, SW_OBSTACLE_GRID); }

/* The energy of the obstacle springs at the current positions, J. */
double sw_obstacle_energy(const swModel *m, const swData *d) {
  Sums sum;
  memset(&sum, 0, sizeof sum);
  visit(m, d, SW_OBSTACLE_GRID, &sum);
  return sum.energy;
}

/* The deepest penetration r - D of obstacle k's rods at t = 0 (m; <= 0:
 * none), and where (rod, element of the rod), from the initial positions. */
double sw_obstacle_start_depth(const swModel *m, int k, int *rod, int *elem) {
  const swObstacleDesc *o = &m->obstacle[k];
  const swPose P = pose_of(m, m->x0, NULL, m->Q0, NULL, k);
  double worst = -INFINITY;
  *rod = *elem = -1;
  for (int j = 0; j < o->nrods; j++) {
    const int r = o->rods[j], na = m->node_adr[r], ea = m->elem_adr[r];
    if (r == o->carrier_rod) continue;
    for (int i = 0; i < m->rod_nelem[r]; i++) {
      double x0[3], x1[3], a[3], b[3], dl[3], s = INFINITY, n[3]; /* s: no quick rejection */
      sw_get3(m, m->x0, na + i, x0);
      sw_get3(m, m->x0, na + i + 1, x1);
      to_local(a, &P, x0);
      to_local(b, &P, x1);
      sw_v3_sub(dl, b, a);
      const double depth = m->radius[ea + i] - sw_obstacle_segment_distance(o, a, dl, &s, n);
      if (depth > worst) worst = depth, *rod = r, *elem = i;
    }
  }
  return worst;
}

/* Step limit of the obstacle springs and dampers.  A node is pressed by
 * its (one or two) elements, each with full weight when the contact point
 * is at the node (s = 0 or 1): w^2 = nel k / m_i, c = nel gamma / m_i, one
 * obstacle at a time.  A carrier node takes one element's spring through
 * its mass and, at the lever l = |arm| + the shape's reach, through its
 * element's least moment of inertia: w^2 = k (1 / m + l^2 / J).  The
 * scheme's limit at zeta = c / (2 w), times 0.95, as ground.c's.  With
 * friction k is the larger of k and k_t: the tangential spring presses the
 * same nodes across the normal, so the two add in no direction.  It acts at
 * the surface too, and so turns the element: its point moves with the
 * nodes and with the element's rotation at the lever r, w^2 = k_t (1 / m_i
 * + r^2 / J) with m_i the lighter node and J the element's least moment of
 * inertia (r^2 / J = 4 / m_e for a solid section), the damper likewise. */
static double limit_of(const swModel *m, double w2, double c) {
  if (!(w2 > 0)) return c > 0 ? 0.95 * 2.0 / c : INFINITY;
  const double w = sqrt(w2);
  return 0.95 * sw_integrator_stability_limit(m->integrator, c / (2 * w)) / w;
}

double sw_obstacle_stable_dt(const swModel *m) {
  double dt = INFINITY;
  for (int k = 0; k < m->nobstacle; k++) {
    const swObstacleDesc *o = &m->obstacle[k];
    /* the tangential spring acts across the normal one: the larger counts */
    const double stiff = o->static_friction > 0 ? fmax(o->stiffness, o->tangential_stiffness) : o->stiffness;
    for (int j = 0; j < o->nrods; j++) {
      const int r = o->rods[j], n = m->rod_nelem[r], na = m->node_adr[r];
      if (r == o->carrier_rod) continue;
      for (int i = 0; i <= n; i++) {
        const int nel = (i > 0) + (i < n);
        dt = fmin(dt, limit_of(m, nel * stiff * m->inv_mass[na + i],
                               nel * o->damping * m->inv_mass[na + i]));
      }
      for (int i = 0; i < n && o->static_friction > 0; i++) { /* the friction's couple */
        const int e = m->elem_adr[r] + i;
        const double kt = o->tangential_stiffness > 0 ? o->tangential_stiffness : o->stiffness;
        double J = INFINITY;
        for (int q = 0; q < 3; q++) J = fmin(J, SW_AT(m, m->inertia, e, q));
        const double lighter = fmax(m->inv_mass[na + i], m->inv_mass[na + i + 1]);
        const double inv = lighter + m->radius[e] * m->radius[e] / J;
        dt = fmin(dt, limit_of(m, kt * inv, o->damping * inv));
      }
    }
    if (o->carrier_rod < 0) continue;
    const double *ext = m->obstacle_extent + 3 * k;
    double reach = 0;
    for (int j = 0; j < 3; j++) reach = fmax(reach, isinf(ext[j]) ? 0.0 : ext[j]);
    const double lever = sw_v3_norm(m->obstacle_arm + 3 * k) + reach;
    const int e = m->obstacle_elem[k], node = m->obstacle_node[k];
    double J = INFINITY;
    for (int q = 0; q < 3; q++) J = fmin(J, SW_AT(m, m->inertia, e, q));
    const double inv = m->inv_mass[node] + lever * lever / J;
    dt = fmin(dt, limit_of(m, stiff * inv, o->damping * inv));
  }
  return dt;
}
