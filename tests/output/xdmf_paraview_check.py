"""Opens one XDMF file that pcsim wrote with ParaView's default XDMF reader
(Xdmf3ReaderS, the XDMF3 library) and checks it against the HDF5 files beside it.

  xdmf_paraview_check.py FILE.xdmf KIND EXPECTED_TIME_STEPS [RENDER.png]

KIND is 'static' (static.xdmf: grids wires, bars, point masses, no time),
'modes' (modes.xdmf: one time step per mode) or 'snapshots' (snapshots.xdmf:
one time step per snapshot: wires, bars and the pantographs). For every time
step it checks the number of points and cells of every grid; that every grid
carries the same node (point) arrays, so that ParaView colours every block by
any of them; and that the fields read equal the HDF5 datasets bit for bit (the
reader reads doubles: no tolerance is needed): the node fields, a mode's
frequency and direction (field data 'frequency_hz', 'vertical'), the
pantographs' points and contact forces. With RENDER.png it also renders the
last time step coloured by the first node field (needs an X display: the test
runs it under xvfb-run) and checks that the lines' pixels are coloured, not
all one colour. Exit 0 when all hold.
"""
import os
import sys

import h5py
import numpy as np
from paraview import servermanager, simple
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkCommonDataModel import VTK_POLY_LINE, VTK_POLY_VERTEX, vtkDataSet


def leaves(data):
    """The datasets of a (nested) multiblock/multipiece output, in order."""
    if isinstance(data, vtkDataSet):
        return [data]
    if hasattr(data, "GetNumberOfBlocks"):
        parts = [data.GetBlock(i) for i in range(data.GetNumberOfBlocks())]
    else:
        parts = [data.GetPiece(i) for i in range(data.GetNumberOfPieces())]
    return [leaf for part in parts if part is not None for leaf in leaves(part)]


class Slice:
    """Slice k of a time x ... dataset, read like a dataset (x[()], x.name)."""

    def __init__(self, dataset, k):
        self.name = f"{dataset.name}[{k}]"
        self.values = dataset[k]

    def __getitem__(self, index):
        return self.values[index]


def expectations(path, kind, folder):
    """Per grid (points, cells, cell type); per time step and grid the
    checked fields: (name, 'point' | 'cell' | 'field', HDF5 dataset)."""
    mesh = h5py.File(os.path.join(folder, "static_mesh.h5"), "r")
    n = mesh["/nodes/position"].shape[0]
    wires = mesh["/cables/connectivity"].shape[0]
    bars = mesh["/bars/connectivity"].shape[0]
    masses = mesh["/point_masses/node"].shape[0]
    line_grids = [(n, wires, VTK_POLY_LINE), (n, bars, VTK_POLY_LINE)]
    if kind == "static":
        shown = ("displacement", "point", mesh["/nodes/displacement"])
        steps = [[[shown], [shown], [shown, ("mass", "cell", mesh["/point_masses/mass"])]]]
        return line_grids + [(n, masses, VTK_POLY_VERTEX)], steps, None
    if kind == "modes":
        modes = h5py.File(os.path.join(folder, "modes.h5"), "r")
        frequencies, vertical = modes["/frequencies_hz"], modes["/vertical"]
        steps = []
        for k in range(frequencies.shape[0]):
            fields = [("mode_shape", "point", modes[f"/shapes/mode_{k}"]),
                      ("frequency_hz", "field", Slice(frequencies, k)),
                      ("vertical", "field", Slice(vertical, k))]
            steps.append([fields, fields])
        return line_grids, steps, None
    if kind != "snapshots":
        sys.exit(f"{path}: unknown kind '{kind}'")
    results = h5py.File(os.path.join(folder, "results.h5"), "r")
    count = results["/snapshots/time"].shape[0]
    # One dataset snapshots x nodes x 3: the XDMF reads slice k at step k.
    displacement = results["/snapshots/displacement"]
    if displacement.shape != (count, n, 3):
        sys.exit(f"{path}: /snapshots/displacement is {displacement.shape}, "
                 f"expected {(count, n, 3)}")
    np_ = results["/snapshots/contact_force"].shape[1]
    points, forces = results["/snapshots/pantograph_points"], results["/snapshots/contact_force"]
    steps = []
    for k in range(count):
        shown = ("displacement", "point", Slice(displacement, k))
        pantographs = [("displacement", "point", results["/snapshots/xdmf/pantograph_displacement"]),
                       ("points", "points", Slice(points, k)),
                       ("contact_force", "cell", Slice(forces, k))]
        steps.append([[shown], [shown], pantographs])
    return line_grids + [(2 * np_, np_, VTK_POLY_LINE)], steps, results["/snapshots/time"][()]


def check_block(block, fields, step):
    """The checked fields of one block: a list of failures."""
    failures = []
    for field, centre, expected in fields:
        if centre == "points":
            array = block.GetPoints().GetData()
        else:
            data = {"point": block.GetPointData(), "cell": block.GetCellData(),
                    "field": block.GetFieldData()}[centre]
            array = data.GetAbstractArray(field)
        if array is None:
            failures.append(f"step {step}: no {centre} data '{field}'")
        elif not np.array_equal(vtk_to_numpy(array).ravel(), np.ravel(expected[()])):
            failures.append(f"step {step}: {centre} '{field}' differs from {expected.name}")
    return failures


def point_arrays(block):
    data = block.GetPointData()
    return sorted(data.GetArrayName(i) for i in range(data.GetNumberOfArrays()))


def check_steps(reader, kind, grids, steps, snapshot_times):
    failures = []
    reported = list(reader.TimestepValues)
    times = reported if reported else [None]  # a grid without time is read once
    if len(steps) != len(times):
        failures.append(f"{len(times)} time steps for {len(steps)} in the HDF5 files")
    # The XDMF gives times with 10 significant digits: equal to 1e-9 relative.
    if snapshot_times is not None and not np.allclose(times, snapshot_times,
                                                      rtol=1e-9, atol=1e-12):
        failures.append(f"times {times} differ from /snapshots/time")
    for step, (time, fields) in enumerate(zip(times, steps)):
        reader.UpdatePipeline(time if time is not None else 0.0)
        blocks = leaves(servermanager.Fetch(reader))
        got = [(b.GetNumberOfPoints(), b.GetNumberOfCells(),
                b.GetCellType(0) if b.GetNumberOfCells() else -1) for b in blocks]
        if got != grids:
            failures.append(f"step {step}: (points, cells, cell type) {got}, expected {grids}")
            continue
        names = [point_arrays(b) for b in blocks]
        if not names[0] or any(n != names[0] for n in names):
            failures.append(f"step {step}: the blocks' node arrays differ or are none: {names}")
        for block, block_fields in zip(blocks, fields):
            failures += check_block(block, block_fields, step)
    return failures, len(reported)


def check_render(reader, png, field):
    """Renders the last time step coloured by the node field 'field' (its
    magnitude) and checks the picture: a failure or None."""
    view = simple.CreateView("RenderView")
    view.ViewSize = [900, 500]
    view.OrientationAxesVisibility = 0
    if reader.TimestepValues:
        view.ViewTime = list(reader.TimestepValues)[-1]
    display = simple.Show(reader, view)
    display.Scale = [1, 1, 10]  # a catenary is long and flat: its height ten times
    display.LineWidth = 3
    simple.ColorBy(display, ("POINTS", field, "Magnitude"))
    display.RescaleTransferFunctionToDataRange(False, True)
    view.CameraPosition, view.CameraFocalPoint, view.CameraViewUp = [0, -1, 0], [0, 0, 0], [0, 0, 1]
    view.ResetCamera()
    simple.SaveScreenshot(png, view, ImageResolution=[900, 500])
    from vtkmodules.vtkIOImage import vtkPNGReader
    image = vtkPNGReader()
    image.SetFileName(png)
    image.Update()
    out = image.GetOutput()
    pixels = vtk_to_numpy(out.GetPointData().GetScalars())[:, :3].astype(int)
    # The background is the commonest colour; the lines are the rest.
    colours, counts = np.unique(pixels, axis=0, return_counts=True)
    background = colours[np.argmax(counts)]
    lines = pixels[np.any(pixels != background, axis=1)]
    # Coloured: the channels differ (white or grey lines have spread 0);
    # both ends of the map (blue low, red high) appear: 40 of 255 levels
    # keeps anti-aliased edges blended with the background out.
    spread = lines.max(axis=1) - lines.min(axis=1)
    blue = np.sum(lines[:, 2] > lines[:, 0] + 40)
    red = np.sum(lines[:, 0] > lines[:, 2] + 40)
    if len(lines) < 500 or np.sum(spread > 60) < 200 or blue < 20 or red < 20:
        return (f"render {png}: {len(lines)} line pixels, {np.sum(spread > 60)} coloured, "
                f"{blue} blue, {red} red: not coloured by '{field}'")
    print(f"render {os.path.basename(png)}: {len(lines)} line pixels, "
          f"{len(np.unique(lines, axis=0))} colours, {blue} blue, {red} red")
    return None


def main():
    path, kind, expected_steps = sys.argv[1], sys.argv[2], int(sys.argv[3])
    png = sys.argv[4] if len(sys.argv) > 4 else None
    folder = os.path.dirname(os.path.abspath(path))
    grids, steps, snapshot_times = expectations(path, kind, folder)
    reader = simple.OpenDataFile(path)
    if reader is None or reader.GetXMLName() != "Xdmf3ReaderS":
        sys.exit(f"{path}: ParaView did not choose its XDMF3 reader")
    failures, reported = check_steps(reader, kind, grids, steps, snapshot_times)
    if reported != expected_steps:
        failures.append(f"{reported} time steps, expected {expected_steps}")
    if png and not failures:
        failure = check_render(reader, png, steps[-1][0][0][0])
        if failure:
            failures.append(failure)
    if failures:
        sys.exit(f"{path}:\n  " + "\n  ".join(failures))
    print(f"ok {os.path.basename(path)}: {reported} time steps, "
          f"grids (points, cells) {[g[:2] for g in grids]}")


if __name__ == "__main__":
    main()
