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


def outer_surface(algorithm_or_data):
    """The surface of a data set or of an algorithm's output, as polygons."""
    surface = vtk.vtkDataSetSurfaceFilter()
    if isinstance(algorithm_or_data, vtk.vtkAlgorithm):
        surface.SetInputConnection(algorithm_or_data.GetOutputPort())
    else:
        surface.SetInputData(algorithm_or_data)
    return surface


def actor(surface, array=None, value_range=None, lookup_table=None):
    """An actor for a surface, coloured by a point array if one is named
    (deal.II writes every field, cell data too, as point data)."""
    mapper = vtk.vtkPolyDataMapper()
    mapper.SetInputConnection(surface.GetOutputPort())
    if array is None:
        mapper.ScalarVisibilityOff()
    else:
        mapper.SetScalarModeToUsePointFieldData()
        mapper.SelectColorArray(array)
        mapper.SetScalarRange(*value_range)
        mapper.SetLookupTable(lookup_table)
    result = vtk.vtkActor()
    result.SetMapper(mapper)
    return result


def scalar_bar(lookup, title, left=0.15, width=0.7):
    """A horizontal colour legend along the bottom of the view, in black."""
    bar = vtk.vtkScalarBarActor()
    bar.SetLookupTable(lookup)
    bar.SetTitle(title)
    bar.SetNumberOfLabels(5)
    bar.SetOrientationToHorizontal()
    bar.SetPosition(left, 0.04)
    bar.SetWidth(width)
    bar.SetHeight(0.12)
    for text in (bar.GetTitleTextProperty(), bar.GetLabelTextProperty()):
        text.SetColor(0, 0, 0)
    return bar


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
