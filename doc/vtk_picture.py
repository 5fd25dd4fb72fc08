"""What the doc/render_*.py scripts share: reading deal.II's VTU/PVTU output
and saving a rendered view as a PNG. Needs python3-vtk9."""
import vtk


def read(path):
    """The data set in a .vtu or .pvtu file (deal.II writes every field,
    cell data too, as point data)."""
    reader = vtk.vtkXMLGenericDataObjectReader()
    reader.SetFileName(path)
    reader.Update()
    return reader.GetOutput()


def point_camera(renderer, focal_point, position, view_up, zoom):
    """Look from POSITION at FOCAL_POINT, fit the scene, then zoom."""
    camera = renderer.GetActiveCamera()
    camera.SetFocalPoint(*focal_point)
    camera.SetPosition(*position)
    camera.SetViewUp(*view_up)
    renderer.ResetCamera()
    camera.Zoom(zoom)


def save_png(renderers, picture, size):
    """Render RENDERERS (one window, each in its viewport) off a virtual
    display and write PICTURE."""
    window = vtk.vtkRenderWindow()
    for renderer in renderers:
        window.AddRenderer(renderer)
    window.SetSize(*size)
    window.Render()
    image = vtk.vtkWindowToImageFilter()
    image.SetInput(window)
    writer = vtk.vtkPNGWriter()
    writer.SetFileName(picture)
    writer.SetInputConnection(image.GetOutputPort())
    writer.Write()
