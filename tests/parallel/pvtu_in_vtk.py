#!/usr/bin/python3
"""The frames of a run over several ranks, read by VTK's own XML readers (the ones ParaView uses):
every .pvtu that particles.pvd lists must open, join its pieces and hold, point for point and bit
for bit, the one-rank run's .vtu frame (a run on N ranks writes .pvtu frames that
ParaView opens).

usage: pvtu_in_vtk.py SPREAD_DIR ONE_RANK_DIR
"""
import re
import sys
from pathlib import Path

from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOXML import vtkXMLPUnstructuredGridReader, vtkXMLUnstructuredGridReader


def frames(folder):
    """The files particles.pvd lists, in order."""
    return re.findall(r'file="([^"]+)"', (Path(folder) / "particles.pvd").read_text())


def read(path, reader):
    reader.SetFileName(str(path))
    reader.Update()
    grid = reader.GetOutput()
    if grid is None or grid.GetNumberOfPoints() == 0:
        sys.exit(f"{path}: VTK read no points")
    data = {"position": vtk_to_numpy(grid.GetPoints().GetData())}
    point_data = grid.GetPointData()
    for k in range(point_data.GetNumberOfArrays()):
        data[point_data.GetArrayName(k)] = vtk_to_numpy(point_data.GetArray(k))
    return grid.GetNumberOfPoints(), grid.GetNumberOfCells(), data


def main():
    spread, one = sys.argv[1], sys.argv[2]
    spread_frames, one_frames = frames(spread), frames(one)
    if len(spread_frames) != len(one_frames) or not spread_frames:
        sys.exit(f"{len(spread_frames)} frames against one rank's {len(one_frames)}")
    for joined, single in zip(spread_frames, one_frames):
        if not joined.endswith(".pvtu"):
            sys.exit(f"{spread}/particles.pvd lists {joined}, not a .pvtu")
        points, cells, data = read(Path(spread) / joined, vtkXMLPUnstructuredGridReader())
        points_1, cells_1, data_1 = read(Path(one) / single, vtkXMLUnstructuredGridReader())
        if (points, cells) != (points_1, cells_1):
            sys.exit(f"{joined}: {points} points and {cells} cells, one rank {points_1}, {cells_1}")
        if sorted(data) != sorted(data_1):
            sys.exit(f"{joined}: arrays {sorted(data)}, one rank {sorted(data_1)}")
        for name, values in data.items():
            if values.tobytes() != data_1[name].tobytes():
                sys.exit(f"{joined}: '{name}' differs from the one-rank frame {single}")
    print(f"pvtu_in_vtk: {len(spread_frames)} frames of {points} points equal to one rank's")


main()
