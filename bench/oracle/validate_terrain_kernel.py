"""Check TerrainContact against PyElastica's RodPlaneContactWithAnisotropicFriction
at identical states: external forces/torques after one synchronize().
Pairs: flat plane vs TerrainContact(h=0); tilted plane z=0.3x-r vs TerrainContact(h=0.3x)."""
import sys, argparse
import numpy as np
sys.argv = [sys.argv[0]]
import snake_oracle as so
def mk(ground):
    a = argparse.Namespace(ground=ground, shear=1.0, twist=1.0, T=1.0, dt=1e-5, n=50, sample=0.01, slip_tol=1e-8, out='x', save_every=1, damping='perlength',
                           arm=1.0, normal='balance', cap=False, element_velocity='weighted', surface_tol=1e-4,
                           muscle_axis='lab')
    return so.build(a)
for ga, gb, nsteps in (('flat', 'flatterrain', 30000), ('slope', 'slopeterrain', 500)):
    simA, rodA, _ = mk(ga); simB, rodB, _ = mk(gb)
    if ga == 'slope':  # lay the straight rod onto the slope z = 0.3 x (rotate about y)
        th = np.arctan(0.3); c, s_ = np.cos(th), np.sin(th)
        x = rodA.position_collection[0].copy()
        rodA.position_collection[0] = c * x; rodA.position_collection[2] = s_ * x - 0.025 + 0.025 * np.sqrt(1.09) - 2e-4
        R = np.array([[c, 0, -s_], [0, 1, 0], [s_, 0, c]])  # lab rotation
        for e in range(rodA.director_collection.shape[2]):
            rodA.director_collection[..., e] = rodA.director_collection[..., e] @ R.T
    st = so.ea.PositionVerlet(); t = np.float64(0)
    for i in range(nsteps):
        t = st.step(simA, t, np.float64(1e-5))
    for name in ['position_collection','velocity_collection','director_collection','omega_collection']:
        getattr(rodB, name)[:] = getattr(rodA, name)
    for sim, rod in ((simA, rodA), (simB, rodB)):
        rod.zeroed_out_external_forces_and_torques(t)
        rod.compute_internal_forces_and_torques(t)
        sim.synchronize(t)
    df = np.abs(rodA.external_forces - rodB.external_forces).max()
    dtq = np.abs(rodA.external_torques - rodB.external_torques).max()
    zc = rodA.compute_position_center_of_mass()
    ep = 0.5*(rodB.position_collection[:,1:]+rodB.position_collection[:,:-1]); _,_,dist = so.local_planes(ep, 0.025, {'flatterrain':0,'slopeterrain':2}[gb]); nc = int(((dist - rodB.radius) <= 1e-4).sum()); print(ga, 'vs', gb, 'elements in contact', nc, 't=%.3f' % t, 'com', zc, 'max|F| %.4g max dF %.3g  max|T| %.4g max dT %.3g' % (
        np.abs(rodA.external_forces).max(), df, np.abs(rodA.external_torques).max(), dtq))
