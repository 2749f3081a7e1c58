# paraview_rods.py — opens a run's XDMF description in ParaView (pvpython,
# under xvfb-run: Debian's ParaView renders through GLX only), checks it
# against the HDF5 file it describes, draws the rods as tubes at the last
# frame and checks the picture.  Run by tests/lang/test_paraview.sh:
#
#   pvpython paraview_rods.py RUN.xdmf RUN.h5 OUT.png
#
# Prints one TAP line per check ("ok" / "not ok" and what was measured) and
# nothing else on stdout; the shell test counts them.
#
# The checks, each against something ParaView did not compute:
#  - the time steps are /time of the HDF5 file, value for value;
#  - at the last step each rod's points are /rods/NAME/position's last frame
#    (read with h5py) to 1e-12 m, its point data `radius` is
#    /rods/NAME/node_radius and `velocity` (when written) the last frame of
#    /rods/NAME/velocity;
#  - the Tube filter, its radius taken from `radius`, makes a tube whose
#    bounds are the rod's points widened by the radius (to within the
#    polygonal tube's inscribed radius, cos(pi / sides) of it);
#  - rendered side on with a parallel projection of known scale, the picture's
#    non-background pixels cover the tube's projected bounding box (to 3
#    pixels) and about its projected area (for rods that do not overlap in
#    the view, as the test's cantilever).
import math
import os
import re
import sys

import h5py
import numpy as np
from paraview import servermanager as sm
from paraview.simple import (ColorBy, CreateView, ExtractSurface, Render, SaveScreenshot, Show,
                             Tube, XDMFReader)
from vtkmodules.numpy_interface import dataset_adapter as dsa
from vtkmodules.vtkCommonDataModel import vtkCompositeDataSet
from vtkmodules.vtkIOImage import vtkPNGReader

xdmf, h5, png = sys.argv[1:4]
n = 0
failed = 0


def check(cond, what):
    global n, failed
    n += 1
    if not cond:
        failed += 1
    print("%s %d - %s" % ("ok" if cond else "not ok", n, what), flush=True)


def leaves(obj, name=""):
    """(name, dataset) of every leaf of a multiblock tree."""
    if obj.IsA("vtkMultiBlockDataSet"):
        for i in range(obj.GetNumberOfBlocks()):
            meta = obj.GetMetaData(i) if obj.HasMetaData(i) else None
            child = meta.Get(vtkCompositeDataSet.NAME()) if meta else ""
            child = re.sub(r"\[\d+\]$", "", child)   # the reader adds "[step]"
            if obj.GetBlock(i) is not None:
                yield from leaves(obj.GetBlock(i), child)
    else:
        yield name, obj


f = h5py.File(h5, "r")
time = f["time"][:]
rods = [r for r in f["rods"] if "position" in f["rods"][r]]

reader = XDMFReader(FileNames=[xdmf])
reader.UpdatePipelineInformation()
steps = np.array(reader.TimestepValues)
check(len(steps) == len(time),
      "ParaView sees %d time steps, /time has %d" % (len(steps), len(time)))
check(len(steps) == len(time) and np.array_equal(steps, time),
      "the time steps are /time's values (largest difference %.3g s)"
      % (np.max(np.abs(steps - time)) if len(steps) == len(time) else float("nan")))

reader.UpdatePipeline(steps[-1])
grids = dict(leaves(sm.Fetch(reader)))
check(sorted(grids) == sorted(rods),
      "one grid per rod with positions: %s" % ", ".join(sorted(grids)))
worst = 0.0
radius_ok = True
lo, hi = np.full(3, np.inf), np.full(3, -np.inf)
rmax = 0.0
for name in rods:
    g = dsa.WrapDataObject(grids.get(name))
    pts = np.array(g.Points)
    want = f["rods"][name]["position"][-1]
    worst = max(worst, np.max(np.abs(pts - want)) if pts.shape == want.shape else np.inf)
    if "velocity" in f["rods"][name]:
        v = np.array(g.PointData["velocity"])
        vwant = f["rods"][name]["velocity"][-1]
        check(v.shape == vwant.shape and np.max(np.abs(v - vwant)) == 0,
              "rod %s: point data velocity is the last frame of its velocity" % name)
    radius = np.array(g.PointData["radius"])
    radius_ok = radius_ok and np.array_equal(radius, f["rods"][name]["node_radius"][:])
    lo, hi = np.minimum(lo, want.min(axis=0)), np.maximum(hi, want.max(axis=0))
    rmax = max(rmax, radius.max())
    check(g.GetNumberOfCells() == 1 and g.GetCellType(0) == 4,
          "rod %s is one polyline of %d points" % (name, g.GetNumberOfPoints()))
check(worst <= 1e-12,
      "points at the last step are the last frame of /rods/NAME/position "
      "(largest difference %.3g m, tolerance 1e-12)" % worst)
check(radius_ok, "point data radius is /rods/NAME/node_radius")

# Tubes: ParaView's Tube takes polydata, hence Extract Surface first.
sides = 24
tube = Tube(Input=ExtractSurface(Input=reader), Scalars=["POINTS", "radius"],
            VaryRadius="By Absolute Scalar", NumberofSides=sides, Capping=1)
tube.UpdatePipeline(steps[-1])
b = np.array(tube.GetDataInformation().GetBounds())
tlo, thi = b[0::2], b[1::2]
# The scenes move in the x-z plane, so across it (y) the tube reaches out by
# its radius on either side, by the inscribed radius at least.
inscribed = rmax * math.cos(math.pi / sides)
widen = np.array([lo[1] - tlo[1], thi[1] - hi[1]])
check(np.all(widen >= inscribed * (1 - 1e-9)) and np.all(widen <= rmax * (1 + 1e-9)),
      "across the plane of motion the tube reaches %.5g and %.5g m beyond the rod, "
      "radius %.5g m (inscribed %.5g m)" % (widen[0], widen[1], rmax, inscribed))

# A side view along +y, parallel projection: world (x, z) maps to pixels by
# a known scale.
W = H = 400
view = CreateView("RenderView")
view.ViewSize = [W, H]
view.OrientationAxesVisibility = 0
view.UseColorPaletteForBackground = 0
view.Background = [1.0, 1.0, 1.0]
shown = Show(tube, view)
ColorBy(shown, None)
shown.DiffuseColor = [0.15, 0.3, 0.7]
shown.AmbientColor = [0.15, 0.3, 0.7]
view.ViewTime = steps[-1]
Render(view)   # the first render places the camera; ours replaces it
center = 0.5 * (tlo + thi)
scale = 0.6 * max(thi[0] - tlo[0], thi[2] - tlo[2])   # half the view's height, m
view.CameraPosition = [center[0], center[1] - 10.0, center[2]]
view.CameraFocalPoint = list(center)
view.CameraViewUp = [0.0, 0.0, 1.0]
view.CameraParallelProjection = 1
view.CameraParallelScale = scale
Render(view)
SaveScreenshot(png, view, ImageResolution=[W, H])

img = vtkPNGReader()
img.SetFileName(png)
img.Update()
pix = dsa.WrapDataObject(img.GetOutput()).PointData[0]
pix = np.array(pix).reshape(H, W, -1)[::-1, :, :3].astype(int)   # rows from the top
drawn = np.any(np.abs(pix - 255) > 24, axis=2)
per_m = H / (2 * scale)
want_box = (W / 2 + (tlo[0] - center[0]) * per_m, W / 2 + (thi[0] - center[0]) * per_m,
            H / 2 - (thi[2] - center[2]) * per_m, H / 2 - (tlo[2] - center[2]) * per_m)
rows, cols = np.nonzero(drawn)
got_box = (cols.min(), cols.max() + 1, rows.min(), rows.max() + 1) if drawn.any() else (0,) * 4
off = max(abs(g - w) for g, w in zip(got_box, want_box))
check(drawn.any() and off <= 3,
      "the drawn pixels' box is the tube's projected box: x %d..%d, y %d..%d px, "
      "expected %.1f..%.1f, %.1f..%.1f (worst %.1f px off)" % (got_box + want_box + (off,)))
# The projected area of the tubes: the polyline's length in the view plane
# times the diameter.
area = 0.0
for name in rods:
    p = f["rods"][name]["position"][-1][:, [0, 2]]
    r = f["rods"][name]["node_radius"][:]
    seg = np.linalg.norm(np.diff(p, axis=0), axis=1)
    area += np.sum(seg * (r[1:] + r[:-1]))
want_px = area * per_m * per_m
ratio = drawn.sum() / want_px
check(0.85 <= ratio <= 1.15,
      "%d pixels drawn (%.2f%% of the picture), %.0f expected from the tube's "
      "projected area (ratio %.3f)" % (drawn.sum(), 100.0 * drawn.mean(), want_px, ratio))
# Leave without ParaView's teardown, which under Xvfb fails on the GLX context
# (X_GLXMakeCurrent: GLXBadContext) and turns a passed run into exit code 1.
sys.stdout.flush()
os._exit(1 if failed else 0)
