/* gen_lower.c — the one mapping from the checked scene to the runtime's
 * description structs (swRodDesc, swJointDesc, swSignal, ...).
 *
 * Design.  The mapping is a table per struct: C member name, offset,
 * component count, and the scene value that fills it.  Two consumers walk the
 * same tables: gen_spec() fills real structs with the default values, so the
 * compiler can hand the scene to the runtime's own validation (sw_compile)
 * and stable-dt estimate; gen_c.c prints an assignment per entry, with the
 * value's folded constant or its param-dependent C expression.  One table
 * means the generated simulator and the compiler's checks cannot drift apart.
 * Scene entries name rods by their index in the scene; the runtime numbers
 * rods in the order they are added, and a muscle adds one rod per filament,
 * so every rod index goes through gen_rod_id() on the way out.
 */
#include <stddef.h>
#include <stdio.h>
#include <string.h>

#include "gen.h"

#define F(member, n, value) {#member, offsetof(swRodDesc, member), n, value}

int gen_rod_fields(const swSceneRod *r, swLowField *out) {
  const swLowField f[] = {
    F(start, 3, &r->start),
    F(direction, 3, &r->direction),
    F(normal, 3, &r->normal),
    F(length, 1, &r->length),
    F(radius_start, 1, &r->radius_start),
    F(radius_end, 1, &r->radius_end),
    F(density, 1, &r->density),
    F(youngs, 1, &r->youngs),
    F(shear_modulus, 1, &r->shear_modulus),
    F(poisson, 1, &r->poisson),
    F(shear_hardening, 1, &r->shear_hardening),
    F(twist_hardening, 1, &r->twist_hardening),
    F(rest_kappa, 3, &r->rest_kappa),
    F(rest_sigma, 3, &r->rest_sigma),
    F(gamma, 1, &r->gamma),
    F(gamma_rot, 1, &r->gamma_rot),
  };
  int n = 0;
  for (size_t i = 0; i < sizeof f / sizeof f[0]; i++)
    if (f[i].value->kind != VAL_ERROR) out[n++] = f[i];
  return n;
}
#undef F

#define F(member, n, value) {#member, offsetof(swMuscleDesc, member), n, value}
int gen_muscle_fields(const swSceneMuscle *m, swLowField *out) {
  const swLowField f[] = {
    F(start, 3, &m->start),
    F(end, 3, &m->end),
    F(normal, 3, &m->normal),
    F(radius, 1, &m->radius),
    F(density, 1, &m->density),
    F(youngs, 1, &m->youngs),
    F(shear_modulus, 1, &m->shear_modulus),
    F(poisson, 1, &m->poisson),
    F(shear_hardening, 1, &m->shear_hardening),
    F(twist_hardening, 1, &m->twist_hardening),
    F(gamma, 1, &m->gamma),
    F(sigma_max, 1, &m->sigma_max),
    F(size_ratio, 1, &m->size_ratio),
    F(twitch_small, 1, &m->twitch_small),
    F(twitch_large, 1, &m->twitch_large),
    F(hill_a, 1, &m->hill_a),
    F(v_max, 1, &m->v_max),
    F(fibre_diameter, 1, &m->fibre_diameter),
    F(attach_stiffness, 1, &m->attach_stiffness),
    F(attach_damping, 1, &m->attach_damping),
    F(via[0], 3, &m->via[0]), F(via[1], 3, &m->via[1]), F(via[2], 3, &m->via[2]),
    F(via[3], 3, &m->via[3]), F(via[4], 3, &m->via[4]), F(via[5], 3, &m->via[5]),
    F(via[6], 3, &m->via[6]), F(via[7], 3, &m->via[7]),
  };
  int n = 0;
  const size_t nf = sizeof f / sizeof f[0] - (size_t)(SW_MUSCLE_MAX_VIA - m->nvia);
  for (size_t i = 0; i < nf; i++)
    if (f[i].value->kind == VAL_NUM || f[i].value->kind == VAL_VEC) out[n++] = f[i];
  return n;
}
#undef F

#define F(member, n, value) {#member, offsetof(swJointDesc, member), n, value}
int gen_joint_fields(const swSceneJoint *j, swLowField *out) {
  const swLowField f[] = {
    F(anchor, 3, &j->anchor),
    F(axis, 3, &j->axis),
    F(stiffness, 1, &j->stiffness),
    F(damping, 1, &j->damping),
    F(rot_stiffness, 1, &j->rot_stiffness),
    F(rot_damping, 1, &j->rot_damping),
  };
  memcpy(out, f, sizeof f);
  /* the limits only when given, so a joint without them lowers as before */
  const swLowField lim[] = {
    F(arm_a, 3, &j->arm_a),
    F(angle_min, 1, &j->angle_min),
    F(angle_max, 1, &j->angle_max),
    F(cone, 1, &j->cone),
    F(limit_stiffness, 1, &j->limit_stiffness),
    F(limit_damping, 1, &j->limit_damping),
  };
  int n = (int)(sizeof f / sizeof f[0]);
  for (size_t i = 0; i < sizeof lim / sizeof lim[0]; i++)
    if (lim[i].value->kind == VAL_NUM || lim[i].value->kind == VAL_VEC) out[n++] = lim[i];
  return n;
}
#undef F

#define F(member, value) {#member, offsetof(swSignal, member), 1, value}
int gen_signal_fields(const swSignalVal *s, swLowField *out) {
  const swLowField f[] = {
    F(a, &s->a), F(b, &s->b), F(t0, &s->t0), F(T, &s->T), F(freq, &s->freq), F(phase, &s->phase),
    F(period, &s->period),
  };
  int n = 0;
  for (size_t i = 0; i < sizeof f / sizeof f[0]; i++)
    if (f[i].value->kind == VAL_NUM) out[n++] = f[i];
  return n;
}
#undef F

/* the entries whose value the model gave */
static int given(const swLowField *f, int n, swLowField *out) {
  int k = 0;
  for (int i = 0; i < n; i++)
    if (f[i].value->kind == VAL_NUM || f[i].value->kind == VAL_VEC) out[k++] = f[i];
  return k;
}

#define F(member, n, value) {#member, offsetof(swGroundDesc, member), n, value}
int gen_ground_fields(const swSceneGround *g, swLowField *out) {
  const swLowField f[] = {
    F(origin, 3, &g->origin),
    F(normal, 3, &g->normal),
    F(stiffness, 1, &g->stiffness),
    F(damping, 1, &g->damping),
    F(mu_kinetic, 3, &g->mu_kinetic),
    F(mu_static, 3, &g->mu_static),
    F(mu_rolling, 1, &g->mu_rolling),
    F(slip_velocity, 1, &g->slip_velocity),
  };
  return given(f, (int)(sizeof f / sizeof f[0]), out);
}
#undef F

#define F(member, n, value) {#member, offsetof(swFluidDesc, member), n, value}
int gen_fluid_fields(const swSceneFluid *fl, swLowField *out) {
  const swLowField f[] = {
    F(viscosity, 1, &fl->viscosity),
    F(density, 1, &fl->density),
    F(drag_coefficient, 1, &fl->drag_coefficient),
    F(body_length, 1, &fl->body_length),
    F(velocity, 3, &fl->velocity),
  };
  return given(f, (int)(sizeof f / sizeof f[0]), out);
}
#undef F

#define F(member, n, value) {#member, offsetof(swContactDesc, member), n, value}
int gen_contact_fields(const swSceneContact *c, swLowField *out) {
  const swLowField f[] = {
    F(stiffness, 1, &c->stiffness),
    F(damping, 1, &c->damping),
    F(static_friction, 1, &c->static_friction),
    F(kinetic_friction, 1, &c->kinetic_friction),
    F(tangential_stiffness, 1, &c->tangential_stiffness),
  };
  return given(f, (int)(sizeof f / sizeof f[0]), out);
}
#undef F

#define F(member, n, value) {#member, offsetof(swObstacleDesc, member), n, value}
int gen_obstacle_fields(const swSceneObstacle *o, swLowField *out) {
  const swLowField f[] = {
    F(centre, 3, &o->centre),
    F(axis, 3, &o->axis),
    F(normal, 3, &o->normal),
    F(radius, 1, &o->radius),
    F(length, 1, &o->length),
    F(half, 3, &o->half),
    F(stiffness, 1, &o->stiffness),
    F(damping, 1, &o->damping),
    F(static_friction, 1, &o->static_friction),
    F(kinetic_friction, 1, &o->kinetic_friction),
    F(tangential_stiffness, 1, &o->tangential_stiffness),
  };
  return given(f, (int)(sizeof f / sizeof f[0]), out);
}
#undef F

#define F(member, n, value) {#member, offsetof(swWaveDesc, member), n, value}
int gen_wave_fields(const swSceneWave *w, swLowField *out) {
  const swLowField f[] = {
    F(coef, w->coef.n, &w->coef),
    F(wavelength, 1, &w->wavelength),
    F(period, 1, &w->period),
    F(phase, 1, &w->phase),
    F(ramp, 1, &w->ramp),
    F(direction, 3, &w->direction),
  };
  return given(f, (int)(sizeof f / sizeof f[0]), out);
}
#undef F

static void fill(void *desc, const swLowField *f, int n) {
  for (int i = 0; i < n; i++) {
    double *dst = (double *)((char *)desc + f[i].offset);
    for (int k = 0; k < f[i].n; k++) dst[k] = f[i].value->v[k];
  }
}

swSignal gen_signal(const swSignalVal *sig) {
  swSignal s = sw_signal_const(1.0);
  if (!sig) return s;
  if (sig->kind == SW_SIG_FUNC) {   /* the compiler's own evaluation of the tree */
    s = sw_signal_func(sema_signal_eval, sig->func, 0.0, sig->func->span);
    if (sig->a.kind == VAL_NUM) s.a = sig->a.v[0];
    return s;
  }
  swLowField f[GEN_MAX_FIELDS];
  s.kind = sig->kind;
  s.a = s.b = s.t0 = s.T = s.freq = s.phase = s.period = 0;
  fill(&s, f, gen_signal_fields(sig, f));
  if (sig->kind == SW_SIG_TABLE || sig->kind == SW_SIG_BSPLINE) {
    s.npts = sig->npts;
    for (int k = 0; k < sig->npts; k++) {
      if (sig->kind == SW_SIG_TABLE) s.times[k] = sig->times.v[k];
      s.values[k] = sig->values.v[k];
    }
  }
  return s;
}

int gen_rod_id(const swScene *sc, int rod) { return rod < 0 ? -1 : sc->rod[rod].id; }

int gen_rod_next(const swScene *sc, int ri, int mi) {
  if (ri >= sc->nrod) return 0;
  return mi >= sc->nmuscle || sc->rod[ri].id < sc->muscle[mi].id;
}

/* An expectation's description: all constants. */
void gen_expect_desc(const swSceneExpect *x, swExpectDesc *d) {
  sw_expect_desc_init(d);
  d->text = x->text;
  d->quantity = x->quantity;
  d->index = x->index;
  d->component = x->component;
  d->window = x->window;
  d->t0 = x->t0;
  d->t1 = x->t1;
  d->lo = x->lo;
  d->hi = x->hi;
  d->scale = x->scale;
  d->unit = x->unit;
  d->reduce = x->reduce;
}

swSpec *gen_spec(const swScene *sc) {
  swSpec *s = sw_spec_new();
  if (!s) return NULL;
  swLowField f[GEN_MAX_FIELDS];
  for (int ri = 0, mi = 0; ri < sc->nrod || mi < sc->nmuscle;) {
    if (gen_rod_next(sc, ri, mi)) {
      const swSceneRod *r = &sc->rod[ri++];
      swRodDesc d;
      sw_rod_desc_init(&d);
      d.name = r->name;
      d.nelem = r->nelem;
      d.damping = r->damping;
      d.rigid = r->rigid;
      d.implicit = r->implicit;
      d.weightless = r->weightless;
      d.law = r->variational ? SW_LAW_VARIATIONAL : SW_LAW_GAZZOLA;
      fill(&d, f, gen_rod_fields(r, f));
      if (r->swell_radius || r->swell_curvature || r->swell_twist || r->swell_twist_radius) {
        d.swell = 1;   /* as gen_c.c's emit_rod */
        d.swell_radius = r->swell_radius ? gen_signal(r->swell_radius) : sw_signal_const(d.radius_start);
        if (r->swell_radius) d.radius_start = d.radius_end = sw_signal_eval(&d.swell_radius, 0.0);
        if (r->swell_curvature) d.swell_curvature = gen_signal(r->swell_curvature);
        if (r->swell_twist) d.swell_twist = gen_signal(r->swell_twist);
        d.swell_twist_radius = r->swell_twist_radius;
        d.swell_mass_grows = r->swell_mass_grows;
      }
      int id = sw_spec_add_rod(s, &d);
      /* shapes as sema_shape.c built them, with the same runtime calls */
      if (id >= 0 && r->xr) sw_spec_set_rest_shape(s, id, r->xr, r->Qr);
      if (id >= 0 && r->x0 && r->x0 != r->xr) sw_spec_set_start_shape(s, id, r->x0, r->Q0);
      continue;
    }
    const swSceneMuscle *m = &sc->muscle[mi++];
    swMuscleDesc d;
    sw_muscle_desc_init(&d);
    d.name = m->name;
    d.filaments = m->filaments;
    d.nelem = m->nelem;
    if (m->motor_units) d.motor_units = (int)m->motor_units;
    if (m->has_damping) d.damping = m->damping;
    if (m->variational) d.law = SW_LAW_VARIATIONAL;
    d.weightless = m->weightless;
    for (int e = 0; e < 2; e++)
      if (m->attach_rod[e] >= 0) {
        d.attach_rod[e] = gen_rod_id(sc, m->attach_rod[e]);
        d.attach_node[e] = m->attach_node[e];
      }
    if (m->activation) d.activation = gen_signal(m->activation);
    if (m->force) {
      d.prescribed = 1;
      d.force = gen_signal(m->force);
    }
    d.nvia = m->nvia;
    for (int k = 0; k < m->nvia; k++) d.via_rod[k] = gen_rod_id(sc, m->via_rod[k]);
    fill(&d, f, gen_muscle_fields(m, f));
    sw_spec_add_muscle(s, &d);
  }
  for (int i = 0; i < sc->npassive; i++)
    sw_spec_set_filament_passive(s, sc->passive[i].muscle, sc->passive[i].filament);
  for (int i = 0; i < sc->nact; i++) {
    const swSceneAction *a = &sc->act[i];
    if (a->is_bc) {
      swBCDesc b;
      memset(&b, 0, sizeof b);
      b.kind = (swBCKind)a->kind;
      b.rod = gen_rod_id(sc, a->rod);
      b.end = a->index;
      if (a->vec.kind == VAL_VEC)
        for (int k = 0; k < 3; k++) b.vec[k] = a->vec.v[k];
      b.signal = gen_signal(a->sig);
      if (a->until.kind == VAL_NUM) b.until = a->until.v[0];
      sw_spec_add_bc(s, &b);
    } else {
      swLoadDesc l;
      memset(&l, 0, sizeof l);
      l.kind = (swLoadKind)a->kind;
      l.rod = gen_rod_id(sc, a->rod);
      l.index = a->index;
      for (int k = 0; k < 3; k++) l.vec[k] = a->vec.v[k];
      l.signal = gen_signal(a->sig);
      sw_spec_add_load(s, &l);
    }
  }
  for (int i = 0; i < sc->njoint; i++) {
    const swSceneJoint *j = &sc->joint[i];
    swJointDesc d;
    sw_joint_desc_init(&d);
    d.name = j->name;
    d.kind = j->kind;
    d.rod_a = gen_rod_id(sc, j->rod_a);
    d.node_a = j->node_a;
    d.rod_b = gen_rod_id(sc, j->rod_b);
    d.node_b = j->node_b;
    d.undamped = j->undamped;
    d.has_range = j->has_range;
    fill(&d, f, gen_joint_fields(j, f));
    sw_spec_add_joint(s, &d);
  }
  for (int i = 0; i < sc->nkin; i++) {
    const swSceneKinematic *k = &sc->kin[i];
    swKinematicDesc d;
    sw_kinematic_desc_init(&d);
    d.name = k->name;
    d.leader_rod = gen_rod_id(sc, k->leader_rod);
    d.leader_elem = k->leader_elem;
    d.leader_xi = k->leader_xi;
    d.follower_rod = gen_rod_id(sc, k->follower_rod);
    d.follower_node = k->follower_node;
    d.follower_elem = k->follower_elem;
    d.reaction_rod = gen_rod_id(sc, k->reaction_rod);
    d.reaction_node = k->reaction_node;
    d.stiffness = k->stiffness.v[0];
    if (k->damping.kind == VAL_NUM) d.damping = k->damping.v[0];
    if (k->reaction_weight.kind == VAL_NUM) d.reaction_weight = k->reaction_weight.v[0];
    sw_spec_add_kinematic(s, &d);
  }
  for (int i = 0; i < sc->nground; i++) {
    const swSceneGround *g = &sc->ground[i];
    swGroundDesc d;
    sw_ground_desc_init(&d);
    d.name = g->name;
    d.nrods = g->rods.n;
    d.rods = g->rods.id;
    if (g->height) {
      d.height = sema_height_eval;
      d.height_ctx = g->height;
    }
    d.contact_point = g->contact_point;
    fill(&d, f, gen_ground_fields(g, f));
    sw_spec_add_ground(s, &d);
  }
  for (int i = 0; i < sc->nfluid; i++) {
    const swSceneFluid *fl = &sc->fluid[i];
    swFluidDesc d;
    sw_fluid_desc_init(&d);
    d.name = fl->name;
    d.model = fl->model;
    d.area = fl->area;
    d.buoyancy = fl->buoyancy;
    d.nrods = fl->rods.n;
    d.rods = fl->rods.id;
    fill(&d, f, gen_fluid_fields(fl, f));
    sw_spec_add_fluid(s, &d);
  }
  for (int i = 0; i < sc->ncontact; i++) {
    const swSceneContact *c = &sc->contact[i];
    swContactDesc d;
    sw_contact_desc_init(&d);
    d.name = c->name;
    d.self = c->self;
    d.nrods = c->rods.n;
    d.rods = c->rods.id;
    fill(&d, f, gen_contact_fields(c, f));
    sw_spec_add_contact(s, &d);
  }
  for (int i = 0; i < sc->nobstacle; i++) {
    const swSceneObstacle *o = &sc->obstacle[i];
    swObstacleDesc d;
    sw_obstacle_desc_init(&d);
    d.name = o->name;
    d.shape = o->shape;
    d.carrier_rod = o->carrier_rod;
    d.carrier_node = o->carrier_node;
    d.nrods = o->rods.n;
    d.rods = o->rods.id;
    fill(&d, f, gen_obstacle_fields(o, f));
    sw_spec_add_obstacle(s, &d);
  }
  for (int i = 0; i < sc->nwave; i++) {
    const swSceneWave *w = &sc->wave[i];
    swWaveDesc d;
    sw_wave_desc_init(&d);
    d.name = w->name;
    d.rod = w->rod;
    d.ncoef = w->coef.n;
    d.reverse = w->reverse;
    fill(&d, f, gen_wave_fields(w, f));
    sw_spec_add_wave(s, &d);
  }
  for (int i = 0; i < sc->nprobe; i++) {
    const swSceneProbe *p = &sc->probe[i];
    swProbeDesc d;
    sw_probe_desc_init(&d);
    d.name = p->name;
    d.kind = p->kind;
    d.nrods = p->rods.n;
    d.rods = p->rods.id;
    d.rod = p->rod;
    d.node = p->node;
    if (p->window.kind == VAL_NUM) d.window = p->window.v[0];
    sw_spec_add_probe(s, &d);
  }
  for (int i = 0; i < sc->nexpect; i++) {
    swExpectDesc d;
    gen_expect_desc(&sc->expect[i], &d);
    sw_spec_add_expect(s, &d);
  }
  if (sc->gravity.kind == VAL_VEC) sw_spec_set_gravity(s, sc->gravity.v);
  if (sc->gravity_sig) sw_spec_set_gravity_signal(s, gen_signal(sc->gravity_sig));
  sw_spec_set_integrator(s, sc->integrator);
  if (sc->dt > 0) sw_spec_set_dt(s, sc->dt);
  return s;
}
