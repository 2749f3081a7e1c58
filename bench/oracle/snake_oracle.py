#!/usr/bin/python3
"""Oracle driver: PyElastica continuum snake with the settings of
Zhang et al. 2019, Supplementary Figs. 10-12.

Own code, written for the sinew project's oracle experiment.  It uses
PyElastica (a checkout of its source, put on PYTHONPATH) as a
library.

Axis convention: gravity along -z.  The rod starts with its first node at
the origin and is laid along +x (director d3 = +x, d1 = normal = +z).  The
muscle torque acts about the d1 = z axis so the body undulates in the x-y
plane; the snake travels towards +x (head = last node).  Lateral = y.

Ground:
  flat    : PyElastica's own Plane + RodPlaneContactWithAnisotropicFriction,
            plane at z = -r, so the centreline rests at z = 0.
  terrain : TerrainContact (below): the same normal response and
            anisotropic kinetic Coulomb friction as
            RodPlaneContactWithAnisotropicFriction, but with the plane
            replaced, element by element, by the local tangent plane of the
            surface z_s(x) = h(x) - r0 (r0 = 0.025 m fixed), h = Fig. 11 height field.  Normal from
            the gradient, penetration measured along that normal to the
            foot point on the surface.  The centreline therefore rests at
            z = h(x).
  flatterrain : TerrainContact with h == 0 (validation against PyElastica's
            own plane contact).

Damping: AnalyticalLinearDamper, "physical" protocol, with
  translational_damping_constant = nu * dl per node (nu*dl/2 at the two end
  nodes, matching the half-element quadrature of the old per-element force),
  rotational_damping_constant   = nu * dl per element,
which integrates exactly m dv/dt = -nu dl v and (J/e) dw/dt = -nu dl w,
i.e. force -nu v and couple -nu w per unit (rest) length, nu = 5 kg/(m s).
"""
import argparse
import json
import os
import sys
import time as wallclock

import numpy as np
from numba import njit

import elastica as ea
from elastica._linalg import (
    _batch_cross,
    _batch_dot,
    _batch_matvec,
    _batch_norm,
    _batch_product_k_ik_to_ik,
    _batch_vector_sum,
)
from elastica.contact_utils import (
    _elements_to_nodes_inplace,
    _find_slipping_elements,
    _node_to_element_mass_or_force,
    _node_to_element_velocity,
)


# --------------------------------------------------------------------------
# terrain (Supplementary Fig. 11)
# --------------------------------------------------------------------------
@njit(cache=True)
def terrain_h(x, mode):
    """mode 0: flat h = 0; 1: Fig. 11 barrier; 2: uniform slope h = 0.3 x
    (mode 2 only for validating the tilted-plane kernel)."""
    if mode == 0:
        return 0.0, 0.0
    if mode == 2:
        return 0.3 * x, 0.3
    if x < 3.0:
        return 0.0, 0.0
    if x > 4.0:
        return 0.2, 0.0
    u = x - 3.0
    return -0.4 * u * u * u + 0.6 * u * u, -1.2 * u * u + 1.2 * u


@njit(cache=True)
def tangent_plane(xs, px, pz, r, mode):
    """At abscissa xs of the surface z_s(x) = h(x) - r: its height, the unit
    normal (nx, nz) there, and the distance of the point (px, pz) from that
    tangent plane along it."""
    h, hp = terrain_h(xs, mode)
    zs = h - r
    inv = 1.0 / np.sqrt(1.0 + hp * hp)
    nx, nz = -hp * inv, inv
    return zs, nx, nz, nx * (px - xs) + nz * (pz - zs)


@njit(cache=True)
def local_planes(element_position, r0, mode):
    """Foot point on the surface z_s(x) = h(x) - r, normal there, and the
    signed distance of each element centre along that normal."""
    n_elem = element_position.shape[1]
    normals = np.zeros((3, n_elem))
    origins = np.zeros((3, n_elem))
    distance = np.zeros(n_elem)
    for k in range(n_elem):
        px = element_position[0, k]
        py = element_position[1, k]
        pz = element_position[2, k]
        r = r0
        xs = px
        for it in range(6):
            zs, nx, nz, d = tangent_plane(xs, px, pz, r, mode)
            xs_new = px - d * nx
            if abs(xs_new - xs) < 1e-13:
                xs = xs_new
                break
            xs = xs_new
        zs, nx, nz, d = tangent_plane(xs, px, pz, r, mode)
        normals[0, k] = nx
        normals[2, k] = nz
        origins[0, k] = xs
        origins[1, k] = py
        origins[2, k] = zs
        distance[k] = d
    return normals, origins, distance


@njit(cache=True)
def terrain_contact_kernel(
    mode,
    r0,
    arm,
    total_normal,
    cap_h,
    mean_velocity,
    surface_tol,
    slip_velocity_tol,
    k,
    nu,
    kinetic_mu_forward,
    kinetic_mu_backward,
    kinetic_mu_sideways,
    radius,
    mass,
    tangents,
    position_collection,
    director_collection,
    velocity_collection,
    omega_collection,
    internal_forces,
    external_forces,
    external_torques,
):
    n_elem = tangents.shape[1]
    element_position = 0.5 * (position_collection[:, 1:] + position_collection[:, :-1])
    normals, origins, distance = local_planes(element_position, r0, mode)

    # ---- normal response (as _calculate_contact_forces_rod_plane) ----
    nodal_total_forces = _batch_vector_sum(internal_forces, external_forces)
    element_total_forces = _node_to_element_mass_or_force(nodal_total_forces)
    f_n = _batch_dot(normals, element_total_forces)
    forces_along_normal = np.zeros((3, n_elem))
    for i in range(3):
        for e in range(n_elem):
            forces_along_normal[i, e] = normals[i, e] * f_n[e]
    for e in range(n_elem):
        if f_n[e] > 0.0:
            forces_along_normal[:, e] = 0.0
    plane_response_force = -forces_along_normal

    penetration = np.minimum(distance - radius, 0.0)
    element_velocity = _node_to_element_velocity(
        mass=mass, node_velocity_collection=velocity_collection
    )
    if mean_velocity:  # sinew's element velocity: the plain mean of its two nodes
        element_velocity = 0.5 * (velocity_collection[:, 1:] + velocity_collection[:, :-1])
    v_n = _batch_dot(normals, element_velocity)
    plane_response_force_total = np.zeros((3, n_elem))
    for i in range(3):
        for e in range(n_elem):
            plane_response_force_total[i, e] = (
                plane_response_force[i, e]
                - k * normals[i, e] * penetration[e]
                - nu * normals[i, e] * v_n[e]
            )
    contact = np.ones(n_elem)
    for e in range(n_elem):
        if (distance[e] - radius[e]) > surface_tol:
            contact[e] = 0.0
            plane_response_force[:, e] = 0.0
            plane_response_force_total[:, e] = 0.0
    _elements_to_nodes_inplace(plane_response_force_total, external_forces)
    if total_normal:  # sinew's: friction from the whole response (balance, penalty, damper), never pulling
        plane_response_force_mag = np.maximum(_batch_dot(plane_response_force_total, normals), 0.0)
    else:  # PyElastica's: from the balance alone
        plane_response_force_mag = _batch_norm(plane_response_force)

    # ---- anisotropic kinetic friction (as ..._with_anisotropic_friction) ----
    t_n = _batch_dot(normals, tangents)
    t_perp = np.zeros((3, n_elem))
    for i in range(3):
        for e in range(n_elem):
            t_perp[i, e] = tangents[i, e] - normals[i, e] * t_n[e]
    t_perp_mag = _batch_norm(t_perp)
    axial_direction = _batch_product_k_ik_to_ik(1.0 / (t_perp_mag + 1e-14), t_perp)
    v_ax_mag = _batch_dot(element_velocity, axial_direction)
    v_ax = _batch_product_k_ik_to_ik(v_ax_mag, axial_direction)
    sgn = np.sign(v_ax_mag)
    kinetic_mu = 0.5 * (
        kinetic_mu_forward * (1.0 + sgn) + kinetic_mu_backward * (1.0 - sgn)
    )
    slip_ax = _find_slipping_elements(v_ax, slip_velocity_tol)

    rolling_direction = _batch_cross(axial_direction, normals)
    torque_arm = np.zeros((3, n_elem))
    for i in range(3):
        for e in range(n_elem):
            torque_arm[i, e] = -normals[i, e] * radius[e] * arm
    v_roll = _batch_dot(element_velocity, rolling_direction)
    # director_collection^T applied = lab frame; same expression as PyElastica
    QT = np.zeros((3, 3, n_elem))
    for i in range(3):
        for j in range(3):
            for e in range(n_elem):
                QT[i, j, e] = director_collection[j, i, e]
    rotation_velocity = _batch_matvec(
        QT, _batch_cross(omega_collection, _batch_matvec(director_collection, torque_arm))
    )
    slip_roll_mag = v_roll + _batch_dot(rotation_velocity, rolling_direction)
    slip_roll = _batch_product_k_ik_to_ik(slip_roll_mag, rolling_direction)
    slip_rollf = _find_slipping_elements(slip_roll, slip_velocity_tol)

    u = slip_roll + v_ax
    u /= _batch_norm(u + 1e-14)

    u_ax = _batch_dot(u, axial_direction)
    u_roll = _batch_dot(u, rolling_direction)
    f_ax = np.zeros((3, n_elem))
    f_roll = np.zeros((3, n_elem))
    for i in range(3):
        for e in range(n_elem):
            f_ax[i, e] = -(
                (1.0 - slip_ax[e]) * kinetic_mu[e] * plane_response_force_mag[e]
                * u_ax[e] * axial_direction[i, e]
            ) * contact[e]
            f_roll[i, e] = -(
                (1.0 - slip_rollf[e]) * kinetic_mu_sideways * plane_response_force_mag[e]
                * u_roll[e] * rolling_direction[i, e]
            ) * contact[e]
    if cap_h > 0.0:  # sinew's cap: no kinetic force larger than m |u| / h, the one that stops the slip in a step
        m_e = 0.5 * (mass[1:] + mass[:-1])
        m_e[0] += 0.5 * mass[0]
        m_e[-1] += 0.5 * mass[-1]
        for e in range(n_elem):
            # the contact point moves as 1 / (1/m_e + r^2/J_a), J_a = m_e r^2 / 2 for a solid cylinder
            m_b = 1.0 / (1.0 / m_e[e] + 2.0 * arm * arm / m_e[e])
            fa = np.sqrt(f_ax[0, e] ** 2 + f_ax[1, e] ** 2 + f_ax[2, e] ** 2)
            la = m_e[e] * abs(v_ax_mag[e]) / cap_h
            if fa > la:
                f_ax[:, e] *= la / fa
            fb = np.sqrt(f_roll[0, e] ** 2 + f_roll[1, e] ** 2 + f_roll[2, e] ** 2)
            lb = m_b * abs(slip_roll_mag[e]) / cap_h
            if fb > lb:
                f_roll[:, e] *= lb / fb
    _elements_to_nodes_inplace(f_ax, external_forces)
    _elements_to_nodes_inplace(f_roll, external_forces)
    external_torques += _batch_matvec(director_collection, _batch_cross(torque_arm, f_roll))
    # static friction: static mu = 0 in this study -> identically zero, omitted.
    return plane_response_force_mag


class TerrainContact(ea.NoForces):
    def __init__(self, k, nu, slip_velocity_tol, kinetic_mu_array, r0, mode=1, arm=1.0,
                 total_normal=False, cap_h=0.0, mean_velocity=False, surface_tol=1.0e-4):
        super().__init__()
        self.total_normal = bool(total_normal)
        self.cap_h = np.float64(cap_h)
        self.mean_velocity = bool(mean_velocity)
        self.arm = np.float64(arm)  # 1: friction at the contact point (as PyElastica); 0: at the centreline
        self.r0 = np.float64(r0)  # fixed offset of the contact surface below h(x)
        self.k = np.float64(k)
        self.nu = np.float64(nu)
        self.surface_tol = np.float64(surface_tol)  # 1e-4 m: as PyElastica's plane contact
        self.slip_velocity_tol = np.float64(slip_velocity_tol)
        self.mu_f, self.mu_b, self.mu_s = [np.float64(m) for m in kinetic_mu_array]
        self.mode = int(mode)
        self.last_normal_force = None

    def apply_forces(self, system, time=0.0):
        self.last_normal_force = terrain_contact_kernel(
            self.mode,
            self.r0,
            self.arm,
            self.total_normal,
            self.cap_h,
            self.mean_velocity,
            self.surface_tol,
            self.slip_velocity_tol,
            self.k,
            self.nu,
            self.mu_f,
            self.mu_b,
            self.mu_s,
            system.radius,
            system.mass,
            system.tangents,
            system.position_collection,
            system.director_collection,
            system.velocity_collection,
            system.omega_collection,
            system.internal_forces,
            system.external_forces,
            system.external_torques,
        )

    def apply_torques(self, system, time=0.0):
        pass


# --------------------------------------------------------------------------
# muscle torque about a body-fixed axis (sinew's torque_wave)
# --------------------------------------------------------------------------
@njit(cache=True)
def body_fixed_muscle_kernel(time, my_spline, s, angular_frequency, wave_number, phase_shift,
                             ramp_up_time, director_collection, external_torques):
    """The moment of PyElastica's MuscleTorques (the same spline, phase,
    ramp and nodes 1..n-1, s from the head), but at node k about the
    normalised mean of the two adjacent elements' d1 (the axis the moment
    had in each element's material frame at t = 0, when d1 = z), as sinew's
    torque_wave applies it, instead of about the lab's z."""
    factor = min(1.0, time / ramp_up_time)
    mag = factor * my_spline * np.sin(angular_frequency * time - wave_number * s + phase_shift)
    n = director_collection.shape[2]
    for k in range(1, n):
        tk = mag[n - 1 - k]  # PyElastica's torque_mag[::-1][k]
        m = director_collection[0, :, k - 1] + director_collection[0, :, k]
        m = m / np.sqrt(m[0] * m[0] + m[1] * m[1] + m[2] * m[2])
        for i in range(3):
            ci = 0.0
            cj = 0.0
            for j in range(3):
                ci += director_collection[i, j, k] * m[j]
                cj += director_collection[i, j, k - 1] * m[j]
            external_torques[i, k] += tk * ci
            external_torques[i, k - 1] -= tk * cj


class BodyFixedMuscleTorques(ea.MuscleTorques):
    def apply_torques(self, system, time=np.float64(0.0)):
        body_fixed_muscle_kernel(np.float64(time), self.my_spline, self.s, self.angular_frequency,
                                 self.wave_number, self.phase_shift, self.ramp_up_time,
                                 system.director_collection, system.external_torques)


# --------------------------------------------------------------------------
class SnakeSim(
    ea.BaseSystemCollection,
    ea.Constraints,
    ea.Forcing,
    ea.Damping,
    ea.CallBacks,
    ea.Contact,
):
    pass


class Recorder(ea.CallBackBaseClass):
    def __init__(self, step_skip, store):
        super().__init__()
        self.every = step_skip
        self.store = store

    def make_callback(self, system, time, current_step):
        if current_step % self.every:
            return
        s = self.store
        s["time"].append(time)
        s["com"].append(system.compute_position_center_of_mass().copy())
        s["position"].append(system.position_collection.copy())
        s["sigma"].append(system.sigma.copy())
        s["kappa"].append(system.kappa.copy())
        if not np.all(np.isfinite(system.position_collection)):
            s["nan"] = True


def build(args):
    sim = SnakeSim()
    L = 1.0
    r = 0.025
    rho = 1000.0
    E = 1e7
    G = 2.0 * E / 3.0
    n = args.n
    g = 9.81
    nu_diss = 5.0
    period = 1.0
    start = np.zeros(3)
    direction = np.array([1.0, 0.0, 0.0])
    normal = np.array([0.0, 0.0, 1.0])
    rod = ea.CosseratRod.straight_rod(
        n, start, direction, normal, L, r, rho, youngs_modulus=E, shear_modulus=G
    )
    # PyElastica builds S = diag(27/28 G A, 27/28 G A, E A); the paper uses 4/3.
    A = np.pi * r * r
    rod.shear_matrix[0, 0, :] = 4.0 / 3.0 * G * A * args.shear
    rod.shear_matrix[1, 1, :] = 4.0 / 3.0 * G * A * args.shear
    # B = diag(E I, E I, G I3) is already built (Voronoi-averaged); harden twist
    rod.bend_matrix[2, 2, :] *= args.twist
    sim.append(rod)

    sim.add_forcing_to(rod).using(ea.GravityForces, acc_gravity=np.array([0.0, 0.0, -g]))
    b_coeff = np.array([0.0, 17.4, 48.5, 5.4, 14.7, 0.0])
    wave_length = 0.97 * L
    sim.add_forcing_to(rod).using(
        BodyFixedMuscleTorques if args.muscle_axis == "body" else ea.MuscleTorques,
        base_length=L,
        b_coeff=b_coeff,
        period=period,
        wave_number=2.0 * np.pi / wave_length,
        phase_shift=0.0,
        rest_lengths=rod.rest_lengths,
        ramp_up_time=period,
        direction=normal,
        with_spline=True,
    )
    mu_f = 0.519
    kinetic_mu = np.array([mu_f, 1.5 * mu_f, 2.0 * mu_f])
    k_w = 1000.0
    gamma_w = 1e-6
    slip_tol = args.slip_tol
    if args.ground in ("flat", "slope"):
        if args.ground == "flat":
            plane = ea.Plane(plane_origin=np.array([0.0, 0.0, -r]), plane_normal=normal)
        else:  # validation only: plane z = 0.3 x - r (same surface as slopeterrain)
            nrm = np.array([-0.3, 0.0, 1.0]) / np.sqrt(1.09)
            plane = ea.Plane(plane_origin=np.array([0.0, 0.0, -r]), plane_normal=nrm)
        sim.append(plane)
        sim.detect_contact_between(rod, plane).using(
            ea.RodPlaneContactWithAnisotropicFriction,
            k=k_w,
            nu=gamma_w,
            slip_velocity_tol=slip_tol,
            static_mu_array=np.zeros(3),
            kinetic_mu_array=kinetic_mu,
        )
    else:
        sim.add_forcing_to(rod).using(
            TerrainContact,
            k=k_w,
            nu=gamma_w,
            slip_velocity_tol=slip_tol,
            kinetic_mu_array=kinetic_mu,
            r0=r,
            mode={"flatterrain": 0, "terrain": 1, "slopeterrain": 2}[args.ground],
            arm=args.arm,
            total_normal=args.normal == "total",
            cap_h=args.dt if args.cap else 0.0,
            mean_velocity=args.element_velocity == "mean",
            surface_tol=args.surface_tol,
        )
    dl = L / n
    if args.damping == "perlength":
        c_t = np.full(n + 1, nu_diss * dl)
        c_t[0] *= 0.5
        c_t[-1] *= 0.5
        c_r = nu_diss * dl
    else:  # "permass": PyElastica v0.2.x-0.3.0 internal nu (force nu*m_node*v, couple nu*m_elem*w)
        c_t = nu_diss * rod.mass
        m_e = 0.5 * (rod.mass[1:] + rod.mass[:-1])
        m_e[0] += 0.5 * rod.mass[0]
        m_e[-1] += 0.5 * rod.mass[-1]
        c_r = nu_diss * m_e
    sim.dampen(rod).using(
        ea.AnalyticalLinearDamper,
        translational_damping_constant=c_t,
        rotational_damping_constant=c_r,
        time_step=args.dt,
    )
    store = ea.defaultdict(list)
    step_skip = int(round(args.sample / args.dt))
    sim.collect_diagnostics(rod).using(Recorder, step_skip=step_skip, store=store)
    sim.finalize()
    return sim, rod, store


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--ground", choices=["flat", "terrain", "flatterrain", "slopeterrain", "slope"], default="flat")
    p.add_argument("--shear", type=float, default=1.0)
    p.add_argument("--twist", type=float, default=1.0)
    p.add_argument("--T", type=float, default=10.0)
    p.add_argument("--dt", type=float, default=1e-5)
    p.add_argument("--n", type=int, default=50)
    p.add_argument("--sample", type=float, default=0.01)
    p.add_argument("--slip_tol", type=float, default=1e-8)
    p.add_argument("--damping", choices=["perlength", "permass"], default="perlength")
    p.add_argument("--arm", type=float, default=1.0,
                   help="terrain grounds only: 1 = friction at the contact point, r below the axis, with its "
                        "rolling couple (PyElastica's); 0 = friction at the centreline, no couple (sinew's default)")
    p.add_argument("--normal", choices=["balance", "total"], default="balance",
                   help="terrain grounds only: the normal force friction scales with: PyElastica's balance of the "
                        "element's loads, or sinew's whole response (balance, penalty and damper)")
    p.add_argument("--cap", action="store_true",
                   help="terrain grounds only: cap each kinetic friction force at m |u| / dt (sinew's)")
    p.add_argument("--element_velocity", choices=["weighted", "mean"], default="weighted",
                   help="terrain grounds only: element velocity as PyElastica's mass-weighted mean of its nodes, "
                        "or their plain mean (sinew's)")
    p.add_argument("--surface_tol", type=float, default=1.0e-4,
                   help="terrain grounds only: gap above the radius up to which an element still touches "
                        "(PyElastica's 1e-4 m; sinew's default is 1e-6 r)")
    p.add_argument("--muscle_axis", choices=["lab", "body"], default="lab",
                   help="the muscle moment about the lab's z (PyElastica's MuscleTorques) or about each "
                        "node's body-fixed axis, the mean of its two elements' d1 (sinew's torque_wave)")
    p.add_argument("--out", required=True)
    p.add_argument("--save_every", type=float, default=5.0, help="checkpoint interval (s)")
    args = p.parse_args()

    sim, rod, store = build(args)
    stepper = ea.PositionVerlet()
    n_steps = int(round(args.T / args.dt))
    dt = np.float64(args.dt)
    t = np.float64(0.0)
    t0 = wallclock.time()
    chk = int(round(args.save_every / args.dt))

    def save(done_steps):
        np.savez_compressed(
            args.out + ".npz",
            time=np.array(store["time"]),
            com=np.array(store["com"]),
            position=np.array(store["position"]),
            sigma=np.array(store["sigma"]),
            kappa=np.array(store["kappa"]),
            nan=bool(store.get("nan", False)),
            args=json.dumps(vars(args)),
            wall=wallclock.time() - t0,
            steps=done_steps,
        )

    # one explicit callback at t=0 (PyElastica calls callbacks after each step)
    sim.apply_callbacks(t, 0)
    for i in range(n_steps):
        t = stepper.step(sim, t, dt)
        if (i + 1) % chk == 0:
            save(i + 1)
            com = rod.compute_position_center_of_mass()
            print(f"t={float(t):.3f} com={com} wall={wallclock.time()-t0:.1f}s", flush=True)
            if store.get("nan", False) or not np.all(np.isfinite(rod.position_collection)):
                print("NaN detected, stopping", flush=True)
                break
    save(i + 1)
    print(json.dumps({"out": args.out, "wall_s": wallclock.time() - t0, "t_end": float(t),
                      "nan": bool(store.get("nan", False))}), flush=True)


if __name__ == "__main__":
    main()
