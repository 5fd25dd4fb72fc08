#!/usr/bin/env python3
"""Render the output of an `Experiment = geometry` run to a PNG.

    python3 doc/render_geometry.py OUTPUT_DIRECTORY PICTURE.png

Shows the membranes (coloured by cell) inside the capillary lumen: the
fluid mesh's wall drawn as a translucent wireframe, with the diffusion mesh's
vessel wall and gas layer cut open in the back half. Needs python3-vtk9;
renders off-screen (run it under xvfb-run where there is no display).
"""
import sys

import vtk


def read(path):
    r = vtk.vtkXMLGenericDataObjectReader()
    r.SetFileName(path)
    r.Update()
    return r.GetOutput()


def surface(path):
    geometry = vtk.vtkDataSetSurfaceFilter()
    geometry.SetInputData(read(path))
    return geometry


def main(directory, picture):
    renderer = vtk.vtkRenderer()
    renderer.SetBackground(1, 1, 1)

    # Membranes, one colour per cell.
    membranes = surface(directory + "/membranes.vtu")
    membranes.Update()
    n_cells = int(membranes.GetOutput().GetPointData().GetArray("cell").GetRange()[1]) + 1
    mapper = vtk.vtkPolyDataMapper()
    mapper.SetInputConnection(membranes.GetOutputPort())
    mapper.SetScalarModeToUsePointFieldData()
    mapper.SelectColorArray("cell")
    mapper.SetScalarRange(0, max(n_cells - 1, 1))
    lut = vtk.vtkLookupTable()
    lut.SetHueRange(0.0, 0.7)
    lut.Build()
    mapper.SetLookupTable(lut)
    actor = vtk.vtkActor()
    actor.SetMapper(mapper)
    renderer.AddActor(actor)

    # The diffusion mesh, back half only (y > 0), coloured by material id:
    # plasma, vessel wall, gas.
    clip = vtk.vtkExtractGeometry()
    clip.SetInputData(read(directory + "/diffusion_mesh_0000.pvtu"))
    plane = vtk.vtkPlane()
    plane.SetOrigin(0, 0, 0)
    plane.SetNormal(0, -1, 0)
    clip.SetImplicitFunction(plane)
    clip.ExtractInsideOn()
    clip.ExtractBoundaryCellsOff()
    threshold = vtk.vtkThreshold()
    threshold.SetInputConnection(clip.GetOutputPort())
    threshold.SetInputArrayToProcess(0, 0, 0, vtk.vtkDataObject.FIELD_ASSOCIATION_POINTS, "material_id")
    threshold.SetLowerThreshold(0.5)
    threshold.SetUpperThreshold(2.5)
    tissue = vtk.vtkDataSetSurfaceFilter()
    tissue.SetInputConnection(threshold.GetOutputPort())
    tissue_mapper = vtk.vtkPolyDataMapper()
    tissue_mapper.SetInputConnection(tissue.GetOutputPort())
    tissue_mapper.SetScalarModeToUsePointFieldData()
    tissue_mapper.SelectColorArray("material_id")
    tissue_mapper.SetScalarRange(0, 2)
    tissue_lut = vtk.vtkLookupTable()
    tissue_lut.SetNumberOfTableValues(3)
    tissue_lut.SetTableValue(0, 1.0, 0.9, 0.9, 1)
    tissue_lut.SetTableValue(1, 0.85, 0.55, 0.55, 1)
    tissue_lut.SetTableValue(2, 0.75, 0.85, 1.0, 1)
    tissue_lut.Build()
    tissue_mapper.SetLookupTable(tissue_lut)
    tissue_actor = vtk.vtkActor()
    tissue_actor.SetMapper(tissue_mapper)
    tissue_actor.GetProperty().EdgeVisibilityOn()
    tissue_actor.GetProperty().SetEdgeColor(0.5, 0.5, 0.5)
    tissue_actor.GetProperty().SetLineWidth(0.5)
    renderer.AddActor(tissue_actor)

    # The fluid mesh's boundary (the lumen wall) as a light wireframe.
    lumen = surface(directory + "/fluid_mesh_boundary.pvtu")
    lumen_mapper = vtk.vtkPolyDataMapper()
    lumen_mapper.SetInputConnection(lumen.GetOutputPort())
    lumen_mapper.ScalarVisibilityOff()
    lumen_actor = vtk.vtkActor()
    lumen_actor.SetMapper(lumen_mapper)
    lumen_actor.GetProperty().SetRepresentationToWireframe()
    lumen_actor.GetProperty().SetColor(0.3, 0.3, 0.6)
    lumen_actor.GetProperty().SetOpacity(0.25)
    renderer.AddActor(lumen_actor)

    camera = renderer.GetActiveCamera()
    camera.SetFocalPoint(10, 0, 0)
    camera.SetPosition(-14, -30, 13)
    camera.SetViewUp(0, 0, 1)
    renderer.ResetCamera()
    camera.Zoom(1.5)

    window = vtk.vtkRenderWindow()
    window.AddRenderer(renderer)
    window.SetSize(1200, 700)
    window.Render()
    image = vtk.vtkWindowToImageFilter()
    image.SetInput(window)
    writer = vtk.vtkPNGWriter()
    writer.SetFileName(picture)
    writer.SetInputConnection(image.GetOutputPort())
    writer.Write()


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2])
