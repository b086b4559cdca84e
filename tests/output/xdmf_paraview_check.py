"""Opens one XDMF file that pcsim wrote with ParaView's default XDMF reader
(Xdmf3ReaderS, the XDMF3 library) and checks it against the HDF5 files beside it.

  xdmf_paraview_check.py FILE.xdmf KIND EXPECTED_TIME_STEPS

KIND is 'static' (static.xdmf: grids wires, bars, point masses, no time),
'modes' (modes.xdmf: one time step per mode) or 'snapshots' (snapshots.xdmf:
one time step per snapshot). For every time step it checks the number of points
and cells of every grid, and that the field read equals the HDF5 dataset bit for
bit (the reader reads doubles: no tolerance is needed). Exit 0 when all hold.
Runs headless: only the reader and the data pipeline are used, nothing renders.
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


def main():
    path, kind, expected_steps = sys.argv[1], sys.argv[2], int(sys.argv[3])
    folder = os.path.dirname(os.path.abspath(path))
    mesh = h5py.File(os.path.join(folder, "static_mesh.h5"), "r")
    n = mesh["/nodes/position"].shape[0]
    wires = mesh["/cables/connectivity"].shape[0]
    bars = mesh["/bars/connectivity"].shape[0]
    masses = mesh["/point_masses/node"].shape[0]
    # Per grid: (points, cells, cell type) and the field checked, with its
    # centring; per time step: the HDF5 dataset of that field.
    line_grids = [(n, wires, VTK_POLY_LINE), (n, bars, VTK_POLY_LINE)]
    if kind == "static":
        grids = line_grids + [(n, masses, VTK_POLY_VERTEX)]
        fields = [("displacement", "point")] * 2 + [("mass", "cell")]
        datasets = [[mesh["/nodes/displacement"]] * 2 + [mesh["/point_masses/mass"]]]
    elif kind == "modes":
        grids, fields = line_grids, [("mode_shape", "point")] * 2
        modes = h5py.File(os.path.join(folder, "modes.h5"), "r")
        count = modes["/frequencies_hz"].shape[0]
        datasets = [[modes[f"/shapes/mode_{k}"]] * 2 for k in range(count)]
    elif kind == "snapshots":
        grids, fields = line_grids, [("displacement", "point")] * 2
        results = h5py.File(os.path.join(folder, "results.h5"), "r")
        count = results["/snapshots/time"].shape[0]
        # One dataset snapshots x nodes x 3: the XDMF reads slice k at step k.
        displacement = results["/snapshots/displacement"]
        if displacement.shape != (count, n, 3):
            sys.exit(f"{path}: /snapshots/displacement is {displacement.shape}, "
                     f"expected {(count, n, 3)}")
        datasets = [[Slice(displacement, k)] * 2 for k in range(count)]
    else:
        sys.exit(f"{path}: unknown kind '{kind}'")

    failures = []
    reader = simple.OpenDataFile(path)
    if reader is None or reader.GetXMLName() != "Xdmf3ReaderS":
        sys.exit(f"{path}: ParaView did not choose its XDMF3 reader")
    reported = list(reader.TimestepValues)
    if len(reported) != expected_steps:
        failures.append(f"{len(reported)} time steps, expected {expected_steps}")
    times = reported if reported else [None]  # a grid without time is read once
    if len(datasets) != len(times):
        failures.append(f"{len(times)} time steps for {len(datasets)} HDF5 datasets")
    # The XDMF gives times with 10 significant digits: equal to 1e-9 relative.
    if kind == "snapshots" and not np.allclose(times, results["/snapshots/time"][()],
                                               rtol=1e-9, atol=1e-12):
        failures.append(f"times {times} differ from /snapshots/time")
    for step, (time, dataset) in enumerate(zip(times, datasets)):
        reader.UpdatePipeline(time if time is not None else 0.0)
        blocks = leaves(servermanager.Fetch(reader))
        got = [(b.GetNumberOfPoints(), b.GetNumberOfCells(),
                b.GetCellType(0) if b.GetNumberOfCells() else -1) for b in blocks]
        if got != grids:
            failures.append(f"step {step}: (points, cells, cell type) {got}, expected {grids}")
            continue
        for b, (field, centre), expected in zip(blocks, fields, dataset):
            data = b.GetPointData() if centre == "point" else b.GetCellData()
            array = data.GetArray(field)
            if array is None:
                failures.append(f"step {step}: no {centre} field '{field}'")
            elif not np.array_equal(vtk_to_numpy(array), expected[()]):
                failures.append(f"step {step}: '{field}' differs from {expected.name}")
    if failures:
        sys.exit(f"{path}:\n  " + "\n  ".join(failures))
    print(f"ok {os.path.basename(path)}: {len(reported)} time steps, "
          f"grids (points, cells) {[g[:2] for g in grids]}")


if __name__ == "__main__":
    main()
